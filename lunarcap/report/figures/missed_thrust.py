"""Figures of the missed thrust page: the delta-V penalty of a burn cut off or ignited late.

Drawn from data that :mod:`lunarcap.report.pages.missed_thrust` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np


def _luminance(rgba) -> float:
    """Relative luminance of a colour, 0 black to 1 white.

    The cell's text is white below 0.45, black above (Rec. 601 weights: 0.299 R +
    0.587 G + 0.114 B).
    """
    r, g, b = rgba[:3]
    return 0.299 * r + 0.587 * g + 0.114 * b


def plot_missed_penalty(cases):
    """Penalty map of a missed burn: fraction flown × delay, the penalty written in each cell.

    Parameters
    ----------
    cases : DataFrame, one row per case with ``fraction``, ``delay_min``, ``status``,
        ``penalty_mps`` and ``cutoff_orbit`` (cells without a recovery are grey, marked
        "none"; an "esc." under the number marks a cut-off on a hyperbola)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fr = sorted(set(cases.fraction.astype(float)))
    de = sorted(set(cases.delay_min.astype(float)))
    grid = np.full((len(fr), len(de)), np.nan)
    fig, ax = plt.subplots(figsize=(7.2, 0.8 + 0.75 * len(fr)), layout="constrained")
    for r in cases.itertuples():
        i, j = fr.index(float(r.fraction)), de.index(float(r.delay_min))
        if r.status == "recovered":
            grid[i, j] = max(float(r.penalty_mps), 0.0)
    vmax = max(np.nanmax(grid), 1.0) if np.isfinite(grid).any() else 1.0
    shown = np.ma.masked_invalid(np.log10(grid + 1.0))
    im = ax.imshow(shown, cmap="viridis_r", vmin=0, vmax=np.log10(vmax + 1.0), aspect="auto",
                   origin="lower")
    ax.set_facecolor("0.85")
    for r in cases.itertuples():
        i, j = fr.index(float(r.fraction)), de.index(float(r.delay_min))
        txt = (("0" if abs(r.penalty_mps) < 0.005 else  # no "-0.0" for a null penalty
                f"{r.penalty_mps:.2f}" if abs(r.penalty_mps) < 1 else f"{r.penalty_mps:.1f}")
               if r.status == "recovered" else "none")
        if r.cutoff_orbit == "escape":
            txt += "\nesc."
        dark = r.status == "recovered" and _luminance(im.cmap(im.norm(shown[i, j]))) < 0.45
        ax.text(j, i, txt, ha="center", va="center", fontsize=9, color="w" if dark else "k")
    ax.set_xticks(range(len(de)), [f"{d:g}" for d in de])
    ax.set_yticks(range(len(fr)), [f"{f:g}" for f in fr])
    ax.set_xlabel("delay before the recovery (min)")
    ax.set_ylabel("fraction of the burn flown")
    cb = fig.colorbar(im, ax=ax)
    ticks = [t for t in (0, 1, 10, 100, 1000) if t <= vmax]
    cb.set_ticks([np.log10(t + 1.0) for t in ticks], labels=[f"{t:g}" for t in ticks])
    cb.set_label("penalty (m/s)")
    return fig
