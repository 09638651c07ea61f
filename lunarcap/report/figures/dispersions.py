"""Figures of the dispersions page: the budget's CDF, the trim, its convergence, sensitivities.

Drawn from data that :mod:`lunarcap.report.pages.dispersions` computes (the samples of
:mod:`lunarcap.studies.dispersions`); nothing here computes a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

from lunarcap.report.figstyle import FIG_WIDTH_IN, SOURCE_COLOURS, SOURCE_MARKERS, label_colour

#: The re-propagation gate's resolution of a delta-V, m/s (a mean below it is unresolved).
RESOLUTION_MPS = 0.01


def _steps(ax, values, n: int, **kw) -> None:
    """An empirical CDF of ``values`` over ``n`` samples (the failures above every value)."""
    v = np.sort(np.asarray(values, float))
    if v.size:
        ax.step(np.concatenate([[v[0]], v]), np.arange(0, v.size + 1) / n, where="post", **kw)


def plot_cdf(tables: dict):
    """Empirical CDF of the delta-V above the nominal, one curve per engine.

    ``tables``: engine label -> its samples. Solid: the burns and the trim (the budget);
    dashed, where the table has it: the burns alone. A failed sample counts as above every
    captured one (the curve stops below 1).
    """
    fig, ax = plt.subplots(figsize=(FIG_WIDTH_IN, 4.0), layout="constrained")
    for k, (label, t) in enumerate(tables.items()):
        nom = float(t.nominal_delta_v_mps.iloc[0])
        ok = t[t.status == "ok"]
        colour = label_colour(label, k)
        _steps(ax, ok.total_delta_v_mps.astype(float) - nom, len(t), color=colour,
               label=f"{label} ({len(t)} samples)")
        if "burns_delta_v_mps" in ok:
            _steps(ax, ok.burns_delta_v_mps.astype(float) - nom, len(t), color=colour,
                   ls="--", lw=0.9)
    ax.plot([], [], color="0.3", label="burns and trim")
    ax.plot([], [], color="0.3", ls="--", lw=0.9, label="burns alone")
    ax.axhline(0.99, color="0.5", lw=0.8, ls=":")
    ax.axvline(0.0, color="0.5", lw=0.8)
    ax.set_xlabel("ΔV above the nominal (m/s)")
    ax.set_ylabel("fraction of samples")
    ax.set_ylim(0, 1.02)
    ax.legend(loc="lower right")
    ax.grid(alpha=0.3)
    return fig


def plot_trim(tables: dict):
    """The final orbit before the trim (perilune against apolune error) and the trim's CDF.

    ``tables``: engine label -> its samples (those with a trim column); the captured and
    corrected ones are drawn.
    """
    fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(FIG_WIDTH_IN, 3.6), layout="constrained")
    for k, (label, t) in enumerate(tables.items()):
        ok = t[t.status == "ok"]
        colour = label_colour(label, k)
        ax0.plot(ok.final_rp_error_km.astype(float), ok.final_ra_error_km.astype(float),
                 ".", color=colour, ms=4, alpha=0.7)
        _steps(ax1, ok.trim_delta_v_mps.astype(float), len(ok), color=colour, label=label)
    ax0.axhline(0.0, color="0.5", lw=0.8)
    ax0.axvline(0.0, color="0.5", lw=0.8)
    ax0.set_xlabel("perilune error before the trim (km)")
    ax0.set_ylabel("apolune error (km)")
    ax0.grid(alpha=0.3)
    ax1.axhline(0.99, color="0.5", lw=0.8, ls=":")
    ax1.set_xlabel("trim ΔV (m/s)")
    ax1.set_ylabel("fraction of samples")
    ax1.set_ylim(0, 1.02)
    ax1.legend(loc="lower right")
    ax1.grid(alpha=0.3)
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


def _plain(v, _pos=None) -> str:
    """A tick as a plain number (0.01, 0.5, 2, 10), never a power of ten."""
    return f"{v:g}"


def plot_sensitivity(rows: list, engine: str, source_labels: dict):
    """One engine's mean ΔV above the nominal against each source's sigma (log-log).

    The x axis is the sigma over the page's example sigma (each source's own unit in the
    legend, named by ``source_labels``). Markers: the mean over the draws (captured
    samples); bars: one standard error of ln(mean) (se / mean), drawn multiplicatively so
    that they stay on the log axis; a mean below the gate's resolution (0.01 m/s, dotted)
    is unresolved and not drawn. Dashed: the costliest sample. The legend sits below the
    axes, clear of the curves; ticks read as plain numbers.
    """
    fig, ax = plt.subplots(figsize=(FIG_WIDTH_IN, 5.4), layout="constrained")
    mine = [r for r in rows if r["engine"] == engine]
    tops = [RESOLUTION_MPS]
    for k, source in enumerate(dict.fromkeys(r["source"] for r in mine)):
        pts = sorted((r for r in mine if r["source"] == source), key=lambda r: r["sigma"])
        colour = SOURCE_COLOURS[k % len(SOURCE_COLOURS)]
        marker = SOURCE_MARKERS[k % len(SOURCE_MARKERS)]
        x = np.array([r["factor"] for r in pts])
        y = np.array([r["mean_above_nominal_mps"] for r in pts])
        se = np.nan_to_num(np.array([r["mean_above_nominal_se_mps"] for r in pts]))
        top = np.array([r["max_above_nominal_mps"] for r in pts])
        seen = y >= RESOLUTION_MPS
        label = f"{source_labels[source]} ({pts[-1]['example']:g} {pts[-1]['unit']} = 1)"
        if seen.any():
            f = np.exp(se[seen] / y[seen])
            ax.errorbar(x[seen], y[seen], yerr=[y[seen] - y[seen] / f, y[seen] * f - y[seen]],
                        color=colour, marker=marker, ms=5, capsize=2, label=label)
            tops += list(y[seen] * f)
        else:
            ax.plot([], [], color=colour, marker=marker, ls="", label=label + ": unresolved")
        shown = np.isfinite(top) & (top >= RESOLUTION_MPS)
        if shown.any():
            ax.plot(x[shown], top[shown], color=colour, ls="--", lw=0.8)
            tops += list(top[shown])
    ax.axhline(RESOLUTION_MPS, color="0.5", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_ylim(RESOLUTION_MPS / 2, 2 * max(tops))
    factors = sorted({r["factor"] for r in mine})
    ax.set_xticks(factors)
    ax.xaxis.set_major_formatter(FuncFormatter(_plain))
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(FuncFormatter(_plain))
    ax.yaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("sigma / the page's example sigma")
    ax.set_ylabel("ΔV above the nominal (m/s)")
    ax.set_title(f"{engine}: mean (markers) and costliest sample (dashed)")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, frameon=False)
    ax.grid(alpha=0.3, which="both")
    return fig
