"""Drawing of the figures of the studies beyond the paper's Figs. 1-5.

Sweeps, trade study, summary, verification meshes, free ignition, steering laws, other
engines, burn count, missed thrust and the exported trajectory; each draws data computed
elsewhere (nothing here computes a trajectory: an import-linter contract checks it through
:mod:`.figures`, which re-exports these).
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import (
    FIG_WIDTH_IN,
    HYPERBOLA_COLOUR,
    ISP_MARKERS,
    LAW_COLOURS,
    OURS_COLOUR,
    OURS_MODEL_COLOUR,
    PAPER_COLOUR,
    RULE_COLOUR,
    burn_colour,
    coast_colour,
    draw_moon,
    isp_colour,
    label_colour,
    model_colour,
)


# =============================================================================== Tables 1-5
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


# =============================================================================== trade study
def _trade_axes(ax, newton_per_ratio: float):
    """Log thrust-to-weight axis with the thrust (N) on a secondary top axis."""
    ax.set_xscale("log")
    top = ax.secondary_xaxis("top", functions=(lambda r: np.asarray(r) * newton_per_ratio,
                                               lambda t: np.asarray(t) / newton_per_ratio))
    top.set_xlabel("thrust (N)")
    top.tick_params(labelsize=9)
    ax.grid(alpha=0.3, which="both")


def _isp_colours(isp_s) -> dict:
    return {float(isp): isp_colour(isp, k) for k, isp in enumerate(isp_s)}


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
        ``part``, ``paper_delta_v_loss_percent``), drawn as stars
    isp_s : the specific impulses (s), one colour each
    part_titles : ``{part: panel title}``, in panel order (four panels, 2 x 2)
    newton_per_ratio : thrust (N) of a thrust-to-weight ratio of 1 (top axis)
    ylim : loss axis limits, %

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = _isp_colours(isp_s)
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
            ax.annotate(f"{r.thrust_N:g} N / {r.isp_s:g} s",
                        (r.thrust_to_weight, r.paper_delta_v_loss_percent), xytext=(6, 3),
                        textcoords="offset points", fontsize=9)
        _trade_axes(ax, newton_per_ratio)
        ax.set_yscale("log")
        ax.set_ylim(*ylim)
        ax.set_title(part_titles[part], fontsize=10)
        ax.set_ylabel("loss (% of the impulsive ΔV)")
    for ax in axes[1]:
        ax.set_xlabel("thrust-to-weight ratio T / (m₀ g₀)")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    handles.append(plt.Line2D([], [], marker="*", ms=11, ls="none", color="0.6", mec="black"))
    labels.append("paper, Table B1 (colour: its Isp)")
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
    colours = _isp_colours(isp_s)
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


# ======================================================== summary and verification pages
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


# ======================================================== free-ignition page
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


# =============================================================================== steering laws
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


# =============================================================================== other engines
def plot_engine_loss(totals, loss_column: str, loss_label: str):
    """Total loss and propellant of the capture against thrust, one marker per engine.

    Parameters
    ----------
    totals : DataFrame, one row per engine (``thrust_N``, ``isp_s``, ``origin``: a name for
        an engine cited by the paper, "paper's engine" for the paper's own,
        ``total_fuel_kg`` and ``loss_column``)
    loss_column : column of the loss drawn (m/s)
    loss_label : y-axis label of the loss, naming its impulsive reference

    Returns
    -------
    matplotlib.figure.Figure
    """
    isp_colours = _isp_colours((200.0, 250.0, 300.0))
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.6), sharex=True,
                                 layout="constrained")
    for r in totals.sort_values("thrust_N").itertuples():
        c = isp_colours.get(float(r.isp_s), isp_colour(r.isp_s, 4))
        cited = r.origin != "paper's engine"
        for a, y in ((ax, getattr(r, loss_column)), (bx, r.total_fuel_kg)):
            a.plot(r.thrust_N, y, "D" if cited else "o", color=c, ms=8,
                   mfc=c if cited else "white", mew=2)
            a.annotate(r.origin if cited else f"{r.thrust_N:g} N", (r.thrust_N, y),
                       xytext=(6, 4), textcoords="offset points", fontsize=9)
    for isp, c in isp_colours.items():
        if isp in set(totals.isp_s.astype(float)):
            ax.plot([], [], "s", color=c, label=f"Isp {isp:g} s")
    ax.plot([], [], "o", color="0.4", mfc="white", mew=2, label="paper's engines")
    ax.plot([], [], "D", color="0.4", label="cited in Sec. 3.1")
    ax.set_ylabel(loss_label)
    ax.legend()
    bx.set_xlabel("thrust (N)")
    bx.set_ylabel("propellant, LOI 1–3 (kg)")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.margins(x=0.2, y=0.12)
    return fig


# =============================================================================== burn count
def plot_burn_count(counts):
    """Total loss and time to the final orbit against the number of burns, one line per plan.

    Parameters
    ----------
    counts : DataFrame, one row per (plan, count) with ``label``, ``n_burns``, ``status``,
        ``total_delta_v_loss_mps`` and ``time_to_final_orbit_h`` (rows not "ok" are drawn as an
        open marker on the axis: no capture with that count)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.4), sharex=True,
                                 layout="constrained")
    for j, (label, g) in enumerate(counts.groupby("label", sort=False)):
        g = g.sort_values("n_burns")
        ok = g[g.status == "ok"]
        c = label_colour(label, j)
        m = ISP_MARKERS[j % len(ISP_MARKERS)]
        ax.plot(ok.n_burns, ok.total_delta_v_loss_mps, "-", marker=m, color=c, label=label)
        bx.plot(ok.n_burns, ok.time_to_final_orbit_h, "-", marker=m, color=c, label=label)
        bad = g[g.status != "ok"]
        for a in (ax, bx):
            a.plot(bad.n_burns, np.zeros(len(bad)), "x", color=c, ms=9, mew=2)
    ax.set_ylabel("total loss vs impulsive limit (m/s)")
    bx.set_ylabel("arrival perilune → end of last burn (h)")
    bx.set_xlabel("number of burns")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.set_xticks(sorted(set(counts.n_burns.astype(int))))
    ax.plot([], [], "x", color="0.4", mew=2, label="no plan (infeasible or failed)")
    ax.legend()
    return fig


# =============================================================================== missed thrust
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
        ax.text(j, i, txt, ha="center", va="center", fontsize=9,
                color="k" if r.status != "recovered" or grid[i, j] < vmax / 3 else "w")
    ax.set_xticks(range(len(de)), [f"{d:g}" for d in de])
    ax.set_yticks(range(len(fr)), [f"{f:g}" for f in fr])
    ax.set_xlabel("delay before the recovery (min)")
    ax.set_ylabel("fraction of the burn flown")
    cb = fig.colorbar(im, ax=ax)
    ticks = [t for t in (0, 1, 10, 100, 1000) if t <= vmax]
    cb.set_ticks([np.log10(t + 1.0) for t in ticks], labels=[f"{t:g}" for t in ticks])
    cb.set_label("penalty (m/s)")
    return fig


# =============================================================================== exchange
def plot_exported_trajectory(arcs, r_moon_km: float):
    """The exported trajectory, as read back from the OEM, in two ICRF projections.

    Parameters
    ----------
    arcs : list of (name, xyz (3, N) km ICRF, is_burn)
    r_moon_km : the Moon's radius, km (the grey disc)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = plt.subplots(1, 2, figsize=(FIG_WIDTH_IN, 3.8), layout="constrained")
    n_burns = sum(bool(is_burn) for _, _, is_burn in arcs)
    for (i, j), ax in zip(((0, 1), (0, 2)), axes):
        draw_moon(ax, r_moon_km, label=False)
        for name, xyz, is_burn in arcs:
            # "burn n" and "coast n" (the orbit burn n reached) by n; the final orbit is
            # the last burn's
            n = n_burns if name == "final orbit" else int(name.split()[-1]) \
                if name.split()[-1].isdigit() else 0
            label = name if ax is axes[0] else None
            if is_burn:
                ax.plot(xyz[i], xyz[j], color=burn_colour(n), lw=3.0, zorder=4,
                        solid_capstyle="butt", label=label)
            else:
                ax.plot(xyz[i], xyz[j], color=coast_colour(n) if n else HYPERBOLA_COLOUR,
                        lw=1.1, label=label)
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel(f"{'xyz'[i]} ICRF (km)")
        ax.set_ylabel(f"{'xyz'[j]} ICRF (km)")
    fig.legend(loc="outside lower center", ncols=4)
    return fig


# =============================================================================== the real Moon
def plot_evolution(histories: dict):
    """The final orbit's revolutions over days, one colour per gravity model.

    Parameters
    ----------
    histories : {label: {"days", "perilune_km", "apolune_km", "inc_deg"}} in drawing order
        (the paper's J2 first), one entry per revolution: the revolution's place in days
        since the last cut-off, its lowest and highest altitude (km) and its mean
        inclination (deg)

    Returns
    -------
    matplotlib.figure.Figure
        Above: perilune (solid) and apolune (dashed) altitudes; below: the inclination;
        the models' colours and the two line styles in one legend below the axes.
    """
    from matplotlib.lines import Line2D

    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.4), sharex=True,
                                 layout="constrained", height_ratios=(3, 2))
    handles = []
    for k, (label, h) in enumerate(histories.items()):
        c = model_colour(k)
        ax.plot(h["days"], h["apolune_km"], "--", color=c, lw=1.2)
        handles += ax.plot(h["days"], h["perilune_km"], "-", color=c, lw=1.6, label=label)
        bx.plot(h["days"], h["inc_deg"], "-", color=c, lw=1.6)
    handles += [Line2D([], [], color="0.3", ls="-", lw=1.6, label="perilune"),
                Line2D([], [], color="0.3", ls="--", lw=1.2, label="apolune")]
    ax.set_ylabel("altitude (km)")
    bx.set_ylabel("mean inclination (deg)")
    bx.set_xlabel("time after the last cut-off (days)")
    for a in (ax, bx):
        a.grid(alpha=0.3)
    fig.legend(handles=handles, loc="outside lower center", ncols=3, frameon=False)
    return fig
