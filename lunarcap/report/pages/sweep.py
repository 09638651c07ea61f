"""The ignition-sweep page (notebooks/loi_sweep.ipynb), beside the paper's Tables 1-5.

One burn of the paper's plan for several ignition offsets.

The notebook solves every case with the public API (:func:`lunarcap.paper_plan`, then
:func:`lunarcap.solve_burn` per offset: the paper's formulation and model, cached);
:func:`build` shapes those solutions like the paper's table
(:func:`lunarcap.studies.sweeps.sweep_frame`), sets our impulsive delta-V in the same
dynamics beside the paper's, draws delta-V against the ignition offset, and writes the
notes the prose needs (offsets from the paper, outliers, the burn durations) from the
comparison itself.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.paper import audit
from lunarcap.paper import printed as paper
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.figures import sweep as draw
from lunarcap.report.page import Page, solver_description
from lunarcap.studies import sweeps

NOTEBOOK = "notebooks/loi_sweep.ipynb"


def _table(name: str, title: str, thrust_N: float, isp_s: float, loi: int, starts: list,
           quick_start: float, after: str | None = None) -> Execution:
    """One execution of the sweep: a table of the paper (its offsets, min; quick: one).

    An LOI 2 or 3 sweep starts from the best solution of the LOI before, which ``after``
    computes and leaves in the cache.
    """
    return Execution(
        name, title,
        parameters=dict(thrust_N=thrust_N, isp_s=isp_s, loi=loi, starts=starts,
                        previous_starts=None,  # the paper's best earlier offsets (Table B1)
                        dynamics="full"),
        quick_parameters=dict(starts=[quick_start]),
        depends_on=(after,) if after else (),
        outputs=table_files(name, "dv", "duration") + figure_files(name, "dv"))


BOOK = BookPage(NOTEBOOK, "The paper's tables", 10, (
    _table("table1", "Table 1: LOI 1, 150 N / 200 s", 150.0, 200.0, 1,
           [0.0, -6.0, -8.0, -10.0, -12.0, -14.0], -10.0),
    _table("table2", "Table 2: LOI 2, 150 N / 200 s", 150.0, 200.0, 2,
           [0.0, -3.0, -6.0, -9.0], -6.0, "table1"),
    _table("table3", "Table 3: LOI 3, 150 N / 200 s", 150.0, 200.0, 3,
           [0.0, -3.0, -5.0, -7.0], -5.0, "table2"),
    _table("table4_loi1", "Table 4: LOI 1, 300 N / 250 s", 300.0, 250.0, 1,
           [0.0, -2.0, -4.0, -6.0], -4.0),
    _table("table4_loi2", "Table 4: LOI 2, 300 N / 250 s", 300.0, 250.0, 2,
           [0.0, -1.0, -3.0, -5.0], -3.0, "table4_loi1"),
    _table("table4_loi3", "Table 4: LOI 3, 300 N / 250 s", 300.0, 250.0, 3,
           [0.0, -1.0, -2.0, -3.0], -2.0, "table4_loi2"),
    _table("table5_loi1", "Table 5: LOI 1, 450 N / 300 s", 450.0, 300.0, 1,
           [0.0, -2.0, -3.0, -4.0], -3.0),
    _table("table5_loi2", "Table 5: LOI 2, 450 N / 300 s", 450.0, 300.0, 2,
           [0.0, -2.0, -4.0], -2.0, "table5_loi1"),
    _table("table5_loi3", "Table 5: LOI 3, 450 N / 300 s", 450.0, 300.0, 3,
           [0.0, -1.0, -2.0, -3.0], -2.0, "table5_loi2"),
))

#: A row whose ours - paper differs from the median row by more than this (%) is discussed.
OUTLIER_PERCENT = 0.25


def _printed(thrust_N, loi):
    """The paper's table rows, Table B1 best row and source, or Nones for other engines."""
    try:
        printed = paper.paper_table(thrust_N, loi)
        return printed, paper.paper_best(thrust_N, loi), printed.attrs["source"]
    except Exception:  # not one of the paper's engines
        return None, None, None


#: The row of the paper's printed impulse beside ours: ours is the impulsive limit in the
#: same dynamics (the reproduction report sets the two-body impulse beside it instead,
#: under its own label, lunarcap.report.reproduction.IMPULSE_ROW_TWO_BODY).
IMPULSE_ROW_LIMIT = "impulse (ours: impulsive limit)"


def dv_table(sweep: pd.DataFrame, impulsive: dict) -> pd.DataFrame:
    """Delta-V rows: the impulsive burn (paper's and ours), then each finite burn.

    Columns: burn, start_min, paper_delta_v_mps, delta_v_mps, delta_v_diff_mps,
    delta_v_diff_percent, paper_delta_v_loss_percent, loss_vs_paper_impulse_percent, best (paper /
    ours / both),
    verified (passed / failed).
    """
    imp = sweep.attrs["impulsive_delta_v_mps"]
    best = np.select([sweep.best & sweep.paper_best, sweep.paper_best, sweep.best],
                     ["both", "paper", "ours"], "")
    ours = impulsive["delta_v_mps"]
    rows = pd.concat([
        pd.DataFrame([{"burn": IMPULSE_ROW_LIMIT, "paper_delta_v_mps": imp, "delta_v_mps": ours,
                       "delta_v_diff_mps": ours - imp,
                       "delta_v_diff_percent": 100 * (ours - imp) / imp,
                       "paper_delta_v_loss_percent": 0.0, "best": "",
                       "verified": "passed" if impulsive["verification_passed"] else "failed"}]),
        pd.DataFrame({"burn": "finite", "start_min": sweep.start_min,
                      "paper_delta_v_mps": sweep.paper_delta_v_mps,
                      "delta_v_mps": sweep.delta_v_mps,
                      "delta_v_diff_mps": sweep.delta_v_diff_mps,
                      "delta_v_diff_percent": sweep.delta_v_diff_percent,
                      "paper_delta_v_loss_percent": sweep.paper_delta_v_loss_percent,
                      "loss_vs_paper_impulse_percent": sweep.loss_vs_paper_impulse_percent,
                      "best": best,
                      "verified": np.where(sweep.verified, "passed", "failed")}),
    ], ignore_index=True)
    return rows[["burn", "start_min", "paper_delta_v_mps", "delta_v_mps", "delta_v_diff_mps",
                 "delta_v_diff_percent", "paper_delta_v_loss_percent",
                 "loss_vs_paper_impulse_percent", "best",
                 "verified"]]


def _paper_findings(thrust_N: float, loi: int) -> pd.DataFrame:
    """The audit's inconsistent findings about this engine's LOI."""
    findings = audit.findings_table(only_inconsistent=True)
    return findings[findings.id.str.contains(rf"/{thrust_N:g}N/LOI{loi}(?:/|-half|$)")]


def median_offsets(sweep: pd.DataFrame) -> tuple[float, float]:
    """Median ours − paper over the rows, in % and in m/s (NaN without printed rows)."""
    diff_pct = sweep.delta_v_diff_percent
    if not diff_pct.notna().any():
        return np.nan, np.nan
    return float(np.nanmedian(diff_pct)), float(np.nanmedian(sweep.delta_v_diff_mps))


def _offset_notes(sweep: pd.DataFrame, impulsive: dict, thrust_f: pd.DataFrame) -> list:
    """The systematic offset of ours − paper, and the rows far from it."""
    imp = sweep.attrs["impulsive_delta_v_mps"]
    diff_pct = sweep.delta_v_diff_percent
    med_pct, med_mps = median_offsets(sweep)
    out = []
    imp_d = impulsive["delta_v_mps"] - imp
    if abs(med_pct) < 0.05:
        out.append(
            f"**No systematic offset.** Ours − paper is {med_mps:+.3f} m/s "
            f"({med_pct:+.2f} %) in the median row (an impulse in our dynamics from the "
            f"same orbit differs from the paper's impulsive value by {imp_d:+.3f} m/s).")
    else:
        out.append(
            f"**A systematic offset.** Ours − paper is {med_mps:+.3f} m/s "
            f"({med_pct:+.2f} %) in the median row. An impulse in our dynamics from the "
            f"same orbit differs from the paper's impulsive value by {imp_d:+.3f} m/s, "
            f"leaving {med_mps - imp_d:+.3f} m/s in the finite burn itself: the arrival is "
            "our {ref}`reconstruction <arrival>` and LOI 2 and 3 start from our own burns. "
            "Common to every row, it moves neither the best offset nor the curve's shape."
            + (" Here the paper's stronger effective engine (below) adds to it."
               if len(thrust_f) else ""))
    for r in sweep[(diff_pct - med_pct).abs() > OUTLIER_PERCENT].itertuples():
        d = r.delta_v_diff_mps
        why = ("The paper's solution needs more delta-V than our verified optimum: it is "
               "not the minimum (the paper calls its solutions semi-optimal)." if d < 0 else
               "Here the paper found less delta-V than our optimum."
               + (" Its rows for this LOI imply a stronger engine (burn durations, below)."
                  if len(thrust_f) else " We have no explanation."))
        out.append(f"**The {r.start_min:g} min row** differs by {d:+.3f} m/s "
                   f"({r.delta_v_diff_percent:+.2f} %), "
                   f"{r.delta_v_diff_percent - med_pct:+.2f} points from the median row. "
                   f"{why}")
    return out


def _best_offset_note(sweep: pd.DataFrame, best_p) -> list:
    """When our best offset is not the paper's: both delta-Vs and the rule of thumb."""
    eq19_min = float(sweep.eq19_duration_min.iloc[0])
    b = sweep[sweep.best].iloc[0]
    at_pbest = sweep[sweep.paper_best]
    nearest = float(sweep.start_min.iloc[(sweep.start_min + eq19_min / 2).abs().argmin()])
    if not (best_p and b.start_min != best_p["start_min"] and len(at_pbest)):
        return []
    dv_at = float(at_pbest.delta_v_mps.iloc[0])
    return [
        f"**A different best offset.** Our smallest delta-V is at {b.start_min:g} min "
        f"({b.delta_v_mps:.3f} m/s); at the paper's best, {best_p['start_min']:g} min, "
        f"we get {dv_at:.3f} m/s, {dv_at - b.delta_v_mps:.3f} m/s more. The paper's rule "
        f"of thumb (ignite half the Eq. (19) duration, {eq19_min / 2:.2f} min, before "
        f"perilune) points at {nearest:g} min."]


def _duration_notes(sweep: pd.DataFrame, printed, findings: pd.DataFrame, thrust_N: float,
                    reproduction_report_linked: bool) -> list:
    """Our burn durations against the paper's, and the paper's implied thrust if any."""
    thrust_f = findings[findings.id.str.startswith("thrust/")]
    out = []
    dur_med = round(float(np.nanmedian(sweep.burn_duration_diff_min)), 2) + 0.0 \
        if sweep.burn_duration_diff_min.notna().any() else np.nan
    big_dur = sweep[(sweep.burn_duration_diff_min - dur_med).abs() > 0.05]
    if len(thrust_f):
        f = thrust_f.iloc[0]
        link = ("{doc}`reproduction report <reproduction_report>`"
                if reproduction_report_linked else "reproduction report")
        out.append(
            f"**Burn durations.** The paper's are shorter than ours by {dur_med:.2f} min in "
            f"the median row: by the rocket equation its rows for this LOI imply "
            f"{f.computed:.0f} N, not {thrust_N:g} N (its other LOIs: {thrust_N:g} N; "
            f"finding `{f.id}`, {link}), so its losses here are smaller than a "
            f"{thrust_N:g} N engine gives.")
    elif printed is not None and len(sweep) > 1:
        tail = "."
        if len(big_dur):
            tail = (". Rows off that by more than 0.05 min: "
                    + ", ".join(f"{r.start_min:g} min ({r.burn_duration_diff_min:+.2f} min)"
                                for r in big_dur.itertuples())
                    + (" (audit notes below)." if len(findings) else "."))
        out.append(f"**Burn durations.** Ours − paper is {dur_med:+.2f} min in the median row "
                   f"(the paper prints 0.01 min){tail}")
    return out


def _findings_note(findings: pd.DataFrame) -> list:
    """The audit's findings about this table, as a dropdown admonition."""
    if not len(findings):
        return []
    items = "\n".join(f"* **{r.where.split(' (also')[0]}**, {r.quantity}: printed "
                      f"{r.printed:g} {r.unit}, recomputed {r.computed:.4g} {r.unit}."
                      for r in findings.itertuples())
    return [":::{admonition} Where the paper contradicts itself in this table "
            "(`lunarcap.paper.audit`; how each is recomputed: the reproduction report)"
            "\n:class: dropdown\n\n" + items + "\n:::"]


def notes(sweep: pd.DataFrame, impulsive: dict, printed, best_p, thrust_N, loi,
          reproduction_report_linked: bool) -> list[str]:
    """The notes the comparison calls for (MyST paragraphs), each only when the data do."""
    findings = _paper_findings(thrust_N, loi)
    thrust_f = findings[findings.id.str.startswith("thrust/")]
    out = []
    if printed is not None and len(sweep) > 1:
        out += _offset_notes(sweep, impulsive, thrust_f)
    if printed is not None:
        out += _best_offset_note(sweep, best_p)
    out += _duration_notes(sweep, printed, findings, thrust_N, reproduction_report_linked)
    if printed is None:
        out.append("This engine is not one of the paper's: there is nothing to compare with.")
    return out + _findings_note(findings)


def prose_values(sweep: pd.DataFrame, impulsive: dict, best_p) -> dict:
    """The numbers the prose quotes (NaN where the paper prints nothing to compare)."""
    nan = float("nan")
    imp = sweep.attrs["impulsive_delta_v_mps"]
    eq19_min = float(sweep.eq19_duration_min.iloc[0])
    b = sweep[sweep.best].iloc[0]
    diff_pct = sweep.delta_v_diff_percent
    at_pbest = sweep[sweep.paper_best]
    has = diff_pct.notna().any()
    values = {
        "best_start_min": b.start_min, "best_delta_v_mps": b.delta_v_mps,
        "best_burn_min": b.burn_duration_min, "best_loss_percent": b.loss_vs_paper_impulse_percent,
        "best_loss_mps": b.delta_v_mps - imp,
        "paper_best_start_min": best_p["start_min"] if best_p else nan,
        "paper_best_delta_v_mps": best_p["delta_v_mps"] if best_p else nan,
        "paper_best_burn_min": best_p["burn_duration_min"] if best_p else nan,
        "paper_best_loss_percent": best_p["diff_percent"] if best_p else nan,
        "best_diff_mps": b.delta_v_mps - best_p["delta_v_mps"] if best_p else nan,
        "best_diff_percent": 100 * (b.delta_v_mps / best_p["delta_v_mps"] - 1)
        if best_p else nan,
        "dv_at_paper_best_mps": at_pbest.delta_v_mps.iloc[0] if len(at_pbest) else nan,
        "diff_min_percent": float(np.nanmin(diff_pct)) if has else nan,
        "diff_max_percent": float(np.nanmax(diff_pct)) if has else nan,
        "diff_median_percent": float(np.nanmedian(diff_pct)) if has else nan,
        "diff_median_mps": float(np.nanmedian(sweep.delta_v_diff_mps)) if has else nan,
        "impulsive_mps": imp, "ours_impulsive_mps": impulsive["delta_v_mps"],
        "impulsive_diff_mps": impulsive["delta_v_mps"] - imp,
        "eq19_min": eq19_min, "eq19_half_min": eq19_min / 2,
        "n_cases": len(sweep), "n_verified": int(sweep.verified.sum()),
    }
    return values


def _add_items(page: Page, sweep: pd.DataFrame, impulsive: dict, printed, case: str,
               source, loi: int, thrust_N: float, isp_s: float) -> None:
    imp = sweep.attrs["impulsive_delta_v_mps"]
    page.table(
        "dv", dv_table(sweep, impulsive),
        caption=(f"Delta-V of {case}. Start: min from the nominal perilune. Δ: ours − paper. "
                 f"Loss: above the paper's impulse, {imp:.3f} m/s. Best: the smallest "
                 "tested."),
        columns={"delta_v_mps": "ΔV, ours (m/s)", "delta_v_diff_mps": "Δ (m/s)",
                 "delta_v_diff_percent": "Δ (%)", "paper_delta_v_loss_percent": "loss, paper (%)",
                 "loss_vs_paper_impulse_percent": "loss, ours (%)", "verified": "gate"},
        floatfmt={"start_min": "g", "paper_delta_v_mps": ".3f", "delta_v_mps": ".3f",
                  "delta_v_diff_mps": "+.3f", "delta_v_diff_percent": "+.2f",
                  "paper_delta_v_loss_percent": ".2f", "loss_vs_paper_impulse_percent": ".2f"},
        paper=source and f"{source}, delta-V")
    eq19_min = float(sweep.eq19_duration_min.iloc[0])
    page.table(
        "duration", sweep[["start_min", "paper_burn_duration_min", "burn_duration_min",
                           "burn_duration_diff_min"]],
        caption=(f"Burn durations (min) of {case}. Start: min from the nominal perilune. "
                 f"Eq. (19) from the two-body impulse and our mass at ignition: "
                 f"{eq19_min:.2f} min."),
        columns={"burn_duration_min": "duration, ours (min)",
                 "burn_duration_diff_min": "ours − paper (min)"},
        floatfmt={"start_min": "g", "paper_burn_duration_min": ".2f",
                  "burn_duration_min": ".2f", "burn_duration_diff_min": "+.2f"},
        paper=source and f"{source}, burn durations")
    page.figure(
        "dv_figure", draw.plot_sweep_dv(sweep, printed, f"Song et al. (2011), {source}"),
        caption=(f"Delta-V (m/s) of LOI {loi} ({thrust_N:g} N / Isp {isp_s:g} s) against the "
                 "ignition offset (min): ours (filled, star: smallest), the paper's (open), "
                 "its impulse (dotted), half the Eq. (19) duration "
                 f"({eq19_min:.2f} min) before perilune (dashed)."),
        alt=f"Delta-V of LOI {loi} against ignition offset, ours and the paper's", name="dv")


def _add_checks(page: Page, sweep: pd.DataFrame, impulsive: dict, best_p, values: dict,
                dynamics: str) -> None:
    """Headline checks: the book build fails if the reproduction drifts."""
    b = sweep[sweep.best].iloc[0]
    page.expect("every solution passes the verification gate", bool(sweep.verified.all()),
                str(sweep[~sweep.verified].start_min.tolist()))
    page.expect("the impulsive limit passes the gate", impulsive["verification_passed"])
    page.expect("one best row, the smallest delta-V",
                sweep.best.sum() == 1 and b.delta_v_mps == sweep.delta_v_mps.min())
    if best_p is not None and dynamics == "full":
        # our best delta-V within 0.5 % of Table B1 (measured: within 0.25 %)
        page.expect("best delta-V within 0.5 % of Table B1",
                    abs(values["best_diff_percent"]) < 0.5, f"{values['best_diff_percent']:.3f} %")


def sweep_of(burns) -> tuple[pd.DataFrame, dict]:
    """The sweep table and the impulsive limit of one LOI solved at several ignitions.

    ``burns``: :func:`lunarcap.solve_burn` of one burn of the paper's plan
    (:func:`lunarcap.paper_plan`), one per ignition offset, the earlier burns the same in
    each, solved with their impulsive limit (``impulsive=True``, the default). Returns
    :func:`lunarcap.studies.sweeps.sweep_frame` of their solutions and the burn's
    impulsive limit in the same dynamics from the same orbit (the same for every offset).
    """
    b = burns[0]
    plan, loi = b.plan, b.burn
    prev = tuple(x.start_min for x in plan.burns[:loi - 1])
    sweep = sweeps.sweep_frame([x.solution for x in burns], plan.engine.thrust_N,
                               plan.engine.isp_s, loi, prev, str(plan.dynamics))
    return sweep, b.result.impulsive


def build(burns, output_name: str = "loi_sweep", quick: bool = False,
          parameters: dict | None = None, reproduction_report_linked: bool = True) -> Page:
    """The page of one ignition sweep computed in the notebook (see the module docstring).

    Parameters
    ----------
    burns : list of lunarcap.BurnSolution
        :func:`lunarcap.solve_burn` of one burn of the paper's plan
        (:func:`lunarcap.paper_plan`) at each ignition offset, in the table's order, each
        with its impulsive limit (:func:`sweep_of`).
    output_name, quick : the page's output name and whether it is a quick build.
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance.
    reproduction_report_linked : bool
        Whether the notes may link the reproduction report (a page of the same book).
    """
    sweep, impulsive = sweep_of(burns)
    a = sweep.attrs
    thrust_N, isp_s, loi, dynamics = a["thrust_N"], a["isp_s"], a["loi"], a["dynamics"]
    prev = a["previous_starts_min"]
    params = {k: list(v) if isinstance(v, (list, tuple)) else v
              for k, v in (parameters or {}).items()}
    page = Page(NOTEBOOK, params, output_name, quick, solver_description())
    printed, best_p, source = _printed(thrust_N, loi)
    prev_txt = ", ".join(s if isinstance(s, str) else f"{s:g}" for s in prev)
    case = (f"LOI {loi}, {thrust_N:g} N / Isp {isp_s:g} s, {dynamics} dynamics"
            + (f"; the earlier LOIs ignite at {prev_txt} min" if prev else ""))
    _add_items(page, sweep, impulsive, printed, case, source, loi, thrust_N, isp_s)
    values = prose_values(sweep, impulsive, best_p)
    for k, v in values.items():
        page.value(k, float(v))
    page.note("notes", "\n\n".join(notes(sweep, impulsive, printed, best_p, thrust_N, loi,
                                         reproduction_report_linked)) or "Nothing to note.")
    _add_checks(page, sweep, impulsive, best_p, values, dynamics)
    page.data["sweep"] = sweep  # the raw table, for readers who want it in the notebook
    t = page.text
    page.headline(f"Smallest ΔV at {t('best_start_min', '.0f')} min: "
                  f"{t('best_delta_v_mps', '.3f', ' m/s')}, {t('best_diff_mps', '+.3f', ' m/s')} "
                  f"from the paper's best ({t('paper_best_delta_v_mps', '.3f', ' m/s')} at "
                  f"{t('paper_best_start_min', '.0f')} min); {t('n_verified', '.0f')} of "
                  f"{t('n_cases', '.0f')} verified ({dynamics} dynamics).")
    page.capture("fixed", dynamics)
    return page
