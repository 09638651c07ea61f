"""Figures of the burn count page: the loss against the number of capture burns.

Drawn from data that :mod:`lunarcap.report.pages.burn_count` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import FIG_WIDTH_IN, ISP_MARKERS, label_colour


def plot_burn_count(counts):
    """Total loss and time to the final orbit against the number of burns, one line per plan.

    Parameters
    ----------
    counts : DataFrame, one row per (plan, count) with ``label``, ``n_burns``, ``status``,
        ``total_delta_v_loss_mps`` and ``time_to_final_orbit_h`` (rows not "ok" are drawn as an
        open marker on the axis: no capture with that count)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.4), sharex=True,
                                 layout="constrained")
    for j, (label, g) in enumerate(counts.groupby("label", sort=False)):
        g = g.sort_values("n_burns")
        ok = g[g.status == "ok"]
        c = label_colour(label, j)
        m = ISP_MARKERS[j % len(ISP_MARKERS)]
        ax.plot(ok.n_burns, ok.total_delta_v_loss_mps, "-", marker=m, color=c, label=label)
        bx.plot(ok.n_burns, ok.time_to_final_orbit_h, "-", marker=m, color=c, label=label)
        bad = g[g.status != "ok"]
        for a in (ax, bx):
            a.plot(bad.n_burns, np.zeros(len(bad)), "x", color=c, ms=9, mew=2)
    ax.set_ylabel("total loss vs impulsive limit (m/s)")
    bx.set_ylabel("arrival perilune → end of last burn (h)")
    bx.set_xlabel("number of burns")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.set_xticks(sorted(set(counts.n_burns.astype(int))))
    ax.plot([], [], "x", color="0.4", mew=2, label="no plan (infeasible or failed)")
    ax.legend()
    return fig
