"""The dispersions page (notebooks/dispersions.ipynb): the delta-V budget under errors.

For each plan (the paper's three engines),
:func:`lunarcap.studies.dispersions.samples.run_dispersions` flies ``samples`` captures with
execution, arrival and knowledge errors, re-planned after every burn (run on Dask, resumed from
``<cache>/study/<output_name>.csv``), under an
*example* error model whose values are assumptions (:data:`DEFAULT_SIGMAS`, the page's
assumptions table). :func:`build` shows the example budget (the mean above the nominal
and the largest sample; a percentile only where the samples bound its interval, else how
many samples it needs), a CDF per engine, and the **sensitivities**: each error source
alone at ``sensitivity_factors`` times its example sigma, the others 0, on the same draws
(:mod:`lunarcap.studies.dispersions.sensitivity`), one figure per engine and a table of the
laws, so a reader scales the budget to their own sigmas.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from lunarcap.mission.plan import load_plan
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
        expected_s=140,  # measured 141 s wall, load 9-11 on 2 cores, nominals cached
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
#: propellant, final-orbit errors and timings stay in the CSV.
BUDGET_SHOWN = ["engine", "samples", "nominal_delta_v_mps", "impulsive_delta_v_two_body_mps",
                "mean_above_nominal_mps", "mean_above_nominal_se_mps", "max_above_nominal_mps",
                "p99_text", "p_failure"]
BUDGET_HEADS = {"engine": "engine", "samples": "samples",
                "nominal_delta_v_mps": "nominal ΔV (m/s)",
                "impulsive_delta_v_two_body_mps": "impulsive ΔV, two-body (m/s)",
                "mean_above_nominal_mps": "mean above nominal (m/s)",
                "mean_above_nominal_se_mps": "its standard error (m/s)",
                "max_above_nominal_mps": "largest sample above nominal (m/s)",
                "p99_text": "99 % above nominal (m/s) [95 % interval]",
                "propellant_p99_kg": "propellant 99 % (kg)",
                "p_failure": "P(not captured or not corrected)",
                "final_rms_rp_error_km": "final r_p error RMS (km)",
                "final_rms_inc_error_deg": "final i error RMS (deg)",
                "median_sample_s": "median s per sample (wall)",
                "median_sample_cpu_s": "median CPU s per sample"}


def percentile_text(s: dict, q: float = 99.0) -> str:
    """A percentile above the nominal with its interval, or how many samples it needs."""
    need, n = s[f"samples_needed_p{q:g}"], s["samples"]
    if n < need:
        return f"needs {need} samples (has {n})"
    nom = s["nominal_delta_v_mps"]
    lo, hi = (v - nom for v in s[f"delta_v_p{q:g}_ci_mps"])
    return f"{s[f'delta_v_p{q:g}_mps'] - nom:.2f} [{lo:.2f}, {hi:.2f}]"


def sample_cpu_s(table: pd.DataFrame) -> pd.Series:
    """Each sample's CPU time, s (its wall time in tables written before CPU was logged)."""
    return table.task_cpu_s if "task_cpu_s" in table else table.task_wall_s


def budget_row(plan, table: pd.DataFrame) -> dict:
    """One engine's line of the budget table from its samples."""
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
            "samples_needed_p99": s["samples_needed_p99"],
            "mean_above_nominal_mps": s["mean_above_nominal_mps"],
            "mean_above_nominal_se_mps": s["mean_above_nominal_se_mps"],
            "max_above_nominal_mps": float(np.where(table.status == "ok",
                                                    table.total_delta_v_mps.astype(float),
                                                    np.inf).max()) - s["nominal_delta_v_mps"],
            "p_not_captured": s["p_not_captured"],
            "p_correction_failed": s["p_correction_failed"],
            "p_failure": s["p_not_captured"] + s["p_correction_failed"],
            "final_rms_rp_error_km": s["final_rms_rp_error_km"],
            "final_rms_ra_error_km": s["final_rms_ra_error_km"],
            "final_rms_inc_error_deg": s["final_rms_inc_error_deg"],
            "median_sample_s": float(ok.task_wall_s.median()) if len(ok) else math.nan,
            "median_sample_cpu_s": float(cpu.median()) if len(ok) else math.nan}


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


def sensitivity_table(rows: list) -> pd.DataFrame:
    """One row per engine and source: the law of the mean and of the costliest sample."""
    from lunarcap.studies.dispersions.sensitivity import slopes

    out = []
    for engine in dict.fromkeys(r["engine"] for r in rows):
        mine = [dict(r, plan=engine) for r in rows if r["engine"] == engine]
        mean = {s["source"]: s for s in slopes(mine)}
        top = {s["source"]: s for s in slopes(mine, "max_above_nominal_mps")}
        for source, m in mean.items():
            at = max((r for r in mine if r["source"] == source), key=lambda r: r["sigma"])
            out.append({"engine": engine, "source": SOURCE_LABELS[source],
                        "sigma": f"{at['sigma']:g} {at['unit']}",
                        "mean_above_nominal_mps": at["mean_above_nominal_mps"],
                        "mean_exponent": _exponent_text(m["exponent"]),
                        "max_above_nominal_mps": at["max_above_nominal_mps"],
                        "max_exponent": _exponent_text(top[source]["exponent"])})
    return pd.DataFrame(out)


def _exponent_text(exponent: float) -> str:
    """A law's exponent, or why there is none (a value <= 0 or a failed sample)."""
    if math.isfinite(exponent):
        return f"{exponent:.2f}"
    return "none (a value <= 0 or a failure)"


def failure_rows(tables: dict) -> pd.DataFrame:
    """Every sample that was not captured or not corrected, with its reason."""
    rows = []
    for label, t in tables.items():
        for r in t[t.status != "ok"].to_dict("records"):
            rows.append({"engine": label, "sample": int(r["sample"]), "status": r["status"],
                         "reason": r["reason"] or r["error"]})
    if not rows:   # a table is never written empty: say that there is nothing to list
        rows.append({"engine": "all", "sample": None, "status": "none",
                     "reason": "every sample was captured and corrected"})
    return pd.DataFrame(rows, columns=["engine", "sample", "status", "reason"])


def _load(plans, dynamics: str | None, formulation: str | None) -> list:
    """The plans, in ``dynamics`` and ``formulation`` where given (None: each plan's own)."""
    from dataclasses import replace

    loaded = []
    for name in plans:
        p = load_plan(name)
        if dynamics is not None and dynamics != p.dynamics:
            p = p.with_dynamics(dynamics)
        if formulation is not None and formulation != p.formulation:
            p = replace(p, formulation=formulation)
        loaded.append(p)
    return loaded


def _per_engine(loaded: list, res, sres, models, sig: dict) -> tuple[dict, list, list]:
    """Each engine's samples, budget row and sensitivity rows (labelled by the engine).

    Returns ``(tables, rows, srows)``: engine label -> its samples (with its two-body
    impulsive delta-V), the budget rows, and the sensitivity rows with each source's
    example sigma and the factor of the sigma run over it.
    """
    from lunarcap.studies.dispersions import sensitivity as sens

    tables, rows, srows = {}, [], []
    for p in loaded:
        t = res.table[res.table.plan_id == plan_id(p)].copy()
        t["impulsive_delta_v_two_body_mps"] = \
            disp.nominal_totals(p)["impulsive_delta_v_two_body_mps"]
        label = f"{p.engine.thrust_N:g} N / {p.engine.isp_s:g} s"
        tables[label] = t
        rows.append(budget_row(p, t))
        for r in sens.sensitivity_rows(sres.table[sres.table.plan_id == plan_id(p)], models):
            srows.append(dict(r, engine=label, example=sig[r["source"]],
                              factor=r["sigma"] / sig[r["source"]]))
    return tables, rows, srows


def build(plans=("song2011-150N", "song2011-300N", "song2011-450N"), samples: int = 10,
          seed: int = 2011, sigmas: dict | None = None, dynamics: str | None = None,
          workers: int = 2, output_name: str = "dispersions", quick: bool = False,
          formulation: str | None = None, sensitivity_samples: int = 4,
          sensitivity_factors=(1.0, 2.0), sensitivity_plans=None) -> Page:
    """The page (see the module docstring); ``dynamics``, ``formulation`` None: the plans'.

    ``sensitivity_samples`` (antithetic pairs: even) per source, sigma and engine, in the
    same dynamics, seed and table as the example budget; ``sensitivity_plans``: the plans
    (names, a subset of ``plans``) whose sensitivities are run (None: every plan).
    """
    from lunarcap.studies.dispersions import sensitivity as sens

    sig = dict(DEFAULT_SIGMAS, **(sigmas or {}))
    model = disp.ErrorModel(**sig)
    params = dict(plans=list(plans), samples=samples, seed=seed, sigmas=sig,
                  dynamics=dynamics, workers=workers, sensitivity_samples=sensitivity_samples,
                  sensitivity_factors=list(sensitivity_factors),
                  sensitivity_plans=None if sensitivity_plans is None else list(sensitivity_plans))
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(**{
        "re-plans": "each burn after the first re-solved from the estimate of the perilune "
                    "reached, warm-started from the nominal steering, verified"}))
    chosen = plans if sensitivity_plans is None else sensitivity_plans
    unknown = sorted(set(chosen) - set(plans))
    if unknown:  # before any sample is flown
        raise ValueError(f"sensitivity_plans: {unknown} not among the page's plans {list(plans)}")
    loaded = _load(plans, dynamics, formulation)
    out = paths.CACHE / "study" / f"{output_name}.csv"
    res = disp.run_dispersions(loaded, samples, seed, model, out=out, workers=workers,
                               progress=False)
    sens_loaded = [p for name, p in zip(plans, loaded) if name in chosen]
    models, sres = sens.run_sensitivity(sens_loaded, sensitivity_samples, seed, model,
                                        factors=tuple(sensitivity_factors), out=out,
                                        workers=workers, progress=False, antithetic=True)
    runs = [res.run, sres.run]
    tables, rows, srows = _per_engine(loaded, res, sres, models, sig)
    budget = pd.DataFrame(rows)
    dyn = loaded[-1].dynamics
    page.data.update(tables=tables, budget=budget, runs=runs, sensitivity=srows)
    _show_budget(page, budget, tables, samples, seed, dyn, res.path)
    _show_sensitivity(page, srows, sensitivity_factors, sensitivity_samples)
    _values(page, model, sig, rows, budget, tables, runs, samples, seed, dyn)
    page.value("sensitivity_samples", int(sensitivity_samples))
    page.value("n_sensitivity", int(len(sres.table)))
    page.value("sensitivity_cpu_s", float(sample_cpu_s(sres.table).sum()))
    _checks(page, tables, sres.table, rows)
    page.capture("fixed", dyn)
    return page


def _show_sensitivity(page: Page, srows: list, factors, n_samples: int) -> None:
    """One figure per engine of each source's sensitivity, and the table of their laws."""
    for label in dict.fromkeys(r["engine"] for r in srows):
        tag = label.split(" N")[0]
        fig = draw.plot_sensitivity(srows, label, SOURCE_LABELS)
        page.figure(f"sensitivity_{tag}N", fig, caption=(
            f"{label}: the ΔV above the nominal with each error source alone at "
            f"{', '.join(f'{f:g}' for f in factors)} times its example sigma "
            f"(the others 0; {n_samples} samples each, antithetic pairs, the same "
            f"draws for every source and sigma): the mean with its standard error, and "
            f"the costliest sample dashed. A slope of 1 is a linear law, 2 a quadratic "
            f"one."), alt=f"Sensitivity of the delta-V to each error source, {label}")
    page.table("sensitivity", sensitivity_table(srows), caption=(
        "The law of each source (d ln ΔV / d ln sigma between the two sigmas: 1 linear, "
        "2 quadratic) for the mean ΔV above the nominal and for the costliest sample, "
        "with their values at the largest sigma run. For your own sigma s, scale the "
        "value by (s / sigma)^exponent."),
        columns={"engine": "engine", "source": "error source", "sigma": "sigma",
                 "mean_above_nominal_mps": "mean above nominal (m/s)",
                 "mean_exponent": "its exponent",
                 "max_above_nominal_mps": "costliest sample above nominal (m/s)",
                 "max_exponent": "its exponent"},
        floatfmt={"mean_above_nominal_mps": ".4f", "max_above_nominal_mps": ".3f"})


def _checks(page: Page, tables: dict, sensitivity: pd.DataFrame, rows: list) -> None:
    """The page's assertions and its headline."""
    sens_bugs = sensitivity[~sensitivity.status.isin(disp.OK_STATUSES)]
    bugs = pd.concat([t[~t.status.isin(disp.OK_STATUSES)] for t in tables.values()]
                     + [sens_bugs])
    page.expect("no sample ended in an unexpected error (failures are reported, not hidden)",
                bugs.empty, "; ".join(bugs.error.astype(str)))
    page.expect("no percentile is shown that its samples do not bound",
                all(r["samples"] >= r["samples_needed_p99"] or "needs" in r["p99_text"]
                    for r in rows))
    t = page.text
    worst = page.listing([(f"max_above_{n}N", f"{n} N") for n in (150, 300, 450)], ".2f",
                         " m/s")
    page.headline(f"With the page's example error model (assumed sigmas), the costliest of "
                  f"{t('n_samples', '.0f')} samples per engine lies {worst} above the nominal "
                  f"(*{capture_name('fixed')}*, re-planned after each burn from an estimate "
                  f"of the state); a 99 % budget needs {t('samples_needed_p99', '.0f')} "
                  f"samples; {t('n_failed', '.0f')} samples not captured or not corrected.")


def _show_budget(page: Page, budget, tables: dict, samples: int, seed: int,
                 dynamics: str, path) -> None:
    """The example budget's table, CDF, convergence (if bounded) and failures."""
    need = disp.samples_needed(0.99)
    page.table("budget", budget, caption=(
        f"The capture's ΔV budget under the *example* error model (assumed values, see "
        f"the assumptions table; {samples} samples per engine, seed {seed}, {dynamics} "
        f"dynamics): the nominal finite-burn ΔV (the plan solved burn by burn), the "
        f"two-body impulsive ΔV of the same capture, the mean ΔV above the nominal over "
        f"the captured samples with its standard error, the costliest sample, the 99 % "
        f"point with its distribution-free 95 % interval from order statistics where the "
        f"samples bound it (from {need} samples; otherwise the count it needs), and the "
        f"probability that a sample is not captured or not corrected. Every sample, with "
        f"its errors and its reason if it failed: {page.data_link(path, 'samples.csv')}."),
        show_columns=BUDGET_SHOWN, columns=BUDGET_HEADS,
        floatfmt={c: ".2f" for c in BUDGET_SHOWN} | {"final_rms_inc_error_deg": ".4f",
                                                     "p_failure": ".3f",
                                                     "mean_above_nominal_mps": ".3f",
                                                     "mean_above_nominal_se_mps": ".3f",
                                                     "median_sample_s": ".2f",
                                                     "median_sample_cpu_s": ".2f"})
    page.figure("cdf", draw.plot_cdf(tables), caption=(
        "Cumulative distribution of the capture's ΔV above its nominal, per engine, under "
        "the example error model (closed-loop re-planning after each burn; dotted line: "
        "99 %). With fewer samples than the 99 % point needs, the curve's top step is the "
        "costliest sample, not a percentile."),
        alt="CDF of the delta-V above nominal per engine")
    conv = plot_convergence(tables)
    if conv is not None:
        page.figure("convergence", conv, caption=(
            f"The 99 % ΔV above the nominal estimated from the first N samples (the order "
            f"statistic of rank ⌈0.99 N⌉), with its distribution-free 95 % interval, from "
            f"N = {need} on (fewer samples do not bound it)."),
            alt="Convergence of the 99 % budget with the number of samples")
    page.table("failures", failure_rows(tables), caption=(
        "Every sample not captured or not corrected, with its reason."), floatfmt=".0f")


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
    for r in rows:
        tag = r["plan"].split("-")[-1]
        page.value(f"mean_above_{tag}", float(r["mean_above_nominal_mps"]))
        page.value(f"max_above_{tag}", float(r["max_above_nominal_mps"]))
        page.value(f"nominal_{tag}", float(r["nominal_delta_v_mps"]))
    page.value("median_sample_s", float(budget.median_sample_s.median()))
    page.value("median_sample_cpu_s", float(budget.median_sample_cpu_s.median()))
    every = pd.concat(tables.values())
    page.value("n_samples_all", int(len(every)))
    page.value("samples_cpu_s", float(sample_cpu_s(every).sum()))
    page.value("wall_s", float(sum(r["wall_s"] for r in runs)))
    page.value("n_failed", int((every.status != "ok").sum()))
