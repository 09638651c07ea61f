"""lunarcap: finite-burn lunar capture, reproducing and extending Song et al. (2011).

Song, Park, Kim, Lee & Sim (2011), "Analysis of Delta-V Losses During Lunar Capture
Sequence Using Finite Thrust", J. Astron. Space Sci. 28(3) 203-216.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("lunarcap")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0+unknown"
