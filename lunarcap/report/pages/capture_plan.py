"""The capture-plan page (notebooks/capture_plan.ipynb): any plan, solved, verified, drawn.

A capture plan (:mod:`lunarcap.mission.plan`: arrival, engine, dynamics, burns) is solved
burn by burn in the notebook with :func:`lunarcap.solve`, each burn beside its impulsive
limit in the same dynamics from the same pre-burn orbit (the loss is the difference), and
drawn with ``CaptureResult.plot``. :func:`build` formats what the notebook computed: the
plan (its YAML and a table of its burns and targets), one row per burn (three tables shown;
the first CSV has every column of each burn's row), the totals, and the whole capture in
the orbit plane. Two kinds of plan get a comparison:

* ``lro-like-5burn``, beside the published LRO figures (:data:`LRO`, sources S7 and S8 of
  the real-missions page);
* a plan that is not the paper's but starts from the paper's arrival (``two-burn-8h``),
  beside the paper's three-burn capture with the same engine and free ignition.
"""

from __future__ import annotations

import math
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from lunarcap.mission.plan import PLAN_DIR, CapturePlan, load_plan
from lunarcap.physics import constants as C
from lunarcap.physics.elements import period_from_semi_major_axis, semi_major_axis_from_period
from lunarcap.physics.rocket import exhaust_speed_mps, rocket_delta_v_mps
from lunarcap.quantities import capture_name
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.display import verdict
from lunarcap.report.labels import period_text
from lunarcap.report.page import Page, solver_description

NOTEBOOK = "notebooks/capture_plan.ipynb"


def _plan_page(name: str, title: str, plan: str, compared: str | None = None) -> Execution:
    """One capture plan in its own dynamics (quick: two-body), a page of the book.

    ``plan``: a packaged plan (``lunarcap/mission/plans``) or a YAML file; ``compared``:
    the stem of the table setting it beside a reference (the published LRO figures or
    the paper), if it has one.
    """
    return Execution(
        name, title,
        parameters=dict(plan=plan, dynamics=None),  # the plan's own dynamics (full)
        quick_parameters=dict(dynamics="two-body"),
        outputs=(table_files(name, "plan", "burns", "masses", "verification", "totals",
                             *([compared] if compared else []))
                 + figure_files(name, "capture")))


BOOK = BookPage(NOTEBOOK, "Beyond the paper", 70, (
    _plan_page("plan_lro_like", "An LRO-like five-burn capture", "lro-like-5burn",
               "published"),
    _plan_page("plan_two_burn", "The paper's arrival captured in two burns", "two-burn-8h",
               "vs_paper"),
))

#: Published LRO figures (book page "Beside published lunar captures", sources S7 and S8).
LRO = {"plan": "lro-like-5burn",
       "loi_burn_min": 40.0,               # S7: "a 40-minute LOI burn"
       "first_orbit_km": (220.0, 3100.0),  # S7: 220 km x 3,100 km (altitudes)
       "launch_mass_kg": 1916.0,           # S8
       "dry_mass_kg": 1018.0,              # S8
       "fuel_kg": 898.0}                   # S8

#: Tolerance of "the final orbit is the plan's circle" (perilune and apolune radius), km.
FINAL_ORBIT_TOL_KM = 0.01


def _load(plan) -> tuple:
    """The plan and the text of its YAML file (None for a plan built in Python)."""
    if isinstance(plan, CapturePlan):
        return plan, None
    p = load_plan(plan)
    path = Path(plan).expanduser()
    if not path.is_file():
        path = PLAN_DIR / f"{plan}.yaml"
    return p, path.read_text(encoding="utf-8")


def _circle_period_s(r_km: float) -> float:
    return float(period_from_semi_major_axis(r_km, C.MU_MOON))


def _apolune_altitude_km(period_s: float, rp_km: float) -> float:
    """Two-body apolune altitude of the ellipse of perilune radius rp and this period, km."""
    a = float(semi_major_axis_from_period(period_s, C.MU_MOON))
    return 2 * a - rp_km - C.R_MOON


def plan_table(plan: CapturePlan) -> pd.DataFrame:
    """One row per burn of the plan as written: target, nominal orbit, ignition, Eq. (19).

    Columns: burn, target, period_h, period (text: h, or min below 3 h) and
    apolune_altitude_km (of the orbit reached, two-body), ignition ("free" or the offset
    in min), impulsive_delta_v_two_body_mps and eq19_duration_min (the plan's two-body impulsive
    chain).
    """
    imp = plan.impulsive()
    rp = plan.perilune_radius_km
    rows = []
    for i, b in enumerate(plan.burns):
        period = b.period_s if b.target != "circular" else _circle_period_s(rp)
        rows.append({
            "burn": i + 1, "target": b.describe(), "period_h": period / 3600.0,
            "period": period_text(period / 3600.0, 4),
            "apolune_altitude_km": _apolune_altitude_km(period, rp),
            "ignition": "free" if b.free_start else f"{b.start_min:g} min",
            "impulsive_delta_v_two_body_mps": imp[i].delta_v_mps,
            "eq19_duration_min": imp[i].eq19_duration_min})
    return pd.DataFrame(rows)


def burn_table(burns: pd.DataFrame) -> pd.DataFrame:
    """Every column of each burn's row (``CaptureResult.to_frame()``), the target second.

    The verdict in words (``verified``) and the released conditions as text are added for
    the page's tables.
    """
    df = burns.copy()
    df.insert(1, "target_orbit", df.pop("target_orbit"))
    df["verified"] = df.verification_passed.map(verdict)
    df["verification_released"] = df.verification_released.map(
        lambda r: ", ".join(map(str, r)) if r else "")
    return df


def mass_table(burns: pd.DataFrame) -> pd.DataFrame:
    """Burn, target, ignition epoch, masses before and after, propellant."""
    return pd.DataFrame({"burn": burns.burn, "target": burns.target_orbit,
                         "ignition_epoch": burns.ignition_epoch,
                         "m_start_kg": burns.m_start_kg, "m_end_kg": burns.m_end_kg,
                         "fuel_kg": burns.fuel_kg})


def plan_verification_table(burns: pd.DataFrame) -> pd.DataFrame:
    """The gate's verdict and residuals of each burn (re-propagated − optimiser / target).

    Radius errors in mm (the gate's tolerance is 10 m), the others in the row's units.
    """
    return pd.DataFrame({
        "burn": burns.burn, "verified": burns.verified,
        "verification_final_position_diff_m": burns.verification_final_position_diff_m,
        "rp_error_mm": 1e3 * burns.verification_rp_error_m,
        "ra_error_mm": 1e3 * burns.verification_ra_error_m,
        "inc_error_deg": burns.verification_inc_error_deg,
        "gamma_error_deg": burns.verification_gamma_error_deg})


#: Totals shown, in order: (key of :func:`totals_of`, words, unit).
TOTALS = [
    ("total_delta_v_mps", "total ΔV", "m/s"),
    ("total_impulsive_limit_mps", "total impulsive ΔV (same dynamics)", "m/s"),
    ("total_delta_v_loss_mps", "total loss", "m/s"),
    ("total_delta_v_loss_percent", "total loss, in % of the impulsive total", "%"),
    ("total_fuel_kg", "propellant", "kg"),
    ("final_mass_kg", "mass in the final orbit", "kg"),
    ("total_burn_duration_min", "burn time", "min"),
    ("time_to_final_orbit_h", "from the arrival perilune to the end of the last burn", "h"),
    ("final_rp_altitude_km", "final orbit, perilune altitude", "km"),
    ("final_ra_altitude_km", "final orbit, apolune altitude", "km"),
    ("final_inc_deg", "final orbit, inclination", "deg"),
]


def totals_of(result) -> dict:
    """:meth:`lunarcap.CaptureResult.totals` with the final orbit's altitudes added (km)."""
    tot = dict(result.totals())
    tot["final_rp_altitude_km"] = tot["final_rp_km"] - C.R_MOON
    tot["final_ra_altitude_km"] = tot["final_ra_km"] - C.R_MOON
    return tot


def totals_table(tot: dict) -> pd.DataFrame:
    """The totals as rows: key, quantity, value, unit."""
    return pd.DataFrame([{"key": k, "quantity": words, "value": float(tot[k]), "unit": unit}
                         for k, words, unit in TOTALS])


# ---------------------------------------------------------------------- comparisons
def constant_thrust_delta_v_mps(m0_kg: float, thrust_N: float, isp_s: float,
                                duration_s: float) -> float:
    """Delta-V of a constant-thrust burn of this duration (the rocket equation), m/s."""
    m1_kg = m0_kg - thrust_N / exhaust_speed_mps(isp_s) * duration_s
    return rocket_delta_v_mps(m0_kg, m1_kg, isp_s)


#: The first orbit "is LRO's" when both its altitudes are within this of the published
#: ones (the sources print them to 10 km; the plan meets its apolune to 50 m), km.
FIRST_ORBIT_TOL_KM = 1.0


def first_orbit_verdict(rp_alt_km: float, ra_alt_km: float, nominal_h: float,
                        period_h: float, perilune_timed: bool,
                        tol_km: float = FIRST_ORBIT_TOL_KM) -> str:
    """Our first orbit against LRO's 220 x 3,100 km, in words computed from the numbers.

    ``perilune_timed``: the burn's target is the paper's (the orbit must hold at the nominal
    epoch of the next perilune), which a long burn can meet only on another ellipse; else
    the apolune itself is the target.

    >>> first_orbit_verdict(220.0, 3100.02, 3.1, 3.1, False)[:62]
    'Our first orbit is 220.0 × 3,100.0 km (osculating, at the next'
    >>> "not 220 × 3,100 km" in first_orbit_verdict(220.0, 3180.0, 3.1, 3.15, True)
    True
    """
    pub_rp, pub_ra = LRO["first_orbit_km"]
    head = (f"Our first orbit is {rp_alt_km:.1f} × {ra_alt_km:,.1f} km (osculating, at the "
            "next perilune)")
    d_rp, d_ra = rp_alt_km - pub_rp, ra_alt_km - pub_ra
    if abs(d_rp) <= tol_km and abs(d_ra) <= tol_km:
        return (f"{head}: LRO's {pub_rp:g} × {pub_ra:,.0f} km, within {tol_km:g} km, since "
                "the plan asks for that ellipse and the burn meets it as asked.")
    why = (f": the target is the perilune radius at the nominal epoch of the next perilune, "
           f"one period of the {pub_rp:g} × {pub_ra:,.0f} km ellipse ({nominal_h:.3f} h) "
           f"after the arrival perilune, but the long burn moves the flown perilune, so the "
           f"ellipse reached has a period of {period_h:.3f} h "
           f"({60 * (period_h - nominal_h):+.1f} min)" if perilune_timed else
           f": its apolune misses the {pub_ra:,.0f} km asked")
    return (f"{head}, not {pub_rp:g} × {pub_ra:,.0f} km{why}; its apolune is "
            f"{abs(d_ra):,.0f} km {'lower' if d_ra < 0 else 'higher'} and its perilune "
            f"{d_rp:+.1f} km from LRO's.")


def lro_comparison(plan: CapturePlan, burns: pd.DataFrame, tot: dict) -> tuple:
    """Our LRO-like capture beside the published LRO figures: (table, values, reading)."""
    b1 = burns.iloc[0]
    rp_alt = float(b1.rp_end_km) - C.R_MOON
    ra_alt = float(b1.ra_end_km) - C.R_MOON
    fuel, final_mass = float(tot["total_fuel_kg"]), float(tot["final_mass_kg"])
    table = pd.DataFrame([
        {"quantity": "first (LOI) burn duration", "published": LRO["loi_burn_min"],
         "ours": float(b1.burn_duration_min), "unit": "min", "source": "S7"},
        {"quantity": "first orbit, perilune altitude", "published": LRO["first_orbit_km"][0],
         "ours": rp_alt, "unit": "km", "source": "S7"},
        {"quantity": "first orbit, apolune altitude", "published": LRO["first_orbit_km"][1],
         "ours": ra_alt, "unit": "km", "source": "S7"},
        {"quantity": f"propellant (LRO: loaded; ours: the {plan.n_burns} burns)",
         "published": LRO["fuel_kg"], "ours": fuel, "unit": "kg", "source": "S8"},
        {"quantity": "mass (LRO: dry; ours: in the final orbit)",
         "published": LRO["dry_mass_kg"], "ours": final_mass, "unit": "kg", "source": "S8"},
    ])
    m0, T, isp = plan.arrival.mass_kg, plan.engine.thrust_N, plan.engine.isp_s
    dv40 = constant_thrust_delta_v_mps(m0, T, isp, 60.0 * LRO["loi_burn_min"])
    # the v_inf at which one tangential perilune impulse of dv40 reaches LRO's first orbit
    rp = plan.perilune_radius_km
    a1 = 0.5 * (rp + C.R_MOON + LRO["first_orbit_km"][1])
    v_ell = math.sqrt(C.MU_MOON * (2 / rp - 1 / a1))
    vinf40 = math.sqrt(max((v_ell + dv40 / 1e3) ** 2 - 2 * C.MU_MOON / rp, 0.0))
    nominal_h = plan.burns[0].period_s / 3600.0
    period_h = float(b1.period_end_h)
    values = {"lro_burn_min": LRO["loi_burn_min"],
              "lro_ours_burn_min": float(b1.burn_duration_min),
              "lro_burn_diff_min": float(b1.burn_duration_min) - LRO["loi_burn_min"],
              "lro_first_rp_alt_km": rp_alt, "lro_first_ra_alt_km": ra_alt,
              "lro_fuel_kg": LRO["fuel_kg"], "lro_ours_fuel_kg": fuel,
              "lro_fuel_left_kg": LRO["fuel_kg"] - fuel,
              "lro_dv40_mps": dv40, "lro_vinf40_kmps": vinf40,
              "lro_ours_dv1_mps": float(b1.delta_v_mps),
              "lro_ours_imp1_mps": float(b1.impulsive_limit_mps)}
    longer = "longer" if values["lro_burn_diff_min"] > 0 else "shorter"
    if values["lro_fuel_left_kg"] > 0:
        fuel_txt = (f"{values['lro_fuel_left_kg']:.0f} kg less than the 898 kg LRO carried "
                    f"(S8) for its whole mission (the capture, the further lowering to its "
                    f"mapping orbit, years of station-keeping); the {final_mass:,.0f} kg left "
                    f"in the final orbit is above LRO's 1,018 kg dry mass.")
    else:
        fuel_txt = (f"{-values['lro_fuel_left_kg']:.0f} kg more than the 898 kg LRO carried "
                    f"(S8): this model of LRO's capture is not the one LRO flew.")
    reading = (
        f"**Beside LRO (published figures).** Our first burn lasts "
        f"{values['lro_ours_burn_min']:.1f} min at {m0:,.0f} kg, "
        f"{abs(values['lro_burn_diff_min']):.1f} min {longer} than LRO's 40 min (S7). Forty "
        f"minutes of a {T:g} N / {isp:g} s engine from {m0:,.0f} kg give {dv40:.0f} m/s "
        f"(rocket equation); our burn needs {values['lro_ours_dv1_mps']:.0f} m/s, and even "
        f"an impulse needs {values['lro_ours_imp1_mps']:.0f} m/s from the arrival we assumed "
        f"(v_inf {plan.arrival.v_inf_kmps:.3f} km/s, the paper's). One impulse of "
        f"{dv40:.0f} m/s would capture into 220 × 3,100 km from a v_inf of {vinf40:.2f} km/s. "
        f"So LRO arrived slower than we assumed, or lighter than its launch mass, or with "
        f"more thrust than \"about 320 N\": the sources consulted give neither its arrival "
        f"speed, nor its mass at arrival, nor its LOI ΔV, so which is not known.\n\n"
        + first_orbit_verdict(rp_alt, ra_alt, nominal_h, period_h,
                              plan.formulation == "song2011"
                              or bool(getattr(plan.burns[0], "nominal_timing", False)))
        + f" Our {plan.n_burns} burns use {fuel:.0f} kg of propellant, " + fuel_txt
        + " LRO's four later burns also lowered its perilune (to a 30 × 216 km orbit, S7); "
        "ours keep it at 220 km and end on the 220 km circle, through intermediate apolunes "
        "of our choosing.")
    return table, values, reading


def paper_comparison(plan: CapturePlan, tot: dict, reference) -> tuple:
    """A plan beside the paper's three-burn capture (same arrival, engine, dynamics).

    ``reference``: the paper's plan (``lunarcap.paper_plan``) with this plan's engine and
    dynamics and free ignition for every burn, solved with its impulsive limits like this
    one (``lunarcap.solve``). Returns (table, values, reading).
    """
    rt = totals_of(reference)
    keys = ["total_delta_v_mps", "total_impulsive_limit_mps", "total_delta_v_loss_mps",
            "total_delta_v_loss_percent", "total_fuel_kg", "time_to_final_orbit_h"]
    ours = {k: float(tot[k]) for k in keys}
    theirs = {k: float(rt[k]) for k in keys}
    d = {k: ours[k] - theirs[k] for k in keys}
    table = pd.DataFrame([
        {"capture": f"this plan, {plan.n_burns} burns", **ours},
        {"capture": "the paper's, 12.235 h → 3.525 h → circle", **theirs},
        {"capture": "this plan − the paper's", **d},
    ])
    values = {"paper_total_delta_v_mps": theirs["total_delta_v_mps"],
              "paper_total_loss_mps": theirs["total_delta_v_loss_mps"],
              "paper_time_to_final_orbit_h": theirs["time_to_final_orbit_h"],
              "vs_paper_delta_v_mps": d["total_delta_v_mps"],
              "vs_paper_loss_mps": d["total_delta_v_loss_mps"],
              "vs_paper_time_h": d["time_to_final_orbit_h"],
              "vs_paper_fuel_kg": d["total_fuel_kg"]}
    more = "more" if d["total_delta_v_loss_mps"] > 0 else "less"
    why = ("fewer, longer burns spend more of their thrust away from the perilune, where it "
           "is most effective" if d["total_delta_v_loss_mps"] > 0 else "its burns are shorter")
    sooner = "sooner" if d["time_to_final_orbit_h"] < 0 else "later"
    reading = (
        f"**Beside the paper's three-burn capture** (the same arrival and engine, "
        f"{plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} s, *{capture_name('free')}*, "
        f"{plan.dynamics} dynamics). All the burns are tangential near a perilune of the same "
        f"radius, so the impulsive totals agree to "
        f"{abs(d['total_impulsive_limit_mps']):.2f} m/s: a chain of tangential perilune "
        f"impulses costs the difference between the arrival and the final perilune speeds, "
        f"whatever the orbits in between. What differs is the finite-burn loss: "
        f"{ours['total_delta_v_loss_mps']:.2f} m/s ({ours['total_delta_v_loss_percent']:.2f} %) "
        f"with "
        f"{plan.n_burns} burns, {abs(d['total_delta_v_loss_mps']):.2f} m/s {more} than the paper's "
        f"{theirs['total_delta_v_loss_mps']:.2f} m/s, because {why}. That costs "
        f"{abs(d['total_fuel_kg']):.2f} kg of propellant "
        f"{'more' if d['total_fuel_kg'] > 0 else 'less'}; the final orbit is reached "
        f"{abs(d['time_to_final_orbit_h']):.2f} h {sooner} "
        f"({ours['time_to_final_orbit_h']:.2f} h against "
        f"{theirs['time_to_final_orbit_h']:.2f} h).")
    return table, values, reading


def _paper_reference(plan: CapturePlan) -> bool:
    """True if the plan starts from the paper's arrival but is not the paper's sequence."""
    paper = load_plan("song2011-150N")
    same_arrival = plan.arrival == paper.arrival and plan.ephemeris == paper.ephemeris
    same_burns = ([(b.target, b.period_s) for b in plan.burns]
                  == [(b.target, b.period_s) for b in paper.burns])
    return same_arrival and not same_burns


def prose_values(n_burns: int, burns: pd.DataFrame, tot: dict) -> dict:
    """The numbers the prose quotes, from :func:`burn_table` and :func:`totals_of`."""
    return {"n_burns": n_burns, "total_delta_v_mps": tot["total_delta_v_mps"],
            "total_impulsive_mps": tot["total_impulsive_limit_mps"],
            "total_delta_v_loss_mps": tot["total_delta_v_loss_mps"],
            "total_delta_v_loss_percent": tot["total_delta_v_loss_percent"],
            "total_fuel_kg": tot["total_fuel_kg"], "final_mass_kg": tot["final_mass_kg"],
            "total_burn_min": tot["total_burn_duration_min"],
            "time_to_final_orbit_h": tot["time_to_final_orbit_h"],
            "final_rp_alt_km": tot["final_rp_altitude_km"],
            "final_ra_alt_km": tot["final_ra_altitude_km"],
            "largest_loss_burn": int(burns.burn[burns.delta_v_loss_mps.idxmax()]),
            "largest_loss_mps": float(burns.delta_v_loss_mps.max()),
            "largest_loss_share_percent": 100 * float(burns.delta_v_loss_mps.max())
            / tot["total_delta_v_loss_mps"],
            "n_verified": int(burns.verification_passed.sum()),
            "max_rp_error_m": float(burns.verification_rp_error_m.abs().max())}


def negative_loss_note(burns: pd.DataFrame) -> str:
    """MyST note on the burns whose ΔV loss is negative (or that every loss is positive)."""
    neg = burns[burns.delta_v_loss_mps < 0]
    if not len(neg):
        return "Every burn's loss is positive."
    items = ", ".join(f"burn {r.burn}: {r.delta_v_loss_mps:+.3f} m/s, but "
                      f"{r.objective_loss_mps:+.3f} m/s in the objective"
                      for r in neg.itertuples())
    return (
        f"**A negative loss** ({items}). The impulsive reference minimises the same "
        "objective as the finite burn (ΔV plus the perilune speed it leaves, Eq. 9), "
        "which is nearly flat along the epoch of the impulse: optima a few seconds "
        "apart trade ~0.1–0.2 m/s of ΔV against the perilune speed, so the ΔV loss of a "
        "short burn is uncertain by that much (`lunarcap.capture.chain.impulsive_limit`); "
        "the loss in the objective and the chain's total are the well-conditioned "
        "numbers.")


def _add_plan(page: Page, p: CapturePlan, own: str, yaml_text, case: str) -> None:
    a = p.arrival
    # ---- the plan
    text = yaml_text if yaml_text is not None else p.to_yaml()
    over = ("" if p.dynamics == own else
            f"\n\nSolved here in **{p.dynamics}** dynamics (overriding the plan's "
            f"`dynamics: {own}`).")
    page.note("plan_yaml", f"```yaml\n{text.rstrip()}\n```{over}")
    page.table(
        "plan", plan_table(p),
        caption=(f"The burns of {case}; first perilune {a.epoch}, "
                 f"{a.perilune_altitude_km:g} km, {a.inclination_deg:g} deg, v_inf "
                 f"{a.v_inf_kmps:.5f} km/s. Period and apolune: each burn's target; impulsive "
                 "ΔV and Eq. (19): two-body."),
        columns={"ignition": "ignition",
                 "impulsive_delta_v_two_body_mps": "impulsive ΔV, two-body (m/s)",
                 "eq19_duration_min": "Eq. (19) duration (min)"},
        floatfmt={"apolune_altitude_km": ",.1f",
                  "impulsive_delta_v_two_body_mps": ".3f", "eq19_duration_min": ".2f"},
        show_columns=["burn", "target", "period", "apolune_altitude_km", "ignition",
                      "impulsive_delta_v_two_body_mps", "eq19_duration_min"])



def _add_burn_tables(page: Page, burns: pd.DataFrame, case: str) -> None:
    # ---- each burn
    page.table(
        "burns", burns,
        caption=(f"Each burn of {case}, solved and verified. Start: min from the nominal "
                 "perilune. Impulsive ΔV: the limit of 4 s and 2 s burns in the same dynamics "
                 "from the same orbit. Loss: ΔV − impulsive ΔV."),
        show_columns=["burn", "start_min", "burn_duration_min", "delta_v_mps",
                      "impulsive_limit_mps", "delta_v_loss_mps", "delta_v_loss_percent"],
        floatfmt={"start_min": "+.3f", "burn_duration_min": ".2f", "delta_v_mps": ".3f",
                  "impulsive_limit_mps": ".3f", "delta_v_loss_mps": "+.3f",
                  "delta_v_loss_percent": "+.2f"})
    page.table(
        "masses", mass_table(burns),
        caption=(f"Ignition epochs (TDB) and masses (kg) of each burn of {case}: before, "
                 "after, and the propellant burned."),
        floatfmt={"m_start_kg": ",.3f", "m_end_kg": ",.3f", "fuel_kg": ".3f"})
    page.table(
        "verification", plan_verification_table(burns),
        caption=("The {doc}`re-propagation gate <verification>` of each burn: flown minus "
                 "optimised end position at the next nominal perilune; r_p, r_a, i and γ "
                 "minus their targets. Gate: 50 m, 10 m, 1e-4 deg (end speed and objective in "
                 "the CSV). '—': not a condition of that target."),
        columns={"verification_final_position_diff_m": "end position (m)", "verified": "gate"},
        floatfmt={"verification_final_position_diff_m": ".3f", "rp_error_mm": "+.3f",
                  "ra_error_mm": "+.3f", "inc_error_deg": "+.6f", "gamma_error_deg": "+.6f"})



def _add_totals(page: Page, p: CapturePlan, fig, tot: dict, case: str) -> None:
    page.table(
        "totals", totals_table(tot),
        caption=(f"Totals of {case}. Impulsive total: the burns' impulsive limits summed. "
                 f"Time to the final orbit: to the last cut-off ({tot['final_orbit_epoch']} "
                 f"TDB); final elements osculating at {tot['final_perilune_epoch']}."),
        show_columns=["quantity", "value", "unit"], floatfmt={"value": ",.3f"})
    plt.close(fig)  # saved and shown by page.show, not by the notebook's build cell
    page.figure(
        "capture", fig,
        caption=(f"The capture of {case}, in the arrival orbit's plane (1 LU = 1,738.2 km): "
                 "hyperbola (dotted: without burn 1), burn arcs (thick), each orbit reached."),
        alt=f"The capture of plan {p.name} in the orbit plane", name="capture")



def _add_comparison(page: Page, p: CapturePlan, burns: pd.DataFrame, tot: dict,
                    case: str, reference=None) -> dict:
    """The LRO or paper comparison table, if any; its values, its reading as a note.

    ``reference``: the paper's capture solved for :func:`paper_comparison` (needed if
    :func:`beside_paper`).
    """
    vals = {}
    if p.name == LRO["plan"]:
        table, vals, reading = lro_comparison(p, burns, tot)
        page.table(
            "comparison", table, name="published",
            caption=("Our LRO-like capture beside the published LRO figures (S7: LROC news, "
                     "23 June 2009; S8: NASA's mission profile; {doc}`sources "
                     f"<real_missions>`). Ours: {case}; the first orbit osculating at its "
                     "next perilune."),
            columns={"quantity": "quantity", "published": "LRO, published", "ours": "ours",
                     "unit": "unit", "source": "source"},
            floatfmt={"published": ",.1f", "ours": ",.1f"})
        page.expect("the capture needs less propellant than LRO carried (S8)",
                    vals["lro_fuel_left_kg"] > 0, f"{vals['lro_ours_fuel_kg']:.1f} kg")
    elif beside_paper(p):
        if reference is None:
            raise ValueError(f"plan {p.name} is set beside the paper's capture: pass it "
                             "solved as reference (see beside_paper)")
        table, vals, reading = paper_comparison(p, tot, reference)
        page.table(
            "comparison", table, name="vs_paper",
            caption=("This plan beside the paper's three burns (12.235 h → 3.525 h → circle) "
                     f"from the same arrival, engine and dynamics ({p.dynamics}), both with "
                     f"*{capture_name('free')}*. Loss: total ΔV − the impulsive total in the "
                     "same dynamics."),
            columns={"capture": "capture", "total_impulsive_limit_mps": "impulsive (m/s)",
                     "total_delta_v_loss_mps": "loss (m/s)",
                     "total_delta_v_loss_percent": "loss (%)",
                     "time_to_final_orbit_h": "to final orbit (h)"},
            floatfmt={"total_delta_v_mps": ".3f", "total_impulsive_limit_mps": ".3f",
                      "total_delta_v_loss_mps": ".3f", "total_delta_v_loss_percent": ".2f",
                      "total_fuel_kg": ".3f", "time_to_final_orbit_h": ".3f"})
    else:
        reading = ("Nothing to set this plan beside: it is neither the LRO-like plan nor a "
                   "variant of the paper's capture from the paper's arrival.")
    page.note("comparison", reading)
    return vals


def _add_checks(page: Page, p: CapturePlan, burns: pd.DataFrame, tot: dict) -> None:
    page.expect("every burn passes the verification gate",
                bool(burns.verification_passed.all()),
                str(burns.burn[~burns.verification_passed].tolist()))
    page.expect("every impulsive limit passes the gate", bool(burns.impulsive_verified.all()))
    page.expect("the total loss is positive", tot["total_delta_v_loss_mps"] > 0,
                f"{tot['total_delta_v_loss_mps']:.3f} m/s")
    if p.targets[-1].circular:
        rp = p.perilune_radius_km
        page.expect("the final orbit is the plan's circle",
                    abs(tot["final_rp_km"] - rp) < FINAL_ORBIT_TOL_KM
                    and abs(tot["final_ra_km"] - rp) < FINAL_ORBIT_TOL_KM,
                    f"{tot['final_rp_km']:.4f} x {tot['final_ra_km']:.4f} km")


# ---------------------------------------------------------------------- the page
def beside_paper(plan: CapturePlan) -> bool:
    """True if the book sets this plan beside the paper's three-burn capture.

    A plan from the paper's arrival that is not the paper's burn sequence (``two-burn-8h``):
    the notebook then solves ``lunarcap.paper_plan`` with the plan's engine and dynamics and
    every ignition free, and passes it to :func:`build` as ``reference``.
    """
    return plan.name != LRO["plan"] and _paper_reference(plan)


def _source(plan, solved: CapturePlan) -> tuple:
    """The plan's own dynamics and the text shown as its file (YAML), before any override.

    ``plan``: the notebook's ``plan`` parameter (a packaged name or a YAML file; anything
    else: the plan solved, written as YAML).
    """
    if isinstance(plan, (str, Path)):
        p, text = _load(plan)
        return p.dynamics, text
    return solved.dynamics, solved.to_yaml()


def build(result, burns: pd.DataFrame, capture_figure, output_name: str = "capture_plan",
          quick: bool = False, parameters: dict | None = None, reference=None) -> Page:
    """The page of a capture plan solved in the notebook (see the module docstring).

    Parameters
    ----------
    result : lunarcap.CaptureResult
        :func:`lunarcap.solve`'s capture, each burn with its impulsive limit.
    burns : pandas.DataFrame
        ``result.to_frame()``: one row per burn.
    capture_figure : matplotlib.figure.Figure
        ``result.plot()``: the capture in the plane of the arrival orbit.
    output_name : str
        Prefix of the CSV and figure files.
    quick : bool
        Set by quick (CI) runs; named in the provenance block.
    parameters : dict, optional
        The notebook's ``plan`` (a packaged name or YAML file: its text is shown) and
        ``dynamics`` (None: the plan's own), shown in the provenance.
    reference : lunarcap.CaptureResult, optional
        The paper's capture solved with this plan's engine and dynamics, every ignition
        free, if :func:`beside_paper` (the comparison table).
    """
    p = result.plan
    params = dict(parameters or {})
    params["plan"] = params.get("plan") if isinstance(params.get("plan"), str) else p.name
    params.setdefault("dynamics", None)
    name = p.name
    own, yaml_text = _source(parameters.get("plan") if parameters else None, p)
    page = Page(NOTEBOOK, params, output_name, quick, solver_description(**{
        "impulsive limit": "4 s and 2 s burns, Richardson-extrapolated"}))
    burns = burn_table(burns)
    tot = totals_of(result)
    a, e = p.arrival, p.engine
    case = (f"plan {name}: {e.thrust_N:g} N / Isp {e.isp_s:g} s, {a.mass_kg:,g} kg at "
            f"arrival, {p.dynamics} dynamics")
    _add_plan(page, p, own, yaml_text, case)
    _add_burn_tables(page, burns, case)
    _add_totals(page, p, capture_figure, tot, case)
    values = prose_values(p.n_burns, burns, tot)
    page.note("burn_notes", negative_loss_note(burns))
    values.update(_add_comparison(page, p, burns, tot, case, reference))
    for k, v in values.items():
        page.value(k, float(v))
    _add_checks(page, p, burns, tot)
    page.data.update(result=result, plan=p, totals=tot)
    t = page.text
    page.headline(f"The {t('n_burns', '.0f')} burns of `{p.name}` ({p.dynamics} dynamics) lose "
                  f"{t('total_delta_v_loss_mps', '.2f', ' m/s')} against impulses in the same "
                  f"dynamics, and the last burn ends {t('time_to_final_orbit_h', '.2f', ' h')} "
                  f"after the arrival perilune.")
    return page
