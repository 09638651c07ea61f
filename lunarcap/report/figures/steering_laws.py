"""Figures of the steering laws page: the delta-V penalty of the simple steering laws.

Drawn from data that :mod:`lunarcap.report.pages.steering_laws` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import FIG_WIDTH_IN, LAW_COLOURS, label_colour


def plot_steering_penalty(steer, engines: list, laws=("inertial", "antivelocity")):
    """Delta-V and J penalties of simple steering laws per LOI, one column per engine.

    Parameters
    ----------
    steer : DataFrame of :func:`lunarcap.studies.sweeps.steering_table` rows of every engine
        (``engine``, ``loi``, ``steering``, ``delta_v_penalty_mps``,
        ``objective_penalty_mps``, ``rp_miss_km``)
    engines : engine labels (the ``engine`` column), one column of panels each, in order
    laws : the laws drawn (bars side by side per LOI); an antivelocity bar whose perilune
        radius is missed is labelled with the miss (km)

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = LAW_COLOURS
    n = len(engines)
    fig, axes = plt.subplots(2, n, figsize=(FIG_WIDTH_IN, 6.0), sharex=True, squeeze=False,
                             layout="constrained")
    w = 0.72 / len(laws)
    for j, eng in enumerate(engines):
        sel = steer[steer.engine == eng]
        for k, law in enumerate(laws):
            s = sel[sel.steering == law].sort_values("loi")
            off = (k - (len(laws) - 1) / 2) * w
            c = colours.get(law, label_colour(law, k))
            axes[0][j].bar(s.loi + off, s.delta_v_penalty_mps, w, color=c, label=law)
            axes[1][j].bar(s.loi + off, s.objective_penalty_mps, w, color=c, label=law)
            if law == "antivelocity":
                for r in s.itertuples():
                    if r.rp_miss_km:
                        axes[1][j].annotate(f"rp {r.rp_miss_km:+.1f} km",
                                            (r.loi + off, r.objective_penalty_mps),
                                            xytext=(0, 2), textcoords="offset points",
                                            ha="center", va="bottom", fontsize=9,
                                            rotation=90)
        axes[0][j].set_title(eng, fontsize=10)
        for ax in axes[:, j]:
            ax.axhline(0, color="k", lw=0.6)
            ax.grid(axis="y", alpha=0.3)
            ax.margins(y=0.15)
        x = np.arange(1, 4)
        axes[1][j].set_xticks(x, [f"LOI {i}" for i in x])
    axes[0][0].set_ylabel("ΔV penalty (m/s)")
    axes[1][0].set_ylabel("J penalty (m/s)")
    axes[0][-1].legend()
    return fig
