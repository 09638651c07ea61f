"""The style shared by the book's figures: sizes, fonts, colours, the Moon, saving.

Every figure module (:mod:`lunarcap.report.figures` and its module per page) draws with
these, so the figures read alike and pass the legibility checks
(tests/report/test_figure_legibility.py).
"""

from __future__ import annotations

import matplotlib
import matplotlib.legend
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
                            "legend.fontsize": 10, "figure.titlesize": 11})

#: One marker per specific impulse (with one colour each), so curves differ in grey too.
ISP_MARKERS = ("o", "s", "^", "D", "v", "P")


def legibility_problems(fig) -> list[str]:
    """What makes a figure hard to read (empty if nothing).

    Text below :data:`MIN_FONT_PT`, or a legend smaller than the axis text.

    The axis text is every axis label and tick label of the figure; a legend's text must be
    at least as large as the largest of them, so the key reads as easily as the axes.
    """
    import matplotlib.text

    out = []
    fig.canvas.draw()
    texts = [t for t in fig.findobj(matplotlib.text.Text)
             if t.get_visible() and t.get_text().strip()]
    small = sorted({(t.get_fontsize(), t.get_text()[:30]) for t in texts
                    if t.get_fontsize() < MIN_FONT_PT - 1e-9})
    out += [f"text of {size:g} pt below {MIN_FONT_PT:g} pt: {text!r}" for size, text in small]
    axis_pt = max([t.get_fontsize() for ax in fig.get_axes()
                   for t in [ax.xaxis.label, ax.yaxis.label,
                             *ax.get_xticklabels(), *ax.get_yticklabels()]
                   if t.get_visible() and t.get_text().strip()], default=0.0)
    for lg in fig.findobj(matplotlib.legend.Legend):
        for t in lg.get_texts():
            if t.get_text().strip() and t.get_fontsize() < axis_pt - 1e-9:
                out.append(f"legend text of {t.get_fontsize():g} pt below the axis text "
                           f"({axis_pt:g} pt): {t.get_text()[:30]!r}")
    return out


def save_figure(fig, name: str, dpi: int = 150) -> dict:
    """Save ``fig`` as ``figures/<name>.png`` and ``.svg`` below ``book/generated`` atomically.

    A figure with a :func:`legibility_problems` is refused (ValueError naming them), so
    no page of the book shows one.

    Returns
    -------
    dict
        ``{"png": Path, "svg": Path}``.
    """
    problems = legibility_problems(fig)
    if problems:
        raise ValueError(f"figure {name!r} is hard to read: " + "; ".join(problems[:5]))
    out = {}
    for fmt in paths.FIGURE_FORMATS:
        path = paths.figure_path(name, fmt)
        meta = {"Date": None} if fmt == "svg" else {"Software": None}
        with paths.atomic_path(path) as tmp:
            fig.savefig(tmp, format=fmt, dpi=dpi, metadata=meta)
        out[fmt] = path
    return out


# ====================================================================== the palette
# Every colour of every figure of the book comes from here (tests/report/test_figstyle.py
# refuses a colour literal in a figure or page module), so one orbit, one burn, one engine
# has one colour on every page.

#: The orbit reached by burn n (n = 1, 2, ...: the first capture orbit is blue on every page).
ORBIT_COLOURS = ("#1f77b4", "#2ca02c", "#9467bd", "#bcbd22", "#17becf", "#e377c2")
#: Burn n (the first is red on every page).
BURN_COLOURS = ("#d62728", "#ff7f0e", "#8c2d04", "#e377c2", "#7f7f7f", "#bcbd22")
#: The names of these colours, for captions ("blue: the 1st capture orbit").
COLOUR_NAMES = {"#1f77b4": "blue", "#2ca02c": "green", "#9467bd": "purple",
                "#bcbd22": "olive", "#17becf": "cyan", "#e377c2": "pink", "#d62728": "red",
                "#ff7f0e": "orange", "#8c2d04": "brown", "#7f7f7f": "grey"}
#: The arrival hyperbola (and the approach arc of an export).
HYPERBOLA_COLOUR = "0.35"
#: Velocity arrows and other neutral marks drawn over coloured orbits.
VELOCITY_COLOUR = "black"
#: The paper's three engines, keyed by their specific impulse (150 N / 200 s, 300 N / 250 s,
#: 450 N / 300 s; in the trade study, every engine of that Isp), then the engines of
#: Sec. 3.1 and any other.
ISP_COLOURS = {200.0: "#0072b2", 250.0: "#e69f00", 300.0: "#009e73"}
ENGINE_COLOURS = {(150.0, 200.0): "#0072b2", (300.0, 250.0): "#e69f00",
                  (450.0, 300.0): "#009e73", (320.0, 200.0): "#cc79a7",
                  (500.0, 300.0): "#56b4e9"}
OTHER_COLOURS = ("#cc79a7", "#56b4e9", "#d55e00", "#f0e442", "#000000")
#: Whose number a mark is: ours, the paper's as printed, a rule or estimate of the paper.
OURS_COLOUR, PAPER_COLOUR, RULE_COLOUR = "#0072b2", "#d55e00", "#009e73"
#: Ours against our own impulsive limit (beside :data:`OURS_COLOUR`, against the paper's).
OURS_MODEL_COLOUR = "#56b4e9"
#: The thrust angles of Eq. (14) and the mass (Figs. 1 and 4).
ALPHA_COLOUR, BETA_COLOUR, MASS_COLOUR = "#7b3294", "#e66101", "0.2"
#: The RTN axes of Fig. 1.
RTN_COLOURS = {"r": "#d62728", "t": "#2ca02c", "n": "#1f77b4"}
#: The steering laws of the steering-law page.
LAW_COLOURS = {"optimal": "#0072b2", "inertial": "#009e73", "antivelocity": "#d55e00"}
#: The error sources of the dispersions page's sensitivities (one colour and marker each).
SOURCE_COLOURS = ("#0072b2", "#e69f00", "#009e73", "#d55e00", "#cc79a7", "#56b4e9",
                  "#000000", "#8c2d04", "#7f7f7f", "#bcbd22", "#9467bd", "#17becf")
SOURCE_MARKERS = ("o", "s", "^", "D", "v", "P", "X", "*", "<", ">", "h", "p")
#: The Moon's gravity models of the real-Moon page: the paper's J2 first, then a lunar
#: field cut to increasing degrees (2x2, 8x8, 20x20, 50x50, ...), each a different hue.
MODEL_COLOURS = ("#000000", "#e69f00", "#009e73", "#0072b2", "#d55e00", "#cc79a7")


def model_colour(k: int) -> str:
    """Colour of the k-th gravity model of a figure (0: J2, then the fields by degree)."""
    return MODEL_COLOURS[k % len(MODEL_COLOURS)]


def coast_colour(burn: int) -> str:
    """Colour of the orbit reached by burn ``burn`` (1-based)."""
    return ORBIT_COLOURS[(burn - 1) % len(ORBIT_COLOURS)]


def burn_colour(burn: int) -> str:
    """Colour of burn ``burn`` (1-based)."""
    return BURN_COLOURS[(burn - 1) % len(BURN_COLOURS)]


def colour_name(colour: str) -> str:
    """The word a caption uses for a palette colour (the colour itself if unnamed)."""
    return COLOUR_NAMES.get(colour, colour)


def isp_colour(isp_s: float, k: int = 0) -> str:
    """Colour of the engines of one specific impulse (the paper's engine of that Isp)."""
    return ISP_COLOURS.get(float(isp_s), OTHER_COLOURS[k % len(OTHER_COLOURS)])


def isp_colours(isp_s) -> dict:
    """``{Isp: colour}`` of the specific impulses of one figure (:func:`isp_colour`)."""
    return {float(isp): isp_colour(isp, k) for k, isp in enumerate(isp_s)}


def engine_colour(thrust_N: float, isp_s: float | None = None, k: int = 0) -> str:
    """Colour of an engine: the paper's three and the two of Sec. 3.1 fixed, others cycled.

    Without ``isp_s`` the thrust alone names the engine (the plans ``song2011-150N`` ...).

    >>> engine_colour(150, 200) == engine_colour(150) == isp_colour(200)
    True
    """
    if isp_s is None:
        match = [c for (t, _), c in ENGINE_COLOURS.items() if t == float(thrust_N)]
        return match[0] if match else OTHER_COLOURS[k % len(OTHER_COLOURS)]
    return ENGINE_COLOURS.get((float(thrust_N), float(isp_s)),
                              OTHER_COLOURS[k % len(OTHER_COLOURS)])


def label_colour(label: str, k: int = 0) -> str:
    """Colour of a series named by a plan or an engine ("song2011-150N", "150 N / 200 s").

    The paper's plans and engines get their engine's colour; any other series the k-th
    other colour.

    >>> label_colour("song2011-300N") == label_colour("300 N / 250 s") == isp_colour(250)
    True
    """
    import re

    m = re.search(r"(\d+(?:\.\d+)?)\s*N\b", str(label))
    if m and float(m.group(1)) in {t for t, _ in ENGINE_COLOURS}:
        return engine_colour(float(m.group(1)))
    return OTHER_COLOURS[k % len(OTHER_COLOURS)]


def draw_moon(ax, radius=1.0, label=True):
    """The Moon as a grey disc of ``radius`` (axis units), labelled unless ``label`` is False."""
    ax.add_patch(plt.Circle((0, 0), radius, color="0.85", zorder=0))
    if label:
        ax.text(0, 0, "Moon", ha="center", va="center", fontsize=9, color="0.3", zorder=1)
