"""Figures of the summary page: the finite-burn loss of each burn and engine.

Drawn from data that :mod:`lunarcap.report.pages.summary` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import FIG_WIDTH_IN, OURS_COLOUR, OURS_MODEL_COLOUR, PAPER_COLOUR


def plot_summary_loss(chains: dict):
    """Delta-V loss per LOI of each engine's best chain: the paper's and ours, two ways.

    Parameters
    ----------
    chains : {engine label: DataFrame} from :func:`lunarcap.studies.sweeps.sequence_table`
        (``loi``, ``paper_delta_v_mps``, ``paper_impulsive_delta_v_mps``,
        ``loss_vs_paper_impulse_mps``,
        ``delta_v_loss_mps``), one bar group per LOI, one panel per engine.

    Returns
    -------
    matplotlib.figure.Figure
    """
    n = len(chains)
    fig, axes = plt.subplots(1, n, figsize=(FIG_WIDTH_IN, 4.0), sharey=True,
                             layout="constrained", squeeze=False)
    w = 0.27
    for ax, (name, s) in zip(axes[0], chains.items()):
        x = np.arange(len(s))
        ax.bar(x - w, s.paper_delta_v_mps - s.paper_impulsive_delta_v_mps, w, color=PAPER_COLOUR,
               label="paper (Table B1)")
        ax.bar(x, s.loss_vs_paper_impulse_mps, w, color=OURS_COLOUR,
               label="ours vs the paper's impulsive ΔV")
        ax.bar(x + w, s.delta_v_loss_mps, w, color=OURS_MODEL_COLOUR,
               label="ours vs our impulsive ΔV")
        ax.set_xticks(x, [f"LOI {k}" for k in s.loi])
        ax.set_title(name, fontsize=10)
        ax.grid(axis="y", alpha=0.3)
    axes[0][0].set_ylabel("ΔV loss (m/s)")
    fig.legend(*axes[0][0].get_legend_handles_labels(), loc="outside lower center",
               ncols=1, frameon=False)
    return fig
