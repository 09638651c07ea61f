"""Figures of the sweep page: the delta-V of an ignition sweep against the offset (Tables 1-5).

Drawn from data that :mod:`lunarcap.report.pages.sweep` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from lunarcap.report.figstyle import OURS_COLOUR, PAPER_COLOUR, RULE_COLOUR


def plot_sweep_dv(sweep, printed=None, printed_label: str = "paper"):
    """Delta-V (m/s) against ignition offset (min) of one ignition sweep.

    Parameters
    ----------
    sweep : DataFrame from :func:`lunarcap.studies.sweeps.sweep_table` (``start_min``,
        ``delta_v_mps``, ``best``, ``eq19_duration_min``; ``attrs["impulsive_delta_v_mps"]``)
    printed : DataFrame of the paper's rows (``start_min``, ``delta_v_mps``), optional
    printed_label : legend text of the paper's rows

    Returns
    -------
    matplotlib.figure.Figure
    """
    imp = sweep.attrs["impulsive_delta_v_mps"]
    eq19_min = float(sweep.eq19_duration_min.iloc[0])
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    order = sweep.sort_values("start_min")
    ax.plot(order.start_min, order.delta_v_mps, "o-", color=OURS_COLOUR, label="lunarcap")
    if printed is not None:
        ax.plot(printed.start_min, printed.delta_v_mps, "s", mfc="none", mec=PAPER_COLOUR, ms=8,
                label=printed_label)
    b = sweep[sweep.best].iloc[0]
    ax.plot(b.start_min, b.delta_v_mps, "*", color=OURS_COLOUR, ms=14, label="our best")
    ax.axhline(imp, color="0.4", ls=":", lw=1, label=f"impulsive, paper ({imp:.3f} m/s)")
    ax.axvline(-eq19_min / 2, color=RULE_COLOUR, ls="--", lw=1,
               label=f"−½ Eq. (19) duration ({-eq19_min / 2:.2f} min)")
    ax.set_xlabel("ignition, min from the nominal perilune")
    ax.set_ylabel("ΔV (m/s)")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, frameon=False)
    return fig
