"""Figures of the burn count page: the loss against the number of capture burns.

Drawn from data that :mod:`lunarcap.report.pages.burn_count` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
from matplotlib.transforms import blended_transform_factory

from lunarcap.report.figstyle import FIG_WIDTH_IN, ISP_MARKERS, label_colour

#: How a count without a capture is marked, by its status: an infeasible count has no
#: plan (physics), a failed one no verified solution (the solver).
NO_CAPTURE_MARKERS = {"infeasible": "x", "failed": "$!$"}
#: What the legend says each mark means.
NO_CAPTURE_LABELS = {"infeasible": "no capture with that N: infeasible (no such plan)",
                     "failed": "no capture with that N: the solver failed"}
#: Half the width of the band that marks a count some plan cannot fly, in counts.
BAND_HALF_WIDTH = 0.3


def plot_burn_count(counts):
    """Total loss and time to the final orbit against the number of burns, one line per plan.

    A count without a capture has no loss and no time to draw: it is not a point on the
    curves (a point at 0 would read as a free capture). Such a count is a hatched band
    across both panels, holding, at the top, one mark per plan it fails for in the plan's
    colour: a cross where it is infeasible (no plan with that count), a diamond where the
    solver failed.

    Parameters
    ----------
    counts : DataFrame, one row per (plan, count) with ``label``, ``n_burns``, ``status``,
        ``total_delta_v_loss_mps`` and ``time_to_final_orbit_h`` (rows not "ok" are
        drawn as described above)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 7.2), sharex=True,
                                 layout="constrained")
    groups = list(counts.groupby("label", sort=False))
    for j, (label, g) in enumerate(groups):
        ok = g[g.status == "ok"].sort_values("n_burns")
        c, m = label_colour(label, j), ISP_MARKERS[j % len(ISP_MARKERS)]
        ax.plot(ok.n_burns, ok.total_delta_v_loss_mps, "-", marker=m, color=c, label=label)
        bx.plot(ok.n_burns, ok.time_to_final_orbit_h, "-", marker=m, color=c, label=label)
    bad = counts[counts.status != "ok"]
    for n in sorted(set(bad.n_burns.astype(int))):
        for a in (ax, bx):
            a.axvspan(n - BAND_HALF_WIDTH, n + BAND_HALF_WIDTH, facecolor="0.94",
                      edgecolor="0.75", hatch="//", lw=0.5, zorder=0)
        trans = blended_transform_factory(ax.transData, ax.transAxes)
        for j, (label, g) in enumerate(groups):
            row = g[(g.n_burns.astype(int) == n) & (g.status != "ok")]
            if len(row):
                ax.plot(n, 0.93 - 0.08 * j, ls="none",
                        marker=NO_CAPTURE_MARKERS.get(row.status.iloc[0], "x"),
                        color=label_colour(label, j), ms=9, mew=2, transform=trans,
                        clip_on=False)
    ax.set_ylabel("total loss vs impulsive limit (m/s)")
    bx.set_ylabel("arrival perilune → end of last burn (h)")
    bx.set_xlabel("number of burns")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.set_xticks(sorted(set(counts.n_burns.astype(int))))
    for status, marker in NO_CAPTURE_MARKERS.items():
        if (bad.status == status).any():
            ax.plot([], [], ls="none", marker=marker, color="0.4", mew=2, ms=9,
                    label=NO_CAPTURE_LABELS[status] + " (hatched; colour: its plan)")
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=1)
    return fig
