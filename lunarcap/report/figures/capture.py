"""The drawing of Fig. 2, the whole capture in its orbit plane: shared by two pages.

The capture sequence (:mod:`lunarcap.report.pages.capture_sequence`) and every capture
plan (:mod:`lunarcap.report.pages.capture_plan`) draw it from
:func:`lunarcap.report.figdata.capture_geometry`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import HYPERBOLA_COLOUR, burn_colour, coast_colour, draw_moon

if TYPE_CHECKING:  # data types, for annotations only
    from lunarcap.report.figdata import CaptureGeometry

#: Axis labels of the orbit-plane views (Figs. 2, 3 and 5).
PLANE_XLABEL = "x′: M-MME2000 equator, along the orbit's ascending node (LU)"
PLANE_YLABEL = "z: M-MME2000 pole (LU)"


def plot_fig2_capture(geo: CaptureGeometry, figsize=None):
    """Draw Fig. 2: the whole capture sequence in the orbit plane, in LU.

    Parameters
    ----------
    geo : CaptureGeometry from :func:`capture_geometry`
    figsize : (width, height), inches (default: 7 in wide, height from the extent)

    Returns
    -------
    matplotlib.figure.Figure
    """
    flown = np.concatenate([a.xy_LU for a in geo.arcs if a.kind != "uncaptured"], axis=1)
    lo, hi = flown.min(axis=1) - 0.35, flown.max(axis=1) + 0.35
    if figsize is None:
        w = 7.0
        figsize = (w, float(np.clip((w - 0.9) * (hi[1] - lo[1]) / (hi[0] - lo[0]) + 0.8,
                                    4.0, 9.0)))
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    draw_moon(ax)
    hyp = HYPERBOLA_COLOUR
    for a in geo.select("uncaptured"):
        ax.plot(*a.xy_LU, color=hyp, lw=0.9, ls=":", label=a.label)
    for a in geo.select("hyperbola"):
        ax.plot(*a.xy_LU, color=hyp, lw=1.4, label=a.label)
        k = a.xy_LU.shape[1] // 3
        ax.annotate("", xy=a.xy_LU[:, k + 5], xytext=a.xy_LU[:, k],
                    arrowprops=dict(arrowstyle="-|>", color=hyp, lw=1.4, mutation_scale=14))
    for a in geo.select("coast"):
        ax.plot(*a.xy_LU, color=coast_colour(a.burn), lw=1.2, label=a.label)
    for a in geo.select("final"):
        ax.plot(*a.xy_LU, color=coast_colour(a.burn), lw=1.2)
    burns = geo.select("burn")
    for i, a in enumerate(burns):
        ax.plot(*a.xy_LU, color=burn_colour(1), lw=3.2, solid_capstyle="butt",
                label=f"finite burn arcs (burns 1 to {len(burns)})" if i == 0 else None,
                zorder=4)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel(PLANE_XLABEL)
    ax.set_ylabel(PLANE_YLABEL)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", framealpha=0.9)
    return fig
