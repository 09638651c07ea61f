"""The engine trade-study page (notebooks/trade_study.ipynb): loss against thrust-to-weight.

The notebook runs (or resumes) the study with lunarcap's public API
(:func:`lunarcap.engine_trade`: one Dask task per engine, the free-ignition chain LOI 1, 2,
3, verified) and solves the paper's engines (:func:`paper_engines`) directly
(:func:`lunarcap.solve`, a failed solve caught as :class:`lunarcap.SolveError`).
:func:`build` is the page's display helper: it sets beside the study Robbins' (1966)
analytic estimate and Eq. (19), and the paper's three engines (Table B1), with the page's
glued numbers and checks.

The loss is the study's (:mod:`lunarcap.studies.engine_trade.trade`): against the impulsive
limit of the same burn in the same dynamics from the same orbit, objective-based (Eq. 9: delta-V
plus the speed left at the next perilune), so it goes to zero as the thrust grows and is never
negative. Robbins' (1966) estimate is drawn only where its expansion in omega_s t_b holds
(:data:`ROBBINS_VALID_OMEGA_T`).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.quantities import capture_name
from lunarcap.report.contents import (
    BookPage,
    Execution,
    at_least,
    at_most,
    figure_files,
    includes,
    one_of,
    table_files,
)
from lunarcap.report.display import markdown_table
from lunarcap.report.figures import trade_study as draw
from lunarcap.report.page import Page
from lunarcap.repro import paths
from lunarcap.studies.engine_trade import trade as study

NOTEBOOK = "notebooks/trade_study.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 20, (
    Execution(
        "trade_study", "Engine trade study: loss against thrust-to-weight",
        parameters=dict(thrust_min_N=50.0, thrust_max_N=2000.0,
                        points=30,  # 90 engines (the floors below)
                        isp_s=[200.0, 250.0, 300.0], workers=2, dynamics="full"),
        quick_parameters=dict(points=4, isp_s=[250.0], workers=1),
        expected_s=250,  # 503 s of CPU measured (2 workers): 34 min wall at load 20-35
        outputs=(table_files("trade_study", "grid", "paper_engines", "runs")
                 + figure_files("trade_study", "loss", "duration")),
        floors=dict(
            points=at_least(30, "30 log-spaced thrusts: curves read between engines"),
            thrust_min_N=at_most(50.0, "from 50 N, a third of the paper's weakest engine"),
            thrust_max_N=at_least(2000.0, "to 2000 N, where the loss has all but vanished"),
            isp_s=includes([200.0, 250.0, 300.0], "the paper's three Isp, so its engines "
                                                  "are solved directly"),
            dynamics=one_of(["full"], "the paper's dynamics"))),
))

#: Panel titles of the parts of the chain (the study's ``part`` values), in panel order.
PART_TITLES = {"LOI1": "LOI 1: hyperbola → 12.235 h", "LOI2": "LOI 2: 12.235 h → 3.525 h",
               "LOI3": "LOI 3: 3.525 h → 100 km circle", "sequence": "whole sequence"}
#: The same, short enough for the duration figure's narrower panels (": duration" follows).
BURN_TITLES = {"LOI1": "LOI 1 → 12.235 h", "LOI2": "LOI 2 → 3.525 h",
               "LOI3": "LOI 3 → 100 km circle"}

#: Loss axis of the loss figure, % of the impulsive delta-V (logarithmic).
LOSS_AXIS_PERCENT = (0.003, 40.0)

#: Points of the dense thrust grid of the analytic curves.
DENSE_POINTS = 200

#: Columns of the grid table's CSV, and those shown in the book (the CSV keeps all).
GRID_COLUMNS = ["thrust_N", "isp_s", "thrust_to_weight", "objective_loss_percent_loi1",
                "objective_loss_percent_loi2", "objective_loss_percent_loi3",
                "objective_loss_percent_sequence",
                "objective_loss_mps_sequence", "analytic_loss_percent_sequence",
                "burn_duration_min_loi1",
                "eq19_duration_min_loi1", "status"]
GRID_SHOWN = GRID_COLUMNS[:7] + ["analytic_loss_percent_sequence"]

#: Columns of the runs table shown in the book (the CSV keeps all).
RUNS_SHOWN = ["source", "started_utc", "workers", "computed", "reused", "wall_s",
              "load_avg_1min"]

LOSS_DEFINITION = ("Loss: against the impulsive limit (same orbit and dynamics) by J of "
                   "Eq. (9), % of the impulsive ΔV; sequence: the three summed.")

#: Robbins' estimate is the leading term of an expansion in omega_s t_b (Schuler rate at
#: the perilune times the burn duration); it is drawn and compared where omega_s t_b is
#: at most this (rad).
ROBBINS_VALID_OMEGA_T = 0.5


def _interp_log(x, xs, ys) -> float:
    """Linear interpolation in log(x); NaN outside the data."""
    xs, ys = np.asarray(xs, float), np.asarray(ys, float)
    if len(xs) < 2 or not (xs.min() <= x <= xs.max()):
        return np.nan
    o = np.argsort(xs)
    return float(np.interp(np.log(x), np.log(xs[o]), ys[o]))


def paper_engines(isp_s) -> list:
    """The paper's engines the page solves directly: (thrust N, Isp s) of Table B1 in the grid.

    Only those whose Isp is among the grid's ``isp_s`` (s): their loss is set beside the
    grid's curve of that Isp (a quick build, one Isp, solves one engine).
    """
    grid = {float(i) for i in isp_s}
    return [(float(t), float(i)) for (t, i), _ in
            study.paper_points().groupby(["thrust_N", "isp_s"], sort=True) if float(i) in grid]


def direct_rows(solved: dict, dynamics: str) -> dict:
    """The study's four rows of each paper engine solved directly, failed or not.

    ``solved``: ``{(thrust N, Isp s): (result, error)}``: ``result`` is
    :func:`lunarcap.solve`'s CaptureResult of the paper's plan with every ignition free
    (the burns verified before a failure, if any: its ``rows()``), ``error`` the
    :class:`lunarcap.SolveError` that stopped it, or None. The rows are the study's task's
    (:func:`lunarcap.studies.engine_trade.trade.engine_rows`: the same free-ignition chain
    and loss as every engine of the grid), a failed burn with its IPOPT status, the later
    ones "not run". Returns ``{(thrust N, Isp s): DataFrame}``.
    """
    out = {}
    for (t, isp), (result, error) in solved.items():
        summaries = [dict(r, verification={"passed": r["verification_passed"]})
                     for r in result.rows()]
        failure = None if error is None else {
            "loi": len(summaries) + 1, "status": "failed",
            "ipopt_status": getattr(error, "status", "") or "", "error": str(error)}
        out[(float(t), float(isp))] = pd.DataFrame(
            study.engine_rows(float(t), float(isp), dynamics, summaries, failure))
    return out


def paper_engines_table(ok: pd.DataFrame, paper: pd.DataFrame,
                        direct: dict | None = None) -> pd.DataFrame:
    """Loss at the paper's three engines: Table B1, ours solved directly, Robbins' estimate.

    Columns: thrust_N, isp_s, part, paper_delta_v_loss_percent (Table B1 as printed; the
    sequence: summed losses over summed impulsive delta-Vs), optimal_loss_percent (our
    verified optimum of that engine, solved directly: ``direct``, see
    :func:`direct_rows`; NaN where not solved or not verified),
    interpolated_loss_percent (the grid's optima of the same Isp interpolated linearly in
    log T/W, NaN outside the grid), interpolation_error_pp (interpolated − direct,
    percentage points: what reading the curve instead of solving would be off by),
    analytic_loss_percent (Robbins).
    """
    direct = direct or {}
    rows = []
    for r in paper.itertuples(index=False):
        d = ok[(ok.part == r.part) & (ok.isp_s == r.isp_s)]
        robbins = study.analytic_curves([r.thrust_N], [r.isp_s]).set_index("part")
        solved = direct.get((float(r.thrust_N), float(r.isp_s)))
        own = (solved[(solved.part == r.part) & (solved.status == "ok")]
               if solved is not None else pd.DataFrame())
        exact = float(own.objective_loss_percent.iloc[0]) if len(own) else np.nan
        interp = _interp_log(r.thrust_to_weight, d.thrust_to_weight, d.objective_loss_percent)
        rows.append({"thrust_N": r.thrust_N, "isp_s": r.isp_s, "part": r.part,
                     "paper_delta_v_loss_percent": r.paper_delta_v_loss_percent,
                     "optimal_loss_percent": exact,
                     "interpolated_loss_percent": interp,
                     "interpolation_error_pp": interp - exact,
                     "analytic_loss_percent": float(robbins.loc[r.part, "analytic_loss_percent"])})
    return pd.DataFrame(rows)


def runs_table(result: study.StudyResult, timing_dir=None) -> pd.DataFrame:
    """The runs recorded for the study's table, and the timing runs in ``timing_dir``.

    Columns: source, started_utc, workers, engines, computed, reused, failed, wall_s,
    cluster_start_s, load_avg_1min (at the start of the run), cache.
    """
    records = [dict(r, source=result.path.name) for r in study.read_runs(result.path)]
    timing_dir = paths.CACHE / "study" / "timing" if timing_dir is None else timing_dir
    for f in sorted(timing_dir.glob("*.runs.json")) if timing_dir.is_dir() else []:
        stem = f.name.removesuffix(".runs.json")
        records += [dict(r, source=f"timing/{stem}")
                    for r in study.read_runs(f.with_name(stem + ".csv"))]
    runs = pd.DataFrame([{
        "source": r["source"], "started_utc": r["started_utc"], "workers": r["workers"],
        "engines": r["engines"], "computed": r["computed"], "reused": r["reused"],
        "failed": r.get("failed_computed", 0), "wall_s": r["wall_s"],
        "cluster_start_s": r.get("cluster_start_s", np.nan),
        "load_avg_1min": r.get("load_avg_1min_start", np.nan),
        "cache": "empty or disabled" if "NO_CACHE" in r.get("cache", "") else r.get("cache", ""),
    } for r in records])
    if len(runs):
        runs["cache"] = runs["cache"].str.replace(str(paths.ROOT) + "/", "", regex=False)
    return runs


def failures_note(result: study.StudyResult, n_engines: int) -> str:
    """The engines whose chain failed (a Markdown table), or that none did."""
    fails = result.failures
    if fails.empty:
        return (f"Every one of the {n_engines} engines was solved and verified for all "
                "three LOIs.")
    shown = fails[["thrust_N", "isp_s", "part", "status", "ipopt_status", "error"]].rename(
        columns={"thrust_N": "thrust (N)", "isp_s": "Isp (s)", "part": "burn",
                 "ipopt_status": "IPOPT status"})
    return ("**Engines whose chain failed**: the LOI, its status and IPOPT's return status "
            "(an LOI after a failed one is not run).\n\n"
            + markdown_table(shown, {"thrust (N)": ".4g", "Isp (s)": ".0f"}))


def _range_text(values, fmt: str = ".1f", unit: str = " %") -> str:
    """``"a to b<unit>"`` of the smallest and largest value (one value if they agree)."""
    v = [float(x) for x in values if np.isfinite(x)]
    if not v:
        return "—"
    lo, hi = format(min(v), fmt), format(max(v), fmt)
    return (lo if lo == hi else f"{lo} to {hi}") + unit


def burn_ratios(loi_ok: pd.DataFrame) -> tuple[pd.Series, pd.Series, pd.Series]:
    """Per solved LOI: optimal / Robbins loss, duration and ignition over Eq. (19).

    The three ratios are dimensionless: the loss over Robbins' estimate (only where it
    holds), the optimal duration over the Eq. (19) one, and the ignition offset over the
    Eq. (19) duration. Robbins' expansion holds where ω_s t_b ≤
    :data:`ROBBINS_VALID_OMEGA_T` (ω_s the Schuler rate at the perilune, t_b the Eq. (19)
    duration).
    """
    w = float(study.schuler_rate_rad_s(study.PERILUNE_RADIUS_KM))
    in_valid = loi_ok[w * 60.0 * loi_ok.eq19_duration_min <= ROBBINS_VALID_OMEGA_T]
    ratio = in_valid.objective_loss_mps / in_valid.analytic_loss_mps
    dur_ratio = loi_ok.burn_duration_min / loi_ok.eq19_duration_min
    start_ratio = loi_ok.start_min / loi_ok.eq19_duration_min
    return ratio, dur_ratio, start_ratio


def prose_values(spec, wide: pd.DataFrame, run: dict, ok: pd.DataFrame,
                 at_paper: pd.DataFrame) -> dict:
    """The numbers the prose quotes (NaN where the grid solved nothing)."""
    nan = float("nan")
    loi_ok = ok[ok.part != "sequence"]
    hi = ok[ok.part == "sequence"]
    hi = hi[hi.thrust_N == hi.thrust_N.max()]
    diffs = at_paper.dropna(subset=["optimal_loss_percent"])
    ratio, dur_ratio, start_ratio = burn_ratios(loi_ok)
    return {
        "n_engines": len(wide), "n_thrusts": spec.points, "n_isp": len(spec.isp_s),
        "thrust_min": spec.thrust_min_N, "thrust_max": spec.thrust_max_N,
        "tw_min": study.thrust_to_weight(spec.thrust_min_N),
        "tw_max": study.thrust_to_weight(spec.thrust_max_N),
        "n_failed": int((wide.status != "ok").sum()) if len(wide) else 0,
        "wall_s": float(run["wall_s"]), "n_computed": int(run["computed"]),
        "seq_loss_high_max_mps": float(hi.objective_loss_mps.max()) if len(hi) else nan,
        "seq_loss_high_max_percent": float(hi.objective_loss_percent.max()) if len(hi) else nan,
        "loss_min_mps": float(ok.objective_loss_mps.min()) if len(ok) else nan,
        "robbins_valid_omega_t": ROBBINS_VALID_OMEGA_T,
        "n_robbins_valid": len(ratio),
        "paper_diff_max": float((diffs.optimal_loss_percent
                                 - diffs.paper_delta_v_loss_percent).abs().max())
        if len(diffs) else nan,
        "robbins_diff_max": float((diffs.analytic_loss_percent
                                   - diffs.optimal_loss_percent).abs().max())
        if len(diffs) else nan,
        "interp_error_max_pp": float(diffs.interpolation_error_pp.abs().max())
        if len(diffs) and diffs.interpolation_error_pp.notna().any() else nan,
        "n_paper_direct": int(diffs.thrust_N.nunique()) if len(diffs) else 0,
        "dur_ratio_max": float(dur_ratio.max()) if len(loi_ok) else nan,
        "start_ratio_min": float(-start_ratio.min()) if len(loi_ok) else nan,
    }


def _add_loss(page: Page, ok, valid, paper, spec, newton_per_ratio: float,
              direct: dict) -> pd.DataFrame:
    """The loss figure and the table at the paper's engines (returned)."""
    loss_def, dynamics = LOSS_DEFINITION, spec.dynamics
    page.figure(
        "loss", draw.plot_trade_study_loss(ok, valid, paper, spec.isp_s, PART_TITLES,
                                              newton_per_ratio, LOSS_AXIS_PERCENT),
        caption=("Loss over the impulsive limit (% of the impulsive ΔV, log) against "
                 f"T/(m₀ g₀), m₀ = 524.895 kg, per LOI and sequence, a curve per Isp; {dynamics} "
                 r"dynamics. Dashed: {cite:t}`robbins1966`, "
                 r"$\tfrac{1}{24}(\omega_s t_b)^2\,\Delta V$, "
                 rf"$\omega_s t_b \le {ROBBINS_VALID_OMEGA_T:g}$ rad. Stars: Table B1."),
        alt="Finite-burn loss against thrust-to-weight ratio, per LOI and for the sequence")
    at_paper = paper_engines_table(ok, paper, direct)
    page.table(
        "paper_engines", at_paper,
        caption=(f"Loss at the paper's engines: Table B1, ours solved directly "
                 f"(*{capture_name('free')}*), read off the grid (linear in log T/W) and its "
                 "error, Robbins'. " + loss_def),
        columns={"part": "burn", "paper_delta_v_loss_percent": "paper, Table B1 (%)",
                 "optimal_loss_percent": "ours, solved (%)",
                 "interpolated_loss_percent": "ours, interpolated (%)",
                 "interpolation_error_pp": "interpolation error (pp)",
                 "analytic_loss_percent": "Robbins (%)"},
        floatfmt={"thrust_N": ".0f", "isp_s": ".0f", "paper_delta_v_loss_percent": ".2f",
                  "optimal_loss_percent": ".2f", "interpolated_loss_percent": ".2f",
                  "interpolation_error_pp": "+.2f", "analytic_loss_percent": ".2f"})
    return at_paper


def _add_duration_grid_runs(page: Page, loi_ok, wide, spec, newton_per_ratio: float,
                            result, timing_dir) -> None:
    loss_def = LOSS_DEFINITION
    page.figure(
        "duration", draw.plot_trade_study_duration(
            loi_ok, spec.isp_s, {p: BURN_TITLES[p] for p in study.PARTS[:3]},
            newton_per_ratio),
        caption=("One row per burn, against T/(m₀ g₀) (thrust in N on top). Left: optimal "
                 "duration over the Eq. (19) estimate. Right: optimal ignition offset over "
                 "the Eq. (19) duration (the paper's rule of thumb: −½)."),
        alt="Optimal burn duration and ignition offset over the Eq. (19) duration")
    grid = wide.reindex(columns=GRID_COLUMNS)
    page.table(
        "grid", grid,
        caption=(f"The grid, with Robbins' estimate for the sequence. {loss_def} Every "
                 f"column: {page.data_link(result.path, 'study.csv')}."),
        columns={"objective_loss_percent_loi1": "LOI 1 (%)",
                 "objective_loss_percent_loi2": "LOI 2 (%)",
                 "objective_loss_percent_loi3": "LOI 3 (%)",
                 "objective_loss_percent_sequence": "sequence (%)",
                 "objective_loss_mps_sequence": "sequence (m/s)",
                 "analytic_loss_percent_sequence": "Robbins, sequence (%)",
                 "burn_duration_min_loi1": "LOI 1 burn (min)",
                 "eq19_duration_min_loi1": "LOI 1 Eq. (19) (min)", "status": "status"},
        floatfmt={"thrust_N": ".4g", "isp_s": ".0f", "thrust_to_weight": ".4f",
                  "objective_loss_percent_loi1": ".3f", "objective_loss_percent_loi2": ".3f",
                  "objective_loss_percent_loi3": ".3f", "objective_loss_percent_sequence": ".3f",
                  "objective_loss_mps_sequence": ".2f", "analytic_loss_percent_sequence": ".3f",
                  "burn_duration_min_loi1": ".2f", "eq19_duration_min_loi1": ".2f"},
        show_columns=GRID_SHOWN)
    page.table(
        "runs", runs_table(result, timing_dir),
        caption=("Runs of the study: workers (0: nothing to compute), engines solved and "
                 "read from the table, wall time with the cluster's start, and the machine's "
                 "load when the run started (other work slows it down)."),
        columns={"source": "table", "started_utc": "started (UTC)", "workers": "workers",
                 "computed": "solved", "reused": "from the table", "wall_s": "wall time (s)",
                 "load_avg_1min": "load (1 min)"},
        floatfmt={"wall_s": ".1f", "cluster_start_s": ".1f", "load_avg_1min": ".1f"},
        show_columns=RUNS_SHOWN)


def _add_checks(page: Page, spec, table, wide, ok, theory, values: dict) -> None:
    seq = ok[ok.part == "sequence"]
    ratio, dur_ratio, _ = burn_ratios(ok[ok.part != "sequence"])
    loi_ok = ok[ok.part != "sequence"]
    page.expect("every engine of the grid is in the table", len(wide) == len(spec.engines),
                f"{len(wide)} of {len(spec.engines)}")
    page.expect("known row statuses", set(table.status) <= set(study.STATUSES),
                str(sorted(set(table.status) - set(study.STATUSES))))
    page.expect("every failure carries a reason",
                bool(((wide.status == "ok") | (wide.failed_part != "")).all()))
    for isp in spec.isp_s:
        s = seq[seq.isp_s == isp].sort_values("thrust_N")
        if len(s) >= 2:
            page.expect(f"Isp {isp:g} s: the weakest engine loses more than the strongest, "
                        "and over 0.5 %",
                        s.objective_loss_percent.iloc[0] > s.objective_loss_percent.iloc[-1]
                        and s.objective_loss_percent.iloc[0] > 0.5,
                        f"{s.objective_loss_percent.iloc[0]:.3f} % vs "
                        f"{s.objective_loss_percent.iloc[-1]:.3f} %")
    if len(spec.isp_s) > 1:  # the prose: at one thrust-to-weight a higher Isp loses more
        by_t = seq.pivot_table(index="thrust_N", columns="isp_s", values="objective_loss_percent")
        lossy = by_t[by_t.min(axis=1) > 1.0]  # where the loss is resolved
        page.expect("at one thrust, a higher Isp loses more (where the loss exceeds 1 %)",
                    bool((lossy.diff(axis=1).iloc[:, 1:] > 0).all().all()))
    page.expect("no negative loss (to 1 mm/s: IPOPT's tolerance on the objective)",
                not len(ok) or values["loss_min_mps"] > -1e-3, f"{values['loss_min_mps']:.4f}")
    page.expect("where Robbins' expansion holds, the optimal loss does not exceed it",
                not len(ratio) or float(ratio.max()) <= 1.0 + 1e-3,
                f"largest ratio {float(ratio.max()):.3f}" if len(ratio) else "")
    page.expect("Robbins' estimate falls as the thrust grows",
                bool(theory.groupby(["isp_s", "part"]).analytic_loss_percent
                     .apply(lambda v: v.is_monotonic_decreasing).all()))
    page.expect("the optimal duration is 0.97 to 2 times Eq. (19)",
                bool(dur_ratio.between(0.97, 2.0).all()),
                f"{dur_ratio.min():.3f} to {dur_ratio.max():.3f}" if len(dur_ratio) else "")
    page.expect("the weakest engines ignite earlier than the paper's rule (−½ Eq. (19))",
                not len(loi_ok) or values["start_ratio_min"] > 0.5,
                f"{values['start_ratio_min']:.3f}")


def build(trade, solved: dict, output_name: str = "trade_study", quick: bool = False,
          parameters: dict | None = None, timing_dir=None) -> Page:
    """The trade-study page from what the notebook computed (see the module docstring).

    Parameters
    ----------
    trade : lunarcap.StudyResult
        :func:`lunarcap.engine_trade`'s result: its ``campaign`` (the grid's table, the
        table's path, this run's record, whose ``grid`` is the study's grid).
    solved : dict
        The paper's engines solved directly, ``{(thrust N, Isp s): (result, error)}``
        (:func:`direct_rows`).
    output_name, quick : the page's output name and whether it is a quick build
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance.
    timing_dir : directory of the timing runs listed in the runs table
        (default ``<cache>/study/timing``)
    """
    params = {k: list(v) if isinstance(v, (list, tuple)) else v
              for k, v in (parameters or {}).items()}
    page = Page(NOTEBOOK, params, output_name, quick)
    result = trade.campaign
    spec = study.StudySpec(**result.run["grid"])
    table, wide, run = result.table, result.wide(), result.run
    ok = table[table.status == "ok"]
    loi_ok = ok[ok.part != "sequence"]
    seq = ok[ok.part == "sequence"]
    theory = study.analytic_curves(
        np.geomspace(spec.thrust_min_N, spec.thrust_max_N, DENSE_POINTS), spec.isp_s)
    paper = study.paper_points()
    newton_per_ratio = float(study.thrust_from_weight_ratio(1.0))
    valid = theory[theory.omega_t_rad <= ROBBINS_VALID_OMEGA_T]
    direct = direct_rows(solved, spec.dynamics)
    at_paper = _add_loss(page, ok, valid, paper, spec, newton_per_ratio, direct)
    _add_duration_grid_runs(page, loi_ok, wide, spec, newton_per_ratio, result, timing_dir)
    page.note("failures", failures_note(result, len(wide)))
    values = prose_values(spec, wide, run, ok, at_paper)
    for k, v in values.items():
        page.value(k, v)
    lo = seq[seq.thrust_N == seq.thrust_N.min()]
    page.value("seq_loss_low_range", _range_text(lo.objective_loss_percent))
    page.value("robbins_ratio_range", _range_text(burn_ratios(loi_ok)[0], ".2f", ""))
    _add_checks(page, spec, table, wide, ok, theory, values)
    t = page.text
    page.headline(f"From {t('thrust_min', 'g')} to {t('thrust_max', 'g', ' N')} "
                  f"(*{capture_name('free')}*, {spec.dynamics} dynamics) the loss falls with "
                  f"thrust-to-weight, to at most {t('seq_loss_high_max_mps', '.3f', ' m/s')} "
                  f"for the whole sequence, never negative; at the paper's engines, solved "
                  f"directly, within {t('paper_diff_max', '.2f')} percentage points of "
                  f"Table B1.")
    page.data.update(direct=direct, result=result, wide=wide, ok=ok, theory=theory, paper=paper)
    page.capture("free", spec.dynamics)
    return page
