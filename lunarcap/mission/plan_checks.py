"""The one validation of a capture plan, whatever built it (a YAML file, Python, a variant).

:meth:`CapturePlan.__post_init__ <lunarcap.mission.plan.CapturePlan>` calls
:func:`validate`, and nothing else checks a plan's values.

Fields are checked first, each against its own range (numbers by :func:`lunarcap.errors.
number`, the one parser of user numbers), then the checks derived from several fields (a
period against the perilune, the ephemeris window, the engine against the mass). So a
value out of range is refused as itself: a perilune 100,000 km up is refused as a perilune,
outside the Moon's sphere of influence, before any orbit is built on it. Every message
names the field as a plan file writes it, burns numbered from 1 (``burns[2].start_min``).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from lunarcap.errors import InputError, number
from lunarcap.mission.impulsive import PAPER_DV_LOI1_MPS, v_inf_from_loi1
from lunarcap.mission.targets import CIRCULAR, PERILUNE, check_inclination
from lunarcap.physics import constants as C
from lunarcap.physics.bplane import REFERENCE_PLANES
from lunarcap.physics.elements import period_from_semi_major_axis, semi_major_axis_from_period
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.forces import PRESETS, ForceModel, force_model
from lunarcap.physics.frames import (
    DEFAULT_LUNAR_POLE,
    LUNAR_POLES,
    POLE_OF_DATE_PREFIX,
    check_lunar_pole,
    pole_of_date,
)

#: The paper's dynamics by their words (a plan may also name its forces as a mapping:
#: :mod:`lunarcap.physics.forces`).
DYNAMICS = PRESETS
#: How a burn's period or apolune target is met (:mod:`lunarcap.mission.targets`):
#: ``orbit``, the orbit named, as osculating elements at the first perilune after the burn
#: (its epoch free); ``song2011``, the paper's Eq. (17): perilune radius, inclination and
#: gamma = 0 at the next nominal perilune (the period only through that timing).
FORMULATIONS = ("orbit", "song2011")
STEERING = ("optimal", "inertial", "antivelocity")
HEMISPHERES = ("north", "south")

#: Largest |ignition offset| from a nominal perilune, min.
MAX_START_MIN = 120.0
#: Margin of the ephemeris window around the plan's first and last perilune, s.
EPHEMERIS_MARGIN_S = 6 * 3600.0
#: Shortest burn the transcription resolves, s (an engine that would finish faster is
#: reported as too strong rather than handed to the optimiser).
MIN_BURN_S = 0.5
#: A burn may last at most this fraction of the coast it starts (Eq. (19) estimate).
MAX_BURN_FRACTION = 0.5

#: Mean Earth-Moon distance, km (semi-major axis of the lunar orbit; Standish 1998, DE405).
EARTH_MOON_DISTANCE_KM = 384_400.0
#: Radius of the Moon's sphere of influence, km: Laplace's a (mu_Moon / mu_Earth)^(2/5),
#: about 66,200 km. A perilune or apolune farther out is an Earth orbit, not a lunar one.
MOON_SOI_RADIUS_KM = EARTH_MOON_DISTANCE_KM * (C.MU_MOON / C.MU_EARTH) ** 0.4
#: Largest hyperbolic excess speed of an arrival, km/s: lunarcap's stated limit, five
#: times a direct transfer's ~1 km/s (the paper's 0.918 km/s); beyond it no capture burn
#: of a chemical engine is plausible (the first burn alone would exceed 3 km/s).
MAX_V_INF_KMPS = 5.0
#: Largest arrival mass, kg: lunarcap's stated limit, twice Apollo 11's CSM + LM at lunar
#: orbit insertion (about 44 t); a heavier "spacecraft" is a typo, not a mission.
MAX_MASS_KG = 100_000.0

_SOI = f"Laplace's radius, {MOON_SOI_RADIUS_KM:,.0f} km from the Moon's centre"


class PlanError(InputError):
    """A capture plan is malformed or physically impossible (the message names the field).

    >>> import lunarcap
    >>> lunarcap.load_plan("two-burn-8h", targets=[{"target_period_h": -6}, None])
    Traceback (most recent call last):
    ...
    lunarcap.mission.plan_checks.PlanError: burns[1].target_period_h: must be positive (h), got -6
    """


def err(where: str, what: str) -> PlanError:
    """A PlanError ``where: what``."""
    return PlanError(f"{where}: {what}")


def num(where: str, value, unit: str, positive: bool = True, **limits) -> float:
    """A finite float (positive unless ``positive`` is False), else PlanError naming ``where``."""
    try:
        return number(where, value, unit, positive=positive, **limits)
    except InputError as exc:
        raise PlanError(str(exc)) from None


def burn_field(i: int, key: str) -> str:
    """The name of burn ``i``'s field (0-based ``i``; a plan file numbers burns from 1)."""
    return f"burns[{i + 1}].{key}"


def keys(where: str, d, known: set, required: set) -> None:
    """PlanError unless ``d`` is a mapping with every required key and no unknown one."""
    if not isinstance(d, dict):
        raise err(where, f"must be a mapping of keys to values, got {type(d).__name__}")
    unknown = sorted(set(d) - known)
    if unknown:
        raise err(f"{where}.{unknown[0]}" if where else unknown[0],
                  f"unknown key (known: {', '.join(sorted(known))})")
    missing = sorted(required - set(d))
    if missing:
        raise err(f"{where}.{missing[0]}" if where else missing[0], "missing")


def choice(where: str, value, allowed) -> str:
    """``value`` if it is one of ``allowed``, else PlanError naming ``where``."""
    if value not in allowed:
        raise err(where, f"must be one of {', '.join(allowed)}, got {value!r}")
    return value


def circle_period_s(r_km: float, mu: float = C.MU_MOON) -> float:
    """Period of the circle of radius ``r_km``, s."""
    return float(period_from_semi_major_axis(r_km, mu))


def period_from_apolune_s(rp_km: float, ra_km: float, mu: float = C.MU_MOON) -> float:
    """Period of the ellipse of perilune and apolune radii ``rp_km``, ``ra_km``, s."""
    return float(period_from_semi_major_axis(0.5 * (rp_km + ra_km), mu))


def start_value(where: str, value):
    """'free' or an ignition offset (min) within +-MAX_START_MIN, as a float."""
    if value == "free":
        return "free"
    v = num(where, value, "min", positive=False)
    if abs(v) > MAX_START_MIN:
        raise err(where, f"{v:g} min is more than {MAX_START_MIN:g} min from perilune")
    return v


def altitude(where: str, value) -> float:
    """An altitude above the mean lunar radius, km: above the surface, inside the SOI."""
    alt = num(where, value, "km", positive=False)
    if alt <= 0:
        raise err(where, f"{alt:g} km puts it at or below the lunar surface (radius "
                         f"{C.R_MOON} km): the altitude must be positive")
    if C.R_MOON + alt >= MOON_SOI_RADIUS_KM:
        raise err(where, f"{alt:g} km is outside the Moon's sphere of influence, which ends "
                         f"{MOON_SOI_RADIUS_KM - C.R_MOON:,.0f} km above the surface ({_SOI})")
    return alt


# ---------------------------------------------------------------------- fields
def checked_engine(e):
    """The engine with its thrust and Isp checked (positive finite numbers), as floats."""
    return replace(e, thrust_N=num("engine.thrust_N", e.thrust_N, "N"),
                   isp_s=num("engine.isp_s", e.isp_s, "s"))


def _check_bplane_reference(a) -> None:
    """A B-plane arrival's reference plane: one of the planes, the arrival's own (PlanError)."""
    choice("arrival.bplane_reference", a.bplane.reference, REFERENCE_PLANES)
    if a.bplane_reference != a.bplane.reference:
        raise err("arrival.bplane_reference", f"the B-plane target is given about "
                                              f"{a.bplane.reference}, the arrival about "
                                              f"{a.bplane_reference}: give one")


def checked_arrival(a):
    """The arrival with each field checked against its own range, numbers as floats."""
    if not isinstance(a.epoch, str):
        raise err("arrival.epoch", f"must be a text like '2017-02-20 03:41:26 TDB', "
                                   f"got {a.epoch!r}")
    try:
        seconds_from_calendar(a.epoch)
    except InputError as exc:
        raise err("arrival.epoch", str(exc)) from None
    alt = altitude("arrival.perilune_altitude_km", a.perilune_altitude_km)
    inc = num("arrival.inclination_deg", a.inclination_deg, "deg", positive=False)
    try:
        check_inclination("arrival.inclination_deg", inc)
    except InputError as exc:
        raise PlanError(str(exc)) from None
    mass = num("arrival.mass_kg", a.mass_kg, "kg", maximum=MAX_MASS_KG,
               limit="lunarcap's limit, twice Apollo 11's CSM + LM")
    vinf = a.v_inf_kmps
    if vinf is not None:
        vinf = num("arrival.v_inf_kmps", vinf, "km/s", maximum=MAX_V_INF_KMPS,
                   limit="lunarcap's limit; a direct transfer arrives at about 1 km/s")
    choice("arrival.hemisphere", a.hemisphere, HEMISPHERES)
    choice("arrival.bplane_reference", a.bplane_reference, REFERENCE_PLANES)
    approach = a.approach_dir
    if approach is not None:
        approach = tuple(num(f"arrival.approach_dir[{j + 1}]", x, "", positive=False)
                         for j, x in enumerate(approach))
        if not np.linalg.norm(approach) > 0:
            raise err("arrival.approach_dir", "must be a non-zero vector")
    return replace(a, perilune_altitude_km=alt, inclination_deg=inc, mass_kg=mass,
                   v_inf_kmps=vinf, approach_dir=approach)


def _scaled(where: str, value_s, factor: float, unit: str) -> float:
    """A positive duration stored in s, checked in the plan file's unit (h: factor 3600)."""
    ok = isinstance(value_s, (int, float, np.integer, np.floating)) and \
        not isinstance(value_s, bool)
    num(where, value_s / factor if ok else value_s, unit)
    return float(value_s)


def checked_burn(i: int, b, altitude_km: float):
    """Burn ``i`` (0-based) with its own fields checked, numbers as floats, period derived.

    A period or apolune target gets its period (s) from ``target_period_h`` or from the
    apolune altitude and the perilune altitude ``altitude_km`` (the burn's own, if it
    names both altitudes).
    """
    choice(burn_field(i, "target"), b.target, (PERILUNE, CIRCULAR))
    choice(burn_field(i, "steering"), b.steering, STEERING)
    fields = dict(start_min=start_value(burn_field(i, "start_min"), b.start_min))
    if b.start_bounds_min is not None:
        fields["start_bounds_min"] = _bounds(i, b.start_bounds_min)
    if b.target == CIRCULAR:
        if b.coast_s is not None:
            fields["coast_s"] = _scaled(burn_field(i, "coast_min"), b.coast_s, 60.0, "min")
        return replace(b, **fields)
    if b.perilune_altitude_km is not None:
        rp = fields["perilune_altitude_km"] = altitude(
            burn_field(i, "target.perilune_altitude_km"), b.perilune_altitude_km)
        key = "target.apolune_altitude_km"
    else:
        rp, key = altitude_km, "target_apolune_altitude_km"
    if b.apolune_altitude_km is not None:
        ra = fields["apolune_altitude_km"] = altitude(burn_field(i, key),
                                                      b.apolune_altitude_km)
        if ra <= rp:
            raise err(burn_field(i, key), f"{ra:g} km is not above the perilune altitude "
                                          f"{rp:g} km")
        if b.period_s is None:
            fields["period_s"] = period_from_apolune_s(C.R_MOON + rp, C.R_MOON + ra)
    else:
        fields["period_s"] = _scaled(burn_field(i, "target_period_h"), b.period_s, 3600.0,
                                     "h")
    return replace(b, **fields)


def _bounds(i: int, bounds) -> tuple:
    where = burn_field(i, "start_bounds_min")
    if not isinstance(bounds, (list, tuple)) or len(bounds) != 2:
        raise err(where, f"must be [lo, hi] in minutes, got {bounds!r}")
    out = tuple(start_value(f"{where}[{j + 1}]", x) for j, x in enumerate(bounds))
    if "free" in out or not out[0] <= out[1]:   # lo == hi: the ignition fixed (a re-plan's)
        raise err(where, f"must be two numbers lo <= hi, got {list(bounds)!r}")
    return out


def checked_start(st):
    """A :class:`~lunarcap.mission.plan.Start` with its epoch, state and coast checked."""
    epoch = num("start.epoch", st.epoch_s, "s", positive=False)
    if len(st.state) != 7:
        raise err("start.mee", f"a state is 7 numbers (p, f, g, h, k, L, m), got "
                               f"{len(st.state)}")
    mee = tuple(num(f"start.mee[{j + 1}]", x, "", positive=False)
                for j, x in enumerate(st.state[:6]))
    if mee[0] <= 0:
        raise err("start.mee[1]", f"p must be positive (km), got {mee[0]!r}")
    mass = num("start.mass_kg", st.state[6], "kg", maximum=MAX_MASS_KG)
    coast = _scaled("start.first_coast_min", st.first_coast_s, 60.0, "min")
    return replace(st, epoch_s=epoch, state=mee + (mass,), first_coast_s=coast)


def checked_dynamics(value):
    """A plan's dynamics: a preset word as such, else its :class:`ForceModel`.

    The words (``full``, ``j2``, ``two-body``) stay words, so the paper's plans and their
    cache keys are what they were; a mapping becomes the model it names (PlanError names
    the key at fault: ``dynamics.degree: ...``).
    """
    if isinstance(value, str) and value in PRESETS:
        return value
    if isinstance(value, ForceModel) and value.name:
        return value.name
    try:
        model = force_model(value)
    except InputError as exc:
        msg = str(exc)
        raise PlanError(msg if msg.startswith("dynamics") else f"dynamics: {msg}") from None
    return model.name or model


def default_pole(dynamics) -> str:
    """The lunar pole of a plan that names none: J2000's for the paper's words, else of date.

    A plan whose dynamics are a mapping measures inclinations about the Moon's axis of
    date (at its arrival epoch): the ``lunar_pole: of-date`` default of new plans.
    """
    return DEFAULT_LUNAR_POLE if isinstance(dynamics, str) and dynamics in PRESETS \
        else "of-date"


def frame_epoch(arrival) -> str:
    """The epoch of a pole of date: the arrival's as given (a state's own epoch)."""
    return arrival.state.epoch if arrival.state is not None else arrival.epoch


# ---------------------------------------------------------------------- the plan
def validate(plan) -> None:
    """Check a plan, field by field and then as a whole; normalise its numbers to floats.

    Called once per plan, by its ``__post_init__`` (PlanError names the field).
    """
    s = object.__setattr__
    choice("formulation", plan.formulation, FORMULATIONS)
    s(plan, "dynamics", checked_dynamics(plan.dynamics))
    if plan.lunar_pole == "of-date":
        s(plan, "lunar_pole", pole_of_date(frame_epoch(plan.arrival)))
    try:
        check_lunar_pole(plan.lunar_pole)
    except ValueError:
        raise err("lunar_pole", f"must be one of {', '.join(LUNAR_POLES)}, of-date or "
                                f"'{POLE_OF_DATE_PREFIX}<epoch>', got {plan.lunar_pole!r}"
                  ) from None
    s(plan, "engine", checked_engine(plan.engine))
    if not plan.burns:
        raise err("burns", "a plan needs at least one burn")
    if plan.start is not None:
        s(plan, "start", checked_start(plan.start))
    if plan.impulsive_loi1_mps is not None:
        s(plan, "impulsive_loi1_mps",
          num("arrival.impulsive_loi1_mps", plan.impulsive_loi1_mps, "m/s"))
    if plan.arrival.state is not None:
        plan._derive_state_arrival()
    if plan.arrival.bplane is not None:
        _check_bplane_reference(plan.arrival)
        plan._derive_bplane_arrival()
    s(plan, "arrival", checked_arrival(plan.arrival))
    alt = plan.arrival.perilune_altitude_km
    s(plan, "burns", tuple(checked_burn(i, b, alt) for i, b in enumerate(plan.burns)))
    _check_sequence(plan)
    if plan.start is not None:
        _check_start(plan)
    _derive_v_inf(plan)
    _check_ephemeris(plan)
    if plan.start is None:
        _check_arrival_geometry(plan)
    _check_engine_fits(plan)


def _check_sequence(plan) -> None:
    """Each burn lowers the orbit; targets fit the perilune; circles and ellipses last."""
    rp = plan.perilune_radius_km
    circle = circle_period_s(rp)
    period_before = math.inf
    for i, b in enumerate(plan.burns):
        last = i == plan.n_burns - 1
        if b.target == CIRCULAR:
            if not last:
                raise err(burn_field(i, "target"), "a circular target must be the last burn (a "
                                                   "burn after it has nothing to lower)")
            period_after = circle
        else:
            period_after = _check_ellipse(plan, i, b, rp, circle)
        if not period_after < period_before:
            raise err(burn_field(i, "target_period_h" if b.target == PERILUNE else "target"),
                      f"the orbit reached ({period_after / 3600:.4g} h) is not shorter than "
                      f"the orbit before ({period_before / 3600:.4g} h): each capture burn "
                      f"must lower the orbit")
        if not b.free_start and math.isfinite(period_before) and \
                abs(b.start_min) * 60.0 > 0.4 * period_before:
            raise err(burn_field(i, "start_min"),
                      f"{b.start_min:g} min from perilune is more than 0.4 of the "
                      f"{period_before / 60:.1f} min orbit it starts on")
        period_before = period_after


def _check_ellipse(plan, i: int, b, rp_km: float, circle_s: float) -> float:
    """The period of burn ``i``'s ellipse, if it exists around this perilune, s."""
    if b.perilune_altitude_km is not None:
        if i != plan.n_burns - 1:
            raise err(burn_field(i, "target"), "an ellipse given by both altitudes is a final "
                                               "orbit: only the last burn may have it")
        if plan.formulation == "song2011":
            raise err(burn_field(i, "target"), "the song2011 formulation (Eq. 17) targets a "
                                               "perilune and a timing, not an apolune: use "
                                               "formulation: orbit for an ellipse by altitudes")
        return b.period_s
    key = "target_apolune_altitude_km" if b.apolune_altitude_km is not None \
        else "target_period_h"
    p = b.period_s
    if p <= circle_s:
        raise err(burn_field(i, key),
                  f"a period of {p / 3600:.4g} h is not longer than the circular orbit's at "
                  f"the perilune radius {rp_km:g} km ({circle_s / 3600:.4g} h): no ellipse "
                  f"has that perilune and period")
    a = float(semi_major_axis_from_period(p, C.MU_MOON))
    if 2 * a - rp_km >= MOON_SOI_RADIUS_KM:
        raise err(burn_field(i, key),
                  f"a period of {p / 3600:.4g} h puts the apolune {2 * a - rp_km:,.0f} km from "
                  f"the Moon's centre, outside its sphere of influence ({_SOI})")
    return p


def _check_start(plan) -> None:
    st, b0 = plan.start, plan.burns[0]
    if b0.free_start and b0.start_bounds_min is None:
        raise err(burn_field(0, "start_bounds_min"),
                  "a plan that starts from a given state needs a window [lo, hi] (min from "
                  "its epoch) for a free first ignition")
    latest = b0.start_bounds_min[1] if b0.free_start else b0.start_min
    if latest * 60.0 >= st.first_coast_s:
        raise err("start.first_coast_min",
                  f"the first coast ({st.first_coast_s / 60:.1f} min) must end after the "
                  f"latest ignition ({latest:g} min)")


def _derive_v_inf(plan) -> None:
    """v_inf from an impulsive first burn (default: the paper's 353.272 m/s), if not given."""
    if plan.start is not None or (plan.impulsive_loi1_mps is None
                                  and plan.arrival.v_inf_kmps is not None):
        return
    dv = PAPER_DV_LOI1_MPS if plan.impulsive_loi1_mps is None else plan.impulsive_loi1_mps
    first = plan.burns[0]
    rp = plan.perilune_radius_km
    period = first.period_s if first.target == PERILUNE else circle_period_s(rp)
    try:
        vinf = v_inf_from_loi1(dv, rp, period)
    except InputError as exc:
        raise err("arrival.impulsive_loi1_mps", str(exc)) from None
    if vinf > MAX_V_INF_KMPS:
        raise err("arrival.impulsive_loi1_mps",
                  f"{dv:g} m/s into the first orbit means arriving at v_inf {vinf:.3g} km/s, "
                  f"above lunarcap's limit of {MAX_V_INF_KMPS:g} km/s")
    object.__setattr__(plan, "arrival", replace(plan.arrival, v_inf_kmps=vinf))


def _check_arrival_geometry(plan) -> None:
    """The arrival hyperbola can be built with this inclination (else PlanError)."""
    a = plan.arrival
    s = a.approach_direction(plan.ephemeris_model())
    lat = math.degrees(math.asin(max(-1.0, min(1.0, float(s[2])))))
    inc = a.inclination_deg
    if min(inc, 180.0 - inc) < abs(lat) - 1e-9:
        raise err("arrival.inclination_deg",
                  f"{inc:g} deg cannot be reached from this arrival: its approach asymptote "
                  f"lies {abs(lat):.2f} deg from the lunar equator (M-MME2000) on {a.epoch}, "
                  f"and an orbit containing it is inclined at least that much (and at most "
                  f"180 deg minus it); ask for {abs(lat):.2f} to {180 - abs(lat):.2f} deg, or "
                  f"give approach_dir")


def _check_ephemeris(plan) -> None:
    eph = plan.ephemeris_model()
    t = plan.nominal_perilunes_s
    a, b = eph.span_s
    if t[0] - EPHEMERIS_MARGIN_S < a or t[-1] + EPHEMERIS_MARGIN_S > b:
        raise err("arrival.epoch",
                  f"the capture from {calendar_from_seconds(t[0], 0)} to "
                  f"{calendar_from_seconds(t[-1], 0)} (with 6 h margins) is outside the "
                  f"ephemeris {eph.name}, which covers {calendar_from_seconds(a, 0)} to "
                  f"{calendar_from_seconds(b, 0)}")


def _check_engine_fits(plan) -> None:
    """Each burn's Eq. (19) duration is resolvable and shorter than half its orbit.

    Except a make-up burn, the first of a plan that starts from a given state after a
    fault (``start.make_up``, :meth:`lunarcap.mission.plan.CapturePlan.resumed`): it may
    need next to nothing (a cut-off just before the planned end), and its impulse,
    tangential where the state is rather than at a perilune, need not size its burn; its
    solver bounds its duration (:data:`lunarcap.studies.missed.recovery.MIN_MAKE_UP_S`,
    0.9 of its coast).
    """
    t = plan.nominal_perilunes_s
    thrust, mass = plan.engine.thrust_N, plan.initial_mass_kg
    for i, ib in enumerate(plan.impulsive()):
        if i == 0 and plan.start is not None and plan.start.make_up:
            continue
        t19 = ib.eq19_duration_min * 60.0
        coast = t[i + 1] - t[i]
        before = t[i] - t[i - 1] if i else coast
        if t19 < MIN_BURN_S:
            raise err("engine.thrust_N",
                      f"{thrust:g} N is too strong: burn {i + 1} ({ib.delta_v_mps:.1f} m/s) "
                      f"would last {t19:.2g} s (Eq. 19), below the {MIN_BURN_S:g} s the "
                      f"transcription resolves; for an impulse, see the impulsive chain "
                      f"(lunarcap impulsive)")
        if t19 > MAX_BURN_FRACTION * min(coast, before):
            raise err("engine.thrust_N",
                      f"{thrust:g} N is too weak for {mass:g} kg: burn {i + 1} "
                      f"({ib.delta_v_mps:.1f} m/s) would last {t19 / 60:.1f} min (Eq. 19), "
                      f"more than half the {min(coast, before) / 60:.1f} min orbit around it")
