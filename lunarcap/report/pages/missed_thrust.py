"""The missed-thrust page (notebooks/missed_thrust.ipynb): a capture burn cut short or late.

The engine stops after a fraction of burn n of the plan, or burn n ignites late; the rest
of the capture is re-planned and re-optimised to the same final orbit
(:mod:`lunarcap.studies.missed.cases`, run on Dask and resumed from
``<cache>/study/<output_name>.csv``). :func:`build` shows the penalty map (fraction ×
delay), the table of every cut-off, the late ignitions and the recoveries' burns.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.quantities import capture_name
from lunarcap.report.contents import (
    BookPage,
    Execution,
    figure_files,
    includes,
    one_of,
    table_files,
)
from lunarcap.report.page import Page, counted, solver_description
from lunarcap.repro import paths
from lunarcap.studies.missed import cases as missed

NOTEBOOK = "notebooks/missed_thrust.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 100, (
    Execution(
        "missed_thrust", "Missed thrust and late ignition: a capture burn gone wrong",
        parameters=dict(
            plan="song2011-150N", burn=1,
            # 4 x 4 cut-offs and 3 late ignitions: 19 cases (the floors below)
            fractions=[0.25, 0.5, 0.75, 0.9], delays_min=[0.0, 30.0, 120.0, 720.0],
            late_min=[1.0, 5.0, 10.0],
            max_period_h=24.0,  # the orbit after burn 1, recovery and nominal alike
            dynamics=None,  # the plan's own (full)
            workers=2),
        quick_parameters=dict(fractions=[0.5, 1.0], delays_min=[0.0, 30.0], late_min=[5.0],
                              dynamics="two-body", workers=1),
        expected_s=125,  # 242 s of CPU measured (2 workers): 14.4 min wall at load 6-23
        outputs=(table_files("missed_thrust", "cases", "late", "recovery")
                 + figure_files("missed_thrust", "penalty")),
        floors=dict(
            plan=one_of(["song2011-150N"], "the paper's 150 N plan, the longest first burn"),
            burn=one_of([1], "the first burn, the one whose failure can leave a hyperbola"),
            fractions=includes([0.25, 0.5, 0.75, 0.9], "cut-offs from a quarter of the burn "
                                                       "to nine tenths"),
            delays_min=includes([0.0, 30.0, 120.0, 720.0], "recoveries at once, after half "
                                                           "an hour, two hours, half a day"),
            late_min=includes([1.0, 5.0, 10.0], "late ignitions to 10 min, the upper end "
                                                "of the KPLO study the page cites"),
            dynamics=one_of([None], "the plan's own (full) dynamics"))),
))

#: Shown (the rest in the CSV: e at cut-off, the partial burn's ΔV, the make-up orbit's
#: period, the time to the final orbit): with them the column broke words ("esca pe").
CASE_SHOWN = ["fraction", "delay_min", "cutoff_orbit", "cutoff_ra_km",
              "recovery_delta_v_mps", "penalty_mps", "make_up_delta_v_mps", "status",
              "reason"]


def recovery_rows(table: pd.DataFrame) -> pd.DataFrame:
    """One row per recovery burn of every recovered case."""
    rows = []
    for r in table.to_dict("records"):
        for b in missed.STUDY.decode(r, "recovery_burns"):
            rows.append({"contingency": r.get("contingency", "cut-off"),
                         "fraction": r["fraction"], "delay_min": r["delay_min"],
                         "late_min": r.get("late_min", 0.0), **b})
    return pd.DataFrame(rows)


LATE_SHOWN = ["late_min", "cutoff_orbit", "recovery_delta_v_mps", "make_up_period_h",
              "penalty_mps", "time_to_final_orbit_h", "status", "reason"]


def cut_offs(table: pd.DataFrame) -> pd.DataFrame:
    """The cut-off cases of a study's table (a table without ``contingency``: all)."""
    if "contingency" not in table:
        return table
    return table[table.contingency.fillna("cut-off") == "cut-off"].reset_index(drop=True)


def late_ignitions(table: pd.DataFrame) -> pd.DataFrame:
    """The late-ignition cases of a study's table, by lateness."""
    if "contingency" not in table:
        return table.iloc[0:0]
    t = table[table.contingency == "late ignition"]
    return t.sort_values("late_min").reset_index(drop=True)


def late_reading(t: pd.DataFrame) -> str:
    """What the late ignitions say, in sentences computed from them."""
    ok = t[t.status == "recovered"]
    if not len(t):
        return ""
    parts = [f"{r.late_min:g} min: {r.penalty_mps:+.2f} m/s" for r in ok.itertuples()]
    out = [f"Igniting late costs ({'; '.join(parts)})." if parts else ""]
    monotone = bool(np.all(np.diff(ok.penalty_mps.to_numpy()) > -0.05))
    if len(ok) > 1:
        out.append("The later, the dearer: each minute of lateness moves the burn away "
                   "from the perilune, where it changes the orbit's energy most cheaply."
                   if monotone else "The penalty is not monotone in the lateness here.")
    bad = t[t.status != "recovered"]
    out += [f"Late by {r.late_min:g} min: {r.status} ({r.reason})." for r in bad.itertuples()]
    return " ".join(x for x in out if x)


#: A penalty within this of zero is "nothing above the nominal" (the solver's tolerance on
#: the total delta-V of the two optimisations it compares), m/s.
ZERO_PENALTY_MPS = 0.01


def bound_verdict(ok: pd.DataFrame, max_period_h: float,
                  zero_mps: float = ZERO_PENALTY_MPS) -> str:
    """Whether the bound on the make-up orbit's period shapes the recovered penalties.

    Computed from the recovered cases ``ok`` (``make_up_period_h``, ``penalty_mps``): a
    recovery whose make-up orbit sits at the bound and whose penalty is above ``zero_mps``
    would cost less with a longer bound; one at the bound that already costs nothing above
    the nominal (within ``zero_mps``) would not.
    """
    rows = ok.dropna(subset=["make_up_period_h"])
    at = rows[rows.make_up_period_h >= max_period_h - 1e-3]
    costly = at[at.penalty_mps > zero_mps]
    head = (f"In {len(at)} of {len(rows)} recoveries with a make-up orbit its period sits at "
            f"the {max_period_h:g} h bound")
    if not len(at):
        return head + ": the bound shapes none of these penalties."
    if not len(costly):
        return (head + f", and none of them costs more than {zero_mps:g} m/s above the "
                "nominal: the bound shapes none of these penalties.")
    free = len(at) - len(costly)
    return (head + f"; for the {len(costly)} of them with a penalty above {zero_mps:g} m/s a "
            "longer bound would lower the penalty"
            + (f", while the other {free} already cost nothing above the nominal (within "
               f"{zero_mps:g} m/s)." if free else "."))


def escape_fractions(t: pd.DataFrame) -> list[float]:
    """The fractions of the burn whose cut-off leaves a hyperbola (whatever the delay).

    A cut-off is a fraction of the burn: the orbit it leaves does not depend on how long
    the spacecraft coasts afterwards, so it is counted once, not once per delay.
    """
    return sorted(set(t.fraction[t.cutoff_orbit == "escape"].astype(float)))


def escape_sentence(t: pd.DataFrame) -> str:
    """Which cut-offs leave a hyperbola, counted as fractions of the burn (and cases).

    >>> t = pd.DataFrame({"fraction": [0.25, 0.25, 0.5, 0.5, 0.9, 0.9],
    ...                   "cutoff_orbit": ["escape"] * 4 + ["captured"] * 2})
    >>> escape_sentence(t)[:70]
    'A cut-off after 0.25 or 0.5 of the burn (2 of the 3 fractions tried; 4'
    """
    esc = escape_fractions(t)
    tried = sorted(set(t.fraction.astype(float)))
    if not esc:
        return (f"No cut-off tried (after {', '.join(f'{f:g}' for f in tried)} of the burn) "
                "leaves the spacecraft on a hyperbola")
    which = " or ".join([", ".join(f"{f:g}" for f in esc[:-1]), f"{esc[-1]:g}"]
                        if len(esc) > 1 else [f"{esc[0]:g}"])
    n_cases = int((t.cutoff_orbit == "escape").sum())
    return (f"A cut-off after {which} of the burn ({len(esc)} of the {len(tried)} fractions "
            f"tried; {n_cases} of the {len(t)} cases with their delays) leaves the spacecraft "
            "on a hyperbola")


def reading(t: pd.DataFrame, max_period_h: float | None = None) -> str:
    """What the table says for mission planning, in sentences computed from it."""
    t = cut_offs(t).reset_index(drop=True)
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
                     f"recovery (see the table for the reason).")
        out.append(first)
    if len(ok):
        worst = ok.loc[ok.penalty_mps.idxmax()]
        out.append(f"The worst recovered case (fraction {worst.fraction:g}, "
                   f"{worst.delay_min:g} min) costs {worst.penalty_mps:.1f} m/s.")
    if len(ok) and max_period_h is not None and "make_up_period_h" in ok:
        out.append(bound_verdict(ok, max_period_h))
    waited = ok[ok.reason.fillna("").str.startswith("make-up burn at")]
    for r in waited.itertuples():   # the make-up waited for a perilune: the reason says why
        out.append(f"Fraction {r.fraction:g}, {r.delay_min:g} min: recovered, the "
                   f"{r.reason[0].lower()}{r.reason[1:]}.")
    refused = t[t.status != "recovered"]
    for r in refused.itertuples():
        out.append(f"Fraction {r.fraction:g}, {r.delay_min:g} min: {r.status}, "
                   f"{r.reason}.")
    return " ".join(out)


def table_file(output_name: str = "missed_thrust"):
    """Where the book keeps this page's study table, resumed on rerun (a Path).

    ``<cache>/study/<output_name>.csv``: the notebook passes it as the study's ``out`` so
    that the book's run resumes the book's own table (not the command line's default).
    """
    return paths.CACHE / "study" / f"{output_name}.csv"


def build(study, table: pd.DataFrame, penalty_figure, output_name: str = "missed_thrust",
          quick: bool = False, parameters: dict | None = None) -> Page:
    """The page of a missed-thrust study computed in the notebook (see the module docstring).

    Parameters
    ----------
    study : lunarcap.StudyResult
        :func:`lunarcap.missed`'s result (its plan, burn, bound, campaign's path and run).
    table : pandas.DataFrame
        ``study.to_frame()``: every case, cut-offs and late ignitions.
    penalty_figure : matplotlib.figure.Figure
        ``study.plot()``: the penalty map of the cut-offs.
    output_name, quick : the page's output name and whether it is a quick build.
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance.
    """
    p, doc = study.plan, study.document()
    burn, max_period_h = int(doc["burn"]), float(doc["max_period_h"])
    params = {k: list(v) if isinstance(v, (list, tuple)) else v
              for k, v in (parameters or {}).items()}
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(**{
        "recovery NLP": "8×16 LGR-5 per leg (12×24 if verification asks), free ignitions, "
                        f"the make-up orbit free up to {max_period_h:g} h"}))
    res = study.campaign
    everything = table
    t, late = cut_offs(everything), late_ignitions(everything)
    page.data.update(table=everything, run=res.run)
    r0 = t.iloc[0]
    page.figure("penalty", penalty_figure, caption=(
        f"Penalty (m/s) of a cut-off in burn {burn} of {p.name} ({p.engine.thrust_N:g} N / "
        f"{p.engine.isp_s:g} s, {p.dynamics} dynamics): partial burn plus recovery minus "
        f"the nominal burns {burn}–{p.n_burns} ({r0.nominal_remaining_delta_v_mps:.1f} m/s), "
        f"the orbit after burn {burn} free up to {max_period_h:g} h. “esc.”: hyperbola; "
        f"“none”: no recovery (table)."),
        alt="Penalty map of a missed capture burn")
    page.table("cases", t, caption=(
        "Every cut-off: the orbit left (escape: hyperbola), the recovery and its penalty "
        "(m/s), and why a case has none. The study's whole table: "
        f"{page.data_link(res.path, 'study.csv')}."),
        show_columns=CASE_SHOWN,
        floatfmt={"fraction": ".2f", "delay_min": ".0f", "cutoff_ra_km": ".0f"},  # else .3f
        columns={"cutoff_orbit": "orbit at cut-off",
                 "cutoff_ra_km": "apolune at cut-off (km)"})
    page.table("late", late, caption=(
        f"Late ignition: burn {burn} ignites the given minutes after its planned ignition, "
        f"is re-optimised from there (its orbit free up to {max_period_h:g} h) and the later "
        f"burns re-planned; penalty against the same nominal."),
        show_columns=LATE_SHOWN, floatfmt={"late_min": ".0f"},
        columns={"cutoff_orbit": "orbit at ignition"})
    page.table("recovery", recovery_rows(everything), caption=(
        "The recovery's burns: ignition (min after the fault is cleared, or after the late "
        "ignition), duration, ΔV."), floatfmt=".3f",
        show_columns=["contingency", "fraction", "delay_min", "late_min", "burn", "target_orbit",
                      "ignition_min_after_fault", "burn_duration_min", "delta_v_mps",
                      "verified"])  # the ignition epochs: in the CSV
    _values(page, p, burn, t, late, res.run, max_period_h)
    page.capture("free_periods", p.dynamics)
    return page


def _values(page: Page, p, burn: int, t: pd.DataFrame, late: pd.DataFrame, run: dict,
            max_period_h: float) -> None:
    """The page's glued numbers, notes and checks."""
    ok = t[t.status == "recovered"]
    r0 = t.iloc[0]
    page.value("plan_name", p.name)
    page.value("burn", int(burn))
    page.value("max_period_h", float(max_period_h))
    page.value("nominal_rest_mps", float(r0.nominal_remaining_delta_v_mps))
    page.value("nominal_burn_min", float(r0.nominal_burn_duration_min))
    page.value("nominal_period_h", float(r0.nominal_period_after_burn_h)
               if pd.notna(r0.nominal_period_after_burn_h) else np.nan)
    page.value("n_cases", int(len(t)))
    page.value("n_recovered", int(len(ok)))
    page.value("n_no_recovery", int((t.status == "no recovery").sum()))
    page.value("recovered_counted", counted(len(ok), len(t), "cases",
                                            ("is recovered", "are recovered")))
    page.value("no_recovery_counted", counted(page.values["n_no_recovery"], len(t),
                                              "cases", ("has", "have")))
    page.value("n_escape", int((t.cutoff_orbit == "escape").sum()))
    esc = escape_fractions(t)
    page.value("n_escape_fractions", len(esc))
    page.value("n_fractions", int(t.fraction.nunique()))
    page.value("escape_sentence", escape_sentence(t))
    page.value("wall_s", float(run["wall_s"]))
    page.value("max_penalty_mps", float(ok.penalty_mps.max()) if len(ok) else np.nan,
               why="no case recovered")
    # + 0.0: a penalty of -0.0003 m/s is shown as 0.00, not -0.00
    page.value("min_penalty_mps", round(float(ok.penalty_mps.min()), 2) + 0.0 if len(ok)
               else np.nan, why="no case recovered")
    page.value("n_failed", int((~t.status.isin(["recovered", "no recovery"])).sum()))
    page.note("reading", reading(t, max_period_h))
    tx = page.text
    n_esc = len(esc)
    page.headline(f"When burn {burn} of `{p.name}` ({p.dynamics} dynamics) is cut short, the "
                  f"cut-off{'' if n_esc == 1 else 's'} at {n_esc} of the "
                  f"{tx('n_fractions', '.0f')} fractions tried leave{'s' if n_esc == 1 else ''} "
                  f"the spacecraft on a hyperbola; "
                  f"{counted(len(ok), len(t), 'cut-off cases', ('is', 'are'))} recovered "
                  f"(penalty at most "
                  f"{tx('max_penalty_mps', '.1f', ' m/s')} against the nominal "
                  f"*{capture_name('free_periods')}*).")
    page.note("late_reading", late_reading(late))
    bugs = t[~t.status.isin(["recovered", "no recovery", "failed"])]
    page.expect("no case ended in an unexpected error (failures are reported, not hidden)",
                bugs.empty, "; ".join(bugs.error.astype(str)))
    # a make-up at a later perilune splits the burn over two perilunes, a freedom the
    # nominal lacks: its penalty may be negative, and its reason says why
    below = ok[ok.penalty_mps < -0.05]
    unexplained = below[~below.reason.fillna("").str.contains("cheaper than the nominal")]
    same = ok[~ok.reason.fillna("").str.startswith("make-up burn at")]
    page.expect("every penalty in the window is >= -0.05 m/s (the nominal has the recovery's "
                "freedoms), and every one below says why", (same.empty or
                same.penalty_mps.min() >= -0.05) and unexplained.empty,
                f"min penalty {same.penalty_mps.min() if len(same) else 0:.3f} m/s; "
                f"{len(unexplained)} below without a reason")
