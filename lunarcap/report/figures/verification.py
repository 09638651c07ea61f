"""Figures of the verification page: the objective's convergence with the mesh.

Drawn from data that :mod:`lunarcap.report.pages.verification` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from lunarcap.report.figstyle import burn_colour


def plot_mesh_convergence(mesh, tol_objective_mps: float, default_points: int):
    """Delta-V change from the finest mesh against the number of collocation points.

    Parameters
    ----------
    mesh : DataFrame with ``case``, ``collocation_points``, ``delta_v_change_vs_finest_mps``
        and ``accepted`` (bool: passed the gate), one row per case and mesh; the finest
        mesh of each case (change exactly 0) is the reference, marked at the foot of the
        log axis
    tol_objective_mps : the gate's tolerance on the objective (m/s), drawn dotted for scale
        (the delta-V itself is reported, not gated)
    default_points : collocation points of the default mesh, drawn dashed

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    finest = []
    for k, (case, g) in enumerate(mesh.groupby("case", sort=False)):
        finest.append((k, g.collocation_points.max()))
        g = g[g.delta_v_change_vs_finest_mps != 0]
        y = g.delta_v_change_vs_finest_mps.abs().clip(lower=1e-12)
        ok = g.accepted.astype(bool)
        ax.plot(g.collocation_points, y, "-", color=burn_colour(k + 1), lw=1)
        if ok.any():
            ax.plot(g.collocation_points[ok], y[ok], "o", color=burn_colour(k + 1),
                    label=f"{case}, accepted")
        if (~ok).any():
            ax.plot(g.collocation_points[~ok], y[~ok], "x", color=burn_colour(k + 1), ms=8,
                    label=f"{case}, rejected by the gate")
    ax.axhline(tol_objective_mps, color="0.4", ls=":", lw=1,
               label=f"{tol_objective_mps:g} m/s: the gate on the objective")
    ax.axvline(default_points, color="0.4", ls="--", lw=1, label="default mesh")
    ax.set_xscale("log")
    ax.set_yscale("log")
    y0 = ax.get_ylim()[0]
    for j, (k, n) in enumerate(finest):
        ax.plot([n], [y0], "v", color=burn_colour(k + 1), ms=8, clip_on=False,
                label="finest mesh (the reference, change 0)" if j == 0 else None)
    ax.set_ylim(bottom=y0)
    ax.set_xticks([20, 30, 50, 100, 200, 300], ["20", "30", "50", "100", "200", "300"])
    ax.set_xticks([], minor=True)
    ax.set_xlabel("collocation points")
    ax.set_ylabel("|ΔV − ΔV on the finest mesh| (m/s)")
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="outside lower center", ncols=2, frameon=False)
    return fig
