"""Figures of the burn count page: the loss against the number of capture burns.

Drawn from data that :mod:`lunarcap.report.pages.burn_count` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from lunarcap.report.figstyle import FIG_WIDTH_IN, ISP_MARKERS, label_colour

#: How a count without a capture is marked, by its status: an infeasible count has no
#: plan (physics), a failed one no verified solution (the solver).
NO_CAPTURE_MARKERS = {"infeasible": "x", "failed": "$!$"}
#: How the strip's title writes each mark.
NO_CAPTURE_SYMBOLS = {"infeasible": "×", "failed": "!"}


def plot_burn_count(counts):
    """Total loss and time to the final orbit against the number of burns, one line per plan.

    A count without a capture has no loss and no time: it is not a point of the curves (a
    point at 0 would read as a free capture, one anywhere else as a value). Such counts
    are marked in a strip above the curves, one row per plan that has one, in the plan's
    colour: a cross where the count is infeasible (no plan with that count), "!" where the
    solver failed.

    Parameters
    ----------
    counts : DataFrame, one row per (plan, count) with ``label``, ``n_burns``, ``status``,
        ``total_delta_v_loss_mps`` and ``time_to_final_orbit_h`` (rows not "ok" are
        drawn in the strip)

    Returns
    -------
    matplotlib.figure.Figure
    """
    groups = list(counts.groupby("label", sort=False))
    colour = {label: label_colour(label, j) for j, (label, _) in enumerate(groups)}
    bad = counts[counts.status != "ok"]
    rows = list(dict.fromkeys(bad.label))          # plans with a count without a capture
    panels = ([0.35 + 0.3 * len(rows)] if rows else []) + [3.0, 3.0]
    fig, axes = plt.subplots(len(panels), 1, figsize=(FIG_WIDTH_IN, sum(panels) + 1.6),
                             sharex=True, layout="constrained", height_ratios=panels)
    ax, bx = axes[-2], axes[-1]
    for j, (label, g) in enumerate(groups):
        ok = g[g.status == "ok"].sort_values("n_burns")
        c, m = colour[label], ISP_MARKERS[j % len(ISP_MARKERS)]
        ax.plot(ok.n_burns, ok.total_delta_v_loss_mps, "-", marker=m, color=c, label=label)
        bx.plot(ok.n_burns, ok.time_to_final_orbit_h, "-", marker=m, color=c, label=label)
    if rows:
        _no_capture_strip(axes[0], bad, rows, colour)
    ax.set_ylabel("total loss vs impulsive limit (m/s)")
    bx.set_ylabel("arrival perilune → end of last burn (h)")
    bx.set_xlabel("number of burns")
    for a in axes:
        a.grid(alpha=0.3)
        a.set_xticks(sorted(set(counts.n_burns.astype(int))))
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=1)
    return fig


def _no_capture_strip(sx, bad, rows: list, colour: dict) -> None:
    """The counts without a capture: one row per plan, a mark per count, no value axis."""
    for i, label in enumerate(rows):
        for r in bad[bad.label == label].itertuples():
            sx.plot(int(r.n_burns), i, ls="none", color=colour[label], ms=10, mew=2,
                    marker=NO_CAPTURE_MARKERS.get(r.status, "x"))
    sx.set_yticks(range(len(rows)), [label.split(" (")[0] for label in rows])
    sx.set_ylim(len(rows) - 0.5, -0.5)
    said = [f"{m}: {s}" for s, m in NO_CAPTURE_SYMBOLS.items() if (bad.status == s).any()]
    sx.set_title("counts with no capture (" + "; ".join(said) + ")", fontsize=10)
