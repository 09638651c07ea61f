"""The style shared by the book's figures: sizes, fonts, colours, the Moon, saving.

Every figure module (:mod:`.figures_capture`, :mod:`.figures_studies`, re-exported by
:mod:`.figures`) draws with these, so the figures read alike and pass the legibility
checks (tests/report/test_figure_legibility.py).
"""

from __future__ import annotations

import matplotlib
import matplotlib.pyplot as plt

from lunarcap.repro import paths

# Reproducible SVG output (no random ids, no date).
matplotlib.rcParams["svg.hashsalt"] = "lunarcap"

#: Width of every figure, inches: the book's text column at 1280 and 1024 px is about 700
#: CSS px, so a figure of this width (96 CSS px per inch) is shown at about its natural
#: size and a font of :data:`MIN_FONT_PT` reads at 9 px or more (``make screenshots``
#: fails on a figure shown below 80 % of its natural width).
FIG_WIDTH_IN = 6.8
#: Smallest font of any figure text, pt (tests/report/test_figures.py checks every text).
MIN_FONT_PT = 9.0
matplotlib.rcParams.update({"font.size": 10, "axes.titlesize": 10, "axes.labelsize": 10,
                            "xtick.labelsize": 9, "ytick.labelsize": 9,
                            "legend.fontsize": 9, "figure.titlesize": 11})

#: One marker per specific impulse (with one colour each), so curves differ in grey too.
ISP_MARKERS = ("o", "s", "^", "D", "v", "P")


def save_figure(fig, name: str, dpi: int = 150) -> dict:
    """Save ``fig`` as ``figures/<name>.png`` and ``.svg`` below ``book/generated`` atomically.

    Returns
    -------
    dict
        ``{"png": Path, "svg": Path}``.
    """
    out = {}
    for fmt in paths.FIGURE_FORMATS:
        path = paths.figure_path(name, fmt)
        meta = {"Date": None} if fmt == "svg" else {"Software": None}
        with paths.atomic_path(path) as tmp:
            fig.savefig(tmp, format=fmt, dpi=dpi, metadata=meta)
        out[fmt] = path
    return out


#: Colours of the capture-sequence figures: one per orbit, one per burn (cycled).
_COAST_COLOURS = ("tab:blue", "tab:green", "tab:purple", "tab:olive", "tab:cyan", "tab:pink")
_BURN_COLOURS = ("#d62728", "#ff7f0e", "#8c2d04", "#e377c2", "#7f7f7f", "#bcbd22")
HYPERBOLA_COLOUR = "0.35"


def coast_colour(burn: int) -> str:
    """Colour of the orbit reached by burn ``burn`` (1-based)."""
    return _COAST_COLOURS[(burn - 1) % len(_COAST_COLOURS)]


def burn_colour(burn: int) -> str:
    """Colour of burn ``burn`` (1-based)."""
    return _BURN_COLOURS[(burn - 1) % len(_BURN_COLOURS)]


def draw_moon(ax, radius=1.0, label=True):
    """The Moon as a grey disc of ``radius`` (axis units), labelled unless ``label`` is False."""
    ax.add_patch(plt.Circle((0, 0), radius, color="0.85", zorder=0))
    if label:
        ax.text(0, 0, "Moon", ha="center", va="center", fontsize=9, color="0.3", zorder=1)
