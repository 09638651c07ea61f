"""The dispersions page (notebooks/dispersions.ipynb): the delta-V budget under errors.

For each plan (the paper's three engines), the notebook's :func:`lunarcap.dispersions`
flies ``samples`` captures with execution, arrival and knowledge errors, re-planned after
every burn and trimmed to the plan's final orbit after the last (run on Dask, resumed from
``<cache>/study/<output_name>.csv``), under an *example* error model whose values are
assumptions (:data:`DEFAULT_SIGMAS`, the page's assumptions table). :func:`build` shows
the example budget with the trim and for the burns alone (the mean above the nominal with
its standard error, the costliest sample, a percentile only where the samples bound its
interval, else how many samples it needs), the final orbit before the trim and the trim's
distribution, a CDF per engine, and the **sensitivities**: each error source alone at
``sensitivity_factors`` times its example sigma, the others 0, on the same antithetic
draws (the notebook's ``lunarcap.dispersions(..., sensitivity=True, factors=...,
antithetic=True)``), one figure per engine and a table
of the laws with their standard errors (or "unresolved"), so a reader scales the budget
to their own sigmas. Every function is correct at any sample count: a number the samples
do not support is replaced by what it needs.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lunarcap.quantities import capture_name
from lunarcap.report.contents import (
    BookPage,
    Execution,
    at_least,
    figure_files,
    includes,
    one_of,
    table_files,
)
from lunarcap.report.figures import dispersions as draw
from lunarcap.report.page import Page, solver_description
from lunarcap.repro import paths
from lunarcap.studies.dispersions import samples as disp
from lunarcap.studies.study import plan_id

NOTEBOOK = "notebooks/dispersions.ipynb"
#: The paper's three engines, the plans of the page's budget and sensitivities.
PAPER_PLANS = ("song2011-150N", "song2011-300N", "song2011-450N")
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 110, (
    Execution(
        "dispersions", "Delta-V budget under dispersions",
        parameters=dict(
            plans=["song2011-150N", "song2011-300N", "song2011-450N"],
            samples=368,  # per engine: bounds the 99 % point with a 95 % interval
            seed=2011,
            sigmas=dict(thrust_sigma_pct=1.0, isp_sigma_pct=0.5, pointing_sigma_deg=0.3,
                        ignition_sigma_s=1.0, arrival_sigma_km=1.0, arrival_sigma_mps=1.0,
                        knowledge_sigma_km=0.1, knowledge_sigma_mps=0.1),
            dynamics=None,  # the plans' own (full)
            workers=2,
            sensitivity_samples=16,  # 8 antithetic pairs: 8 independent draws per level
            sensitivity_factors=[0.5, 1.0, 2.0],
            sensitivity_plans=["song2011-150N", "song2011-300N", "song2011-450N"]),
        quick_parameters=dict(samples=2, dynamics="two-body", workers=1, sensitivity_samples=2,
                              sensitivity_factors=[1.0, 2.0],
                              sensitivity_plans=["song2011-150N"]),
        expected_s=700,  # 1398 s of CPU measured (2 workers, 2256 samples)
        outputs=(table_files("dispersions", "budget", "failures", "sensitivity")
                 + figure_files("dispersions", "cdf", "sensitivity_150N")),
        floors=dict(
            plans=includes(PAPER_PLANS, "a budget for each of the paper's three engines"),
            samples=at_least(368, "the 99 % point bounded on both sides by order statistics "
                                  "at 95 % confidence (samples_needed(0.99))"),
            sensitivity_plans=includes(PAPER_PLANS, "each engine's sensitivity to each source"),
            sensitivity_factors=includes([0.5, 1.0, 2.0], "each source's law from three levels "
                                                          "of its sigma"),
            sensitivity_samples=at_least(16, "8 independent draws (antithetic pairs) per "
                                             "level and source: each exponent with its "
                                             "standard error"),
            dynamics=one_of([None], "the plans' own (full) dynamics"))),
))

#: The example error model of the page (1 sigma), assumed: see the page's assumptions.
DEFAULT_SIGMAS = {"thrust_sigma_pct": 1.0, "isp_sigma_pct": 0.5, "pointing_sigma_deg": 0.3,
                  "ignition_sigma_s": 1.0, "arrival_sigma_km": 1.0, "arrival_sigma_mps": 1.0,
                  "knowledge_sigma_km": 0.1, "knowledge_sigma_mps": 0.1}
#: What each source is called on the page.
SOURCE_LABELS = {"thrust_sigma_pct": "thrust", "isp_sigma_pct": "Isp",
                 "pointing_sigma_deg": "pointing", "ignition_sigma_s": "ignition epoch",
                 "arrival_sigma_km": "arrival position", "arrival_sigma_mps": "arrival velocity",
                 "knowledge_sigma_km": "knowledge position",
                 "knowledge_sigma_mps": "knowledge velocity",
                 "gates_magnitude_pct": "Gates magnitude (prop.)",
                 "gates_magnitude_mps": "Gates magnitude (fixed)",
                 "gates_pointing_deg": "Gates pointing (prop.)",
                 "gates_pointing_mps": "Gates pointing (fixed)"}

#: Shown on the page, to fit its 688 px column at 1280 px (`make screenshots` checks it):
#: propellant, the impulsive delta-V, the largest sample and timings stay in the CSV.
BUDGET_SHOWN = ["engine", "samples", "nominal_delta_v_mps", "mean_text", "p99_text",
                "p99_burns_text", "max_above_nominal_mps", "p_failure"]
BUDGET_HEADS = {"engine": "engine", "samples": "samples",
                "nominal_delta_v_mps": "nominal ΔV (m/s)",
                "mean_text": "mean above nominal ± s.e. (m/s)",
                "p99_text": "99 % above nominal, with the trim (m/s) [95 % interval]",
                "p99_burns_text": "99 %, burns alone (m/s)",
                "max_above_nominal_mps": "costliest sample above nominal (m/s)",
                "p_failure": "P(not captured or not corrected)"}
#: The trim table's shown columns and their heads.
TRIM_SHOWN = ["engine", "rp_text", "ra_text", "inc_text", "trim_p50_mps", "trim_p99_text",
              "trim_max_mps", "trimmed_max_abs_rp_error_m"]
TRIM_HEADS = {"engine": "engine", "rp_text": "r_p error before the trim, RMS / max (km)",
              "ra_text": "r_a error before, RMS / max (km)",
              "inc_text": "i error before, RMS / max (deg)",
              "trim_p50_mps": "trim, median (m/s)",
              "trim_p99_text": "trim, 99 % (m/s) [95 % interval]",
              "trim_max_mps": "largest trim (m/s)",
              "trimmed_max_abs_rp_error_m": "largest r_p error after the trim (m)"}


def percentile_text(s: dict, q: float = 99.0, key: str | None = None) -> str:
    """A percentile above the nominal with its interval, or how many samples it needs.

    ``key``: the summary's entry of another budget (``budget_p99_burns_above_nominal_mps``,
    the burns alone); default the total's ``delta_v_p{q}``.
    """
    need, n = s[f"samples_needed_p{q:g}"], s["samples"]
    if n < need:
        return f"needs {need} samples (has {n})"
    if key is not None:
        lo, hi = s[key.replace("above_nominal_mps", "ci_mps")]
        return f"{s[key]:.2f} [{lo:.2f}, {hi:.2f}]"
    nom = s["nominal_delta_v_mps"]
    lo, hi = (v - nom for v in s[f"delta_v_p{q:g}_ci_mps"])
    return f"{s[f'delta_v_p{q:g}_mps'] - nom:.2f} [{lo:.2f}, {hi:.2f}]"


def sample_cpu_s(table: pd.DataFrame) -> pd.Series:
    """Each sample's CPU time, s (its wall time in tables written before CPU was logged)."""
    return table.task_cpu_s if "task_cpu_s" in table else table.task_wall_s


def budget_row(plan, table: pd.DataFrame) -> dict:
    """One engine's line of the budget table (and of the trim table) from its samples."""
    s = disp.summarise(table)
    lo, hi = s["budget_p99_ci_mps"]
    ok = table[table.status == "ok"]
    cpu = sample_cpu_s(ok)
    return {"engine": f"{plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} s",
            "plan": plan.name, "samples": s["samples"],
            "nominal_delta_v_mps": s["nominal_delta_v_mps"],
            "impulsive_delta_v_two_body_mps": float(table.impulsive_delta_v_two_body_mps.iloc[0])
            if "impulsive_delta_v_two_body_mps" in table else disp.nominal_totals(plan)[
                "impulsive_delta_v_two_body_mps"],
            **{f"delta_v_p{q:g}_mps": s[f"delta_v_p{q:g}_mps"] for q in disp.PERCENTILES},
            **{f"propellant_p{q:g}_kg": s[f"propellant_p{q:g}_kg"] for q in disp.PERCENTILES},
            "budget_p99_above_nominal_mps": s["budget_p99_above_nominal_mps"],
            "ci_lo_mps": lo, "ci_hi_mps": hi, "p99_text": percentile_text(s),
            "budget_p99_burns_above_nominal_mps": s["budget_p99_burns_above_nominal_mps"],
            "p99_burns_text": percentile_text(s, key="budget_p99_burns_above_nominal_mps"),
            "samples_needed_p99": s["samples_needed_p99"],
            "mean_above_nominal_mps": s["mean_above_nominal_mps"],
            "mean_above_nominal_se_mps": s["mean_above_nominal_se_mps"],
            "mean_text": f"{s['mean_above_nominal_mps']:.2f} ± "
                         f"{s['mean_above_nominal_se_mps']:.2f}",
            "max_above_nominal_mps": float(np.where(table.status == "ok",
                                                    table.total_delta_v_mps.astype(float),
                                                    np.inf).max()) - s["nominal_delta_v_mps"],
            "p_not_captured": s["p_not_captured"],
            "p_correction_failed": s["p_correction_failed"],
            "p_failure": s["p_not_captured"] + s["p_correction_failed"],
            **_final_orbit_fields(s),
            "median_sample_s": float(ok.task_wall_s.median()) if len(ok) else math.nan,
            "median_sample_cpu_s": float(cpu.median()) if len(ok) else math.nan}


def _final_orbit_fields(s: dict) -> dict:
    """The final orbit before the trim and the trim's distribution, for the trim table."""
    out = {k: s[k] for k in s if k.startswith(("final_rms_", "final_max_abs_", "trim",
                                               "trimmed_")) and k != "trim_p99_ci_mps"}
    out["trim_p99_ci_lo_mps"], out["trim_p99_ci_hi_mps"] = s["trim_p99_ci_mps"]
    for c, unit, fmt in (("rp", "km", ".2f"), ("ra", "km", ".2f"), ("inc", "deg", ".4f")):
        rms, top = s[f"final_rms_{c}_error_{unit}"], s[f"final_max_abs_{c}_error_{unit}"]
        out[f"{c}_text"] = f"{rms:{fmt}} / {top:{fmt}}"
    n, need = s["captured_and_corrected"], s["samples_needed_p99"]
    if n >= need and math.isfinite(s["trim_p99_mps"]):
        lo, hi = s["trim_p99_ci_mps"]
        out["trim_p99_text"] = f"{s['trim_p99_mps']:.2f} [{lo:.2f}, {hi:.2f}]"
    else:
        out["trim_p99_text"] = f"needs {need} samples (has {n})"
    return out


def convergence_curves(tables: dict) -> dict | None:
    """Each engine's 99 % estimate and its 95 % interval against the samples N.

    From the first N whose samples bound the interval (368) on; None when no table has
    that many samples (the page then shows no such figure).
    """
    need = disp.samples_needed(0.99)
    if max(len(t) for t in tables.values()) < need:
        return None
    curves = {}
    for label, t in tables.items():
        c = disp.convergence(t)
        curves[label] = c[c.samples >= need]
    return curves


def plot_convergence(tables: dict):
    """The figure of :func:`convergence_curves`, or None when it has no curve."""
    curves = convergence_curves(tables)
    return None if curves is None else draw.plot_convergence(curves)


def sensitivity_table(rows: list, laws: list) -> pd.DataFrame:
    """One row per engine and source: its law (exponent and standard error, or why none).

    ``rows``: :func:`lunarcap.studies.dispersions.sensitivity.sensitivity_rows` with
    ``engine``, ``example`` and ``factor``; ``laws``: its ``laws`` with ``engine``. The
    mean above the nominal is the one at the example sigma (factor 1, else the largest).
    """
    out = []
    for law in laws:
        mine = [r for r in rows if r["engine"] == law["engine"] and
                r["source"] == law["source"]]
        if not mine:
            continue
        at = min(mine, key=lambda r: (abs(math.log(r["factor"])), -r["factor"]))
        out.append({"engine": law["engine"], "source": SOURCE_LABELS[law["source"]],
                    "sigma": f"{at['sigma']:g} {at['unit']}",
                    "draws": int(law["draws"]),
                    "mean_above_nominal_mps": at["mean_above_nominal_mps"],
                    "mean_above_nominal_se_mps": at["mean_above_nominal_se_mps"],
                    "mean_text": _mean_text(at),
                    "exponent": law["exponent"], "exponent_se": law["exponent_se"],
                    "exponent_text": exponent_text(law),
                    "draws_needed": law["draws_needed"]})
    return pd.DataFrame(out, columns=["engine", "source", "sigma", "draws",
                                      "mean_above_nominal_mps", "mean_above_nominal_se_mps",
                                      "mean_text", "exponent", "exponent_se",
                                      "exponent_text", "draws_needed"])


def _mean_text(r: dict) -> str:
    """The mean above the nominal with its standard error, or "unresolved" below 0.01 m/s."""
    se = r["mean_above_nominal_se_mps"]
    if not r["resolved"]:
        return f"unresolved ({r['mean_above_nominal_mps']:+.4f})"
    return f"{r['mean_above_nominal_mps']:.3f}" + (f" ± {se:.3f}" if math.isfinite(se) else "")


def exponent_text(law: dict) -> str:
    """A law's exponent with its standard error, or its status and reason."""
    if law["status"] != "fitted":
        return f"{law['status']}: {law['reason']}"
    se = law["exponent_se"]
    return f"{law['exponent']:.2f}" + (f" ± {se:.2f}" if math.isfinite(se) else
                                        " (one draw: no standard error)")


def failure_rows(tables: dict) -> pd.DataFrame:
    """Every sample that was not captured or not corrected, with its reason."""
    rows = []
    for label, t in tables.items():
        for r in t[t.status != "ok"].to_dict("records"):
            rows.append({"engine": label, "sample": int(r["sample"]), "status": r["status"],
                         "reason": r["reason"] or r["error"]})
    if not rows:   # a table is never written empty: say that there is nothing to list
        rows.append({"engine": "every engine", "sample": "", "status": "none failed",
                     "reason": "every sample was captured and corrected"})
    return pd.DataFrame(rows, columns=["engine", "sample", "status", "reason"])


def table_file(output_name: str = "dispersions"):
    """Where the book keeps the samples of this page's runs, resumed on rerun (a Path).

    ``<cache>/study/<output_name>.csv``: the notebook passes it as every run's ``out``
    (the budgets and the sensitivities: one table, each row keyed by its plan, sample and
    sigmas), so the book resumes its own table.
    """
    return paths.CACHE / "study" / f"{output_name}.csv"


def _per_engine(budgets: list, sensitivities: list, sig: dict) -> tuple:
    """Each engine's samples, budget row, sensitivity rows and laws (labelled by engine).

    ``budgets``, ``sensitivities``: the notebook's :func:`lunarcap.dispersions` runs, one
    per plan (a sensitivity's ``raw`` is ``(models, campaign)``). Returns ``(tables, rows,
    srows, laws)``: engine label -> its samples (with its two-body impulsive delta-V), the
    budget rows, the sensitivity rows with each source's example sigma and the factor of
    the sigma run over it, and each source's law.
    """
    from lunarcap.studies.dispersions import sensitivity as sens

    by_plan = {plan_id(s.plan): s.raw for s in sensitivities}
    tables, rows, srows, laws = {}, [], [], []
    for b in budgets:
        p, t = b.plan, b.campaign.table.copy()   # a run's table: its own samples only
        t["impulsive_delta_v_two_body_mps"] = \
            disp.nominal_totals(p)["impulsive_delta_v_two_body_mps"]
        label = f"{p.engine.thrust_N:g} N / {p.engine.isp_s:g} s"
        tables[label] = t
        rows.append(budget_row(p, t))
        if plan_id(p) not in by_plan:
            continue
        models, sres = by_plan[plan_id(p)]
        st = sres.table
        for r in sens.sensitivity_rows(st, models):
            srows.append(dict(r, engine=label, example=sig[r["source"]],
                              factor=r["sigma"] / sig[r["source"]]))
        laws += [dict(law, engine=label) for law in (sens.laws(st, models) if len(st) else [])]
    return tables, rows, srows, laws


def build(budgets: list, sensitivities: list, output_name: str = "dispersions",
          quick: bool = False, parameters: dict | None = None) -> Page:
    """The page of the dispersion runs made in the notebook (see the module docstring).

    Parameters
    ----------
    budgets : list of lunarcap.StudyResult
        :func:`lunarcap.dispersions` of each plan, in the page's order, under the example
        sigmas (``samples`` per plan, one seed, the table :func:`table_file`).
    sensitivities : list of lunarcap.StudyResult
        :func:`lunarcap.dispersions` with ``sensitivity=True``, ``factors`` and
        ``antithetic=True`` of the plans in ``sensitivity_plans`` (the same seed, sigmas
        and table).
    output_name, quick : the tables' prefix; recorded in the provenance
    parameters : dict
        The notebook's ``plans``, ``samples``, ``seed``, ``sigmas``, ``dynamics``,
        ``workers``, ``sensitivity_samples``, ``sensitivity_factors`` and
        ``sensitivity_plans`` (None: every plan): the captions and the provenance.
        ValueError if ``sensitivity_plans`` names a plan outside ``plans``.
    """
    prm = dict(parameters or {})
    plans, samples, seed = list(prm["plans"]), int(prm["samples"]), int(prm["seed"])
    sensitivity_samples = int(prm["sensitivity_samples"])
    sensitivity_factors = list(prm["sensitivity_factors"])
    sensitivity_plans = prm.get("sensitivity_plans")
    chosen = plans if sensitivity_plans is None else sensitivity_plans
    unknown = sorted(set(chosen) - set(plans))
    if unknown:
        raise ValueError(f"sensitivity_plans: {unknown} not among the page's plans {plans}")
    sig = dict(DEFAULT_SIGMAS, **(prm.get("sigmas") or {}))
    model = disp.ErrorModel(**sig)
    params = dict(plans=plans, samples=samples, seed=seed, sigmas=sig,
                  dynamics=prm.get("dynamics"), workers=prm.get("workers"),
                  sensitivity_samples=sensitivity_samples,
                  sensitivity_factors=sensitivity_factors,
                  sensitivity_plans=None if sensitivity_plans is None else list(sensitivity_plans))
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(**{
        "re-plans": "each burn after the first re-solved from the estimate of the perilune "
                    "reached, warm-started from the nominal steering, verified",
        "trim": "two impulses after the last burn, corrected in the plan's dynamics until "
                "the orbit passes the verification gate"}))
    runs = [b.campaign.run for b in budgets] + [s.campaign.run for s in sensitivities]
    sres_tables = [s.campaign.table for s in sensitivities]
    sres_table = (pd.concat(sres_tables, ignore_index=True) if sres_tables
                  else pd.DataFrame(columns=["status", "error"]))
    tables, rows, srows, laws = _per_engine(budgets, sensitivities, sig)
    budget = pd.DataFrame(rows)
    dyn = budgets[-1].plan.dynamics
    page.data.update(tables=tables, budget=budget, runs=runs, sensitivity=srows, laws=laws)
    _show_budget(page, budget, tables, samples, seed, dyn, budgets[0].campaign.path)
    _show_sensitivity(page, srows, laws, sensitivity_factors, sensitivity_samples)
    _values(page, model, sig, rows, budget, tables, runs, samples, seed, dyn)
    page.value("sensitivity_samples", int(sensitivity_samples))
    page.value("sensitivity_pairs", int(sensitivity_samples) // 2)
    page.value("n_sensitivity", int(len(sres_table)))
    page.value("sensitivity_cpu_s", float(sample_cpu_s(sres_table).sum())
               if len(sres_table) else 0.0)
    from lunarcap.studies.dispersions import sensitivity as sens

    page.value("target_exponent_se", float(sens.TARGET_EXPONENT_SE))
    needed = [law["draws_needed"] for law in laws if law["draws_needed"]]
    page.value("pairs_needed_max", max(needed) if needed else None,
               "no law was fitted with two or more pairs")
    _checks(page, tables, sres_table, rows)
    page.capture("fixed", dyn)
    return page


def _show_sensitivity(page: Page, srows: list, laws: list, factors, n_samples: int) -> None:
    """One figure per engine of each source's sensitivity, and the table of their laws."""
    from lunarcap.studies.dispersions import sensitivity as sens

    for label in dict.fromkeys(r["engine"] for r in srows):
        tag = label.split(" N")[0]
        fig = draw.plot_sensitivity(srows, label, SOURCE_LABELS)
        page.figure(f"sensitivity_{tag}N", fig, caption=(
            f"{label}: mean ΔV above the nominal (bars: ± 1 standard error over "
            f"{n_samples // 2} antithetic pairs) and costliest sample (dashed), each source "
            f"alone at {', '.join(f'{f:g}' for f in factors)} times its example sigma. "
            f"Below the dotted 0.01 m/s: unresolved, not drawn."),
            alt=f"Sensitivity of the delta-V to each error source, {label}")
    page.table("sensitivity", sensitivity_table(srows, laws), caption=(
        "Each source's law y ~ sigma^b (b: 1 linear, 2 quadratic), fitted to the mean ΔV "
        "above the nominal, with its standard error over the independent pairs; "
        "\"unresolved\" where fewer than two sigmas reach 0.01 m/s. For your sigma s, "
        "scale the mean by (s / sigma)^b."),
        columns={"engine": "engine", "source": "error source", "sigma": "example sigma",
                 "draws": "pairs", "mean_text": "mean above nominal ± s.e. (m/s)",
                 "exponent_text": "exponent b ± s.e.",
                 "draws_needed": f"pairs for ± {sens.TARGET_EXPONENT_SE:g}"},
        show_columns=["engine", "source", "sigma", "draws", "mean_text", "exponent_text",
                      "draws_needed"],
        floatfmt={"mean_above_nominal_mps": ".4f", "draws_needed": ".0f"})


def _checks(page: Page, tables: dict, sensitivity: pd.DataFrame, rows: list) -> None:
    """The page's assertions and its headline."""
    from lunarcap.optim.gate import TOL_ANGLE_DEG, TOL_RA_M, TOL_RP_M

    sens_bugs = sensitivity[~sensitivity.status.isin(disp.OK_STATUSES)]
    bugs = pd.concat([t[~t.status.isin(disp.OK_STATUSES)] for t in tables.values()]
                     + [sens_bugs])
    page.expect("no sample ended in an unexpected error (failures are reported, not hidden)",
                bugs.empty, "; ".join(bugs.error.astype(str)))
    page.expect("no percentile is shown that its samples do not bound",
                all(r["samples"] >= r["samples_needed_p99"] or "needs" in r["p99_text"]
                    for r in rows))
    every = pd.concat(tables.values())
    ok = every[every.status == "ok"]
    page.expect("every captured sample's trimmed orbit is within the verification gate",
                bool((ok.trimmed_rp_error_m.abs() < TOL_RP_M).all()
                     and (ok.trimmed_ra_error_m.abs().fillna(0) < TOL_RA_M).all()
                     and (ok.trimmed_inc_error_deg.abs() < TOL_ANGLE_DEG).all()))
    page.expect("the total of every sample is its burns plus its trim",
                bool(np.allclose(ok.total_delta_v_mps, ok.burns_delta_v_mps
                                 + ok.trim_delta_v_mps, rtol=0, atol=1e-9)))
    page.headline(_headline(page, rows))


def _headline(page: Page, rows: list) -> str:
    """The page's finding: the 99 % budgets with the trim where bounded, else the largest."""
    t = page.text
    engines = [(n, f"{n} N") for n in (150, 300, 450)]
    trim = page.listing([(f"trim_top_{n}N", lab) for n, lab in engines], ".2f", " m/s")
    flown = f"*{capture_name('fixed')}*, re-planned from estimates, trimmed"
    if all(r["samples"] >= r["samples_needed_p99"] for r in rows):
        budget = page.listing([(f"p99_above_{n}N", lab) for n, lab in engines], ".1f",
                              " m/s")
        what = f"the 99 % ΔV budget lies {budget} above the nominal ({flown})"
    else:
        worst = page.listing([(f"max_above_{n}N", lab) for n, lab in engines], ".2f",
                             " m/s")
        what = (f"the costliest of {t('n_samples', '.0f')} samples per engine lies {worst} "
                f"above the nominal ({flown}); a 99 % budget needs "
                f"{t('samples_needed_p99', '.0f')} samples")
    return (f"Under the example (assumed) error model, {what}; the trim alone costs up to "
            f"{trim} at {t('trim_top_what')}; {t('n_failed', '.0f')} samples failed.")


def _show_budget(page: Page, budget, tables: dict, samples: int, seed: int,
                 dynamics: str, path) -> None:
    """The example budget's table, the trim, the CDF, convergence (if bounded), failures."""
    need = disp.samples_needed(0.99)
    page.table("budget", budget, caption=(
        f"The capture's ΔV budget under the *example* error model ({samples} samples per "
        f"engine, seed {seed}, {dynamics} dynamics): the 99 % point above the nominal with "
        f"its distribution-free 95 % interval (from {need} samples), with the trim and for "
        f"the burns alone. Every sample: {page.data_link(path, 'samples.csv')}."),
        show_columns=BUDGET_SHOWN, columns=BUDGET_HEADS,
        floatfmt={c: ".2f" for c in BUDGET_SHOWN} | {"p_failure": ".3f"})
    page.table("trim", budget, caption=(
        "The final orbit before the trim (errors against the target at the plan's end) and "
        "the trim that returns it to the plan's final orbit (two impulses, corrected in the "
        "plan's dynamics), over the captured samples; after it, every orbit is within the "
        "verification gate."),
        show_columns=TRIM_SHOWN, columns=TRIM_HEADS,
        floatfmt={"trim_p50_mps": ".2f", "trim_max_mps": ".2f",
                  "trimmed_max_abs_rp_error_m": ".2f"})
    page.figure("cdf", draw.plot_cdf(tables), caption=(
        "Cumulative distribution of the capture's ΔV above its nominal per engine: with "
        "the trim (solid), the burns alone (dashed). Dotted: 99 %."),
        alt="CDF of the delta-V above nominal per engine, with and without the trim")
    page.figure("trim_orbit", draw.plot_trim(tables), caption=(
        "Left: each captured sample's final perilune and apolune errors before the trim. "
        "Right: the cumulative distribution of its trim's ΔV."),
        alt="Final-orbit errors before the trim and the distribution of the trim")
    conv = plot_convergence(tables)
    if conv is not None:
        page.figure("convergence", conv, caption=(
            f"The 99 % ΔV above the nominal (trim included) from the first N samples, with "
            f"its distribution-free 95 % interval, from N = {need} on."),
            alt="Convergence of the 99 % budget with the number of samples")
    page.table("failures", failure_rows(tables), caption=(
        "Every sample not captured or not corrected, with its reason."), floatfmt=".0f")


def _counts_note(page: Page, bounded: bool) -> str:
    """What this run's sample counts support (the 99 % point, or the count it needs)."""
    t = page.text
    if bounded:
        return (f"{t('n_samples', '.0f')} samples per engine bound the 99 % point: its "
                f"distribution-free 95 % interval from order statistics has both ends from "
                f"{t('samples_needed_p99', '.0f')} samples on, and the page prints it.")
    return (f"{t('n_samples', '.0f')} samples per engine bound no 99 % point: its "
            f"distribution-free 95 % interval needs {t('samples_needed_p99', '.0f')} samples "
            f"before it has an upper end, so the page prints the mean and the costliest "
            f"sample instead and says what the percentile needs.")


def _budget_note(page: Page, bounded: bool) -> str:
    """The budget's sentence: the 99 % points with and without the trim, or the largest."""
    engines = [(n, f"{n} N") for n in (150, 300, 450)]
    if bounded:
        with_trim = page.listing([(f"p99_above_{n}N", lab) for n, lab in engines], ".2f",
                                 " m/s")
        burns = page.listing([(f"p99_burns_above_{n}N", lab) for n, lab in engines], ".2f",
                             " m/s")
        return (f"The 99 % point of the ΔV above the nominal, trim included, is {with_trim}; "
                f"the burns alone would read {burns}, a budget that leaves the final "
                f"orbit's error uncorrected.")
    worst = page.listing([(f"max_above_{n}N", lab) for n, lab in engines], ".2f", " m/s")
    return (f"The costliest sample, trim included, lies {worst} above the nominal: not a "
            f"99 % budget, which needs {page.text('samples_needed_p99', '.0f')} samples.")


def _values(page: Page, model, sig: dict, rows: list, budget, tables: dict, runs: list,
            samples: int, seed: int, dynamics: str) -> None:
    """The numbers the page's prose quotes (glue)."""
    page.value("n_samples", int(samples))
    page.value("seed", int(seed))
    page.value("dynamics", dynamics)
    page.value("error_model", model.describe())
    page.value("samples_needed_p99", int(disp.samples_needed(0.99)))
    for k, v in sig.items():
        page.value(k, float(v))
    need = disp.samples_needed(0.99)
    for r in rows:
        tag = r["plan"].split("-")[-1]
        few = f"a 99 % point needs {need} samples, this run has {r['samples']}"
        bounded = r["samples"] >= need
        page.value(f"mean_above_{tag}", float(r["mean_above_nominal_mps"]))
        page.value(f"max_above_{tag}", float(r["max_above_nominal_mps"]))
        page.value(f"nominal_{tag}", float(r["nominal_delta_v_mps"]))
        page.value(f"p99_above_{tag}", r["budget_p99_above_nominal_mps"] if bounded else None,
                   few)
        page.value(f"p99_burns_above_{tag}",
                   r["budget_p99_burns_above_nominal_mps"] if bounded else None, few)
        page.value(f"trim_p99_{tag}", r["trim_p99_mps"] if bounded else None, few)
        page.value(f"trim_top_{tag}", r["trim_p99_mps"] if bounded else r["trim_max_mps"])
        page.value(f"trim_median_{tag}", r["trim_p50_mps"])
        page.value(f"final_max_rp_{tag}", r["final_max_abs_rp_error_km"])
        page.value(f"final_rms_rp_{tag}", r["final_rms_rp_error_km"])
    bounded = all(r["samples"] >= need for r in rows)
    page.value("trim_top_what", "the 99 % point" if bounded else "the largest sample")
    page.note("counts_note", _counts_note(page, bounded))
    page.note("budget_note", _budget_note(page, bounded))
    page.value("median_sample_s", float(budget.median_sample_s.median()))
    page.value("median_sample_cpu_s", float(budget.median_sample_cpu_s.median()))
    every = pd.concat(tables.values())
    page.value("n_samples_all", int(len(every)))
    page.value("samples_cpu_s", float(sample_cpu_s(every).sum()))
    page.value("wall_s", float(sum(r["wall_s"] for r in runs)))
    page.value("n_failed", int((every.status != "ok").sum()))
