"""The reproduction report (notebooks/reproduction_report.ipynb): every printed number beside ours.

Three parts, each a few tables and the numbers the prose quotes:

(a) every entry of Tables 1-5 and B1 beside the same case solved with lunarcap (the
    paper's ignition offsets, :func:`paper_starts`), and the impulsive row of every table
    beside our two-body impulsive chain (:meth:`lunarcap.CapturePlan.impulsive`);
(b) every number of the paper's prose (:data:`lunarcap.paper.printed.QUOTES`) beside our
    equivalent from the best chains of the three engines (:func:`paper_engines`, Table
    B1's offsets), and the printed perilune epochs beside the plan's nominal ones;
(c) the audit of the paper's consistency (:mod:`lunarcap.paper.audit`).

The notebook solves (a) and (b) with the public API: :func:`lunarcap.solve_burn` of
:func:`lunarcap.paper_plan` per printed ignition, :func:`lunarcap.solve` of
:func:`lunarcap.paper_plan` per engine (the cached solves of
:func:`lunarcap.studies.sweeps.sweep_table` and :func:`lunarcap.capture.chain.solve_plan`:
the same plan keys). :func:`build` shapes them like the paper's tables
(:func:`lunarcap.report.pages.sweep.sweep_of`); the tables are assembled by
:mod:`lunarcap.report.reproduction`.
"""

from __future__ import annotations

import re

import pandas as pd

from lunarcap.mission.plan import paper_plan
from lunarcap.mission.scenario import paper_engines as paper_engines_of_scenario
from lunarcap.paper import audit
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.report import figdata
from lunarcap.report import reproduction as rep
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.page import Page, solver_description
from lunarcap.report.pages.sweep import sweep_of
from lunarcap.repro import paths

NOTEBOOK = "notebooks/reproduction_report.ipynb"
BOOK = BookPage(NOTEBOOK, "Reproduction report", 10, (
    Execution(
        "reproduction_report", "Reproduction report: every printed number beside ours",
        parameters=dict(dynamics="full"),
        # quick: part (a) for one engine; (b) and (c) unchanged
        quick_parameters=dict(engines=[[150.0, 200.0]]),
        depends_on=("table3", "table4_loi3", "table5_loi3"),
        outputs=table_files("reproduction_report", "tables", "tables_data", "tables_summary",
                            "quotes", "quotes_data", "epochs", "findings_by_group",
                            "findings", "findings_data")),
))

#: Labels of the quantities of part (a), with their units.
QUANTITY_LABELS = {"burn duration": "duration (min)", "delta-V": "ΔV (m/s)",
                   "difference from impulsive": "ΔV above impulsive (%)",
                   rep.IMPULSE_ROW_TWO_BODY: "impulse, ours two-body (m/s)"}

#: Findings the prose of part (c) discusses: each must be inconsistent.
DISCUSSED_FINDINGS = ("sun-gm", "fuel/150N/which-is-larger", "mass/arrival-implied",
                      "loss-percent/150N/total", "period/final", "eq19a/as-printed",
                      "thrust/300N/LOI1", "epoch/perilune2-ignition-reading")

#: Prose numbers whose paper and our values the page's prose quotes.
PROSE_QUOTES = ("loss_total_150N_mps", "loss_total_300N_mps", "loss_total_450N_mps",
                "loss_total_150N_percent", "loss_total_300N_percent",
                "loss_total_450N_percent", "mass_final_150N_kg", "fuel_finite_150N_kg",
                "fuel_impulsive_150N_kg", "burn_total_150N_min", "fig4_alpha_start_deg",
                "fig4_alpha_end_deg")

#: Quotes of the masses we compute (the gaps to the printed ones are discussed in (c)).
MASS_QUOTES = ("mass_after_loi1_150N_kg", "mass_after_loi2_150N_kg", "mass_final_150N_kg",
               "mass_final_300N_kg", "mass_final_450N_kg")


def _link(key_name: str) -> str:
    """A MyST download link to ``tables/<key_name>.csv``."""
    csv = paths.table_path(key_name)
    return f"{{download}}`{csv.name} <{paths.relative_to_page(csv)}>`"


def _tables_range(sources) -> str:
    """"Tables 1–5" (or "Tables 1–3", "Table 4") from the sources of part (a)."""
    nums = sorted({int(m.group(1)) for s in sources if (m := re.match(r"Table (\d)", s))})
    if not nums:
        return "no table"
    return f"Table {nums[0]}" if len(nums) == 1 else f"Tables {nums[0]}–{nums[-1]}"


#: Quantities of part (a) in the wide form: long name -> column stem and unit suffix.
WIDE_QUANTITIES = {"burn duration": ("duration", "min"), "delta-V": ("delta_v", "mps"),
                   rep.IMPULSE_ROW_TWO_BODY: ("delta_v", "mps"),
                   "difference from impulsive": ("excess", "percent")}
#: Glossary names of the wide form's columns: (column stem, paper / ours / difference).
WIDE_NAMES = {
    ("duration", "paper"): "paper_burn_duration_min", ("duration", "ours"): "burn_duration_min",
    ("duration", "difference"): "burn_duration_diff_min",
    ("delta_v", "paper"): "paper_delta_v_mps", ("delta_v", "ours"): "delta_v_mps",
    ("delta_v", "difference"): "delta_v_difference_mps",
    ("excess", "paper"): "paper_loss_vs_paper_impulse_percent",
    ("excess", "ours"): "loss_vs_paper_impulse_percent",
    ("excess", "difference"): "loss_vs_paper_impulse_diff_percent"}
#: Headers of the wide form (the CSV keeps the column names); ``row`` is the start with the
#: best mark, shown instead of ``start`` and ``best`` (one column less: it fits at 1024 px).
WIDE_LABELS = {"source": "source", "thrust_N": "thrust (N)", "isp_s": "Isp (s)",
               "start": "start (min)", "best": "best", "row": "start (min), best",
               **{WIDE_NAMES[stem, who]: f"{head}, {who_head}"
                  for stem, head in (("duration", "duration (min)"), ("delta_v", "ΔV (m/s)"),
                                     ("excess", "ΔV above impulsive (%)"))
                  for who, who_head in (("paper", "paper"), ("ours", "ours"),
                                        ("difference", "ours − paper"))}}


def tables_wide(long: pd.DataFrame) -> pd.DataFrame:
    """Part (a) in wide form: one row per row of the paper's tables, as the paper prints them.

    Columns ``source`` (Table B1's rows name their engine: "Table B1, 300 N"),
    ``thrust_N``, ``isp_s`` (NaN for the impulsive rows, which hold for every engine),
    ``start`` (the ignition offset, min, or "impulse, LOI n (ours: two-body)" for the
    paper's impulsive delta-Vs, which go in the ΔV columns), ``best`` (paper / ours /
    both), then paper, ours and ours − paper for the duration (min), the ΔV (m/s) and
    the ΔV above the impulsive one (%). A third as many rows as the long form, and every
    number of a row side by side. A row is keyed by its source, engine, LOI and start:
    Table B1 repeats the best row of each engine's tables, and two engines may share a
    start (300 N and 450 N LOI 3 both ignite 2 min before perilune).
    """
    rows: dict = {}
    for r in long.itertuples(index=False):
        impulsive = r.quantity == rep.IMPULSE_ROW_TWO_BODY
        start = f"impulse, LOI {r.loi} (ours: two-body)" if impulsive else f"{r.start_min:g}"
        source = r.source.replace(" (impulsive)", "")
        thrust = float(r.thrust_N)
        if source == "Table B1":
            source = f"Table B1, {thrust:g} N"
        engine = (None, None) if impulsive else (thrust, float(r.isp_s))
        row = rows.setdefault((source, engine, r.loi, start),
                              {"source": source, "thrust_N": engine[0], "isp_s": engine[1],
                               "start": start, "best": ""})
        stem, _ = WIDE_QUANTITIES[r.quantity]
        for who, v in (("paper", r.paper), ("ours", r.ours), ("difference", r.difference)):
            row[WIDE_NAMES[stem, who]] = v
        best = ("both" if r.paper_best and r.ours_best else "paper" if r.paper_best
                else "ours" if r.ours_best else "")
        row["best"] = row["best"] or best
        row["row"] = start + (f" ({row['best']})" if row["best"] else "")
    return pd.DataFrame(list(rows.values()), columns=list(WIDE_LABELS))


def tables_summary(main: pd.DataFrame) -> pd.DataFrame:
    """Differences of part (a) by quantity: count, mean, median and largest |difference|."""
    return (main.groupby(["quantity", "unit"], sort=False)
            .agg(numbers=("difference", "size"),
                 mean_difference=("difference", "mean"),
                 median_abs_difference=("difference", lambda d: d.abs().median()),
                 max_abs_difference=("difference", lambda d: d.abs().max()))
            .reset_index())


def findings_by_group(ft: pd.DataFrame) -> pd.DataFrame:
    """The audit's checks by group: how many, how many inconsistent."""
    groups = (ft.assign(inconsistent=ft.verdict == audit.INCONSISTENT)
              .groupby("check").agg(checks=("id", "size"), inconsistent=("inconsistent", "sum"))
              .reset_index())
    groups.insert(1, "group", [audit.AUDIT_CHECK_TITLES.get(c, "") for c in groups.check])
    return groups


def paper_starts(thrust_N: float, loi: int) -> list:
    """The ignition offsets (min) of the paper's table of one engine's LOI (Tables 1-5).

    >>> paper_starts(150, 1)
    [0.0, -6.0, -8.0, -10.0, -12.0, -14.0]
    """
    starts = paper.PAPER_STARTS_MIN.get((float(thrust_N), int(loi)))
    if starts is None:
        raise ValueError(f"the paper has no table for {float(thrust_N):g} N")
    return [float(s) for s in starts]


def paper_engines() -> list:
    """The paper's three engines, ``[(thrust_N, isp_s)]``, whose best chains part (b) reads.

    >>> engines = paper_engines()
    >>> len(engines), engines[0]
    (3, (150.0, 200.0))
    """
    return [(float(t), float(i)) for t, i in tuple(paper_engines_of_scenario().items())]


def sweeps_of(burns: dict) -> dict:
    """The paper's sweeps the notebook solved, shaped like its tables: (thrust, loi) -> table.

    ``burns``: {(thrust_N, loi): [lunarcap.BurnSolution per offset of :func:`paper_starts`]}
    (:func:`lunarcap.solve_burn` of :func:`lunarcap.paper_plan`, the earlier burns at
    Table B1's offsets); each table :func:`lunarcap.studies.sweeps.sweep_frame`'s.
    """
    return {(float(t), int(loi)): sweep_of(b)[0] for (t, loi), b in burns.items()}


def gate_text(long: pd.DataFrame) -> str:
    """Whether every case passed the gate, else which failed."""
    failed = long[~long.verified]
    return ("Every case passed the re-propagation gate (the verification page)."
            if failed.empty else
            "Cases that failed the re-propagation gate: "
            + ", ".join(sorted({f"{r.source} {r.start_min:g} min"
                                for r in failed.itertuples()})) + ".")


def part_a_values(long: pd.DataFrame, sweeps: dict) -> dict:
    """The numbers of part (a) the prose quotes: counts, worst and median differences."""
    main = long[~long.source.isin(["Table B1", "Tables 1-5, B1 (impulsive)"])]
    dv = main[main.quantity == "delta-V"]
    dur = main[main.quantity == "burn duration"]
    worst_dv = dv.loc[dv.difference.abs().idxmax()]
    worst_dur = dur.loc[dur.difference.abs().idxmax()]
    b1dv = long[(long.source == "Table B1") & (long.quantity == "delta-V")]
    best_agree = sum(int(df.loc[df.best, "start_min"].iloc[0]
                         == df.loc[df.paper_best, "start_min"].iloc[0])
                     for df in sweeps.values() if df.paper_best.any())
    return {
        "tables_range": _tables_range(main.source), "n_cases": int(len(dv)),
        "n_table_numbers": int(len(main)), "n_numbers_a": int(len(long)),
        "n_sweeps": int(len(sweeps)), "n_best_agree": int(best_agree),
        "n_verified": int(dv.verified.sum()),
        "max_dv_diff_mps": float(worst_dv.difference),
        "max_dv_diff_percent": float(100 * worst_dv.difference / worst_dv.paper),
        "max_dv_case": f"{worst_dv.source}, ignition {worst_dv.start_min:g} min",
        "max_dur_diff_min": float(worst_dur.difference),
        "max_dur_case": f"{worst_dur.source}, ignition {worst_dur.start_min:g} min",
        "median_dv_diff_mps": float(dv.difference.abs().median()),
        "n_dv_within_1mps": int((dv.difference.abs() <= 1.0).sum()),
        "b1_max_dv_diff_percent": (float((100 * b1dv.difference / b1dv.paper).abs().max())
                                   if len(b1dv) else float("nan")),
        "n_b1": int(len(b1dv))}


def _add_part_a_tables(page: Page, long: pd.DataFrame, dynamics: str,
                       output_name: str) -> None:
    main = long[~long.source.isin(["Table B1", "Tables 1-5, B1 (impulsive)"])]
    rng = _tables_range(main.source)
    gate = gate_text(long)
    page.table(
        "tables", tables_wide(long),
        caption=(f"Tables 1–5 and B1 beside ours, row by row ({rng}; {dynamics} dynamics). "
                 "Best: the paper's, ours or both. Last rows: the printed impulses against "
                 "our two-body chain. "
                 f"{gate} Long form: {_link(f'{output_name}_tables_data')}."),
        columns=WIDE_LABELS,
        floatfmt={c: ("+.3f" if "difference" in c else ".3f") for c in WIDE_LABELS
                  if c not in ("source", "thrust_N", "isp_s", "start", "best", "row")},
        show_columns=[c for c in WIDE_LABELS
                      if c not in ("thrust_N", "isp_s", "start", "best")])
    page.table("tables_data", long,
               caption="Every number of Tables 1–5 and B1 beside ours, all columns.")
    page.table(
        "tables_summary", tables_summary(main),
        caption=(f"The differences of the table above by quantity ({rng}; not Table B1, "
                 "which repeats their best rows), in the unit given."),
        columns={"unit": "unit", "numbers": "numbers", "mean_difference": "mean difference",
                 "median_abs_difference": "median |diff.|",
                 "max_abs_difference": "largest |diff.|"},
        floatfmt={"mean_difference": "+.3f", "median_abs_difference": ".3f",
                  "max_abs_difference": ".3f"})


def _part_a(page: Page, engines, sweeps: dict, dynamics: str, output_name: str):
    """Tables 1-5 and B1 beside ours; returns the sweeps and the burn-duration rows."""
    two_body = paper_plan(150.0, 200.0, dynamics=dynamics).impulsive()
    long = rep.paper_tables_long(sweeps, impulsive_dv_mps=[b.delta_v_mps for b in two_body])
    _add_part_a_tables(page, long, dynamics, output_name)
    values = part_a_values(long, sweeps)
    for k, x in values.items():
        page.value(k, x)
    page.expect("every case of part (a) passes the verification gate",
                bool(long.verified.all()), gate_text(long))
    b1 = paper.paper_table_b1()
    n_b1 = int(b1.thrust_N.isin([int(t) for t, _ in engines]).sum())
    wide = page.items["tables"].df
    shown = int(wide.source.str.startswith("Table B1").sum())
    page.expect("the wide table holds every row of Table B1 of this run's engines, each once",
                shown == n_b1, f"{shown} rows for Table B1's {n_b1}")
    if dynamics == "full":  # the paper's dynamics: the agreement is the reproduction
        b1 = values["b1_max_dv_diff_percent"]
        page.expect("Table B1: our delta-Vs within 0.25 % of the paper's",
                    values["n_b1"] == 0 or b1 < 0.25, f"{b1:.3f} %")
        page.expect("every delta-V of Tables 1-5 within 6 m/s of ours",
                    abs(values["max_dv_diff_mps"]) < 6.0,
                    f"{values['max_dv_diff_mps']:+.3f} m/s in {values['max_dv_case']}")
    page.data.update(sweeps=sweeps, long=long)
    main = long[~long.source.isin(["Table B1", "Tables 1-5, B1 (impulsive)"])]
    return sweeps, main[main.quantity == "burn duration"]


def _part_b(page: Page, sweeps: dict, solutions: dict, dynamics: str, output_name: str,
            findings):
    """The numbers of the prose and the perilune epochs; returns (chains, quotes).

    ``solutions``: {thrust_N: the Solutions of its best chain, in order}.
    """
    chains = {t: rep.paper_chain_rows([s.summary() for s in sols])
              for t, sols in solutions.items()}
    imp_final = {float(t): paper_plan(t, isp).impulsive()[-1].m_after_kg
                 for t, isp in tuple(paper_engines_of_scenario().items())}
    best_starts = {k: float(df.loc[df.best, "start_min"].iloc[0]) for k, df in sweeps.items()}
    fig4 = figdata.fig4_steering(solutions[150.0][0])
    ours = rep.quote_equivalents(chains, imp_final, best_starts, fig4,
                                 {f.id: f.computed for f in findings})
    quotes = rep.quotes_comparison(ours)
    page.table(
        "quotes", rep.quotes_display(quotes),
        caption=("Every number of the paper's prose beside ours (§ section, ¶ paragraph, "
                 "words cut short; t: metric tons): computed from the best chains unless the "
                 f"note says input. In full: {_link(f'{output_name}_quotes_data')}."),
        columns={"words": "printed with", "printed": "paper", "ours": "ours",
                 "difference": "ours − paper", "note": "note"})
    page.table("quotes_data", quotes,
               caption="Every number of the paper's prose beside ours, all columns.")
    plan = paper_plan(150.0, 200.0, dynamics=dynamics)
    epochs = rep.epochs_comparison(plan.nominal_perilunes_s)
    page.table(
        "epochs", epochs,
        caption=("The perilune epochs of Sec. 3.2.1 (TDB) beside our chain's: the arrival, "
                 "then 12.235 h and 3.525 h later. The periods are printed to 0.001 h "
                 "(3.6 s), the epochs to 1 s."),
        columns={"perilune": "perilune", "where": "where", "paper": "paper (TDB)",
                 "ours": "ours (TDB)", "difference_s": "ours − paper (s)"},
        floatfmt={"difference_s": "+.0f"})
    has = quotes.ours.notna()
    is_input = quotes.note.str.startswith("input") | quotes.note.str.startswith("corrected")
    v = page.value
    v("n_quotes", int(len(quotes)))
    v("n_quotes_computed", int((has & ~is_input).sum()))
    v("n_quotes_input", int((has & is_input).sum()))
    v("n_quotes_none", int((~has).sum()))
    q = quotes.set_index("name")
    for name in PROSE_QUOTES:
        v(f"ours_{name}", float(q.loc[name, "ours"]))
        v(f"paper_{name}", float(q.loc[name, "paper"]))
    v("max_epoch_diff_s", float(epochs.difference_s.abs().max()))
    gaps = [float(q.loc[n, "difference"]) for n in MASS_QUOTES]
    v("mass_gap_min_kg", min(gaps))
    v("mass_gap_max_kg", max(gaps))
    page.expect("one row per number of the prose",
                quotes.name.is_unique and len(quotes) == len(paper.QUOTES))
    page.expect("our perilune epochs within 4 s of the printed ones",
                epochs.difference_s.abs().max() <= 4.0,
                f"{epochs.difference_s.abs().max():.1f} s")
    page.expect("our masses lie above the printed ones (the stated arrival mass)",
                min(gaps) > 0, f"{min(gaps):+.3f} kg")
    page.data.update(chains=chains, quotes=quotes, epochs=epochs, fig4=fig4)
    return chains, quotes


def duration_remark(dur: pd.DataFrame) -> str:
    """Whether Table 4's LOI 1 rows hold the largest duration differences of part (a)."""
    d = dur.difference.abs()
    t4 = (dur.thrust_N == 300.0) & (dur.loi == 1)
    if not t4.any():
        return "Table 4 is not in part (a) of this run"
    if (~t4).any() and d[t4].min() > d[~t4].max():
        return ("and Table 4's LOI 1 rows have the largest duration differences of "
                f"part (a), {d[t4].min():.2f} to {d[t4].max():.2f} min")
    return ("though Table 4's LOI 1 rows do not hold all the largest duration "
            "differences of part (a)")


def _add_findings_tables(page: Page, output_name: str) -> None:
    ft = audit.findings_table()
    page.table(
        "findings_by_group", findings_by_group(ft),
        caption=("The audit's checks of the paper's printed numbers by group, and how many "
                 "are inconsistent beyond rounding."),
        columns={"check": "group", "group": "what is checked", "checks": "checks",
                 "inconsistent": "inconsistent"})
    bad = audit.findings_table(only_inconsistent=True)
    page.table(
        "findings", rep.findings_display(bad),
        caption=("Every inconsistency of Song et al. (2011) found by `lunarcap.paper.audit` "
                 "(group letter as above, and id): printed, what the paper's other numbers "
                 "or physics give, where, and the computation. In full: "
                 f"{_link(f'{output_name}_findings_data')}."),
        columns={"finding": "finding", "printed": "printed", "computed": "computed",
                 "explanation": "where, and why"})
    page.table("findings_data", bad,
               caption="Every inconsistency found by the audit, all columns.")


def _finding_values(findings, ft: pd.DataFrame, chains: dict) -> dict:
    """The audit's numbers the prose of part (c) quotes."""
    F = {f.id: f for f in findings}
    out = {"n_findings": int(len(ft)),
           "n_inconsistent": int((ft.verdict == audit.INCONSISTENT).sum()),
           "n_consistent": int((ft.verdict == audit.CONSISTENT).sum())}
    v = out.__setitem__  # v(name, number): one number of the prose
    sun = F["sun-gm"]
    v("sun_printed", float(sun.printed))
    v("sun_correct", float(sun.computed))
    v("sun_ratio", float(sun.extra["ratio_correct_over_printed"]))
    v("sun_tcb", float(sun.extra["tcb_value"]))
    fuel = audit.fuel_sentence_check(150)
    for k in ("printed_finite_kg", "printed_impulsive_kg", "computed_finite_kg",
              "computed_impulsive_kg", "mismatch_as_labelled_kg", "mismatch_if_swapped_kg"):
        v(f"fuel150_{k}", float(fuel[k]))
    v("fuel150_printed_percent", float(F["fuel/150N/difference-percent"].printed))
    v("fuel150_swapped_percent",
      float(F["fuel/150N/difference-percent"].extra["if_swapped_percent"]))
    arr = F["mass/arrival-implied"]
    v("arrival_printed_kg", float(arr.printed))
    v("arrival_implied_kg", float(arr.computed))
    v("arrival_gap_kg", float(arr.printed - arr.computed))
    v("arrival_spread_kg", float(arr.extra["spread"]))
    v("mass1_printed_kg", float(F["mass/150N/after-LOI1"].printed))
    v("mass1_computed_kg", float(F["mass/150N/after-LOI1"].computed))
    for t in (150, 300, 450):
        f = F[f"loss-percent/{t}N/total"]
        v(f"pct{t}_printed", float(f.printed))
        v(f"pct{t}_total", float(f.computed))
        v(f"pct{t}_mean_printed", float(f.extra["mean_of_printed_percentages"]))
    v("loss150_printed", float(F["loss/150N/total"].printed))
    v("loss150_sum", float(F["loss/150N/total"].computed))
    per = F["period/final"]
    v("period_printed_min", float(per.printed))
    v("period_two_body_min", float(per.computed))
    v("period_implied_alt_km", float(per.extra["implied_radius_km"] - C.R_MOON))
    e19 = F["eq19a/as-printed"]
    v("eq19a_printed_min", float(e19.printed))
    v("eq19a_as_printed_min", float(e19.computed))
    v("eq19_corrected_min", float(F["eq19/150N/LOI1"].computed))
    thr = F["thrust/300N/LOI1"]
    v("t300_implied_N", float(thr.computed))
    v("t300_paper_dur_min", float(paper.paper_best(300, 1)["burn_duration_min"]))
    v("t300_ours_dur_min", float(chains[300.0][0]["burn_duration_min"]))
    v("t300_half_implied_N", float(F["eq19/300N/LOI1-half"].extra["implied_thrust_N"]))
    ep2, ep3 = F["epoch/perilune2-ignition-reading"], F["epoch/perilune3-ignition-reading"]
    v("epoch2_gap_s", float(ep2.printed - ep2.computed))
    v("epoch3_gap_s", float(ep3.printed - ep3.computed))
    v("fig4_printed_end_kg", float(F["fig4/mass-end"].printed))
    v("fig4_loi1_end_kg", float(F["fig4/mass-end"].computed))
    v("eq19_half_computed_min", float(F["eq19/150N/LOI1-half"].computed))
    v("n_pct_rows", int(sum(f.verdict == audit.INCONSISTENT for f in findings
                            if f.check == "b")))
    return out


def _part_c(page: Page, findings, chains: dict, dur: pd.DataFrame, output_name: str):
    """The audit: groups, the numbers the prose quotes, every inconsistent finding."""
    _add_findings_tables(page, output_name)
    ft = audit.findings_table()
    bad = audit.findings_table(only_inconsistent=True)
    values = _finding_values(findings, ft, chains)
    values["t300_dur_remark"] = duration_remark(dur)
    for k in ("epoch2_gap_s", "epoch3_gap_s", "fig4_printed_end_kg", "fig4_loi1_end_kg",
              "eq19_half_computed_min", "n_pct_rows"):
        values[k] = values.pop(k)  # the order of the values as before
    for k, x in values.items():
        page.value(k, x)
    fuel = audit.fuel_sentence_check(150)
    arr = {f.id: f for f in findings}["mass/arrival-implied"]
    page.expect("the findings table lists every inconsistent check",
                len(bad) == int((ft.verdict == audit.INCONSISTENT).sum()) > 0)
    page.expect("every finding the prose discusses is inconsistent",
                set(DISCUSSED_FINDINGS) <= set(bad.id),
                str(sorted(set(DISCUSSED_FINDINGS) - set(bad.id))))
    page.expect("the 150 N fuel labels are swapped", bool(fuel["labels_swapped"]))
    page.expect("the printed masses imply an arrival mass of 523.98 kg",
                abs(arr.computed - 523.98) < 0.01, f"{arr.computed:.3f} kg")
    page.data.update(findings=ft)


def build(burns: dict, captures, output_name: str = "reproduction_report",
          quick: bool = False, parameters: dict | None = None) -> Page:
    """The reproduction report of the solves the notebook made (see the module docstring).

    Parameters
    ----------
    burns : dict
        Part (a): {(thrust_N, loi): [lunarcap.BurnSolution per offset of
        :func:`paper_starts`]} for LOI 1-3 of each engine compared, in the notebook's order
        (:func:`lunarcap.solve_burn` of :func:`lunarcap.paper_plan`, one dynamics).
    captures : list of lunarcap.CaptureResult
        Part (b): :func:`lunarcap.solve` of :func:`lunarcap.paper_plan` for each of the
        paper's three engines (:func:`paper_engines`), Table B1's offsets.
    output_name : str
        Prefix of the CSV files.
    quick : bool
        Recorded in the provenance (the quick run compares fewer engines in (a)).
    parameters : dict, optional
        The notebook's ``engines`` and ``dynamics``, shown in the provenance (default:
        read from the solves).
    """
    dynamics = str(captures[0].plan.dynamics)
    compared = {(b[0].plan.engine.thrust_N, b[0].plan.engine.isp_s): 1 for b in burns.values()}
    prm = dict(parameters or dict(engines=list(compared), dynamics=dynamics))
    engines = [(float(t), float(i)) for t, i in prm["engines"]]
    params = dict(engines=[list(e) for e in engines], dynamics=prm["dynamics"])
    page = Page(NOTEBOOK, params, output_name, quick, solver_description())
    findings = audit.audit_findings()
    sweeps, dur = _part_a(page, engines, sweeps_of(burns), dynamics, output_name)
    solutions = {float(c.plan.engine.thrust_N): [b.solution for b in c.burns]
                 for c in captures}
    chains, _ = _part_b(page, sweeps, solutions, dynamics, output_name, findings)
    _part_c(page, findings, chains, dur, output_name)
    t = page.text
    page.headline(f"{t('n_table_numbers')} numbers of the paper's tables beside ours: the "
                  f"median ΔV difference is {t('median_dv_diff_mps', '.3f', ' m/s')}, Table B1 "
                  f"agrees within {t('b1_max_dv_diff_percent', '.2f', ' %')}; "
                  f"{t('n_inconsistent', 'd')} of {t('n_findings', 'd')} checks of the paper "
                  f"against itself find an inconsistency beyond print resolution.")
    return page
