"""Drawing of the book's figures: each function draws data computed elsewhere.

A figure one page draws is drawn in the module named after that page
(``figures/<page>.py``, beside ``pages/<page>.py``, which computes its data); what
several pages draw or share is here: the style (:mod:`lunarcap.report.figstyle`) and
Fig. 2, the capture in its orbit plane (:mod:`.capture`). Nothing in this package
computes a trajectory or solves anything (an import-linter contract: it imports neither
the propagator nor the optimiser, the studies or :mod:`lunarcap.report.figdata`), so the
data behind every figure is computed, and tested, apart from its drawing.
"""

from lunarcap.report.figstyle import (
    FIG_WIDTH_IN,
    HYPERBOLA_COLOUR,
    ISP_MARKERS,
    MIN_FONT_PT,
    burn_colour,
    coast_colour,
    draw_moon,
    legibility_problems,
    save_figure,
)
from lunarcap.report.figures.capture import plot_fig2_capture

__all__ = [
    "FIG_WIDTH_IN", "HYPERBOLA_COLOUR", "ISP_MARKERS", "MIN_FONT_PT", "burn_colour",
    "coast_colour", "draw_moon", "legibility_problems", "save_figure", "plot_fig2_capture",
]
