"""The KPLO-class page (notebooks/kplo_capture.ipynb): a capture designed in the real Moon.

The packaged plan ``kplo-like-3burn`` is the lunar orbit insertion of the Korea Pathfinder
Lunar Orbiter as KARI designed it (:data:`lunarcap.report.pages.real_missions.SOURCES`
S13: perilune speeds, impulsive delta-Vs, about 550 kg; four 30 N thrusters from
{cite:t}`song2016`), its engine's specific impulse, epoch and approach assumed, designed
with finite burns in LP165P. The notebook designs it (:func:`lunarcap.solve`), runs the
missed-thrust and the burns studies on it (:func:`lunarcap.missed`, :func:`lunarcap.burns`)
and re-flies it in GMAT (``CaptureResult.fly_in_gmat``); :func:`build` formats them and

* sets the plan beside its sources and says which numbers are assumed (:func:`sources_table`)
  and gives its arrival as the B-plane target it amounts to, in EME2000 axes (GMAT's
  ``BdotT``/``BdotR``) and about the lunar equator (:func:`bplane_table`);
* justifies the field's degree: the capture designed again in lower and higher degrees
  (its total delta-V) and its final orbit flown for days in each (:func:`degree_table`);
* tabulates the design (:func:`design_table`: each burn beside KARI's impulse and the
  impulsive limit in the field, or why there is none);
* tabulates the studies and the GMAT flight the notebook ran and follows its orbit for days.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd

from lunarcap.capture.chain import after_capture, arrival_for, plan_result
from lunarcap.mission.plan import PLAN_DIR
from lunarcap.physics import constants as C
from lunarcap.physics.bplane import bplane_from_rv
from lunarcap.physics.elements import rv_from_mee, semi_major_axis_from_period
from lunarcap.physics.forces import force_model
from lunarcap.physics.frames import icrf_from_mme
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.figures import real_moon as draw
from lunarcap.report.page import Page, solver_description
from lunarcap.report.pages.gmat_flight import comparison_table, final_table
from lunarcap.report.pages.missed_thrust import cut_offs, late_ignitions, late_reading, reading
from lunarcap.report.pages.real_missions import KPLO_DV_MPS, KPLO_SPEED_KMPS
from lunarcap.report.pages.real_moon import evolution_table, histories, model_name
from lunarcap.repro import paths
from lunarcap.studies.burn_count import counts as burns
from lunarcap.studies.families import field_dynamics
from lunarcap.studies.missed import cases as missed

NOTEBOOK = "notebooks/kplo_capture.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 75, (
    Execution(
        "kplo_capture", "A KPLO-class capture in the real Moon",
        parameters=dict(
            plan="kplo-like-3burn", dynamics=None,  # the plan's own: LP165P 20x20
            check_degrees=[10, 30],  # the capture designed again in these degrees
            evolve_degrees=[8, 20, 30, 40], after_days=7.0,  # its final orbit, flown
            fractions=[0.5, 0.9], delays_min=[0.0, 30.0], late_min=[2.0],  # burn 1
            counts=[2, 3], gmat=True, workers=2),
        # quick: two-body, one cut-off, one count, a day after (no field, no degree)
        quick_parameters=dict(dynamics="two-body", check_degrees=[], evolve_degrees=[],
                              after_days=1.0, fractions=[0.9], delays_min=[0.0], late_min=[],
                              counts=[2], workers=1),
        expected_s=900,
        outputs=(table_files("kplo_capture", "sources", "bplane", "degree", "design",
                             "missed", "counts", "gmat", "gmat_final", "after")
                 + figure_files("kplo_capture", "evolution"))),
))

#: The plan's sources as the page names them (the real-missions page's keys).
K1, K2 = "S13", "Song et al. (2016)"
#: The engine the plan takes from K2, N: "Four 30 N thrusters will be used as the main
#: thrusters" (Song, Bae, Kim & Kim 2016, Sec. 1).
K2_THRUST_N = 4 * 30.0
#: KARI's launch mass (S13 Sec. 1: "approximately 550 kg"), kg.
K1_MASS_KG = 550.0
#: The 7-day perilunes of two fields agree "within a kilometre" up to this, km.
AGREE_KM = 1.5


def perilune_speed_kmps(v_inf_kmps: float, rp_km: float, mu: float = C.MU_MOON) -> float:
    """Two-body perilune speed of a hyperbola of ``v_inf_kmps`` at radius ``rp_km``, km/s."""
    return math.sqrt(v_inf_kmps ** 2 + 2 * mu / rp_km)


def ellipse_perilune_speed_kmps(period_s: float, rp_km: float, mu: float = C.MU_MOON) -> float:
    """Two-body perilune speed of the ellipse of ``period_s`` and perilune radius, km/s."""
    a = float(semi_major_axis_from_period(period_s, mu))
    return math.sqrt(mu * (2 / rp_km - 1 / a))


def sources_table(plan) -> pd.DataFrame:
    """Each number of the plan beside its source's, and which are assumed.

    Perilune speeds (km/s) on arrival and after LOI 1 and 2, the plan's as the two-body
    speeds of its v_inf and target periods at its perilune radius (lunarcap's GM and
    radius); the final orbit, the mass, the engine, the epoch and the field.
    """
    rp, a = plan.perilune_radius_km, plan.arrival
    speeds = [perilune_speed_kmps(a.v_inf_kmps, rp)] + [
        ellipse_perilune_speed_kmps(b.period_s, rp) for b in plan.burns[:2]]
    rows = [(f"perilune speed {w} (km/s)", f"{k:.3f}", f"{s:.4f}", K1)
            for w, k, s in zip(("on arrival", "after LOI 1", "after LOI 2"),
                               KPLO_SPEED_KMPS, speeds)]
    rows += [
        ("final orbit", "100 km circle, polar", f"{a.perilune_altitude_km:g} km circle, "
         f"{a.inclination_deg:g} deg", K1),
        ("mass at arrival (kg)", f"about {K1_MASS_KG:g} (launch)", f"{a.mass_kg:g}",
         f"{K1} (an upper bound: the launch mass)"),
        ("thrust (N)", f"4 × 30 = {K2_THRUST_N:g}", f"{plan.engine.thrust_N:g}", K2),
        ("specific impulse (s)", "not given", f"{plan.engine.isp_s:g}", "assumed"),
        ("arrival epoch (TDB)", "not given", a.epoch, "assumed"),
        ("hemisphere of the perilune, approach", "not given",
         f"{a.hemisphere}, anti-parallel to the Moon's velocity", "assumed"),
        ("gravity field", "not given", str(force_model(plan.dynamics)),
         "assumed; its degree is justified below")]
    return pd.DataFrame(rows, columns=["quantity", "source_value", "plan_value", "source"])


def bplane_table(plan) -> pd.DataFrame:
    """The arrival's B-plane target (km) in EME2000 axes and about the lunar equator.

    From the arrival perilune state's two-body hyperbola
    (:func:`lunarcap.physics.bplane.bplane_from_rv`): T = S x k / |S x k|, R = S x T, with
    k the ICRF z axis (EME2000: GMAT's ``BdotT``/``BdotR``) or the plan frame's pole (the
    lunar equator of ``lunar_pole``).
    """
    arr = arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole)
    r, v = (np.asarray(q, float) for q in rv_from_mee(*arr.state[:6], C.MU_MOON))
    rows = []
    for ref, rr, vv in (("EME2000 (ICRF z; GMAT's BdotT, BdotR)",
                         icrf_from_mme(r, plan.lunar_pole), icrf_from_mme(v, plan.lunar_pole)),
                        ("lunar equator (the plan's frame: its pole of date)", r, v)):
        b = bplane_from_rv(rr, vv, C.MU_MOON)
        rows.append({"reference": ref, "b_t_km": b.b_t_km, "b_r_km": b.b_r_km,
                     "v_inf_kmps": b.v_inf_kmps})
    return pd.DataFrame(rows)


def design_table(result) -> pd.DataFrame:
    """Each burn: ignition, duration, delta-V, KARI's impulse, the impulsive limit or why none.

    ``delta_v_difference_mps`` is ours minus KARI's impulsive delta-V (S13 Table 2): the
    finite burn's loss and the field's and the Earth's and Sun's effect together.
    """
    rows = []
    for k, b in enumerate(result.burns):
        row = b.row()
        rows.append({"burn": k + 1, "target_orbit": result.plan.burns[k].describe(),
                     "ignition_epoch": row["ignition_epoch"], "start_min": row["start_min"],
                     "burn_duration_min": row["burn_duration_min"],
                     "delta_v_mps": row["delta_v_mps"],
                     "kplo_delta_v_mps": KPLO_DV_MPS[k] if k < len(KPLO_DV_MPS) else np.nan,
                     "impulsive_limit_mps": row["impulsive_limit_mps"],
                     "delta_v_loss_mps": row["delta_v_loss_mps"],
                     "impulsive_limit_reason": row.get("impulsive_limit_reason") or "",
                     "verified": bool(row["verification_passed"])})
    df = pd.DataFrame(rows)
    df["delta_v_difference_mps"] = df.delta_v_mps - df.kplo_delta_v_mps
    return df


def degree_table(designs: dict, plan_degree: int) -> pd.DataFrame:
    """Per field degree: the capture's total delta-V and its change from the plan's degree.

    ``designs``: {degree: PlanResult}. Rows in degree order.
    """
    ref = designs[plan_degree].totals()["total_delta_v_mps"]
    rows = []
    for d in sorted(designs):
        tot = designs[d].totals()["total_delta_v_mps"]
        rows.append({"model": model_name(field_dynamics(d)), "total_delta_v_mps": tot,
                     "delta_v_change_mps": tot - ref})
    return pd.DataFrame(rows)


def perilune_spread_km(evolutions: dict, label: str, against: str) -> float:
    """The largest difference (km) of two evolutions' perilune altitudes, per revolution."""
    a = np.asarray(evolutions[label].perilune_altitude_km, float)
    b = np.asarray(evolutions[against].perilune_altitude_km, float)
    n = min(a.size, b.size)
    return float(np.max(np.abs(a[:n] - b[:n])))


def model_label(dynamics) -> str:
    """How the tables name a model: "LP165P 20x20", or the model's own words."""
    f = force_model(dynamics)
    return model_name(dynamics) if f.is_field else str(f)


#: The missed-thrust table's columns shown (the rest in the CSV).
MISSED_SHOWN = ["contingency", "fraction", "delay_min", "late_min", "cutoff_orbit",
                "recovery_delta_v_mps", "penalty_mps", "make_up_delta_v_mps", "status",
                "reason"]
#: The burns table's columns shown.
COUNTS_SHOWN = ["n_burns", "status", "periods_h", "total_delta_v_mps",
                "total_impulsive_limit_mps", "total_fuel_kg", "time_to_final_orbit_h",
                "reason"]
#: Tolerance of the days after the capture (:data:`lunarcap.report.pages.real_moon.
#: EVOLUTION_RTOL`'s reason: 3 mm on the perilunes of 7 days in LP165P 20x20).
EVOLUTION_RTOL = 1e-10


def table_file(output_name: str = "kplo_capture", study: str = "missed") -> Path:
    """Where the book keeps one study's table of this page, resumed on rerun.

    ``<cache>/study/<output_name>_<study>.csv`` (``study``: ``"missed"`` or ``"burns"``):
    the notebook passes it as the study's ``out``, so the book resumes its own table.
    """
    return paths.CACHE / "study" / f"{output_name}_{study}.csv"


def export_dir(output_name: str = "kplo_capture") -> Path:
    """Where the book keeps the capture exported for GMAT (a Path): its flight's files."""
    return paths.export_dir(output_name)


def build(result, missed_study=None, counts_study=None, flight=None,
          output_name: str = "kplo_capture", quick: bool = False,
          parameters: dict | None = None, check_degrees=(), evolve_degrees=(),
          after_days: float = 7.0) -> Page:
    """The page of the KPLO-class capture computed in the notebook (see the module docstring).

    Parameters
    ----------
    result : lunarcap.CaptureResult
        :func:`lunarcap.solve`'s design, each burn with its impulsive limit.
    missed_study : lunarcap.StudyResult, optional
        :func:`lunarcap.missed` on burn 1 (None: not run in this build).
    counts_study : lunarcap.StudyResult, optional
        :func:`lunarcap.burns` on the plan (None: not run in this build).
    flight : lunarcap.GmatFlight, optional
        ``result.fly_in_gmat(export_dir(output_name))`` (None: not flown in this build).
    output_name, quick : the tables' prefix; recorded in the provenance
    parameters : dict, optional
        The notebook's parameters, shown in the provenance (``plan``: the plan file shown).
    check_degrees : LP165P degrees the capture is designed again in (its field's degree)
    evolve_degrees : LP165P degrees its final orbit is flown in for ``after_days`` days
        These two have no public call: the page computes them (:func:`_degree_section`).
    """
    p = result.plan
    params = {k: list(v) if isinstance(v, (list, tuple)) else v
              for k, v in (parameters or {}).items()}
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(),
                ephemeris=p.ephemeris_model())
    page.data.update(plan=p, result=result)
    _plan_section(page, p, params.get("plan", p.name))
    _design_section(page, result)
    _degree_section(page, p, result, [int(d) for d in check_degrees],
                    [int(d) for d in evolve_degrees], float(after_days))
    _missed_section(page, p, missed_study)
    _counts_section(page, p, counts_study)
    _gmat_section(page, result, flight)
    _headline(page)
    return page


def _plan_section(page: Page, p, name: str) -> None:
    """The plan file, its sources, its B-plane target."""
    path = Path(name) if Path(name).is_file() else PLAN_DIR / f"{name}.yaml"
    page.note("plan_yaml", "```yaml\n" + path.read_text(encoding="utf-8").rstrip() + "\n```")
    page.table("sources", sources_table(p), caption=(
        "The plan beside its sources: KARI's KPLO insertion design ({cite:t}`song2017`, "
        "Table 2; S13) and thrusters ({cite:t}`song2016`, Sec. 1); perilune speeds are "
        "two-body, lunarcap's GM and radius. What no source gives is marked assumed."),
        columns={"quantity": "quantity", "source_value": "source",
                 "plan_value": "this plan", "source": "from"})
    b = bplane_table(p)
    page.table("bplane", b, caption=(
        "The arrival as a B-plane target (km), two-body: T = S × k / |S × k|, R = S × T, S "
        "the incoming asymptote, k the reference pole. The plan's v_inf needs no reference "
        "plane; these are its target in either convention."),
        columns={"reference": "reference plane"},
        floatfmt={"b_t_km": ".1f", "b_r_km": ".1f", "v_inf_kmps": ".5f"})
    page.value("plan_name", p.name)
    page.value("model", model_label(p.dynamics))
    page.value("mass_kg", float(p.arrival.mass_kg))
    page.value("thrust_N", float(p.engine.thrust_N))
    page.value("isp_s", float(p.engine.isp_s))
    page.value("b_t_eme_km", float(b.b_t_km.iloc[0]))
    page.value("b_r_eme_km", float(b.b_r_km.iloc[0]))
    page.value("b_t_lunar_km", float(b.b_t_km.iloc[1]))
    page.value("b_r_lunar_km", float(b.b_r_km.iloc[1]))


def _design_section(page: Page, res) -> None:
    """The design, burn by burn, beside KARI's impulses."""
    d = design_table(res)
    page.data["design"] = d
    page.table("design", d, caption=(
        f"The capture designed burn by burn in {page.values['model']} (free ignitions, each "
        "burn re-flown in that model) beside KARI's impulses (S13); the impulsive limit and "
        "the loss against it, or why a burn has none."),
        show_columns=["burn", "target_orbit", "start_min", "burn_duration_min", "delta_v_mps",
                      "kplo_delta_v_mps", "delta_v_difference_mps", "impulsive_limit_mps",
                      "delta_v_loss_mps", "verified"],
        floatfmt={"start_min": "+.2f", "burn_duration_min": ".2f", "delta_v_mps": ".3f",
                  "kplo_delta_v_mps": ".3f", "delta_v_difference_mps": "+.3f",
                  "impulsive_limit_mps": ".3f", "delta_v_loss_mps": ".3f"})
    tot = res.totals()
    page.value("total_delta_v_mps", tot["total_delta_v_mps"])
    page.value("kplo_total_mps", float(sum(KPLO_DV_MPS)))
    page.value("total_vs_kplo_mps", tot["total_delta_v_mps"] - sum(KPLO_DV_MPS))
    page.value("total_fuel_kg", tot["total_fuel_kg"])
    page.value("total_burn_min", tot["total_burn_duration_min"])
    page.value("time_to_final_orbit_h", tot["time_to_final_orbit_h"])
    page.value("loi1_min", float(d.burn_duration_min.iloc[0]))
    page.value("loi1_vs_kplo_mps", float(d.delta_v_difference_mps.iloc[0]))
    none = d[d.impulsive_limit_reason != ""]
    page.note("no_limit", "Every burn has an impulsive limit in this model." if none.empty
              else " ".join(f"Burn {r.burn} has none: {r.impulsive_limit_reason}."
                            for r in none.itertuples()))
    page.expect("every burn of the design is verified in its model", bool(d.verified.all()))


def _with_degree(forces, degree: int):
    """The plan's field model at another degree (and order), its other settings kept."""
    from dataclasses import replace

    return replace(force_model(forces), degree=int(degree), order=int(degree), name="")


def _degree_section(page: Page, p, res, check: list, evolve: list, days: float) -> None:
    """The field's degree justified: the design and its final orbit in other degrees."""
    f = force_model(p.dynamics)
    designs = {f.degree if f.is_field else 0: res}
    if f.is_field:
        for d in check:
            designs[d] = plan_result(p.with_dynamics(_with_degree(f, d)), impulsive=False)
        degree = degree_table(designs, f.degree)
    else:
        degree = pd.DataFrame([{"model": model_label(p.dynamics),
                                "total_delta_v_mps": res.totals()["total_delta_v_mps"],
                                "delta_v_change_mps": 0.0}])
    page.table("degree", degree, caption=(
        f"The capture designed in LP165P of each degree (the plan's: {page.values['model']}), "
        "with the Earth and the Sun: its total ΔV, and its change from the plan's degree "
        "(m/s)."), floatfmt={"total_delta_v_mps": ".3f", "delta_v_change_mps": "+.3f"})
    models = [_with_degree(f, d) for d in sorted(set(evolve) | {f.degree})] if f.is_field \
        and evolve else [p.dynamics]
    evolutions = {model_label(m): after_capture(res, days, dynamics=m, rtol=EVOLUTION_RTOL)
                  for m in models}
    page.data["evolutions"] = evolutions
    page.table("after", evolution_table(evolutions), caption=(
        f"The final orbit flown {days:g} days from the last cut-off in each model "
        "(the capture designed in the plan's): revolutions, lowest perilune and highest "
        "apolune (km), the last revolution's, and the change of the mean inclination (deg)."),
        floatfmt={"after_min_perilune_altitude_km": ".2f",
                  "after_max_apolune_altitude_km": ".2f",
                  "after_last_perilune_altitude_km": ".2f",
                  "after_last_apolune_altitude_km": ".2f",
                  "after_inclination_change_deg": "+.3f"})
    page.figure("evolution", draw.plot_evolution(histories(evolutions)), caption=(
        f"The final orbit over {days:g} days in each model: each revolution's lowest "
        "(perilune, solid) and highest (apolune, dashed) altitude, and its mean inclination."),
        alt="Perilune and apolune altitude of the final orbit over days, per gravity model")
    own = evolutions[model_label(p.dynamics)].summary()
    page.value("after_days", days)
    page.value("after_min_perilune_km", own["after_min_perilune_altitude_km"])
    page.value("after_last_perilune_km", own["after_last_perilune_altitude_km"])
    page.value("after_max_apolune_km", own["after_max_apolune_altitude_km"])
    page.value("after_inc_change_deg", own["after_inclination_change_deg"])
    page.note("degree_verdict", _degree_verdict(page, f, designs, evolutions, days))


def _degree_verdict(page: Page, f, designs: dict, evolutions: dict, days: float) -> str:
    """Why the plan's degree, in sentences computed from the designs and the evolutions."""
    if not f.is_field or len(evolutions) < 2:
        for k in ("design_spread_mps", "spread_own_km", "spread_low_km"):
            page.value(k, None, why="no other degree in this run")
        return (f"(The capture was designed and flown in {page.values['model']} only in this "
                "run: no degree to compare.)")
    own, labels = model_label(f), list(evolutions)
    deep, low = labels[-1], labels[0]
    others = [d for d in designs if d != f.degree]
    change = max((abs(designs[d].totals()["total_delta_v_mps"]
                      - designs[f.degree].totals()["total_delta_v_mps"]) for d in others
                  if d > f.degree), default=float("nan"))
    page.value("design_spread_mps", change, why="no deeper design in this run")
    page.value("spread_own_km", perilune_spread_km(evolutions, own, deep) if own != deep
               else float("nan"), why="the plan's field is the deepest flown")
    page.value("spread_low_km", perilune_spread_km(evolutions, low, deep))
    page.value("deep_model", deep)
    page.value("low_model", low)
    t = page.text
    if own != deep:
        page.expect(f"the plan's field flies the final orbit within {AGREE_KM:g} km of "
                    f"{deep}'s perilunes", page.values["spread_own_km"] < AGREE_KM,
                    t("spread_own_km", ".2f", " km"))
    return (f"A deeper field than {own} changes the capture's total ΔV by at most "
            f"{t('design_spread_mps', '.3f', ' m/s')}, and flies the final orbit's perilunes "
            f"within {t('spread_own_km', '.2f', ' km')} of {deep}'s over {days:g} days, "
            f"where {low} is {t('spread_low_km', '.1f', ' km')} off: the design needs no "
            f"more than {own}, and the days after it need at least that.")


def _not_run(columns: list, why: str) -> pd.DataFrame:
    """A table's one row saying why it was not computed (a page's tables are never empty)."""
    row = dict.fromkeys(columns, np.nan)
    row[columns[-1]] = why
    return pd.DataFrame([row])


def _missed_section(page: Page, p, study) -> None:
    """Burn 1 cut off or ignited late: ``lunarcap missed`` on the plan (None: not run)."""
    if study is None:
        page.table("missed", _not_run(MISSED_SHOWN, f"not run ({page.missing_reason})"),
                   caption="Missed thrust: not run in this build.")
        for k in ("n_cases", "n_recovered", "max_penalty_mps"):
            page.value(k, None)
        page.note("missed_reading", f"(Not run: {page.missing_reason}.)")
        return
    t, path = study.to_frame(), study.campaign.path
    page.data["missed"] = t
    page.table("missed", t, caption=(
        f"Burn 1 cut off (fault cleared after the delay) or ignited late, the rest "
        f"re-planned in {page.values['model']}: penalty against the nominal (the orbit "
        f"after burn 1 free up to {missed.DEFAULT_MAX_PERIOD_H:g} h on both sides). "
        f"`lunarcap missed {p.name}`; the table: {page.data_link(path, 'missed.csv')}."),
        show_columns=MISSED_SHOWN, floatfmt={"fraction": ".2f", "delay_min": ".0f",
                                             "late_min": ".0f"},
        columns={"cutoff_orbit": "orbit left"})
    ok = t[t.status == "recovered"]
    page.value("n_cases", int(len(t)))
    page.value("n_recovered", int(len(ok)))
    page.value("max_penalty_mps", float(ok.penalty_mps.max()) if len(ok) else np.nan,
               why="no case recovered")
    page.note("missed_reading", " ".join(x for x in (reading(cut_offs(t)),
                                                    late_reading(late_ignitions(t))) if x))
    bugs = t[~t.status.isin(["recovered", "no recovery", "failed"])]
    page.expect("no missed-thrust case ended in an unexpected error", bugs.empty,
                "; ".join(bugs.error.astype(str)))
    page.expect("every penalty is >= -0.05 m/s (the nominal has the recovery's freedoms)",
                ok.empty or ok.penalty_mps.min() >= -0.05)


def _counts_section(page: Page, p, study) -> None:
    """The capture in N burns, the periods between optimised: ``lunarcap burns`` (or None)."""
    if study is None:
        page.table("counts", _not_run(COUNTS_SHOWN, f"not run ({page.missing_reason})"),
                   caption="How many burns: not run in this build.")
        page.value("best_count", None)
        page.value("best_count_mps", None)
        return
    t, path = study.to_frame(), study.campaign.path
    t["periods_h"] = [", ".join(f"{float(x):.3f}" for x in s.split(";")) if
                      isinstance(s, str) and s else "—" for s in t.periods_h]
    page.table("counts", t, caption=(
        f"The capture in N burns in {page.values['model']}, intermediate periods optimised "
        f"(at most {burns.DEFAULT_MAX_PERIOD_H:g} h, all within "
        f"{burns.DEFAULT_MAX_DAYS:g} days) in one NLP. `lunarcap burns {p.name}`; the "
        f"table: {page.data_link(path, 'burns.csv')}."),
        show_columns=COUNTS_SHOWN, floatfmt={"total_delta_v_mps": ".3f",
                                             "total_impulsive_limit_mps": ".3f",
                                             "total_fuel_kg": ".2f",
                                             "time_to_final_orbit_h": ".2f"})
    ok = t[t.status == "ok"]
    best = ok.loc[ok.total_delta_v_mps.idxmin()] if len(ok) else None
    page.value("best_count", None if best is None else int(best.n_burns), why="no count solved")
    page.value("best_count_mps", None if best is None else float(best.total_delta_v_mps),
               why="no count solved")
    page.expect("every count is answered (solved or infeasible with a reason)",
                bool(t.status.isin(burns.STUDY.ok_statuses).all()),
                "; ".join(t.reason[~t.status.isin(burns.STUDY.ok_statuses)].astype(str)))


def _gmat_section(page: Page, res, flight) -> None:
    """The verified capture exported and flown again in GMAT (``flight``; None: not flown)."""
    if flight is None:
        why = f"not flown ({page.missing_reason})"
        page.table("gmat", _not_run(["flight", "position_diff_m", "velocity_diff_mmps", "note"],
                                    why), caption="GMAT: not flown in this build.")
        page.table("gmat_final", _not_run(["at", "final_rp_diff_m", "note"], why),
                   caption="GMAT: not flown in this build.")
        for k in ("gmat_burn_max_m", "gmat_burn_max_mmps", "gmat_final_max_m"):
            page.value(k, None, why=why)
        return
    c = flight.comparison
    label = f"{res.plan.name} ({model_label(res.plan.dynamics)})"
    page.table("gmat", comparison_table(c, label), caption=(
        "GMAT's states minus lunarcap's: each burn flown by GMAT from lunarcap's state at "
        "its ignition (at its cut-off), each coast from lunarcap's cut-off, and the whole "
        "capture open loop from the arrival: position (m), velocity (mm/s), mass (g)."),
        show_columns=["flight", "position_diff_m", "velocity_diff_mmps", "mass_diff_g"],
        columns={"flight": "flight", "position_diff_m": "position (m)",
                 "velocity_diff_mmps": "velocity (mm/s)", "mass_diff_g": "mass (g)"},
        floatfmt={"position_diff_m": ".3g", "velocity_diff_mmps": ".3g", "mass_diff_g": "+.2g"})
    fin = final_table({label: c})
    page.table("gmat_final", fin, caption=(
        "The final orbit of the whole capture flown open loop by GMAT, at the last cut-off and "
        "one revolution later: perilune and apolune altitudes, lunarcap's and GMAT's (km), "
        "GMAT's minus lunarcap's (m)."),
        show_columns=["at", "final_rp_altitude_km", "final_ra_altitude_km",
                      "gmat_final_rp_altitude_km", "gmat_final_ra_altitude_km",
                      "final_rp_diff_m", "final_ra_diff_m"],
        floatfmt={"final_rp_altitude_km": ".4f", "final_ra_altitude_km": ".4f",
                  "gmat_final_rp_altitude_km": ".4f", "gmat_final_ra_altitude_km": ".4f",
                  "final_rp_diff_m": "+.3g", "final_ra_diff_m": "+.3g"})
    page.value("gmat_burn_max_m", max(b["position_diff_m"] for b in c.burns))
    page.value("gmat_burn_max_mmps", max(b["velocity_diff_mmps"] for b in c.burns))
    page.value("gmat_final_max_m", float(np.max(np.abs(fin[["final_rp_diff_m",
                                                              "final_ra_diff_m"]].to_numpy()))))
    page.expect("GMAT flies the capture within its gates", not c.failures(),
                "; ".join(c.failures()))


def _headline(page: Page) -> None:
    t = page.text
    page.headline(
        f"A KPLO-class capture ({t('mass_kg', '.0f')} kg, {t('thrust_N', '.0f')} N) designed "
        f"in {t('model')} needs {t('total_delta_v_mps', '.1f', ' m/s')}, "
        f"{t('total_vs_kplo_mps', '.1f', ' m/s')} more than KARI's impulsive "
        f"{t('kplo_total_mps', '.1f', ' m/s')}; {t('n_recovered', '.0f')} of its "
        f"{t('n_cases', '.0f')} missed-thrust cases are recovered, GMAT flies "
        f"its final orbit within {t('gmat_final_max_m', '.2g', ' m')}, and its perilune is "
        f"at {t('after_last_perilune_km', '.1f', ' km')} {t('after_days', 'g')} days after "
        f"the capture.")
