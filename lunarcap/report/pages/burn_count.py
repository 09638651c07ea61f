"""The number-of-burns page (notebooks/burn_count.ipynb): how many capture burns to plan.

For each plan, the capture from its arrival to its final orbit in N = 1, 2, ... burns,
the intermediate periods optimised (:mod:`lunarcap.studies.burn_count.counts`, run on Dask and
resumed from the table ``<cache>/study/<output_name>.csv``). :func:`build` shows one row per
plan and count, one row per burn, and the figure: total loss and time to the final orbit against
N, one line per plan.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pandas as pd

from lunarcap.mission.impulsive import capture_total_mps
from lunarcap.quantities import capture_name
from lunarcap.report.contents import (
    BookPage,
    Execution,
    figure_files,
    includes,
    one_of,
    table_files,
)
from lunarcap.report.figures import burn_count as draw
from lunarcap.report.page import Page, counted, solver_description
from lunarcap.repro import paths
from lunarcap.studies.burn_count import counts as burns
from lunarcap.studies.study import plan_id

NOTEBOOK = "notebooks/burn_count.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 90, (
    Execution(
        "burn_count", "How many capture burns",
        parameters=dict(
            plans=["song2011-150N", "song2011-300N", "song2011-450N", "lro-like-5burn"],
            counts=[1, 2, 3, 4, 5],  # the five burns of LRO, SELENE and Chang'e
            max_period_h=12.235, max_days=3.0,
            dynamics=None,  # each plan's own (full)
            workers=2),
        quick_parameters=dict(plans=["song2011-150N"], counts=[1, 2, 3], dynamics="two-body",
                              workers=1),
        expected_s=115,  # 228 s of CPU measured (2 workers): 10.7 min wall at load 19-24
        outputs=(table_files("burn_count", "counts", "burns")
                 + figure_files("burn_count", "loss")),
        floors=dict(
            plans=includes(["song2011-150N", "song2011-300N", "song2011-450N",
                            "lro-like-5burn"], "the paper's three engines and the LRO-like "
                                               "plan"),
            counts=includes([1, 2, 3, 4, 5], "one to five burns, as LRO, SELENE and Chang'e "
                                             "flew"),
            dynamics=one_of([None], "each plan's own (full) dynamics"))),
))

COUNT_SHOWN = ["plan", "n_burns", "status", "periods_h", "total_delta_v_mps",
               "total_impulsive_limit_mps", "total_delta_v_loss_mps", "total_fuel_kg",
               "time_to_final_orbit_h"]
BURN_SHOWN = ["plan", "n_burns", "burn", "target_orbit", "start_min", "burn_duration_min",
              "delta_v_mps", "impulsive_limit_mps", "delta_v_loss_mps", "verified"]


def label_of(plan) -> str:
    """'song2011-150N (150 N / 200 s, 524.895 kg)'."""
    return (f"{plan.name} ({plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} s, "
            f"{plan.arrival.mass_kg:g} kg)")


def count_table(table: pd.DataFrame, labels: dict) -> pd.DataFrame:
    """One row per plan and count (the study's columns; periods as text, h)."""
    t = table.copy()
    t.insert(0, "label", [labels[p] for p in t.plan_id])
    t["periods_h"] = [", ".join(f"{float(p):.3f}" for p in s.split(";")) if
                      isinstance(s, str) and s else "—" for s in t.periods_h]
    return t


def burn_rows(table: pd.DataFrame) -> pd.DataFrame:
    """One row per burn of every successful count."""
    rows = []
    for r in table.to_dict("records"):
        for b in burns.STUDY.decode(r, "burns"):
            rows.append({"plan": r["plan"], "n_burns": int(r["n_burns"]), **b})
    return pd.DataFrame(rows)


def reading(table: pd.DataFrame) -> str:
    """Per plan, what the counts say (loss and time at the fewest and most burns solved)."""
    out = []
    for label, g in table.groupby("label", sort=False):
        ok = g[g.status == "ok"].sort_values("n_burns")
        bad = g[g.status != "ok"]
        if len(ok) >= 2:
            a, b = ok.iloc[0], ok.iloc[-1]
            step = ok.total_delta_v_loss_mps.diff().iloc[-1]
            out.append(f"{label}: from {int(a.n_burns)} to {int(b.n_burns)} burns the loss "
                       f"goes from {a.total_delta_v_loss_mps:.1f} to "
                       f"{b.total_delta_v_loss_mps:.1f} m/s and "
                       f"the final orbit is reached {b.time_to_final_orbit_h:.1f} h after "
                       f"arrival instead of {a.time_to_final_orbit_h:.1f} h; the last burn "
                       f"added changes the loss by {step:+.2f} m/s.")
        elif len(ok) == 1:
            out.append(f"{label}: only N = {int(ok.n_burns.iloc[0])} solved "
                       f"(loss {ok.total_delta_v_loss_mps.iloc[0]:.1f} m/s).")
        if len(bad):
            out.append(f"{label}: " + " ".join(f"N = {int(r.n_burns)}: {r.status} "
                                               f"({str(r.reason)[:160]})."
                                               for r in bad.itertuples()))
    return "\n\n".join(f"* {x}" for x in out)


#: How finely the impulsive limit's delta-V is resolved along its flat objective, m/s
#: (:func:`lunarcap.capture.chain._impulsive_limit`: near-equal optima a few seconds apart
#: differ by ~0.2 m/s in delta-V and ~0.003 m/s in the objective).
IMPULSIVE_DV_RESOLUTION_MPS = 0.2


def negative_losses(rows: pd.DataFrame) -> str:
    """A sentence on per-burn delta-V losses below zero, or "" if there is none.

    A finite burn cannot beat an impulse from the same orbit; a per-burn delta-V loss
    below zero but within the impulsive limit's resolution is that resolution, not a
    gain; one beyond it would be a defect (said so).
    """
    neg = rows[rows.delta_v_loss_mps < 0] if "delta_v_loss_mps" in rows else rows.iloc[:0]
    if neg.empty:
        return ""
    worst = float(neg.delta_v_loss_mps.min())
    within = worst > -IMPULSIVE_DV_RESOLUTION_MPS
    return (f"{len(neg)} burn(s) show a ΔV loss below zero (down to {worst:.3f} m/s): "
            + ("within the ~0.2 m/s to which the impulsive limit's ΔV is resolved along "
               "its nearly flat objective (near-equal optima a few seconds apart), so not a "
               "gain over an impulse; the totals, where these differences cancel, are the "
               "quantities to compare." if within else
               "beyond the impulsive limit's resolution (~0.2 m/s): treat these rows as "
               "suspect."))


def table_file(output_name: str = "burn_count"):
    """Where the book keeps this page's study table, resumed on rerun (a Path).

    ``<cache>/study/<output_name>.csv``: the notebook passes it as each study's ``out``, so
    that every plan's counts go to the book's one table (not the command line's default).
    """
    return paths.CACHE / "study" / f"{output_name}.csv"


def one_run(studies) -> dict:
    """The run record of the plans' studies together: the first's, its ``wall_s`` the sum (s).

    The notebook runs one study per plan (:func:`lunarcap.burns`); the page quotes the time
    they took together.
    """
    runs = [s.campaign.run for s in studies]
    return dict(runs[0], wall_s=round(sum(float(r["wall_s"]) for r in runs), 2),
                cases=sum(int(r["cases"]) for r in runs))


def build(studies, table: pd.DataFrame, output_name: str = "burn_count", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The page of the plans' burns studies computed in the notebook (see the module).

    Parameters
    ----------
    studies : list of lunarcap.StudyResult
        :func:`lunarcap.burns`'s result for each plan (the first is the page's reference),
        all written to one table (:func:`table_file`).
    table : pandas.DataFrame
        Their tables one after the other (``pd.concat([s.to_frame() for s in studies])``).
    output_name, quick : the page's output name and whether it is a quick build.
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance (``dynamics`` None:
        each plan's own, as the page's capture note says).
    """
    params = {k: list(v) if isinstance(v, (list, tuple)) else v
              for k, v in (parameters or {}).items()}
    ps = [s.plan for s in studies]
    doc = studies[0].document()
    counts = sorted(set(table.n_burns.astype(int)))
    max_period_h, max_days = float(doc["max_period_h"]), float(doc["max_days"])
    dynamics = params.get("dynamics")   # None: each plan's own
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(**{
        "all-burns NLP": "8×16 LGR-5 per leg, free ignitions and intermediate periods",
        "impulsive limit": "4 s and 2 s burns, Richardson-extrapolated"}))
    res = SimpleNamespace(table=table.reset_index(drop=True), run=one_run(studies),
                          path=studies[0].campaign.path)
    labels = {plan_id(p): label_of(p) for p in ps}
    table = count_table(res.table, labels)
    page.data.update(table=table, run=res.run)
    page.table("counts", table, caption=(
        f"Each plan's capture in N burns, intermediate periods minimising the total ΔV (each "
        f"at most {max_period_h:g} h and no longer than the one before; all within "
        f"{max_days:g} days). Loss: against the burns' impulsive limits. Time: to the last "
        f"cut-off. The whole table: {page.data_link(res.path, 'study.csv')}."),
        show_columns=COUNT_SHOWN, floatfmt=".3f",
        columns={"periods_h": "periods (h)", "n_burns": "N"})
    page.table("burns", burn_rows(res.table), caption=(
        "Every burn of every count: ignition (min from its nominal perilune), duration, "
        "ΔV, its impulsive limit and loss (m/s), verification."),
        show_columns=BURN_SHOWN, floatfmt=".3f", columns={"n_burns": "N"})
    page.figure("loss", draw.plot_burn_count(table), caption=(
        "Total loss, then the time to the last cut-off, against the number of burns; one "
        "line per plan. A count with no capture is marked in the strip above (× infeasible, "
        "! solver failed; the table says why)."),
        alt="Total loss and time to the final orbit against the number of burns")
    # ---- numbers the prose quotes (the first plan is the reference)
    ref = table[table.plan_id == plan_id(ps[0])]
    ok = ref[ref.status == "ok"].sort_values("n_burns")
    page.value("ref_plan", ps[0].name)
    page.value("two_body_total_mps", capture_total_mps(ps[0].perilune_radius_km,
                                                       ps[0].arrival.v_inf_kmps))
    page.value("wall_s", float(res.run["wall_s"]))
    page.value("n_cases", int(len(table)))
    page.value("n_infeasible", int((table.status == "infeasible").sum()))
    page.value("infeasible_counted", counted(page.values["n_infeasible"], len(table),
                                             "plan-and-count cases",
                                             ("lacks a plan", "lack a plan")))
    page.value("n_failed", int((~table.status.isin(["ok", "infeasible"])).sum()))
    for n in sorted(set(range(1, 6)) | set(counts)):  # the prose quotes N = 1 to 3
        row = ok[ok.n_burns == n]
        page.value(f"loss_{n}_mps",
                   float(row.total_delta_v_loss_mps.iloc[0]) if len(row) else np.nan)
        page.value(f"time_{n}_h", float(row.time_to_final_orbit_h.iloc[0]) if len(row)
                   else np.nan)
    if len(ok) >= 2:
        a, b = ok.iloc[0], ok.iloc[-1]
        page.value("first_n", int(a.n_burns))
        page.value("last_n", int(b.n_burns))
        page.value("loss_drop_mps", float(a.total_delta_v_loss_mps - b.total_delta_v_loss_mps))
        page.value("time_added_h", float(b.time_to_final_orbit_h - a.time_to_final_orbit_h))
        steps = np.diff(ok.total_delta_v_loss_mps.to_numpy(float))
        page.value("last_step_gain_mps", float(-steps[-1]))
        page.expect("the loss falls as burns are added (reference plan)", bool(np.all(steps < 0)),
                    f"losses {list(np.round(ok.total_delta_v_loss_mps, 3))}")
    negative = negative_losses(burn_rows(table))
    page.note("reading", reading(table) + (f"\n\n* {negative}" if negative else ""))
    bugs = table[~table.status.isin(["ok", "infeasible", "failed"])]
    page.expect("no count ended in an unexpected error (failures are reported, not hidden)",
                bugs.empty, "; ".join(bugs.error.astype(str)))
    t = page.text
    page.headline(f"For {t('ref_plan')} (*{capture_name('free_periods')}*), the loss is "
                  f"{t('loss_1_mps', '.1f', ' m/s')} in one burn, "
                  f"{t('loss_2_mps', '.1f', ' m/s')} in two and {t('loss_3_mps', '.1f', ' m/s')} "
                  f"in three: impulses cost the same whatever the count, the finite burns do not.")
    page.capture("free_periods", dynamics)
    return page
