"""Figures of the dispersions page: the budget's CDF, its convergence, the sensitivities.

Drawn from data that :mod:`lunarcap.report.pages.dispersions` computes (the samples of
:mod:`lunarcap.studies.dispersions`); nothing here computes a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import FIG_WIDTH_IN, SOURCE_COLOURS, SOURCE_MARKERS, label_colour


def plot_cdf(tables: dict):
    """Empirical CDF of the delta-V above the nominal, one step curve per engine.

    ``tables``: engine label -> its samples. A failed sample counts as above every
    captured one (the curve stops below 1).
    """
    fig, ax = plt.subplots(figsize=(FIG_WIDTH_IN, 4.0), layout="constrained")
    for k, (label, t) in enumerate(tables.items()):
        nom = float(t.nominal_delta_v_mps.iloc[0])
        v = np.sort(t.loc[t.status == "ok", "total_delta_v_mps"].astype(float) - nom)
        n = len(t)
        if v.size:
            ax.step(np.concatenate([[v[0]], v]), np.arange(0, v.size + 1) / n, where="post",
                    label=f"{label} ({n} samples)", color=label_colour(label, k))
    ax.axhline(0.99, color="0.5", lw=0.8, ls=":")
    ax.axvline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel("ΔV above the nominal (m/s)")
    ax.set_ylabel("fraction of samples")
    ax.set_ylim(0, 1.02)
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    return fig


def plot_convergence(curves: dict):
    """The 99 % estimate above the nominal and its 95 % interval against the samples.

    ``curves``: engine label -> its estimates (columns ``samples``, ``estimate_mps``,
    ``ci_lo_mps``, ``ci_hi_mps``), from the first N whose samples bound the interval.
    """
    fig, ax = plt.subplots(figsize=(FIG_WIDTH_IN, 4.0), layout="constrained")
    for k, (label, c) in enumerate(curves.items()):
        color = label_colour(label, k)
        ax.plot(c.samples, c.estimate_mps, color=color, label=label, drawstyle="steps-post")
        ax.fill_between(c.samples, c.ci_lo_mps, c.ci_hi_mps.replace(np.inf, np.nan),
                        color=color, alpha=0.15, step="post")
    ax.set_xlabel("samples N")
    ax.set_ylabel("99 % ΔV above the nominal (m/s)")
    ax.legend()
    ax.grid(alpha=0.3)
    return fig


def plot_sensitivity(rows: list, engine: str, source_labels: dict):
    """One engine's mean ΔV above the nominal against each source's sigma (log-log).

    The x axis is the sigma over the page's example sigma (each source's own unit in the
    legend, named by ``source_labels``); the mean over the samples (captured ones) with its
    standard error, and the costliest sample dashed.
    """
    fig, ax = plt.subplots(figsize=(FIG_WIDTH_IN, 4.6), layout="constrained")
    mine = [r for r in rows if r["engine"] == engine]
    for k, source in enumerate(dict.fromkeys(r["source"] for r in mine)):
        pts = sorted((r for r in mine if r["source"] == source), key=lambda r: r["sigma"])
        x = [r["factor"] for r in pts]
        y = np.array([r["mean_above_nominal_mps"] for r in pts])
        se = np.array([r["mean_above_nominal_se_mps"] for r in pts])
        color = SOURCE_COLOURS[k % len(SOURCE_COLOURS)]
        ax.errorbar(x, np.clip(y, 1e-6, None), yerr=se, color=color,
                    marker=SOURCE_MARKERS[k % len(SOURCE_MARKERS)], ms=4,
                    capsize=2, label=f"{source_labels[source]} ({pts[-1]['example']:g} "
                                     f"{pts[-1]['unit']} = 1)")
        ax.plot(x, np.clip([r["max_above_nominal_mps"] for r in pts], 1e-6, None),
                color=color, ls="--", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("sigma / the page's example sigma")
    ax.set_ylabel("ΔV above the nominal (m/s)")
    ax.set_title(f"{engine}: mean (markers) and costliest sample (dashed)")
    ax.legend(ncol=2)
    ax.grid(alpha=0.3, which="both")
    return fig
