"""lunarcap: finite-burn lunar capture, reproducing and extending Song et al. (2011).

Song, Park, Kim, Lee & Sim (2011), "Analysis of Delta-V Losses During Lunar Capture
Sequence Using Finite Thrust", J. Astron. Space Sci. 28(3) 203-216.
"""



def __getattr__(name):
    """``lunarcap.__version__``, read from the installed metadata when first asked."""
    if name == "__version__":
        from importlib.metadata import PackageNotFoundError, version

        try:
            return version("lunarcap")
        except PackageNotFoundError:  # a source tree without installation
            return "0+unknown"
    raise AttributeError(f"module 'lunarcap' has no attribute {name!r}")
