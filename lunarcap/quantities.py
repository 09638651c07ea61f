"""The glossary of reported quantities: one name, one unit, one label, one definition each.

Every CSV column and JSON key lunarcap writes is a name of this glossary, used alike in
code, tables, JSON, axis labels and the book's prose. A name carries its unit as a
suffix (``delta_v_mps``, ``burn_duration_min``, ``period_after_h``); a dimensionless or
text quantity carries none. :data:`GLOSSARY` holds the quantities; a few families are
composed from one of them by a prefix (:data:`PREFIXES`: ``paper_delta_v_mps`` is the
delta-V as Song et al. (2011) print it, ``total_fuel_kg`` the propellant of every burn)
or an LOI suffix (:data:`SUFFIXES`: ``loss_percent_loi1``). :func:`lookup` resolves
either kind and :func:`is_known` says whether a name is in the glossary.

The losses, named apart because they differ (issue 17):

* ``delta_v_loss_mps``: delta-V minus the impulsive limit in the *same* dynamics
  (``impulsive_limit_mps``): the finite-burn loss, model against model, the book's loss;
* ``objective_loss_mps``: the same, measured by the objective of Eq. (9) (delta-V plus the
  speed at the next perilune), which is flat along the ignition epoch;
* ``loss_vs_paper_impulse_mps``: delta-V minus the paper's printed impulse
  (``paper_impulsive_delta_v_mps``), a comparison with the paper's printed numbers;
* ``analytic_loss_mps``: the closed-form estimate of :mod:`lunarcap.physics.losses`.

Examples
--------
>>> lookup("delta_v_loss_mps").unit, lookup("paper_delta_v_mps").label
('m/s', 'ΔV, paper')
>>> is_known("loss_mps")
False
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Quantity:
    """A reported quantity.

    Attributes
    ----------
    name : str
        The column / JSON key, unit suffix included.
    unit : str
        The unit as printed (``"m/s"``); ``""`` for a dimensionless number or text.
    label : str
        Short words for a table header or an axis (without the unit).
    definition : str
        One sentence: what the number is, measured from where to where.
    kind : str
        JSON type: ``"number"``, ``"integer"``, ``"string"``, ``"boolean"``, ``"array"``
        or ``"object"`` (:mod:`lunarcap.schemas` is generated from it).
    """

    name: str
    unit: str
    label: str
    definition: str
    kind: str = "number"

    @property
    def header(self) -> str:
        """Label and unit, e.g. ``"ΔV (m/s)"``."""
        return f"{self.label} ({self.unit})" if self.unit else self.label


#: Unit suffixes of names and the unit printed (matched longest first).
UNIT_SUFFIXES = {
    "_mps2": "m/s²", "_kmps2": "km/s²", "_kmps": "km/s", "_mps": "m/s", "_percent": "%",
    "_pct": "%", "_min": "min", "_deg": "deg", "_kg": "kg", "_km": "km", "_mm": "mm",
    "_m": "m", "_s": "s", "_h": "h", "_N": "N", "_LU": "LU", "_days": "d", "_bytes": "bytes",
    "_pp": "percentage points", "_mmps": "mm/s", "_g": "g",
}


def unit_of(name: str) -> str:
    """The unit a name's suffix states (``""`` if none)."""
    for suffix in sorted(UNIT_SUFFIXES, key=len, reverse=True):
        if name.endswith(suffix) and len(name) > len(suffix):
            return UNIT_SUFFIXES[suffix]
    return ""


_Q: list = []


def _add(name: str, label: str, definition: str, kind: str = "number") -> None:
    _Q.append(Quantity(name, unit_of(name) if kind in ("number", "integer") else "", label,
                       definition, kind))


# ------------------------------------------------------------------ engine and arrival
_add("thrust_N", "thrust", "Engine thrust, constant during a burn.")
_add("isp_s", "Isp", "Engine specific impulse; exhaust speed over standard gravity 9.80665 m/s².")
_add("mass_kg", "mass", "Spacecraft mass at the arrival perilune, before the first burn.")
_add("v_inf_kmps", "v∞", "Hyperbolic excess speed of the arrival orbit relative to the Moon.")
_add("thrust_to_weight", "T/(m₀g₀)",
     "Thrust over the arrival mass times standard gravity (dimensionless).")
_add("thrust_to_lunar_weight", "T/(m₀g☾)",
     "Thrust over the arrival mass times the Moon's surface gravity (dimensionless).")
_add("dynamics", "dynamics", "Force model: full (lunar J2, Earth, Sun), j2, or two-body (the "
     "paper's), or the forces a plan names, e.g. 'LP165P 20x20 (de405), Earth, Sun'.",
     "string")
_add("plan", "plan", "Name of the capture plan (or, in JSON, the plan itself).", "string")
_add("engine", "engine", "Engine as 'thrust N / Isp s'.", "string")
# ------------------------------------------------------------------ a burn
_add("burn", "burn", "Burn number, from 1 in the order flown.", "integer")
_add("loi", "LOI", "Lunar orbit insertion burn number (1, 2, 3) of the paper's sequence.",
     "integer")
_add("part", "burn", "Row of a study: LOI1, LOI2, LOI3, or the whole sequence.", "string")
_add("n_burns", "N", "Number of capture burns.", "integer")
_add("target_kind", "target",
     "Conditions the burn's optimisation imposes at the end of its coast: 'perilune' (the "
     "paper's formulation: perilune radius, inclination and zero flight-path angle at the "
     "perilune the plan's period places), 'ellipse' (apolune and period as asked, at a "
     "perilune of free epoch) or 'circular'.", "string")
_add("target_orbit", "orbit asked", "The orbit the plan asks of a burn, in words.", "string")
_add("steering", "steering", "Thrust direction law: optimal, or a fixed rule.", "string")
_add("free_start", "free ignition", "True if the ignition epoch was optimised.", "boolean")
_add("start_min", "start",
     "Ignition time relative to the nominal perilune of the orbit the burn starts from "
     "(negative: before it).")
_add("ignition_epoch", "ignition (TDB)", "Calendar epoch of ignition, TDB.", "string")
_add("end_epoch", "coast end (TDB)", "Calendar epoch of the end of the coast after the burn "
     "(the next perilune), TDB.", "string")
_add("burn_duration_min", "duration", "Duration of the finite burn, ignition to cut-off.")
_add("eq19_duration_min", "Eq. (19)",
     "Burn duration Eq. (19) estimates from the two-body impulse and the rocket equation.")
_add("eq19_burn_duration_min", "Eq. (19)", "Eq. (19) estimate of the burn duration "
     "(the impulsive command's name of eq19_duration_min).")
_add("burn_to_eq19_ratio", "duration / Eq. (19)",
     "Finite burn duration over its Eq. (19) estimate (dimensionless).")
_add("delta_v_mps", "ΔV",
     "Delta-V of the finite burn: Isp g₀ ln(m_start/m_end), from the propellant used.")
_add("impulsive_delta_v_two_body_mps", "two-body impulse",
     "Closed-form two-body impulse of the burn: tangential at perilune, between the "
     "vis-viva speeds of the orbits before and after (the model page's 353.272 m/s for LOI 1).")
_add("impulsive_limit_mps", "impulsive limit",
     "Impulsive limit of the burn in the same dynamics: the finite burn's delta-V "
     "extrapolated to zero duration (Table 1's 353.110 m/s for LOI 1 in full dynamics).")
_add("paper_impulsive_delta_v_mps", "impulse, paper",
     "Impulsive delta-V Song et al. (2011) print for the burn, taken from Song et al. "
     "(2009c) (353.272 m/s for LOI 1, equal to our two-body impulse).")
_add("impulsive_verified", "impulsive limit verified",
     "True if both short burns defining the impulsive limit passed verification.",
     "boolean")
_add("delta_v_loss_mps", "ΔV loss",
     "Delta-V minus the impulsive limit in the same dynamics (delta_v_mps - "
     "impulsive_limit_mps): the finite-burn loss, model against model. The paper measures "
     "its loss against the impulse it prints instead (loss_vs_paper_impulse_mps).")
_add("delta_v_loss_percent", "ΔV loss",
     "delta_v_loss_mps as a percentage of impulsive_limit_mps.")
_add("objective_j_mps", "J",
     "Objective of Eq. (9): the burn's delta-V plus the speed at the next perilune "
     "(minimised by the optimiser).")
_add("objective_loss_mps", "J loss",
     "Objective J minus J at the impulsive limit, same dynamics: the loss measured by the "
     "objective, flat along the ignition epoch and never negative for an optimal burn.")
_add("objective_loss_percent", "J loss",
     "objective_loss_mps as a percentage of impulsive_limit_mps.")
_add("loss_vs_paper_impulse_mps", "loss vs paper's impulse",
     "Delta-V minus the impulse Song et al. (2011) print for the same burn "
     "(paper_impulsive_delta_v_mps): the paper's loss as the paper measures it (its "
     "Tables 1-5 and B1), which set against our delta-V mixes our dynamics with theirs.")
_add("loss_vs_paper_impulse_percent", "loss vs paper's impulse",
     "loss_vs_paper_impulse_mps as a percentage of paper_impulsive_delta_v_mps (Table B1's "
     "'difference from impulsive').")
_add("analytic_loss_mps", "analytic loss",
     "Closed-form estimate of the delta-V loss (lunarcap.physics.losses, after Robbins 1966 as "
     "quoted in Confraria 2020).")
_add("analytic_loss_percent", "analytic loss",
     "analytic_loss_mps as a percentage of the two-body impulse.")
_add("analytic_eq19_duration_min", "analytic Eq. (19)",
     "Eq. (19) burn duration of the closed-form estimate.")
_add("m_start_kg", "mass before", "Mass at ignition.")
_add("m_end_kg", "mass after", "Mass at cut-off.")
_add("m_before_kg", "mass before", "Mass before the burn (impulsive chain).")
_add("m_after_kg", "mass after", "Mass after the burn (impulsive chain).")
_add("fuel_kg", "propellant", "Propellant used by the burn (m_start_kg - m_end_kg).")
_add("final_mass_kg", "final mass", "Mass after the last burn.")
_add("v_end_kmps", "speed at coast end", "Speed at the end of the coast after the burn "
     "(the next perilune).")
_add("v_perilune_before_kmps", "v_p before", "Perilune speed on the orbit before the impulse.")
_add("v_perilune_after_kmps", "v_p after", "Perilune speed on the orbit after the impulse.")
_add("rp_end_km", "r_p after", "Osculating perilune radius at the end of the coast.")
_add("ra_end_km", "r_a after",
     "Osculating apolune radius at the end of the coast (null on a hyperbola).")
_add("inc_end_deg", "i after", "Inclination at the end of the coast, M-MME2000.")
_add("period_end_h", "period after",
     "Osculating period at the end of the coast (null on a hyperbola).")
_add("period_before_h", "period before",
     "Period of the orbit before the burn (null for the arrival hyperbola).")
_add("period_after_h", "period after", "Period of the orbit the burn leaves.")
_add("periods_h", "periods", "Periods of the intermediate orbits, in flight order.", "array")
_add("target_period_h", "period asked", "Period a plan asks of an ellipse.")
_add("ipopt_status", "IPOPT status", "IPOPT's return status of the accepted mesh.", "string")
_add("ipopt_iterations", "iterations", "IPOPT iterations of the accepted mesh.", "integer")
_add("mesh", "mesh", "Collocation mesh of the accepted solution.", "string")
_add("nlp_solve_s", "IPOPT", "Wall time inside IPOPT.")
_add("solve_wall_s", "wall", "Wall time of the whole solve (all meshes and verification).")
_add("task_wall_s", "task wall", "Wall time of a study task on its worker.")
_add("attempts", "attempts", "The meshes tried, in order, and how each ended.", "array")
_add("previous_starts_min", "earlier starts", "start_min of the earlier burns.", "array")
_add("u_inertial", "steering", "Fixed inertial thrust direction (null if optimal).", "array")
# ------------------------------------------------------------------ verification
_add("verification", "verification", "Residuals of the re-propagated flight.", "object")
_add("passed", "passed", "True if every verification gate holds.", "boolean")
_add("verified", "verified", "True if the solution (and its impulsive limit) passed "
     "verification.", "boolean")
_add("verification_passed", "verified", "True if every verification gate holds.", "boolean")
_add("all_verified", "all verified", "True if every burn and impulsive limit passed.",
     "boolean")
_add("delta_v_diff_mps", "ΔV, flown - collocated", "Re-flown minus collocated delta-V "
     "(reported, not gated).")
_add("objective_diff_mps", "J, flown - collocated", "Re-flown minus collocated objective.")
_add("rp_error_m", "r_p error", "Re-flown perilune radius minus its target.")
_add("ra_error_m", "r_a error", "Re-flown apolune radius minus its target (null if not "
     "targeted).")
_add("inc_error_deg", "i error", "Re-flown inclination minus its target.")
_add("gamma_error_deg", "γ error", "Re-flown flight-path angle at the end (null if not "
     "targeted).")
_add("period_error_s", "period error", "Re-flown period minus the period asked (ellipse "
     "targets only).")
_add("final_position_diff_m", "end position, flown - collocated",
     "Distance between the re-flown and collocated positions at the end of the coast.")
_add("end_speed_diff_mps", "end speed, flown - collocated",
     "Re-flown minus collocated speed at the end of the coast.")
_add("nfev", "evaluations", "Right-hand-side evaluations of the re-flown trajectory.",
     "integer")
_add("released", "released targets", "Targets the steering law leaves free (not gated).",
     "array")
_add("end_e_cos_nu", "e cos ν at end",
     "e cos(true anomaly) at the end of the coast (dimensionless): >= 0 on the perilune "
     "side, as a perilune target requires.")
_add("ellipse", "ellipse gates", "True if the apolune and period of an ellipse are gated.",
     "boolean")
# ------------------------------------------------------------------ a plan's totals
_add("final_rp_km", "final r_p", "Perilune radius of the final orbit.")
_add("final_ra_km", "final r_a", "Apolune radius of the final orbit.")
_add("final_inc_deg", "final i", "Inclination of the final orbit, M-MME2000.")
_add("final_perilune_epoch", "final perilune (TDB)", "First perilune on the final orbit, TDB.",
     "string")
_add("final_orbit_epoch", "final orbit reached (TDB)", "End of the last burn, TDB.", "string")
_add("time_to_final_orbit_h", "time to final orbit",
     "From the arrival perilune to the end of the last burn "
     "(lunarcap.capture.chain.time_to_final_orbit_h).")
_add("complete", "complete", "True if every burn of the plan was solved.", "boolean")
_add("totals", "totals", "Totals over the plan's burns.", "object")
_add("burns", "burns", "One record per burn.", "array")
# ------------------------------------------------------------------ studies
_add("status", "status", "Outcome of a case (each study lists its statuses).", "string")
_add("error", "error", "The error message of a failed case.", "string")
_add("worker", "worker", "Dask worker that ran the case.", "string")
_add("code_version", "code version", "Version of the code that computed the row.", "string")
_add("completed_utc", "completed (UTC)", "When the case finished, UTC.", "string")
_add("table", "table", "Path of the study's CSV table.", "string")
_add("run", "run", "Log of the study's run (cases, timing, workers).", "object")
_add("max_period_h", "longest period", "Longest intermediate period allowed.")
_add("max_days", "longest time", "Longest time from the arrival perilune to the end of the "
     "last burn allowed, days.")
_add("counts", "counts", "One record per number of burns.", "array")
_add("cases", "cases", "One record per case.", "array")
_add("samples", "samples", "One record per Monte Carlo sample.", "array")
_add("summary", "summary", "Statistics of the samples.", "object")
_add("seed", "seed", "Seed of the random generator.", "integer")
_add("description", "description", "Words describing the record.", "string")

# ------------------------------------------------------------------ a plan file's keys
_add("name", "name", "Name of the plan.", "string")
_add("arrival", "arrival", "The arrival: perilune epoch, altitude, inclination, mass "
     "(or a state).", "object")
_add("epoch", "epoch (TDB)", "Calendar epoch of the arrival perilune (or state), TDB.",
     "string")
_add("perilune_altitude_km", "perilune altitude", "Altitude of a perilune above the mean "
     "lunar radius 1738.2 km.")
_add("apolune_altitude_km", "apolune altitude", "Altitude of an apolune above the mean "
     "lunar radius.")
_add("inclination_deg", "inclination", "Inclination to the M-MME2000 equator.")
_add("impulsive_loi1_mps", "LOI 1 impulse", "Two-body impulse of the first burn from which "
     "the plan derives the arrival v∞ (the paper's way of stating its arrival).")
_add("hemisphere", "hemisphere", "Lunar hemisphere of the arrival perilune.", "string")
_add("approach_dir", "approach direction", "Unit vector of the approach (M-MME2000; of a "
     "B-plane arrival, in its frame).", "array")
_add("frame", "frame", "Reference frame of a state.", "string")
_add("position_km", "position", "Position vector.", "array")
_add("velocity_kmps", "velocity", "Velocity vector.", "array")
_add("opm", "OPM", "CCSDS OPM file of the arrival state.", "string")
_add("b_r_km", "B·R", "Component along R of the arrival's B-plane miss vector (R = S x T, "
     "T = S x pole / |S x pole|, S the incoming asymptote).")
_add("b_t_km", "B·T", "Component along T of the arrival's B-plane miss vector.")
_add("ephemeris", "ephemeris", "SPK file of the Earth and Sun.", "string")
_add("lunar_pole", "lunar pole", "Pole fixing M-MME2000: the IAU (2009) pole at J2000, its "
     "constant terms, or at an epoch ('iau2009@<epoch>', a plan's pole of date).", "string")
_add("impulsive_limit_reason", "no impulsive limit", "Why a burn in a gravity field has no "
     "impulsive limit (the limit of ever shorter burns does not exist there).", "string")
# ------------------------------------------------------------------ after the capture
_add("after", "after the capture", "The final orbit propagated for some days in the plan's "
     "dynamics, revolution by revolution (--after-days).", "object")
_add("after_days", "days after", "How long the final orbit is propagated after the last "
     "cut-off.")
_add("after_dynamics", "dynamics after", "Force model the final orbit is propagated in.",
     "string")
_add("after_start_epoch", "after from (TDB)", "Start of the propagation after the capture: "
     "the last cut-off, TDB.", "string")
_add("after_revolutions", "revolutions", "Whole revolutions of the final orbit within the "
     "days propagated.", "integer")
_add("after_min_perilune_altitude_km", "lowest perilune", "Lowest altitude over the days "
     "propagated (above 1738.2 km).")
_add("after_max_apolune_altitude_km", "highest apolune", "Highest altitude over the days "
     "propagated.")
_add("after_last_perilune_altitude_km", "last perilune", "Lowest altitude of the last whole "
     "revolution.")
_add("after_last_apolune_altitude_km", "last apolune", "Highest altitude of the last whole "
     "revolution.")
_add("after_inclination_change_deg", "inclination change", "Mean inclination of the last "
     "whole revolution minus the first's.")
# ------------------------------------------------------------------ a capture flown elsewhere
_add("position_diff_m", "position difference", "Distance between a flight's position and a "
     "reference flight's at the same epoch, |r - r_ref| (GMAT's flight against lunarcap's; "
     "the design flown open loop against the design).")
_add("velocity_diff_mmps", "velocity difference", "Size of the difference between a flight's "
     "velocity and a reference flight's at the same epoch, |v - v_ref|.")
_add("mass_diff_g", "mass difference", "A flight's mass minus a reference flight's at the "
     "same epoch.")
_add("final_rp_diff_m", "final r_p difference", "A flight's osculating perilune radius of the "
     "final orbit minus a reference flight's at the same epoch (GMAT's minus lunarcap's).")
_add("final_ra_diff_m", "final r_a difference", "A flight's osculating apolune radius of the "
     "final orbit minus a reference flight's at the same epoch (GMAT's minus lunarcap's).")
_add("open_loop_miss_km", "miss", "Distance of the design flown open loop (its steering "
     "replayed in another model) from the design's own state, at the epoch where the "
     "design's final orbit is asked: position_diff_m there, in km.")
_add("open_loop_miss_mps", "miss", "Size of the velocity difference of the design flown open "
     "loop from the design's own state, at the epoch of open_loop_miss_km: "
     "velocity_diff_mmps there, in m/s.")
_add("open_loop_inc_change_deg", "Δi, open loop", "Final inclination of the design flown "
     "open loop minus the design's own final inclination, at the epoch of open_loop_miss_km "
     "(not the change over days after the capture, after_inclination_change_deg).")
_add("delta_v_change_mps", "ΔV change", "Delta-V of the capture designed again in the model "
     "it is flown in minus its delta-V as designed (redesign_delta_v_mps - "
     "design_delta_v_mps).")
_add("revolutions", "revolutions", "One record per whole revolution (a turn of the true "
     "longitude): its lowest and highest points and mean inclination.", "array")
_add("perilune_epoch", "perilune (TDB)", "Epoch of a revolution's lowest point, TDB.",
     "string")
_add("mean_inclination_deg", "mean inclination", "Mean osculating inclination over a "
     "revolution, to the plan frame's equator.")
_add("formulation", "formulation", "How the burns are targeted: song2011 (the next "
     "perilune at the plan's epoch) or orbit (the orbit asked, free epoch).", "string")
_add("target", "target", "Plan file: the orbit a burn is asked for ('circular', or an "
     "object of perilune and apolune altitudes).", "string")
_add("target_apolune_altitude_km", "apolune asked", "Apolune altitude a plan asks of an "
     "ellipse.")
_add("coast_min", "coast", "Coast after a burn to the perilune where its target is met.")
_add("start_bounds_min", "start bounds", "Plan file: the interval [lo, hi] a free ignition is "
     "optimised within, min from the nominal perilune (negative: before it).", "array")
_add("start", "start state", "Plan file: a known state the capture starts from instead of "
     "the arrival perilune (a re-plan after a fault).", "object")
_add("mee", "MEE", "Modified equinoctial elements (p km, f, g, h, k, L rad), M-MME2000.",
     "array")
_add("first_coast_min", "first coast", "Plan file: from a start state's epoch to the nominal "
     "perilune where the first burn's target must hold.")
# ------------------------------------------------------------------ a study's run log
for _k, _l, _d, _t in (
        ("study", "study", "Which study.", "string"),
        ("started_utc", "started (UTC)", "When the run started, UTC.", "string"),
        ("wall_s", "wall", "Wall time of the run.", "number"),
        ("cluster_start_s", "cluster start", "Time to start the Dask cluster.", "number"),
        ("scheduler", "scheduler", "Dask scheduler used.", "string"),
        ("workers", "workers", "Dask workers.", "integer"),
        ("computed", "computed", "Cases computed by this run.", "integer"),
        ("reused", "reused", "Cases taken from the table.", "integer"),
        ("failed_computed", "failed", "Cases computed that failed.", "integer"),
        ("interrupted", "interrupted", "True if the run was interrupted.", "boolean"),
        ("cache", "cache", "Where the solve cache lives (or 'off').", "string"),
        ("host", "host", "Host name.", "string"),
        ("cpu_count", "CPUs", "CPUs of the host.", "integer"),
        ("load_avg_1min_start", "load at start", "1-minute load average at the start "
         "(dimensionless).", "number"),
        ("load_avg_1min_end", "load at end", "1-minute load average at the end "
         "(dimensionless).", "number"),
        ("grid", "grid", "The study's grid.", "object"),
        ("plan_id", "plan id", "Hash of what a plan's solves depend on.", "string"),
        ("reason", "reason", "Why a case failed or was infeasible, in physical terms.",
         "string"),
        ("nominal_perilune_epoch", "nominal perilune (TDB)", "The perilune the burn's start "
         "is measured from, TDB.", "string"),
        ("total_ipopt_iterations", "iterations", "IPOPT iterations of the whole solve.",
         "integer"),
        ("failures", "failures", "The verification gates that failed, in words.", "array")):
    _add(_k, _l, _d, _t)
# ------------------------------------------------------------------ missed thrust
for _k, _l, _d, _t in (
        ("contingency", "contingency", "'cut-off' (the engine stops early) or 'late "
         "ignition'.", "string"),
        ("fraction", "fraction flown", "Share of the nominal burn flown before the cut-off "
         "(dimensionless).", "number"),
        ("delay_min", "delay", "Time from the cut-off to the recovery.", "number"),
        ("late_min", "late by", "Ignition delay of a late ignition.", "number"),
        ("captured", "captured", "True if the orbit at the cut-off is bound to the Moon.",
         "boolean"),
        ("cutoff_orbit", "orbit at cut-off", "'escape', 'captured' or 'beyond the sphere of "
         "influence'.", "string"),
        ("cutoff_epoch", "cut-off (TDB)", "Epoch of the cut-off, TDB.", "string"),
        ("cutoff_min_after_ignition", "cut-off after ignition", "Time from ignition to the "
         "cut-off, min.", "number"),
        ("partial_delta_v_mps", "ΔV before cut-off", "Delta-V flown before the cut-off.",
         "number"),
        ("nominal_burn_duration_min", "nominal duration", "Duration of the nominal burn.",
         "number"),
        ("nominal_burn_delta_v_mps", "nominal ΔV", "Delta-V of the nominal burn.", "number"),
        ("cutoff_energy_km2ps2", "energy at cut-off", "Specific orbital energy at the "
         "cut-off, km²/s².", "number"),
        ("cutoff_e", "e at cut-off", "Eccentricity at the cut-off (dimensionless).",
         "number"),
        ("cutoff_rp_km", "r_p at cut-off", "Perilune radius at the cut-off.", "number"),
        ("cutoff_ra_km", "r_a at cut-off", "Apolune radius at the cut-off.", "number"),
        ("cutoff_period_h", "period at cut-off", "Period at the cut-off.", "number"),
        ("cutoff_soi_radius_km", "sphere of influence", "The Moon's sphere of influence.",
         "number"),
        ("recovery_start_e", "e at recovery", "Eccentricity where the recovery starts "
         "(dimensionless).", "number"),
        ("recovery_delta_v_mps", "recovery ΔV", "Delta-V of the recovery burns.", "number"),
        ("penalty_mps", "penalty", "Partial plus recovery delta-V minus the nominal delta-V "
         "of the burns they replace.", "number"),
        ("nominal_remaining_delta_v_mps", "nominal remaining ΔV", "Nominal delta-V from the "
         "missed burn on.", "number"),
        ("make_up_delta_v_mps", "make-up ΔV", "Delta-V of the first recovery burn.",
         "number"),
        ("make_up_estimate_mps", "make-up estimate", "Two-body estimate of the make-up "
         "delta-V.", "number"),
        ("make_up_period_h", "make-up period", "Osculating period after the make-up burn.",
         "number"),
        ("nominal_period_after_burn_h", "nominal period after", "Period the nominal burn "
         "leaves.", "number"),
        ("first_coast_h", "first coast", "Coast from the cut-off to the make-up burn.",
         "number"),
        ("make_up_estimate_h", "make-up time estimate", "Two-body estimate of the first "
         "coast.", "number"),
        ("recovery_burns", "recovery burns", "One record per recovery burn.", "array"),
        ("ignition_min_after_fault", "ignition after fault", "Time from the cut-off (or "
         "late ignition) to the burn's ignition.", "number"),
        ("error_model", "error model", "Standard deviations of the execution errors.",
         "object")):
    _add(_k, _l, _d, _t)
# ------------------------------------------------------------------ dispersions
for _k, _l, _d, _t in (
        ("sample", "sample", "Index of a Monte Carlo sample.", "integer"),
        ("antithetic", "antithetic", "True if the sample is the negated draws of its pair.",
         "boolean"),
        ("thrust_sigma_pct", "σ thrust", "One-sigma thrust error, %.", "number"),
        ("isp_sigma_pct", "σ Isp", "One-sigma Isp error, %.", "number"),
        ("pointing_sigma_deg", "σ pointing", "One-sigma pointing error per axis.", "number"),
        ("ignition_sigma_s", "σ ignition", "One-sigma ignition-time error.", "number"),
        ("arrival_sigma_km", "σ arrival position", "One-sigma arrival position error per "
         "axis.", "number"),
        ("arrival_sigma_mps", "σ arrival velocity", "One-sigma arrival velocity error per "
         "axis.", "number"),
        ("arrival_cov", "arrival covariance", "Hash of the arrival covariance file (empty "
         "if none).", "string"),
        ("knowledge_sigma_km", "σ knowledge position", "One-sigma orbit-determination "
         "position error per RTN axis of the state each re-plan starts from.", "number"),
        ("knowledge_sigma_mps", "σ knowledge velocity", "One-sigma orbit-determination "
         "velocity error per RTN axis of the state each re-plan starts from.", "number"),
        ("knowledge_cov", "knowledge covariance", "Hash of the knowledge covariance file "
         "(empty if none).", "string"),
        ("gates_magnitude_pct", "σ Gates magnitude, proportional", "Gates (1963) "
         "proportional magnitude error, % of the burn's planned delta-V.", "number"),
        ("gates_magnitude_mps", "σ Gates magnitude, fixed", "Gates (1963) fixed magnitude "
         "error.", "number"),
        ("gates_pointing_deg", "σ Gates pointing, proportional", "Gates (1963) proportional "
         "pointing error (an angle) per transverse axis.", "number"),
        ("gates_pointing_mps", "σ Gates pointing, fixed", "Gates (1963) fixed pointing error "
         "(a transverse delta-V) per axis.", "number"),
        ("bplane_cov", "B-plane covariance", "Hash of the B-plane covariance file (empty if "
         "none).", "string"),
        ("arrival_db_km", "arrival B-plane error", "Size of the sample's B-plane miss "
         "error (B.R, B.T).", "number"),
        ("arrival_dt_s", "arrival time error", "The sample's error of the time of closest "
         "approach (later > 0).", "number"),
        ("knowledge_dr_km", "knowledge position error", "Size of the position error of the "
         "estimate the burn was re-planned from.", "number"),
        ("knowledge_dv_mps", "knowledge velocity error", "Size of the velocity error of the "
         "estimate the burn was re-planned from.", "number"),
        ("mean_above_nominal_mps", "mean ΔV above nominal", "Mean over the captured samples "
         "of the total delta-V minus the nominal.", "number"),
        ("mean_above_nominal_se_mps", "its standard error", "Standard error of "
         "mean_above_nominal_mps.", "number"),
        ("max_above_nominal_mps", "costliest sample above nominal", "Largest total "
         "delta-V of the samples minus the nominal (infinite if one failed).", "number"),
        ("burns_flown", "burns flown", "Burns flown before the sample ended.", "integer"),
        ("propellant_kg", "propellant", "Propellant of the burns flown.", "number"),
        ("delta_v_above_nominal_mps", "ΔV above nominal", "Total delta-V minus the nominal "
         "plan's.", "number"),
        ("final_rp_error_km", "final r_p error", "Final perilune radius minus its target.",
         "number"),
        ("final_ra_error_km", "final r_a error", "Final apolune radius minus its target.",
         "number"),
        ("final_inc_error_deg", "final i error", "Final inclination minus its target.",
         "number"),
        ("final_rp_altitude_km", "final perilune altitude", "Final perilune altitude.",
         "number"),
        ("final_ra_altitude_km", "final apolune altitude", "Final apolune altitude.",
         "number"),
        ("arrival_dr_km", "arrival position error", "Size of the sample's arrival position "
         "error.", "number"),
        ("arrival_dv_mps", "arrival velocity error", "Size of the sample's arrival velocity "
         "error.", "number"),
        ("task_cpu_s", "task CPU", "CPU time of the study task.", "number"),
        ("sample_wall_s", "sample wall", "Wall time of the sample.", "number"),
        ("sample_cpu_s", "sample CPU", "CPU time of the sample.", "number"),
        ("planned_delta_v_mps", "planned ΔV", "Delta-V of the burn as re-planned.", "number"),
        ("ignition_min", "ignition", "Ignition relative to the perilune reached.", "number"),
        ("duration_min", "duration", "Planned burn duration (cut off on the timer).",
         "number"),
        ("thrust_error_pct", "thrust error", "The burn's thrust error, %.", "number"),
        ("isp_error_pct", "Isp error", "The burn's Isp error, %.", "number"),
        ("pointing_error_deg", "pointing error", "Angle of the burn's pointing error.",
         "number"),
        ("ignition_error_s", "ignition error", "The burn's ignition-time error.", "number"),
        ("captured_and_corrected", "captured and corrected", "Samples captured and "
         "corrected to the final orbit.", "integer"),
        ("ci_level", "confidence level", "Confidence level of the intervals (dimensionless).",
         "number"),
        ("budget_p99_above_nominal_mps", "99 % budget above nominal", "99th percentile of "
         "the total delta-V minus the nominal.", "number"),
        ("budget_p99_ci_mps", "99 % budget interval", "Distribution-free confidence interval "
         "of budget_p99_above_nominal_mps.", "array"),
        ("budget_p99_ci_ranks", "interval ranks", "Order statistics bounding the interval.",
         "array"),
        ("p_not_captured", "P(not captured)", "Share of samples not captured "
         "(dimensionless).", "number"),
        ("p_not_captured_upper95", "P(not captured), 95 % bound", "Clopper-Pearson upper "
         "bound of p_not_captured (dimensionless).", "number"),
        ("p_correction_failed", "P(correction failed)", "Share of samples whose correction "
         "failed (dimensionless).", "number"),
        ("p_correction_failed_upper95", "P(correction failed), 95 % bound", "Clopper-Pearson "
         "upper bound of p_correction_failed (dimensionless).", "number"),
        ("final_rms_rp_error_km", "RMS final r_p error", "RMS of final_rp_error_km over the "
         "captured samples.", "number"),
        ("final_rms_ra_error_km", "RMS final r_a error", "RMS of final_ra_error_km.",
         "number"),
        ("final_rms_inc_error_deg", "RMS final i error", "RMS of final_inc_error_deg.",
         "number")):
    _add(_k, _l, _d, _t)
for _k, _l, _d, _t in (
        ("iterations", "iterations", "IPOPT iterations of one mesh attempt.", "integer"),
        ("fractions", "fractions", "The cut-off fractions of a missed-thrust run.", "array"),
        ("delays_min", "delays", "The recovery delays of a missed-thrust run, min.", "array"),
        ("burns_json", "burns (JSON)", "CSV only: the per-burn records of the row as JSON "
         "text (the CLI's JSON gives them as 'burns').", "string"),
        ("recovery_burns_json", "recovery burns (JSON)", "CSV only: the recovery burns as "
         "JSON text (the CLI's JSON gives them as 'recovery_burns').", "string"),
        ("final_max_abs_rp_error_km", "max |final r_p error|", "Largest |final_rp_error_km| "
         "over the captured samples.", "number"),
        ("final_max_abs_ra_error_km", "max |final r_a error|", "Largest |final_ra_error_km|.",
         "number"),
        ("final_max_abs_inc_error_deg", "max |final i error|", "Largest "
         "|final_inc_error_deg|.", "number")):
    _add(_k, _l, _d, _t)
for _q in (1, 5, 10, 50, 90, 95, 99):
    _add(f"delta_v_p{_q}_mps", f"ΔV, {_q}th percentile", f"{_q}th percentile of the total "
         "delta-V over every sample (a failed one counts as infinite).")
    _add(f"propellant_p{_q}_kg", f"propellant, {_q}th percentile", f"{_q}th percentile of "
         "the propellant over every sample.")
    _add(f"delta_v_p{_q}_ci_mps", f"ΔV, {_q}th percentile interval", f"Distribution-free "
         f"confidence interval of delta_v_p{_q}_mps (order statistics).", "array")
    _add(f"samples_needed_p{_q}", f"samples for the {_q}th percentile", f"Fewest samples "
         f"whose order statistics bound the {_q}th percentile's interval on both sides.",
         "integer")

# ------------------------------------------------------------------ the book pages' tables
for _k, _l, _d in (
        ("burn_duration_diff_min", "duration, ours - paper", "burn_duration_min minus "
         "paper_burn_duration_min."),
        ("delta_v_diff_percent", "ΔV, ours - paper", "delta_v_mps over paper_delta_v_mps "
         "minus one, in %."),
        ("delta_v_difference_mps", "ΔV, ours - published", "Our delta-V minus the one "
         "published for the same burn (by Song et al. or by a mission)."),
        ("loss_vs_paper_impulse_diff_percent", "loss vs paper's impulse, ours - paper",
         "loss_vs_paper_impulse_percent minus the paper's, in percentage points."),
        ("impulsive_limit_effect_mps", "impulsive limit effect", "Impulsive limit with the "
         "IAU lunar pole at J2000 minus with the constant pole."),
        ("delta_v_loss_new_mps", "ΔV loss, J2000 pole", "delta_v_loss_mps with the IAU lunar "
         "pole at J2000."),
        ("delta_v_loss_effect_mps", "ΔV loss effect", "delta_v_loss_new_mps minus the delta-V "
         "loss with the constant pole."),
        ("difference_mps", "ΔV, ours - other", "Delta-V minus the one it is compared with "
         "on the row (the paper's, or the sequential chain's)."),
        ("difference_min", "duration, ours - paper", "Eq. (19) duration minus the one the "
         "paper prints."),
        ("difference_s", "epoch, ours - paper", "Our epoch minus the one the paper prints."),
        ("total_difference_mps", "total ΔV, sequential - joint", "Summed difference_mps of "
         "a chain."),
        ("largest_leg_shift_mps", "largest burn ΔV shift", "Largest |difference_mps| of a "
         "chain's burns."),
        ("largest_start_shift_s", "largest start shift", "Largest |joint start - sequential "
         "start| of a chain's burns."),
        ("joint_solve_s", "joint solve", "Wall time of the joint optimisation of a chain."),
        ("delta_v_gain_mps", "ΔV gain", "grid_delta_v_mps minus free_delta_v_mps."),
        ("objective_gain_mps", "J gain", "Objective J with the grid's best start minus J "
         "with the free ignition epoch."),
        ("fuel_saved_kg", "propellant saved", "free_final_mass_kg minus grid_final_mass_kg."),
        ("burn_midpoint_min", "burn midpoint", "free_start_min plus half the free burn's "
         "duration."),
        ("start_minus_rule_min", "start - rule", "free_start_min minus rule_start_min."),
        ("rule_delta_v_cost_mps", "ΔV cost of the rule", "Delta-V with the rule's start "
         "minus free_delta_v_mps."),
        ("rule_objective_cost_mps", "J cost of the rule", "Objective J with the rule's start "
         "minus J with the free ignition epoch."),
        ("delta_v_penalty_mps", "ΔV penalty", "Delta-V of a fixed steering law minus the "
         "optimal steering's."),
        ("objective_penalty_mps", "J penalty", "Objective J of a fixed steering law minus "
         "the optimal steering's."),
        ("rp_miss_km", "r_p miss", "Perilune radius reached minus the target's, under a "
         "steering law that releases it."),
        ("inc_miss_deg", "i miss", "Inclination reached minus the target's, under a "
         "steering law that releases it."),
        ("rp_error_mm", "r_p error", "verification_rp_error_m in mm."),
        ("ra_error_mm", "r_a error", "verification_ra_error_m in mm."),
        ("verified_delta_v_diff_mps", "|ΔV, flown - collocated|", "|delta_v_diff_mps| of a "
         "verified solution."),
        ("delta_v_change_vs_finest_mps", "ΔV - finest mesh's", "Delta-V on the mesh minus "
         "the delta-V on the finest mesh of the same case."),
        ("burn_long_s", "long burn", "Duration of the longer of the two short burns "
         "defining the impulsive limit."),
        ("burn_short_s", "short burn", "Duration of the shorter of the two short burns "
         "defining the impulsive limit."),
        ("delta_v_long_mps", "ΔV, long burn", "Delta-V of the longer short burn."),
        ("delta_v_short_mps", "ΔV, short burn", "Delta-V of the shorter short burn."),
        ("extrapolation_mps", "limit - short", "impulsive_limit_mps minus delta_v_short_mps."),
        ("ci_lo_mps", "CI low", "Lower bound of a 95 % confidence interval of a delta-V."),
        ("ci_hi_mps", "CI high", "Upper bound of a 95 % confidence interval of a delta-V."),
        ("median_sample_s", "median sample wall", "Median wall time of a Monte Carlo "
         "sample."),
        ("median_sample_cpu_s", "median sample CPU", "Median CPU time of a Monte Carlo "
         "sample."),
        ("optimal_loss_percent", "J loss, ours", "Our verified optimal objective_loss_percent"
         " at the engine, the engine solved directly (free ignitions)."),
        ("interpolated_loss_percent", "J loss, interpolated", "objective_loss_percent read "
         "off the trade study's curve of the engine's Isp, linear in log thrust-to-weight "
         "between the grid's optima."),
        ("interpolation_error_pp", "interpolation error", "interpolated_loss_percent minus "
         "optimal_loss_percent, percentage points: what reading the curve instead of "
         "solving the engine is off by."),
        ("perilune_from_ignition_min", "perilune after ignition", "Time from ignition to "
         "the nominal perilune."),
        ("ignition_from_perilune_deg", "ignition from perilune", "True anomaly of the "
         "ignition point from the perilune (negative: before it)."),
        ("cutoff_from_perilune_deg", "cut-off from perilune", "True anomaly of the cut-off "
         "point from the perilune."),
        ("m_kg", "mass", "Spacecraft mass along the burn."),
        ("m0_kg", "mass at ignition", "Mass at ignition from which Eq. (19) is evaluated."),
        ("period_h", "period", "Period of the orbit a burn leaves (plan pages)."),
        ("alpha_deg", "α", "In-plane thrust angle of Eq. (14) (the paper's Figs. 1 and 4)."),
        ("beta_deg", "β", "Out-of-plane thrust angle of Eq. (14) (the paper's Figs. 1 and "
         "4)."),
        ("x_km", "x", "Position along the first axis of a figure's plane."),
        ("y_km", "y", "Position along the second axis of a figure's plane."),
        ("vx_kmps", "v_x", "Velocity along the first axis of a figure's plane."),
        ("vy_kmps", "v_y", "Velocity along the second axis of a figure's plane."),
        ("ax_thrust_mps2", "a_x, thrust", "Thrust acceleration along the first axis of a "
         "figure's plane."),
        ("ay_thrust_mps2", "a_y, thrust", "Thrust acceleration along the second axis of a "
         "figure's plane."),
        ("angle_thrust_velocity_deg", "thrust to velocity", "Angle between the thrust and "
         "the velocity."),
        ("ra_deg", "α₀", "Right ascension of a lunar pole, ICRF."),
        ("dec_deg", "δ₀", "Declination of a lunar pole, ICRF."),
        ("from_ecliptic_pole_deg", "from ecliptic pole", "Angle between a lunar pole and "
         "the ecliptic pole."),
        ("dv_new_mps", "ΔV, J2000 pole", "Delta-V with the IAU lunar pole at J2000."),
        ("dv_old_mps", "ΔV, constant pole", "Delta-V with the constant pole used before."),
        ("dv_effect_mps", "ΔV effect", "dv_new_mps minus dv_old_mps."),
        ("interpolation_error_m", "interpolation error", "Largest position error of an "
         "exchanged ephemeris segment against the trajectory it interpolates."),
        ("kplo_delta_v_mps", "impulsive ΔV, KPLO", "Impulsive delta-V KPLO's published "
         "plan gives for the burn."),
        ("kplo_speed_kmps", "speed, KPLO", "Speed KPLO's published plan gives at the point."),
        ("our_speed_kmps", "speed, ours", "Our speed at the same point."),
        ("speed_difference_mps", "speed, ours - KPLO", "our_speed_kmps minus "
         "kplo_speed_kmps, in m/s."),
        ("published_min", "published", "Burn duration a mission published."),
        ("ours_paper_spacecraft_min", "ours, paper's spacecraft", "Our burn duration with "
         "the paper's spacecraft mass."),
        ("ours_at_mission_mass_min", "ours, mission's mass", "Our burn duration scaled to "
         "the mission's mass and engine (rocket equation).")):
    _add(_k, _l, _d)

#: Every quantity by name.
GLOSSARY: dict = {q.name: q for q in _Q}

#: Composition prefixes: ``prefix`` -> (label prefix, label suffix, how the definition reads).
PREFIXES = {
    "paper_": ("", ", paper", "As printed by Song et al. (2011): {}"),
    "total_": ("total ", "", "Summed over the burns: {}"),
    "verification_": ("", "", "Verification of the burn: {}"),
    "nominal_": ("nominal ", "", "Of the nominal (error-free) plan: {}"),
    "free_": ("", ", free", "With the ignition epoch optimised: {}"),
    "grid_": ("", ", grid", "With the best ignition epoch of the study's grid of starts: {}"),
    "rule_": ("", ", rule", "With the ignition half the Eq. (19) duration before the "
              "perilune: {}"),
    "joint_": ("", ", joint", "With every burn of the chain optimised together: {}"),
    "sequential_": ("", ", sequential", "With the burns optimised one after another: {}"),
    "design_": ("", ", design", "Of the capture as designed in the plan's own dynamics, "
                "before it is flown or designed again in another model (the real-Moon "
                "page: the J2 design): {}"),
    "redesign_": ("", ", re-designed", "Of the capture designed again (the same plan, "
                  "targets and ignitions) in the model it is flown in (the real-Moon page: "
                  "the lunar gravity field): {}"),
    "gmat_": ("", ", GMAT", "As NASA's GMAT flies lunarcap's exported script of the "
              "capture: {}"),
}

#: Composition suffixes (after the unit): ``suffix`` -> (label suffix, definition).
SUFFIXES = {
    "_loi1": (", LOI 1", "For LOI 1: {}"), "_loi2": (", LOI 2", "For LOI 2: {}"),
    "_loi3": (", LOI 3", "For LOI 3: {}"), "_sequence": (", sequence", "For the sequence: {}"),
}

#: Old names that must never appear (each had several meanings).
RETIRED = ("loss_mps", "loss_percent", "objective_mps", "impulsive_two_body_mps",
           "verification_branch")


def lookup(name: str) -> Quantity:
    """The quantity named ``name`` (direct or composed); KeyError if not in the glossary."""
    if name in GLOSSARY:
        return GLOSSARY[name]
    for suffix, (lab, text) in SUFFIXES.items():
        if name.endswith(suffix) and name[: -len(suffix)] in GLOSSARY:
            q = GLOSSARY[name[: -len(suffix)]]
            return Quantity(name, q.unit, q.label + lab, text.format(q.definition), q.kind)
    for prefix, (before, after, text) in PREFIXES.items():
        if name.startswith(prefix) and name not in RETIRED:
            try:
                q = lookup(name[len(prefix):])
            except KeyError:
                continue
            return Quantity(name, q.unit, before + q.label + after,
                            text.format(q.definition[0].lower() + q.definition[1:]), q.kind)
    raise KeyError(f"{name!r} is not in the glossary of quantities (lunarcap.quantities)")


def is_known(name: str) -> bool:
    """True if ``name`` is a glossary quantity (directly or composed)."""
    try:
        lookup(name)
    except KeyError:
        return False
    return True


def unknown(names) -> list:
    """The names of ``names`` that are not in the glossary, in order."""
    return [n for n in names if not is_known(n)]


# ------------------------------------------------------------------ the captures compared
#: The captures of the paper's arrival the book compares, by the name every page uses for
#: them ("the 150 N capture" is one of these, in some dynamics; each page names which):
#: key -> (name, definition).
CAPTURES = {
    "fixed": ("the paper's fixed timings",
              "The paper's three burns (hyperbola to 12.235 h, to 3.525 h, to the 100 km "
              "circle), each ignited at the paper's best offset of its Table B1 (150 N: 10, 6 "
              "and 5 min before the perilune) and optimised after the one before (Eq. 9), its "
              "coast ending at the nominal perilune (Eq. 17): the packaged song2011-* plans."),
    "free": ("free ignitions",
             "The same three burns and orbits, every ignition time optimised (within two "
             "Eq. (19) durations of the perilune, and at least 30 min, in full dynamics), "
             "one burn after the other."),
    "joint": ("free ignitions, jointly optimised",
              "The same three burns and orbits with free ignitions, all in one optimisation "
              "whose objective is their total delta-V."),
    "free_periods": ("re-optimised with free periods",
                     "All the burns in one optimisation of their total delta-V, ignitions "
                     "free and the periods of the intermediate orbits free up to a bound "
                     "(the missed-thrust nominal: the orbit after burn 1 up to 24 h; the "
                     "burn-count study: every period up to 12.235 h)."),
}


def capture_name(key: str) -> str:
    """The glossary name of a capture (:data:`CAPTURES`), e.g. "the paper's fixed timings".

    >>> capture_name("free")
    'free ignitions'
    """
    return CAPTURES[key][0]
