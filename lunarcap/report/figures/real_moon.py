"""Figures of the real moon page: the orbit's evolution in the lunar gravity field.

Drawn from data that :mod:`lunarcap.report.pages.real_moon` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from lunarcap.report.figstyle import FIG_WIDTH_IN, ISP_MARKERS, model_colour


def plot_evolution(histories: dict):
    """The final orbit's revolutions over days, one colour per gravity model.

    Parameters
    ----------
    histories : {label: {"days", "perilune_km", "apolune_km", "inc_deg"}} in drawing order
        (the paper's J2 first), one entry per revolution: the revolution's place in days
        since the last cut-off, its lowest and highest altitude (km) and its mean
        inclination (deg)

    Returns
    -------
    matplotlib.figure.Figure
        Above: perilune (solid) and apolune (dashed) altitudes; below: the inclination;
        the models' colours and the two line styles in one legend below the axes. Each
        model has its hue and a marker every eighth of its revolutions, so neighbouring
        degrees (8x8, 20x20) are told apart in print as on screen.
    """
    from matplotlib.lines import Line2D

    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.4), sharex=True,
                                 layout="constrained", height_ratios=(3, 2))
    handles = []
    for k, (label, h) in enumerate(histories.items()):
        c = model_colour(k)
        mark = dict(marker=ISP_MARKERS[k % len(ISP_MARKERS)], ms=5,
                    markevery=max(1, len(h["days"]) // 8))
        ax.plot(h["days"], h["apolune_km"], "--", color=c, lw=1.2)
        handles += ax.plot(h["days"], h["perilune_km"], "-", color=c, lw=1.6, label=label,
                           **mark)
        bx.plot(h["days"], h["inc_deg"], "-", color=c, lw=1.6, **mark)
    handles += [Line2D([], [], color="0.3", ls="-", lw=1.6, label="perilune"),
                Line2D([], [], color="0.3", ls="--", lw=1.2, label="apolune")]
    ax.set_ylabel("altitude (km)")
    bx.set_ylabel("mean inclination (deg)")
    bx.set_xlabel("time after the last cut-off (days)")
    for a in (ax, bx):
        a.grid(alpha=0.3)
    fig.legend(handles=handles, loc="outside lower center", ncols=3, frameon=False)
    return fig
