"""The other-engines page (notebooks/other_engines.ipynb): LRO- and SELENE-class engines.

Song et al. (2011, Sec. 3.1) chose their three engines after those of LRO (about 320 N,
Isp 200 s) and SELENE (about 500 N, Isp 300 s), which they did not analyse. The notebook
flies the paper's capture plan (:func:`lunarcap.paper_plan`, the paper's spacecraft and
orbits) with those engines and with the paper's own, every ignition free by default
(:func:`lunarcap.solve`); :func:`build` sets each beside the paper's printed numbers
(:func:`sequence_of`).

Two impulsive references, named wherever a loss is shown:

* **vs paper**: delta-V above the paper's printed impulsive delta-V of each LOI (Table
  B1: 353.272, 254.034, 245.363 m/s), the reference of the paper's Tables 1-5;
* **vs ours** (``model_loss``): against our impulsive limit of the same burn, one
  impulse in the same dynamics from the same pre-burn orbit
  (:func:`lunarcap.capture.chain.impulsive_limit`, as :func:`lunarcap.capture.chain.plan_result`),
  measured by the objective of Eq. (9) (:func:`lunarcap.capture.chain.burn_loss`: delta-V
  plus the speed left at the next perilune), as on the trade-study page; the plain
  delta-V difference ("ΔV above ours") is in the CSV.

The figure, and the numbers the prose quotes beside it (``plotted_*`` values), use "vs
ours" when ``model_loss`` is on, else "vs paper"; the note ``loss_note`` says which and
gives the other.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper.printed import PAPER_IMPULSIVE_DV_MPS, paper_best
from lunarcap.quantities import capture_name
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.display import verdict
from lunarcap.report.figures import other_engines as draw
from lunarcap.report.page import Page, solver_description
from lunarcap.studies import sweeps

NOTEBOOK = "notebooks/other_engines.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 50, (
    Execution(
        "other_engines", "LRO-class and SELENE-class engines (Sec. 3.1)",
        parameters=dict(engines=[[320.0, 200.0], [500.0, 300.0]],  # Sec. 3.1: LRO, SELENE
                        engine_names=["LRO-class", "SELENE-class"],
                        starts=["free", "free", "free"], dynamics="full", model_loss=True),
        quick_parameters=dict(engines=[[320.0, 200.0]], engine_names=["LRO-class"],
                              paper_engines=[], model_loss=False, dynamics="two-body"),
        outputs=(table_files("other_engines", "burns", "losses", "totals", "budget")
                 + figure_files("other_engines", "loss"))),
))

#: Origin of the paper's own engines in the tables and the figure.
PAPER_ENGINE = "paper's engine"

#: Engines the prose quotes by thrust (glued values are NaN for an engine not built).
PROSE_THRUSTS_N = (320.0, 500.0, 150.0, 300.0, 450.0)

#: Display labels of the loss columns: each names its impulsive reference.
LOSS_LABELS = {
    "engine": "engine (thrust / Isp)",
    "loss_vs_paper_impulse_mps": "loss vs paper (m/s)",
    "loss_vs_paper_impulse_percent": "loss vs paper (%)",
    "impulsive_limit_mps": "impulsive ΔV, ours (m/s)",
    "delta_v_loss_mps": "ΔV above ours (m/s)", "delta_v_loss_percent": "ΔV above ours (%)",
    "objective_loss_mps": "loss vs ours (m/s)", "objective_loss_percent": "loss vs ours (%)",
    "total_loss_vs_paper_impulse_mps": "loss vs paper (m/s)",
    "total_loss_vs_paper_impulse_percent": "loss vs paper (%)",
    "total_delta_v_loss_mps": "ΔV above ours (m/s)",
    "total_delta_v_loss_percent": "ΔV above ours (%)",
    "total_objective_loss_mps": "loss vs ours (m/s)",
    "total_objective_loss_percent": "loss vs ours (%)",
    "burn_duration_min_loi1": "LOI 1 burn (min)",
}

REF_PAPER = ("the paper's printed impulsive ΔV of each LOI (Table B1: "
             + ", ".join(f"{x:.3f}" for x in PAPER_IMPULSIVE_DV_MPS) + " m/s)")
REF_OURS = ("our impulsive limit of each burn (same dynamics, same pre-burn orbit), by the "
            "objective J of Eq. (9)")


def _start_text(starts) -> str:
    return "free" if all(s == "free" for s in starts) else f"{list(starts)} min"


def engine_rows(engines, engine_names, paper_engines):
    """``[(thrust_N, isp_s, origin, label)]``: the cited engines, then the paper's not cited."""
    if len(engine_names) != len(engines):
        raise ValueError("engine_names needs one name per engine")
    rows = [(float(t), float(i), str(n), f"{n}, {t:g} N / {i:g} s")
            for (t, i), n in zip(engines, engine_names)]
    cited = {(t, i) for t, i, _, _ in rows}
    rows += [(float(t), float(i), PAPER_ENGINE, f"paper, {t:g} N / {i:g} s")
             for t, i in paper_engines if (float(t), float(i)) not in cited]
    return rows


def burns_frame(seqs: dict, rows, model_loss: bool) -> pd.DataFrame:
    """One row per burn of the cited engines (not the paper's), with engine and origin.

    ``seqs`` maps an engine label to its :func:`lunarcap.studies.sweeps.sequence_table`;
    ``rows`` are :func:`engine_rows`; verified becomes "passed" / "failed".
    """
    burns = pd.concat([seqs[lab].assign(engine=lab, origin=o, thrust_N=t, isp_s=i)
                       for t, i, o, lab in rows if o != PAPER_ENGINE], ignore_index=True)
    burns = burns.assign(verified=burns.verified.map(verdict))
    cols = ["engine", "origin", "thrust_N", "isp_s", "loi", "start_min", "burn_duration_min",
            "delta_v_mps", "fuel_kg", "m_end_kg", "verified", "paper_impulsive_delta_v_mps",
            "loss_vs_paper_impulse_mps", "loss_vs_paper_impulse_percent"]
    cols += ["impulsive_limit_mps", "delta_v_loss_mps", "delta_v_loss_percent",
             "objective_loss_mps", "objective_loss_percent"] if model_loss else []
    return burns[cols]


def totals_frame(seqs: dict, rows, model_loss: bool) -> pd.DataFrame:
    """One row per engine, sorted by thrust: the totals of its capture sequence."""
    trows = []
    for t, i, o, lab in sorted(rows, key=lambda r: (r[0], r[1])):
        x = sweeps.sequence_totals(seqs[lab])
        row = {"engine": lab, "origin": o, "thrust_N": t, "isp_s": i,
               "total_delta_v_mps": x["total_delta_v_mps"],
               "total_paper_impulsive_delta_v_mps": x["total_paper_impulsive_delta_v_mps"],
               "total_loss_vs_paper_impulse_mps": x["total_loss_vs_paper_impulse_mps"],
               "total_loss_vs_paper_impulse_percent": x["total_loss_vs_paper_impulse_percent"]}
        if model_loss:
            row.update({k: x[k] for k in ("total_impulsive_limit_mps",
                                          "total_delta_v_loss_mps", "total_delta_v_loss_percent",
                                          "total_objective_loss_mps",
                                          "total_objective_loss_percent")})
        row.update({"total_fuel_kg": x["total_fuel_kg"],
                    "total_burn_duration_min": x["total_burn_duration_min"],
                    "burn_duration_min_loi1": float(seqs[lab].burn_duration_min.iloc[0]),
                    "final_mass_kg": x["final_mass_kg"]})
        trows.append(row)
    return pd.DataFrame(trows)


def loss_columns(model_loss: bool) -> tuple[str, str, str]:
    """The plotted loss column, its % column and the short name of its reference."""
    if model_loss:
        return ("total_objective_loss_mps", "total_objective_loss_percent",
                "our impulsive limits")
    return ("total_loss_vs_paper_impulse_mps", "total_loss_vs_paper_impulse_percent",
            "the paper's impulsive ΔVs")


def _by_thrust(totals: pd.DataFrame, seqs: dict, rows) -> tuple[dict, dict]:
    """Totals row and sequence per thrust (N); the first engine of a thrust wins."""
    by_thrust = {}
    for r in totals.itertuples():
        by_thrust.setdefault(float(r.thrust_N), r)
    seq_by_thrust = {t: seqs[lab] for t, i, o, lab in reversed(rows)}
    return by_thrust, seq_by_thrust


def prose_values(totals: pd.DataFrame, seqs: dict, rows, model_loss: bool) -> dict:
    """The numbers the prose quotes, per thrust of :data:`PROSE_THRUSTS_N` (NaN if absent)."""
    nan = float("nan")
    loss_col, pct_col, _ = loss_columns(model_loss)
    by_thrust, seq_by_thrust = _by_thrust(totals, seqs, rows)
    out = {}
    for thrust in PROSE_THRUSTS_N:
        tag = f"{thrust:g}N"
        r, s = by_thrust.get(thrust), seq_by_thrust.get(thrust)
        out[f"plotted_loss_mps_{tag}"] = float(getattr(r, loss_col)) if r else nan
        out[f"plotted_loss_percent_{tag}"] = float(getattr(r, pct_col)) if r else nan
        out[f"total_paper_loss_mps_{tag}"] = \
            float(r.total_loss_vs_paper_impulse_mps) if r else nan
        out[f"total_paper_loss_percent_{tag}"] = \
            float(r.total_loss_vs_paper_impulse_percent) if r else nan
        for key in ("total_delta_v_mps", "total_fuel_kg", "total_burn_duration_min",
                    "final_mass_kg"):
            out[f"{key}_{tag}"] = float(getattr(r, key)) if r else nan
        for n in (1, 2, 3):
            out[f"burn_loi{n}_{tag}_min"] = (float(s.burn_duration_min.iloc[n - 1])
                                             if s is not None else nan)
            out[f"dv_loi{n}_{tag}_mps"] = (float(s.delta_v_mps.iloc[n - 1])
                                           if s is not None else nan)
    # same Isp, twice the thrust: the LRO-class engine against the paper's 150 N (both 200 s)
    lc = "objective_loss_mps" if model_loss else "loss_vs_paper_impulse_mps"
    a, b = seq_by_thrust.get(150.0), seq_by_thrust.get(320.0)
    both = a is not None and b is not None
    out["loss_ratio_150_320"] = float(a[lc].iloc[0] / b[lc].iloc[0]) if both else nan
    out["duration_ratio_sq_150_320"] = (
        float((a.burn_duration_min.iloc[0] / b.burn_duration_min.iloc[0]) ** 2) if both else nan)
    return out


def _add_burn_tables(page: Page, burns: pd.DataFrame, case: str, model_loss: bool) -> None:
    page.table(
        "burns", burns,
        caption=(f"The capture flown by the engines cited in Sec. 3.1 of the paper, on {case}. "
                 "Start: min from each nominal perilune; verified: passed the re-propagation "
                 "gate. Losses: next table."),
        columns=LOSS_LABELS | {"engine": "engine"},
        floatfmt={"start_min": ".2f", "burn_duration_min": ".2f", "delta_v_mps": ".3f",
                  "fuel_kg": ".3f", "m_end_kg": ".3f"},
        show_columns=["engine", "loi", "start_min", "burn_duration_min", "delta_v_mps",
                      "fuel_kg", "m_end_kg", "verified"])
    loss_cols = ["engine", "loi", "paper_impulsive_delta_v_mps", "loss_vs_paper_impulse_mps",
                 "loss_vs_paper_impulse_percent"]
    loss_cols += ["impulsive_limit_mps", "objective_loss_mps"] if model_loss else []
    page.table(
        "losses", burns[loss_cols + (["objective_loss_percent", "delta_v_loss_mps",
                                      "delta_v_loss_percent"] if model_loss else [])],
        caption=("Loss of each burn of the same captures against "
                 + ("two impulsive references. " if model_loss else "an impulsive reference. ")
                 + f"Vs paper: ΔV above {REF_PAPER}, as Tables 1–5"
                 + (f"; vs ours: against {REF_OURS}" if model_loss else
                    "; vs our own impulsive limit: not computed in this build")
                 + "."),
        columns=LOSS_LABELS | {"engine": "engine"},
        floatfmt={"paper_impulsive_delta_v_mps": ".3f", "loss_vs_paper_impulse_mps": ".3f",
                  "loss_vs_paper_impulse_percent": ".3f", "impulsive_limit_mps": ".3f",
                  "delta_v_loss_mps": ".3f", "delta_v_loss_percent": ".3f",
                  "objective_loss_mps": ".3f", "objective_loss_percent": ".3f"},
        show_columns=loss_cols)


def _add_totals_tables(page: Page, totals: pd.DataFrame, ignition: str,
                       model_loss: bool) -> None:
    paper_total = float(sum(PAPER_IMPULSIVE_DV_MPS))
    shown = ["engine", "total_delta_v_mps", "total_loss_vs_paper_impulse_mps",
             "total_loss_vs_paper_impulse_percent"]
    shown += ["total_objective_loss_mps", "total_objective_loss_percent"] if model_loss else []
    page.table(
        "totals", totals,
        caption=(f"Totals of the capture sequence per engine (thrust / Isp), ignition "
                 f"{ignition}: total ΔV of the three LOIs (m/s); loss vs paper: above the "
                 f"paper's impulsive ΔVs, m/s and % of their total {paper_total:.3f} m/s"
                 + ("; loss vs ours: against our impulsive limits in the same dynamics, by "
                    "the objective of Eq. (9), m/s and % of their total (the CSV adds the "
                    "plain ΔV above them)" if model_loss else "")
                 + ". Propellant, burn times and final mass: next table."),
        columns=LOSS_LABELS,
        floatfmt={"total_delta_v_mps": ".3f", "total_loss_vs_paper_impulse_mps": ".3f",
                  "total_loss_vs_paper_impulse_percent": ".3f", "total_delta_v_loss_mps": ".3f",
                  "total_delta_v_loss_percent": ".3f", "total_objective_loss_mps": ".3f",
                  "total_objective_loss_percent": ".3f"},
        show_columns=shown)
    page.table(
        "budget", totals[["engine", "total_fuel_kg", "total_burn_duration_min",
                          "burn_duration_min_loi1", "final_mass_kg"]],
        caption=(f"Propellant of LOI 1–3 (kg), burn time of the three LOIs and of LOI 1 (min) "
                 f"and mass after LOI 3 (kg, from {paper_scenario().mass_kg:g} kg) per engine "
                 f"(thrust / Isp), ignition {ignition}."),
        columns=LOSS_LABELS | {"total_fuel_kg": "propellant (kg)",
                               "total_burn_duration_min": "burn time (min)"},
        floatfmt={"total_fuel_kg": ".3f", "total_burn_duration_min": ".2f",
                  "burn_duration_min_loi1": ".2f", "final_mass_kg": ".3f"})


def _add_figure(page: Page, totals: pd.DataFrame, ignition: str, model_loss: bool) -> None:
    loss_col, _, ref_short = loss_columns(model_loss)
    page.figure(
        "loss_figure",
        draw.plot_engine_loss(totals, loss_col, f"total ΔV loss vs {ref_short} (m/s)"),
        caption=("Top: total ΔV loss of the capture (m/s) above "
                 + (REF_OURS if model_loss else REF_PAPER)
                 + f". Bottom: propellant of LOI 1–3 (kg). Against thrust (N), ignition "
                 f"{ignition}; colours: Isp; diamonds: Sec. 3.1's engines, circles: the "
                 "paper's."),
        alt="Total delta-V loss and propellant against thrust for each engine", name="loss")


def _add_checks(page: Page, totals: pd.DataFrame, seqs: dict, results: dict, rows,
                model_loss: bool) -> None:
    loss_col = loss_columns(model_loss)[0]
    by_thrust, _ = _by_thrust(totals, seqs, rows)
    page.expect("every burn passes the verification gate",
                all(s.verified.all() for s in seqs.values()))
    page.expect("every loss vs paper is positive",
                bool((totals.total_loss_vs_paper_impulse_mps > 0).all()))
    if model_loss:
        page.expect("every impulsive limit passes the gate",
                    all(res.totals()["all_verified"] for res in results.values()))
        page.expect("every loss vs ours is positive, burn by burn",
                    all(bool((s.objective_loss_mps > 0).all()) for s in seqs.values()))
    ordered = totals.sort_values("thrust_N")
    page.expect("the plotted loss falls as the thrust rises",
                bool((np.diff(ordered[loss_col].to_numpy()) < 0).all()),
                str(ordered[["thrust_N", loss_col]].values.tolist()))
    if {300.0, 320.0, 450.0} <= set(by_thrust):
        page.expect("LRO-class plotted loss between the paper's 450 N and 300 N",
                    getattr(by_thrust[450.0], loss_col) < getattr(by_thrust[320.0], loss_col)
                    < getattr(by_thrust[300.0], loss_col))
    if 500.0 in by_thrust and len(totals) > 1:
        page.expect("SELENE-class: the least plotted loss",
                    getattr(by_thrust[500.0], loss_col) == totals[loss_col].min())
    if {150.0, 300.0, 320.0} <= set(by_thrust):
        f = {t: by_thrust[t].total_fuel_kg for t in (150.0, 300.0, 320.0)}
        page.expect("LRO-class propellant nearer the 150 N / 200 s engine's than the 300 N's",
                    abs(f[320.0] - f[150.0]) < abs(f[320.0] - f[300.0]), str(f))


def _add_measured_checks(page: Page, totals: pd.DataFrame, seqs: dict, rows,
                         model_loss: bool) -> None:
    """Ranges measured in full dynamics with free ignition (the book's parameters, :data:`BOOK`)."""
    by_thrust, seq_by_thrust = _by_thrust(totals, seqs, rows)
    if 320.0 in seq_by_thrust:  # measured: LOI 1 8.90 min, loss 4.30 (paper), 4.70 (ours)
        s, r = seq_by_thrust[320.0], by_thrust[320.0]
        page.expect("LRO-class LOI 1 burns 8.5-9.3 min",
                    8.5 < s.burn_duration_min.iloc[0] < 9.3)
        page.expect("LRO-class loss vs paper 3.5-5.0 m/s",
                    3.5 < r.total_loss_vs_paper_impulse_mps < 5.0,
                    f"{r.total_loss_vs_paper_impulse_mps:.3f}")
        if model_loss:
            page.expect("LRO-class loss vs ours 4.0-5.4 m/s",
                        4.0 < r.total_delta_v_loss_mps < 5.4, f"{r.total_delta_v_loss_mps:.3f}")
    if 500.0 in seq_by_thrust:  # measured: LOI 1 5.84 min, loss 1.76 (paper), 2.16 (ours)
        s, r = seq_by_thrust[500.0], by_thrust[500.0]
        page.expect("SELENE-class LOI 1 burns 5.5-6.2 min",
                    5.5 < s.burn_duration_min.iloc[0] < 6.2)
        page.expect("SELENE-class loss vs paper 1.2-2.3 m/s",
                    1.2 < r.total_loss_vs_paper_impulse_mps < 2.3,
                    f"{r.total_loss_vs_paper_impulse_mps:.3f}")
        if model_loss:
            page.expect("SELENE-class loss vs ours 1.6-2.8 m/s",
                        1.6 < r.total_delta_v_loss_mps < 2.8, f"{r.total_delta_v_loss_mps:.3f}")


def sequence_of(result) -> pd.DataFrame:
    """One engine's capture as the paper's Table B1 rows, from its solved plan.

    ``result``: ``lunarcap.solve(lunarcap.paper_plan(thrust_N, isp_s, starts, dynamics))``
    (``impulsive=True`` for the losses vs ours). The columns of
    :func:`lunarcap.studies.sweeps.sequence_table`: each burn's start, duration, delta-V and
    masses beside the paper's printed ones and its printed impulse (Table B1), and, with
    the impulsive limits, the loss against them.
    """
    rows = []
    for r in result.rows():
        loi = int(r["burn"])
        try:
            pb = paper_best(r["thrust_N"], loi)
        except Exception:  # not one of the paper's engines
            pb = None
        imp = PAPER_IMPULSIVE_DV_MPS[loi - 1]
        row = {"loi": loi, "start_min": r["start_min"],
               "paper_start_min": np.nan if pb is None else pb["start_min"],
               "burn_duration_min": r["burn_duration_min"],
               "paper_burn_duration_min": np.nan if pb is None else pb["burn_duration_min"],
               "delta_v_mps": r["delta_v_mps"],
               "paper_delta_v_mps": np.nan if pb is None else pb["delta_v_mps"],
               "paper_impulsive_delta_v_mps": imp,
               "loss_vs_paper_impulse_mps": r["delta_v_mps"] - imp,
               "loss_vs_paper_impulse_percent": 100.0 * (r["delta_v_mps"] - imp) / imp,
               "paper_delta_v_loss_percent": np.nan if pb is None else pb["diff_percent"],
               "m_start_kg": r["m_start_kg"], "m_end_kg": r["m_end_kg"],
               "fuel_kg": r["fuel_kg"], "v_end_kmps": r["v_end_kmps"],
               "verified": r["verification_passed"]}
        if r["impulsive_limit_mps"] is not None:
            row.update({k: r[k] for k in ("impulsive_limit_mps", "delta_v_loss_mps",
                                          "delta_v_loss_percent", "objective_loss_mps",
                                          "objective_loss_percent")})
        rows.append(row)
    return pd.DataFrame(rows)


def build(results: dict, output_name: str = "other_engines", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The page of the engines cited in Sec. 3.1, solved in the notebook (module docstring).

    Parameters
    ----------
    results : dict
        ``{label: lunarcap.CaptureResult}``, one per engine of :func:`engine_rows` (its
        label): the paper's plan with that engine solved by :func:`lunarcap.solve`, with
        the impulsive limits if ``model_loss``.
    output_name, quick : the tables' prefix; recorded in the provenance
    parameters : dict
        The notebook's ``engines``, ``engine_names``, ``paper_engines``, ``starts``,
        ``dynamics`` and ``model_loss``: the rows, the captions and the provenance.
    """
    prm = dict(parameters or {})
    engines, engine_names = prm["engines"], prm["engine_names"]
    paper_engines, starts = prm.get("paper_engines", ()), prm.get("starts", ("free",) * 3)
    dynamics, model_loss = prm.get("dynamics", "full"), bool(prm.get("model_loss", True))
    start_arg = tuple(s if s == "free" else float(s) for s in starts)
    params = dict(engines=[list(e) for e in engines], engine_names=list(engine_names),
                  paper_engines=[list(e) for e in paper_engines], starts=list(starts),
                  dynamics=dynamics, model_loss=model_loss)
    solver = solver_description()
    solver["ignition"] = ("free (an NLP variable)" if _start_text(start_arg) == "free"
                          else f"fixed {list(starts)} min")
    page = Page(NOTEBOOK, params, output_name, quick, solver)
    rows = engine_rows(engines, engine_names, paper_engines)
    seqs = {lab: sequence_of(results[lab]) for _, _, _, lab in rows}
    results = {lab: results[lab] for _, _, _, lab in rows} if model_loss else {}
    ignition = _start_text(start_arg)
    case = (f"the paper's spacecraft ({paper_scenario().mass_kg:g} kg at the first perilune) and "
            f"orbits, {dynamics} dynamics, ignition {ignition}")
    _add_burn_tables(page, burns_frame(seqs, rows, model_loss), case, model_loss)
    totals = totals_frame(seqs, rows, model_loss)
    _add_totals_tables(page, totals, ignition, model_loss)
    _add_figure(page, totals, ignition, model_loss)
    for name, v in prose_values(totals, seqs, rows, model_loss).items():
        page.value(name, v)
    loss_col, pct_col, ref_short = loss_columns(model_loss)
    page.note("placement", placement_note(totals, seqs, rows, loss_col, pct_col, ref_short))
    page.note("loss_note", loss_note(totals, seqs, rows, model_loss, dynamics))
    _add_checks(page, totals, seqs, results, rows, model_loss)
    if dynamics == "full" and ignition == "free":
        _add_measured_checks(page, totals, seqs, rows, model_loss)
    page.data.update({"sequences": seqs, "totals": totals, "plan_results": results})
    t = page.text
    page.headline(f"The LRO-class engine (320 N / 200 s, *{capture_name('free')}*) burns "
                  f"{t('total_fuel_kg_320N', '.1f', ' kg')} of propellant; going from 150 to "
                  f"320 N at 200 s divides the LOI 1 loss by {t('loss_ratio_150_320', '.2f')}.")
    page.capture("free", dynamics)
    return page


def placement_note(totals: pd.DataFrame, seqs: dict, rows, loss_col: str, pct_col: str,
                   ref_short: str) -> str:
    """Where each cited engine's loss falls among the others (MyST paragraph).

    The loss is the figure's (``loss_col``, against ``ref_short``).
    """
    paper = totals[totals.origin == PAPER_ENGINE].sort_values(loss_col)

    def name(p):
        return f"{p.thrust_N:g} N / {p.isp_s:g} s ({p[loss_col]:.2f} m/s)"

    out = []
    for _, _, o, lab in rows:
        if o == PAPER_ENGINE:
            continue
        r = totals[totals.engine == lab].iloc[0]
        s = seqs[lab]
        loss = getattr(r, loss_col)
        text = (f"The {o} engine ({r.thrust_N:g} N, {r.isp_s:g} s) loses {loss:.2f} m/s over "
                f"the capture against {ref_short} ({getattr(r, pct_col):.2f} % of their total)")
        below = paper[paper[loss_col] < loss]
        above = paper[paper[loss_col] > loss]
        if len(below) and len(above):
            text += (f", between the paper's {name(above.iloc[0])} and "
                     f"{name(below.iloc[-1])} engines")
        elif len(above) and len(totals) > 1 and loss == totals[loss_col].min():
            text += f", the least of the {len(totals)} engines"
        elif len(above):
            text += f", less than any of the paper's engines (least: {name(above.iloc[0])})"
        elif len(below):
            text += f", more than any of the paper's engines (most: {name(below.iloc[-1])})"
        text += (f"; its LOI 1 burns {s.burn_duration_min.iloc[0]:.2f} min and the whole "
                 f"sequence {s.burn_duration_min.sum():.2f} min.")
        out.append(text)
    return " ".join(out) or "No engine of Sec. 3.1 in this build."


def loss_note(totals: pd.DataFrame, seqs: dict, rows, model_loss: bool, dynamics: str) -> str:
    """Which impulsive reference the figure and the prose use, and the other one (MyST)."""
    paper_total = float(sum(PAPER_IMPULSIVE_DV_MPS))
    cited = [(o, lab) for _, _, o, lab in rows if o != PAPER_ENGINE]
    if not model_loss:
        return ("**Which impulsive reference.** These losses, and those drawn in the "
                f"figure, are ΔV above {REF_PAPER}, {paper_total:.3f} m/s in total, the "
                "reference of the paper's Tables 1–5. The loss against our own impulsive "
                "limit in the same dynamics is not computed in this build (`model_loss` is "
                "false).")
    parts = []
    for o, lab in cited:
        r = totals[totals.engine == lab].iloc[0]
        parts.append(
            f"the {o} engine loses {r.total_objective_loss_mps:.2f} m/s against its impulses "
            f"(which total {r.total_impulsive_limit_mps:.3f} m/s; its ΔV exceeds "
            f"theirs by {r.total_delta_v_loss_mps:.2f} m/s) and "
            f"{r.total_loss_vs_paper_impulse_mps:.2f} m/s "
            f"({r.total_loss_vs_paper_impulse_percent:.2f} %) against the paper's "
            f"{paper_total:.3f} m/s")
    lower = bool((totals.total_impulsive_limit_mps < paper_total).all())
    higher = bool((totals.total_impulsive_limit_mps > paper_total).all())
    compare = ("Our impulses need less ΔV than the paper's, so a loss against ours is the "
               "larger" if lower else
               "Our impulses need more ΔV than the paper's, so a loss against ours is the "
               "smaller" if higher else "The two references differ")
    return (
        "**Which impulsive reference.** These losses, and those drawn in the figure, are "
        f"measured against {REF_OURS}, in {dynamics} dynamics "
        "(`lunarcap.capture.chain.impulsive_limit`): the finite-burn loss of our model against "
        "our model. The paper measures its losses against its printed impulsive ΔVs "
        f"(Table B1: {', '.join(f'{x:.3f}' for x in PAPER_IMPULSIVE_DV_MPS)} m/s), the "
        f"'vs paper' columns above. {compare}: " + "; ".join(parts) + ". The impulse is the "
        "one of least J (Eq. 9: ΔV plus the speed left at the next perilune); J is nearly "
        "flat along the epoch of the impulse, and local optima a few seconds apart can "
        "differ by about 0.2 m/s in ΔV while their J agree within a few mm/s, so a ΔV "
        "difference against an impulse is defined to about 0.2 m/s per burn, and the loss "
        "drawn and quoted here is the difference in J: the extra ΔV of the finite burn plus "
        "the extra speed it leaves for the next burn to remove.")
