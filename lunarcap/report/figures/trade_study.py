"""Figures of the trade study page: the loss and the duration against thrust-to-weight.

Drawn from data that :mod:`lunarcap.report.pages.trade_study` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import FIG_WIDTH_IN, ISP_MARKERS, isp_colours


def _trade_axes(ax, newton_per_ratio: float):
    """Log thrust-to-weight axis with the thrust (N) on a secondary top axis."""
    ax.set_xscale("log")
    top = ax.secondary_xaxis("top", functions=(lambda r: np.asarray(r) * newton_per_ratio,
                                               lambda t: np.asarray(t) / newton_per_ratio))
    top.set_xlabel("thrust (N)")
    top.tick_params(labelsize=9)
    ax.grid(alpha=0.3, which="both")


def plot_trade_study_loss(ok, theory, paper, isp_s, part_titles: dict,
                          newton_per_ratio: float, ylim=(0.01, 40.0)):
    """Loss (% of the impulsive delta-V, log) against thrust-to-weight, one panel per part.

    Parameters
    ----------
    ok : DataFrame of the study's verified rows (``part``, ``isp_s``, ``thrust_to_weight``,
        ``objective_loss_percent``); rows with a loss <= 0 are not drawn (log axis)
    theory : DataFrame of Robbins' estimate on a dense grid (``analytic_loss_percent``), only where
    it
        is to be drawn
    paper : DataFrame of the paper's engines (``thrust_N``, ``isp_s``, ``thrust_to_weight``,
        ``part``, ``paper_delta_v_loss_percent``), drawn as stars in their Isp's colour and
        named in the legend (labels beside the stars collide: the 300 N and 450 N engines
        are half a decade of loss apart at most)
    isp_s : the specific impulses (s), one colour each
    part_titles : ``{part: panel title}``, in panel order (four panels, 2 x 2)
    newton_per_ratio : thrust (N) of a thrust-to-weight ratio of 1 (top axis)
    ylim : loss axis limits, %

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = isp_colours(isp_s)
    fig, axes = plt.subplots(2, 2, figsize=(FIG_WIDTH_IN, 8.2), layout="constrained",
                             sharex=True)
    for ax, part in zip(axes.flat, part_titles):
        for k, isp in enumerate(isp_s):
            d = ok[(ok.part == part) & (ok.isp_s == isp) & (ok.objective_loss_percent > 0)]
            d = d.sort_values("thrust_to_weight")
            ax.plot(d.thrust_to_weight, d.objective_loss_percent, "-", marker=ISP_MARKERS[k % 6],
                    ms=4,
                    lw=1.4, color=colours[float(isp)], label=f"optimal, Isp {isp:g} s")
            th = theory[(theory.part == part) & (theory.isp_s == isp)]
            ax.plot(th.thrust_to_weight, th.analytic_loss_percent, ls=(0, (5, 2)),
                    color=colours[float(isp)], lw=1.6, label=f"Robbins (1966), Isp {isp:g} s")
        for r in paper[paper.part == part].itertuples(index=False):
            ax.plot(r.thrust_to_weight, r.paper_delta_v_loss_percent, marker="*", ms=13, ls="none",
                    color=colours.get(float(r.isp_s), "black"), mec="black", mew=0.7)
        _trade_axes(ax, newton_per_ratio)
        ax.set_yscale("log")
        ax.set_ylim(*ylim)
        ax.set_title(part_titles[part], fontsize=10)
        ax.set_ylabel("loss (% of the impulsive ΔV)")
    for ax in axes[1]:
        ax.set_xlabel("thrust-to-weight ratio T / (m₀ g₀)")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    for (t, isp), _ in paper.groupby(["thrust_N", "isp_s"], sort=True):
        handles.append(plt.Line2D([], [], marker="*", ms=11, ls="none", mec="black",
                                  color=colours.get(float(isp), "black")))
        labels.append(f"paper, Table B1: {t:g} N / {isp:g} s")
    fig.legend(handles, labels, loc="outside lower center", ncol=2)
    return fig


def plot_trade_study_duration(ok, isp_s, part_titles: dict, newton_per_ratio: float):
    """Optimal burn duration and ignition offset, each over the Eq. (19) duration.

    Parameters
    ----------
    ok : DataFrame of the study's verified LOI rows (``part``, ``isp_s``,
        ``thrust_to_weight``, ``burn_duration_min``, ``start_min``, ``eq19_duration_min``)
    isp_s : the specific impulses (s), one colour each
    part_titles : ``{part: column title}`` of the burns (three columns)
    newton_per_ratio : thrust (N) of a thrust-to-weight ratio of 1 (top axis)

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = isp_colours(isp_s)
    parts = list(part_titles)
    fig, axes = plt.subplots(len(parts), 2, figsize=(FIG_WIDTH_IN, 2.6 * len(parts) + 0.8),
                             layout="constrained", sharex=True, squeeze=False)
    for i, part in enumerate(parts):
        for k, isp in enumerate(isp_s):
            d = ok[(ok.part == part) & (ok.isp_s == isp)].sort_values("thrust_to_weight")
            style = dict(marker=ISP_MARKERS[k % 6], ms=4, lw=1.4, color=colours[float(isp)],
                         label=f"Isp {isp:g} s")
            axes[i, 0].plot(d.thrust_to_weight, d.burn_duration_min / d.eq19_duration_min,
                            **style)
            axes[i, 1].plot(d.thrust_to_weight, d.start_min / d.eq19_duration_min, **style)
        axes[i, 0].axhline(1.0, color="0.4", ls="--", lw=1, label="Eq. (19)")
        axes[i, 1].axhline(-0.5, color="0.4", ls="--", lw=1, label="−½ Eq. (19) (the rule)")
        axes[i, 0].set_title(f"{part_titles[part]}: duration", fontsize=10)
        axes[i, 1].set_title(f"{part_titles[part]}: ignition", fontsize=10)
        axes[i, 0].set_ylabel("optimal / Eq. (19)")
        axes[i, 1].set_ylabel("offset / Eq. (19) duration")
        for ax in axes[i]:
            _trade_axes(ax, newton_per_ratio)
    for ax in axes[-1]:
        ax.set_xlabel("T / (m₀ g₀)")
    axes[0, 0].legend()
    axes[0, 1].legend()
    return fig
