"""Figures of the other engines page: the loss and propellant of the other engines.

Drawn from data that :mod:`lunarcap.report.pages.other_engines` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from lunarcap.report.figstyle import FIG_WIDTH_IN, isp_colour, isp_colours


def plot_engine_loss(totals, loss_column: str, loss_label: str):
    """Total loss and propellant of the capture against thrust, one marker per engine.

    Parameters
    ----------
    totals : DataFrame, one row per engine (``thrust_N``, ``isp_s``, ``origin``: a name for
        an engine cited by the paper, "paper's engine" for the paper's own,
        ``total_fuel_kg`` and ``loss_column``)
    loss_column : column of the loss drawn (m/s)
    loss_label : y-axis label of the loss, naming its impulsive reference

    Returns
    -------
    matplotlib.figure.Figure
    """
    by_isp = isp_colours((200.0, 250.0, 300.0))
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.6), sharex=True,
                                 layout="constrained")
    for r in totals.sort_values("thrust_N").itertuples():
        c = by_isp.get(float(r.isp_s), isp_colour(r.isp_s, 4))
        cited = r.origin != "paper's engine"
        for a, y in ((ax, getattr(r, loss_column)), (bx, r.total_fuel_kg)):
            a.plot(r.thrust_N, y, "D" if cited else "o", color=c, ms=8,
                   mfc=c if cited else "white", mew=2)
            a.annotate(r.origin if cited else f"{r.thrust_N:g} N", (r.thrust_N, y),
                       xytext=(6, 4), textcoords="offset points", fontsize=9)
    for isp, c in by_isp.items():
        if isp in set(totals.isp_s.astype(float)):
            ax.plot([], [], "s", color=c, label=f"Isp {isp:g} s")
    ax.plot([], [], "o", color="0.4", mfc="white", mew=2, label="paper's engines")
    ax.plot([], [], "D", color="0.4", label="cited in Sec. 3.1")
    ax.set_ylabel(loss_label)
    ax.legend()
    bx.set_xlabel("thrust (N)")
    bx.set_ylabel("propellant, LOI 1–3 (kg)")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.margins(x=0.2, y=0.12)
    return fig
