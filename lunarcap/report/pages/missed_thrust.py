"""The missed-thrust page (notebooks/missed_thrust.ipynb): a capture burn cut short.

The engine stops after a fraction of burn n of the plan; after a delay the rest of the
capture is re-planned and re-optimised to the same final orbit (:mod:`lunarcap.runs.missed`,
run on Dask and resumed from ``<cache>/study/<output_name>.csv``). :func:`build` shows the
penalty map (fraction × delay), the table of every case and the recovery's burns.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.mission.plan import load_plan
from lunarcap.report import figures
from lunarcap.report.page import Page, solver_description
from lunarcap.repro import paths
from lunarcap.runs import missed

NOTEBOOK = "notebooks/missed_thrust.ipynb"

CASE_SHOWN = ["fraction", "delay_min", "cutoff_orbit", "cutoff_ra_km",  # e: in the CSV
              "partial_delta_v_mps", "recovery_delta_v_mps", "penalty_mps", "first_coast_h",
              "time_to_final_orbit_h", "status"]


def recovery_rows(table: pd.DataFrame) -> pd.DataFrame:
    """One row per recovery burn of every recovered case."""
    rows = []
    for r in table.to_dict("records"):
        for b in missed.recovery_burns_of(r):
            rows.append({"fraction": r["fraction"], "delay_min": r["delay_min"], **b})
    return pd.DataFrame(rows)


def reading(t: pd.DataFrame) -> str:
    """What the table says for mission planning, in sentences computed from it."""
    t = t.reset_index(drop=True)
    ok = t[t.status == "recovered"]
    out = []
    for d, g in t.groupby("delay_min", sort=True):
        rec = g[g.status == "recovered"]
        esc = int((rec.cutoff_orbit == "escape").sum())
        if len(rec) == len(g):
            first = (f"With a delay of {d:g} min every cut-off is recovered, at a penalty of "
                     f"at most {rec.penalty_mps.max():.2f} m/s"
                     + (f" (including {esc} that left a hyperbola)" if esc else "") + ".")
        else:
            lo, hi = rec.penalty_mps.min(), rec.penalty_mps.max()
            span = (f" (penalty {lo:+.1f} m/s)" if len(rec) == 1 else
                    f" (penalty {lo:+.1f} to {hi:+.1f} m/s)" if len(rec) else "")
            first = (f"With a delay of {d:g} min, {len(rec)} of {len(g)} cut-offs "
                     f"{'is' if len(rec) == 1 else 'are'} recovered{span}; the "
                     f"{'other has' if len(g) - len(rec) == 1 else 'others have'} no verified "
                     f"recovery (see the table).")
        out.append(first)
    if len(ok):
        worst = ok.loc[ok.penalty_mps.idxmax()]
        out.append(f"Waiting is what costs: the worst recovered "
                   f"case (fraction {worst.fraction:g}, {worst.delay_min:g} min) costs "
                   f"{worst.penalty_mps:.1f} m/s, because the make-up burn is flown ever "
                   f"farther from the perilune, where a burn changes the orbit's energy most "
                   f"cheaply.")
        bound = ok.first_coast_h.dropna()
        if len(bound):
            out.append(f"In {int((bound >= bound.max() - 1e-6).sum())} of {len(bound)} "
                       f"recoveries the make-up orbit's coast sits at its upper bound "
                       f"({bound.max():.3f} h): the longest orbit allowed is what the "
                       f"recovery wants, so that bound shapes these penalties.")
    return " ".join(out)


def build(plan: str = "song2011-150N", burn: int = 1, fractions=(0.25, 0.5, 0.75, 0.9),
          delays_min=(0.0, 30.0, 120.0, 720.0), dynamics: str | None = None, workers: int = 2,
          output_name: str = "missed_thrust", quick: bool = False) -> Page:
    """The page (see the module docstring); ``dynamics`` None keeps the plan's own."""
    p = load_plan(plan)
    if dynamics is not None and dynamics != p.dynamics:
        p = p.with_dynamics(dynamics)
    params = dict(plan=plan, burn=burn, fractions=list(fractions),
                  delays_min=list(delays_min), dynamics=dynamics, workers=workers)
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(**{
        "recovery NLP": "8×16 LGR-5 per leg, free ignitions, the make-up orbit's coast free"}))
    res = missed.run_missed(p, burn, list(fractions), list(delays_min),
                            out=paths.CACHE / "study" / f"{output_name}.csv", workers=workers,
                            progress=False)
    t = res.table
    page.data.update(table=t, run=res.run)
    r0 = t.iloc[0]
    page.figure("penalty", figures.plot_missed_penalty(t), caption=(
        f"Penalty (m/s) of a cut-off in burn {burn} of {p.name} ({p.engine.thrust_N:g} N / "
        f"{p.engine.isp_s:g} s, {p.dynamics} dynamics): ΔV of the partial burn plus the "
        f"recovery's, minus the nominal burns {burn}–{p.n_burns} "
        f"({r0.nominal_remaining_delta_v_mps:.1f} m/s). “esc.”: the cut-off left a "
        f"hyperbola; “none”: no recovery within the plan's bounds (or the solver failed: "
        f"see the table)."), alt="Penalty map of a missed capture burn")
    page.table("cases", t, caption=(
        "Every case: the orbit at cut-off (escape: hyperbola; captured: apolune inside the "
        "Moon's sphere of influence), ΔV of the partial burn and of the recovery, penalty "
        "(m/s), the make-up orbit's coast to its perilune (h) and the time from the "
        "perilune before the burn to the end of the last burn (h)."),
        show_columns=CASE_SHOWN,
        floatfmt={"fraction": ".2f", "delay_min": ".0f", "cutoff_ra_km": ".0f"},  # else .3f
        columns={"cutoff_orbit": "orbit at cut-off",
                 "cutoff_ra_km": "apolune at cut-off (km)"})
    page.table("recovery", recovery_rows(t), caption=(
        "The recovery's burns: ignition (min after the fault is cleared), duration, ΔV."),
        floatfmt=".3f")
    ok = t[t.status == "recovered"]
    page.value("plan_name", p.name)
    page.value("burn", int(burn))
    page.value("nominal_rest_mps", float(r0.nominal_remaining_delta_v_mps))
    page.value("nominal_burn_min", float(r0.nominal_burn_duration_min))
    page.value("n_cases", int(len(t)))
    page.value("n_recovered", int(len(ok)))
    page.value("n_escape", int((t.cutoff_orbit == "escape").sum()))
    page.value("wall_s", float(res.run["wall_s"]))
    prompt = ok[ok.delay_min == ok.delay_min.min()] if len(ok) else ok
    page.value("max_prompt_penalty_mps", float(prompt.penalty_mps.max()) if len(prompt)
               else np.nan)
    page.value("max_penalty_mps", float(ok.penalty_mps.max()) if len(ok) else np.nan)
    late = ok[ok.delay_min == ok.delay_min.max()] if len(ok) else ok
    page.value("max_delay_min", float(t.delay_min.max()))
    page.value("n_late_recovered", int(len(late)))
    page.note("reading", reading(t))
    bugs = t[~t.status.isin(["recovered", "no recovery", "failed"])]
    page.value("n_failed", int((t.status == "failed").sum()))
    page.expect("no case ended in an unexpected error (failures are reported, not hidden)",
                bugs.empty, "; ".join(bugs.error.astype(str)))
    return page
