"""Figures of the free ignition page: the Eq. (19) ignition rule against the free optimum.

Drawn from data that :mod:`lunarcap.report.pages.free_ignition` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import FIG_WIDTH_IN, label_colour


def plot_free_ignition_rule(rule):
    """Optimal ignition against the Eq. (19)/2 rule (top) and the residual (bottom).

    Parameters
    ----------
    rule : DataFrame from :func:`lunarcap.report.pages.free_ignition.rule_table`
        (``engine``, ``burn``, ``rule_start_min``, ``free_start_min``, ``grid_start_min``,
        ``eq19_duration_min``, ``start_minus_rule_min``; min).

    Returns
    -------
    matplotlib.figure.Figure
    """
    marks = {1: "o", 2: "s", 3: "^"}
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 7.6), layout="constrained")
    for k, engine in enumerate(dict.fromkeys(rule.engine)):
        c = label_colour(engine, k)
        for r in rule[rule.engine == engine].itertuples():
            m = marks.get(int(r.burn), "D")
            ax.plot(r.rule_start_min, r.free_start_min, m, color=c, ms=7)
            if np.isfinite(r.grid_start_min):
                ax.plot(r.rule_start_min, r.grid_start_min, m, color=c, ms=9,
                        mfc="none", alpha=0.7)
            bx.plot(r.eq19_duration_min, r.start_minus_rule_min, m, color=c, ms=7)
        ax.plot([], [], "-", color=c, lw=6, label=engine)
    lo = np.nanmin([rule.rule_start_min.min(), rule.free_start_min.min(),
                    rule.grid_start_min.min()]) - 0.7
    ax.plot([lo, 0], [lo, 0], "k--", lw=0.8, label="optimal = −Eq. (19)/2")
    for n in sorted(set(int(b) for b in rule.burn)):
        ax.plot([], [], marks.get(n, "D"), color="0.4", label=f"burn {n}")
    ax.plot([], [], "o", color="0.4", mfc="none", label="best grid point")
    ax.set_xlabel("rule start, −Eq. (19) duration / 2 (min)")
    ax.set_ylabel("ignition (min from the nominal perilune)")
    ax.set_title("filled: free optimum; open: paper's best grid point", fontsize=9)
    ax.legend(loc="upper left")
    ax.grid(alpha=0.3)
    bx.axhline(0, color="k", lw=0.8)
    bx.set_xlabel("Eq. (19) duration (min)")
    bx.set_ylabel("optimal start − rule start (min)")
    bx.set_title("negative: the optimum ignites earlier than the rule", fontsize=9)
    bx.grid(alpha=0.3)
    return fig
