"""Capture plans: a lunar capture described as data, validated once, solved by name.

A plan (a YAML file, or a :class:`CapturePlan` built in Python) says where the
spacecraft arrives, with which engine, in which dynamics, and which burns capture it::

    name: song2011-150N
    arrival:
      epoch: "2017-02-20 03:41:26 TDB"   # first perilune, TDB
      perilune_altitude_km: 100
      inclination_deg: 90
      impulsive_loi1_mps: 353.272         # or v_inf_kmps: 0.91837
      hemisphere: north                   # optional (north | south)
      mass_kg: 524.895
    engine: {thrust_N: 150, isp_s: 200}
    dynamics: full                        # full | j2 | two-body
    burns:                                # any number >= 1, in order
      - {target_period_h: 12.235, start_min: -10}
      - {target_period_h: 3.525, start_min: -6}
      - {target: circular, start_min: -5, coast_min: 117.848}

Burns
-----
Each burn ignites ``start_min`` minutes from the perilune of the orbit it starts on
(negative: before; ``free``: optimised), and its target is the orbit it must leave
(:mod:`lunarcap.mission.targets`). How a period or apolune is met is the plan's
``formulation``:

* ``orbit`` (default): as asked. ``target_period_h`` or ``target_apolune_altitude_km`` is
  an ellipse with the plan's perilune radius and inclination, and that period or apolune,
  as the osculating orbit at the first perilune after the burn (its epoch free, within a
  fifth of the period of the perilune the plan predicts); the next burn's ignition is
  counted from that perilune. The last burn may instead name both altitudes,
  ``target: {perilune_altitude_km: 100, apolune_altitude_km: 300}``.
* ``song2011``: the paper's Eq. (17). The coast ends at the next nominal perilune (this
  one + the period, Song 2011 Sec. 2.2), where perilune radius, inclination and gamma = 0
  hold; the period is met only through that timing. The packaged ``song2011-*`` plans.

``target: circular`` is the circle at the perilune radius, last burn only; the coast
after it lasts ``coast_min`` (default one period of the circle).

Optional keys per burn: ``steering`` (optimal | inertial | antivelocity) and
``start_bounds_min: [lo, hi]`` (the window of a free ignition; default +-2 Eq. (19)
durations around perilune, within +-120 min and half the orbit before the burn).

Arrival from a state
--------------------
Instead of ``v_inf_kmps`` and the reconstructed geometry, ``arrival`` may give a
Moon-centred state, as a navigation team hands it over::

    arrival:
      epoch: "2017-02-20 03:11:26 UTC"     # UTC or TDB, the scale named in the string
      frame: ICRF                          # ICRF (Moon-centred, ICRF axes) or M-MME2000
      position_km: [x, y, z]
      velocity_kmps: [vx, vy, vz]
      mass_kg: 650

or ``arrival: {opm: approach.opm}`` (a CCSDS OPM in KVN, relative to the plan's
directory; ``mass_kg`` beside it if the OPM has no ``MASS``). The arrival perilune is
derived from the state in the plan's dynamics (:func:`lunarcap.mission.arrival.
perilune_from_state`): its epoch, altitude, inclination and hemisphere then act as a v_inf
arrival's do (``start_min`` counts from that perilune; every target uses its altitude and
inclination). A state that cannot be captured (moving away from the Moon, bound to it,
perilune below the surface, outside the ephemeris) is refused with its cause.

Nominal perilune epochs are the arrival epoch plus the coasts; with them the arrival
epoch and every coast must lie inside the ephemeris. Every error names the field.

A plan may also start from a known state instead of the arrival perilune (a ``start``:
epoch, state, and the coast from it to the first nominal perilune), for a capture
re-planned after a fault (:meth:`CapturePlan.resumed`); its first burn then ignites
``start_min`` after that epoch, within its ``start_bounds_min``. The arrival section still
gives the perilune radius and inclination every target uses.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.arrival import STATE_FRAMES, ArrivalSpec, StateArrival, perilune_from_state
from lunarcap.mission.impulsive import (
    PAPER_DV_LOI1_MPS,
    ImpulsiveBurn,
    impulsive_chain,
    tangential_impulse_mps,
    v_inf_from_loi1,
)
from lunarcap.mission.scenario import PAPER_PLANS, PLAN_DIR, paper_plan_name
from lunarcap.mission.targets import CIRCULAR, ELLIPSE, PERILUNE, Target, check_inclination
from lunarcap.physics import constants as C
from lunarcap.physics.elements import period_from_semi_major_axis, semi_major_axis_from_period
from lunarcap.physics.ephemeris import Ephemeris, default_ephemeris
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.frames import DEFAULT_LUNAR_POLE, LUNAR_POLES

DYNAMICS = ("full", "j2", "two-body")
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

_TOP_KEYS = {"name", "description", "arrival", "engine", "dynamics", "burns", "ephemeris",
             "lunar_pole", "start", "formulation"}
_START_KEYS = {"epoch", "mee", "mass_kg", "first_coast_min"}
_ARRIVAL_KEYS = {"epoch", "perilune_altitude_km", "inclination_deg", "v_inf_kmps",
                 "impulsive_loi1_mps", "hemisphere", "approach_dir", "mass_kg"}
_STATE_ARRIVAL_KEYS = {"epoch", "frame", "position_km", "velocity_kmps", "mass_kg"}
_ENGINE_KEYS = {"thrust_N", "isp_s"}
_BURN_KEYS = {"target", "target_period_h", "target_apolune_altitude_km", "start_min",
              "coast_min", "steering", "start_bounds_min"}


class PlanError(InputError):
    """A capture plan is malformed or physically impossible (the message names the field)."""


def _err(where: str, what: str) -> PlanError:
    return PlanError(f"{where}: {what}")


def _number(where: str, value, unit: str, positive: bool = True) -> float:
    """A finite float (positive unless ``positive`` is False), else PlanError."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _err(where, f"must be a number of {unit}, got {value!r}")
    v = float(value)
    if not math.isfinite(v):
        raise _err(where, f"must be a finite number of {unit}, got {value!r}")
    if positive and v <= 0:
        raise _err(where, f"must be positive ({unit}), got {value!r}")
    return v


def _keys(where: str, d, known: set, required: set) -> None:
    if not isinstance(d, dict):
        raise _err(where, f"must be a mapping of keys to values, got {type(d).__name__}")
    unknown = sorted(set(d) - known)
    if unknown:
        raise _err(f"{where}.{unknown[0]}" if where else unknown[0],
                   f"unknown key (known: {', '.join(sorted(known))})")
    missing = sorted(required - set(d))
    if missing:
        raise _err(f"{where}.{missing[0]}" if where else missing[0], "missing")


@dataclass(frozen=True)
class Engine:
    """Constant-thrust engine: thrust (N) and specific impulse (s)."""

    thrust_N: float
    isp_s: float

    @property
    def exhaust_speed_mps(self) -> float:
        """g0 Isp, m/s."""
        return C.G0_MPS2 * self.isp_s


@dataclass(frozen=True)
class Burn:
    """One capture burn and the orbit its coast must reach.

    Attributes
    ----------
    target : {"perilune", "circular"}
    period_s : float or None
        Period of the ellipse reached (perilune targets), s.
    start_min : float or "free"
        Ignition offset from the nominal perilune of the orbit it starts on, min.
    coast_s : float or None
        Coast after a circular burn, s (None: one period of the circle).
    apolune_altitude_km : float or None
        The apolune altitude the period was derived from, if the plan gave one.
    steering : {"optimal", "inertial", "antivelocity"}
    start_bounds_min : (lo, hi) or None
        Window of a free ignition, min from the nominal perilune.
    perilune_altitude_km : float or None
        The perilune altitude of an explicit final ellipse (``target: {perilune_altitude_km,
        apolune_altitude_km}``), km; None: the plan's.
    nominal_timing : bool
        The paper's formulation (Eq. 17 at the next nominal perilune) for this burn's
        ellipse, whatever the plan's: the studies that optimise the orbits themselves move
        the nominal perilunes (:meth:`CapturePlan.with_burn_count`).
    """

    target: str = PERILUNE
    period_s: float | None = None
    start_min: float | str = "free"
    coast_s: float | None = None
    apolune_altitude_km: float | None = None
    steering: str = "optimal"
    start_bounds_min: tuple | None = None
    perilune_altitude_km: float | None = None
    nominal_timing: bool = False

    @property
    def free_start(self) -> bool:
        """True if the ignition epoch is optimised."""
        return self.start_min == "free"

    def describe(self) -> str:
        """A few words on the target: 'ellipse, 12.235 h' or 'circle'."""
        if self.target == CIRCULAR:
            return "circle"
        if self.perilune_altitude_km is not None:
            return (f"ellipse, {self.perilune_altitude_km:g} x {self.apolune_altitude_km:g} "
                    "km altitude")
        if self.apolune_altitude_km is not None:
            return f"ellipse, apolune altitude {self.apolune_altitude_km:g} km"
        return f"ellipse, {self.period_s / 3600:.6g} h"


@dataclass(frozen=True)
class Start:
    """A known state a capture starts from, instead of the arrival perilune.

    Attributes
    ----------
    epoch_s : float
        Epoch of the state, TDB s past J2000.
    state : tuple of 7 floats
        (p km, f, g, h, k, L rad, m kg) in M-MME2000.
    first_coast_s : float
        From ``epoch_s`` to the nominal perilune where the first burn's target must hold, s
        (it replaces the first burn's period as the first coast).
    """

    epoch_s: float
    state: tuple
    first_coast_s: float

    def __post_init__(self):
        object.__setattr__(self, "state", tuple(float(v) for v in self.state))
        object.__setattr__(self, "epoch_s", _number("start.epoch", self.epoch_s, "s",
                                                    positive=False))
        if len(self.state) != 7:
            raise _err("start.mee", f"a state is 7 numbers (p, f, g, h, k, L, m), got "
                                    f"{len(self.state)}")
        if not all(math.isfinite(v) for v in self.state):
            raise _err("start.mee", f"must be finite numbers, got {self.state!r}")
        if self.state[0] <= 0:
            raise _err("start.mee", f"p must be positive (km), got {self.state[0]!r}")
        if self.state[6] <= 0:
            raise _err("start.mass_kg", f"must be positive (kg), got {self.state[6]!r}")
        _number("start.first_coast_min", self.first_coast_s / 60.0, "min")

    @property
    def mass_kg(self) -> float:
        """Mass of the state, kg."""
        return self.state[6]

    def orbit(self, mu: float = C.MU_MOON) -> dict:
        """The osculating orbit of the state, with its energy and semi-major axis.

        :func:`lunarcap.physics.elements.orbit_summary` plus ``energy_km2ps2`` (specific
        energy, km^2/s^2) and ``a_km`` (semi-major axis, km; negative if open).
        """
        from lunarcap.physics.elements import orbit_summary

        o = orbit_summary(np.array(self.state), mu)
        o["energy_km2ps2"] = o["v_kmps"] ** 2 / 2 - mu / o["r_km"]
        o["a_km"] = -mu / (2 * o["energy_km2ps2"])
        return o


@dataclass(frozen=True)
class CapturePlan:
    """A capture: arrival, engine, dynamics and burns (validated on construction).

    Build one with :func:`load_plan` (a file or a packaged name) or :meth:`from_dict`;
    derive variants with :meth:`with_engine`, :meth:`with_starts`, :meth:`with_dynamics`.
    """

    name: str
    arrival: ArrivalSpec
    engine: Engine
    burns: tuple
    dynamics: str = "full"
    ephemeris: str | None = None
    impulsive_loi1_mps: float | None = None
    description: str = field(default="", compare=False)
    lunar_pole: str = DEFAULT_LUNAR_POLE
    start: Start | None = None
    formulation: str = "orbit"

    # ------------------------------------------------------------------ validation
    def __post_init__(self):
        object.__setattr__(self, "burns", tuple(self.burns))
        _validate_engine(self.engine)
        if self.arrival.state is not None:
            self._derive_state_arrival()
        _validate_arrival(self.arrival)
        if self.formulation not in FORMULATIONS:
            raise _err("formulation", f"must be one of {', '.join(FORMULATIONS)}, got "
                                      f"{self.formulation!r}")
        if self.dynamics not in DYNAMICS:
            raise _err("dynamics", f"must be one of {', '.join(DYNAMICS)}, got {self.dynamics!r}")
        if self.lunar_pole not in LUNAR_POLES:
            raise _err("lunar_pole", f"must be one of {', '.join(LUNAR_POLES)}, "
                                     f"got {self.lunar_pole!r}")
        if not self.burns:
            raise _err("burns", "a plan needs at least one burn")
        rp = self.perilune_radius_km
        period_before = math.inf
        if self.start is not None:
            self._check_start()
        for i, b in enumerate(self.burns):
            _validate_burn(f"burns[{i}]", b, rp, period_before, last=i == len(self.burns) - 1)
            if b.perilune_altitude_km is not None:
                self._check_explicit_ellipse(i)
            period_before = b.period_s if b.target == PERILUNE else _circle_period_s(rp)
        if self.start is None and (self.impulsive_loi1_mps is not None
                                   or self.arrival.v_inf_kmps is None):
            # v_inf from an impulsive first burn (default: the paper's 353.272 m/s)
            dv = PAPER_DV_LOI1_MPS if self.impulsive_loi1_mps is None else \
                _number("arrival.impulsive_loi1_mps", self.impulsive_loi1_mps, "m/s")
            first = self.burns[0]
            period = first.period_s if first.target == PERILUNE else _circle_period_s(rp)
            try:
                vinf = v_inf_from_loi1(dv, rp, period)
            except InputError as exc:
                raise _err("arrival.impulsive_loi1_mps", str(exc)) from None
            object.__setattr__(self, "arrival", replace(self.arrival, v_inf_kmps=vinf))
        self._check_ephemeris()
        if self.start is None:
            self._check_arrival_geometry()
        self._check_engine_fits()

    def _derive_state_arrival(self) -> None:
        """Replace the perilune numbers of a state arrival by those of its propagation."""
        if self.dynamics not in DYNAMICS or self.lunar_pole not in LUNAR_POLES:
            return  # refused below with the field named
        a = self.arrival
        try:
            peri = perilune_from_state(a.state, float(a.mass_kg), self.dynamics,
                                       self.ephemeris_model(), self.lunar_pole)
        except InputError as exc:
            where = "arrival.opm" if a.state.opm else "arrival"
            raise _err(where, str(exc)) from None
        object.__setattr__(self, "arrival", replace(
            a, epoch=peri["epoch"], perilune_altitude_km=peri["altitude_km"],
            inclination_deg=peri["inclination_deg"], hemisphere=peri["hemisphere"],
            v_inf_kmps=peri["v_inf_kmps"], perilune_mee=peri["mee"],
            approach_dir=peri["approach_dir"]))

    def _check_explicit_ellipse(self, i: int) -> None:
        """An ellipse given by both altitudes: the last burn, in the orbit formulation."""
        if i != self.n_burns - 1:
            raise _err(f"burns[{i}].target", "an ellipse given by both altitudes is a final "
                                             "orbit: only the last burn may have it")
        if self.formulation == "song2011":
            raise _err(f"burns[{i}].target", "the song2011 formulation (Eq. 17) targets a "
                                             "perilune and a timing, not an apolune: use "
                                             "formulation: orbit for an ellipse by altitudes")

    def _check_start(self) -> None:
        st = self.start
        if not isinstance(st, Start):
            raise _err("start", f"must be a Start, got {type(st).__name__}")
        b0 = self.burns[0]
        if b0.free_start and b0.start_bounds_min is None:
            raise _err("burns[0].start_bounds_min",
                       "a plan that starts from a given state needs a window [lo, hi] (min "
                       "from its epoch) for a free first ignition")
        latest = b0.start_bounds_min[1] if b0.free_start else b0.start_min
        if latest * 60.0 >= st.first_coast_s:
            raise _err("start.first_coast_min",
                       f"the first coast ({st.first_coast_s / 60:.1f} min) must end after the "
                       f"latest ignition ({latest:g} min)")

    def _check_arrival_geometry(self) -> None:
        """The arrival hyperbola can be built with this inclination (else PlanError)."""
        a = self.arrival
        s = a.approach_direction(self.ephemeris_model())
        lat = math.degrees(math.asin(max(-1.0, min(1.0, float(s[2])))))
        inc = a.inclination_deg
        if min(inc, 180.0 - inc) < abs(lat) - 1e-9:
            raise _err("arrival.inclination_deg",
                       f"{inc:g} deg cannot be reached from this arrival: its approach "
                       f"asymptote lies {abs(lat):.2f} deg from the lunar equator (M-MME2000) "
                       f"on {a.epoch}, and an orbit containing it is inclined at least that "
                       f"much (and at most 180 deg minus it); ask for {abs(lat):.2f} to "
                       f"{180 - abs(lat):.2f} deg, or give approach_dir")

    def _check_ephemeris(self) -> None:
        eph = self.ephemeris_model()
        t = self.nominal_perilunes_s
        a, b = eph.span_s
        if t[0] - EPHEMERIS_MARGIN_S < a or t[-1] + EPHEMERIS_MARGIN_S > b:
            raise _err("arrival.epoch",
                       f"the capture from {calendar_from_seconds(t[0], 0)} to "
                       f"{calendar_from_seconds(t[-1], 0)} (with 6 h margins) is outside the "
                       f"ephemeris {eph.name}, which covers {calendar_from_seconds(a, 0)} to "
                       f"{calendar_from_seconds(b, 0)}")

    def _check_engine_fits(self) -> None:
        for i, ib in enumerate(self.impulsive()):
            t19 = ib.eq19_duration_min * 60.0
            coast = self.nominal_perilunes_s[i + 1] - self.nominal_perilunes_s[i]
            before = self.nominal_perilunes_s[i] - self.nominal_perilunes_s[i - 1] if i else coast
            if t19 < MIN_BURN_S:
                raise _err("engine.thrust_N",
                           f"{self.engine.thrust_N:g} N is too strong: burn {i + 1} "
                           f"({ib.delta_v_mps:.1f} m/s) would last {t19:.2g} s (Eq. 19), "
                           f"below the {MIN_BURN_S:g} s the transcription resolves; for an "
                           f"impulse, see the impulsive chain (lunarcap impulsive)")
            if t19 > MAX_BURN_FRACTION * min(coast, before):
                raise _err("engine.thrust_N",
                           f"{self.engine.thrust_N:g} N is too weak: burn {i + 1} "
                           f"({ib.delta_v_mps:.1f} m/s) would last {t19 / 60:.1f} min "
                           f"(Eq. 19), more than half the {min(coast, before) / 60:.1f} min "
                           f"orbit around it")

    # ------------------------------------------------------------------ derived numbers
    @property
    def perilune_radius_km(self) -> float:
        """Radius of every perilune and of the final circle, km."""
        return self.arrival.perilune_radius_km

    @property
    def n_burns(self) -> int:
        """Number of burns."""
        return len(self.burns)

    @property
    def targets(self) -> tuple:
        """The :class:`~lunarcap.mission.targets.Target` of each burn.

        A period or apolune target is an ``ellipse`` (the orbit as asked, at its first
        perilune) unless the plan's formulation is ``song2011`` or the burn keeps the
        nominal timing, when it is the paper's ``perilune`` target (Eq. 17).
        """
        return tuple(self._target(b) for b in self.burns)

    def _target(self, b: Burn) -> Target:
        rp, inc = self.perilune_radius_km, self.arrival.inclination_deg
        if b.target == CIRCULAR:
            return Target(CIRCULAR, rp, inc)
        if b.perilune_altitude_km is not None:
            rp = C.R_MOON + b.perilune_altitude_km
        if self.formulation == "song2011" or b.nominal_timing:
            return Target(PERILUNE, rp, inc)
        if b.apolune_altitude_km is not None:
            return Target(ELLIPSE, rp, inc, C.R_MOON + b.apolune_altitude_km)
        a = float(semi_major_axis_from_period(b.period_s, C.MU_MOON))
        return Target(ELLIPSE, rp, inc, 2 * a - rp)

    def coast_s(self, i: int) -> float:
        """Time from the nominal perilune before burn ``i`` (0-based) to the next, s.

        For the first burn of a plan with a :class:`Start`, from the start's epoch.
        """
        if i == 0 and self.start is not None:
            return self.start.first_coast_s
        b = self.burns[i]
        if b.target == PERILUNE:
            return b.period_s
        return b.coast_s if b.coast_s is not None else _circle_period_s(self.perilune_radius_km)

    @property
    def nominal_perilunes_s(self) -> tuple:
        """Nominal perilune epochs (TDB s past J2000): arrival, then after each coast.

        With a :class:`Start`, the first is the start's epoch (not a perilune).
        """
        t = [seconds_from_calendar(self.arrival.epoch) if self.start is None
             else self.start.epoch_s]
        for i in range(self.n_burns):
            t.append(t[-1] + self.coast_s(i))
        return tuple(t)

    def impulsive(self, eq19_masses_kg=None) -> list[ImpulsiveBurn]:
        """The two-body impulsive chain of this plan (tangential perilune impulses)."""
        periods = [b.period_s if b.target == PERILUNE else None for b in self.burns]
        first = None
        if self.start is not None:  # the first burn from the start's radius and speed
            o = self.start.orbit()
            a = None if self.burns[0].target == CIRCULAR else \
                float(semi_major_axis_from_period(periods[0], C.MU_MOON))
            if a is None:
                a = self.perilune_radius_km
            first = tangential_impulse_mps(o["r_km"], o["v_kmps"], a)
        return impulsive_chain(self.perilune_radius_km, self.arrival.v_inf_kmps, periods,
                               self.engine.thrust_N, self.engine.isp_s, self.initial_mass_kg,
                               eq19_masses_kg=eq19_masses_kg, first_delta_v_mps=first)

    @property
    def initial_mass_kg(self) -> float:
        """Mass before the first burn: the arrival's, or the start state's, kg."""
        return self.arrival.mass_kg if self.start is None else self.start.mass_kg

    # ------------------------------------------------------------------ variants
    def with_engine(self, thrust_N: float, isp_s: float, name: str | None = None
                    ) -> "CapturePlan":
        """The same plan with another engine."""
        return replace(self, engine=Engine(float(thrust_N), float(isp_s)),
                       name=name or f"{self.name} ({thrust_N:g} N / {isp_s:g} s)")

    def with_dynamics(self, dynamics: str) -> "CapturePlan":
        """The same plan in other dynamics."""
        return replace(self, dynamics=dynamics)

    def with_start(self, i: int, start_min) -> "CapturePlan":
        """The same plan with burn ``i`` (0-based) igniting at ``start_min`` (or 'free')."""
        self._index(i)
        burns = list(self.burns)
        burns[i] = replace(burns[i], start_min=_start_value(f"burns[{i}].start_min", start_min))
        return replace(self, burns=tuple(burns))

    def with_starts(self, starts) -> "CapturePlan":
        """The same plan with every burn's ignition offset replaced (one per burn)."""
        starts = list(starts)
        if len(starts) != self.n_burns:
            raise _err("burns", f"{self.n_burns} ignition offsets expected (one per burn), "
                                f"got {len(starts)}")
        plan = self
        for i, s in enumerate(starts):
            plan = plan.with_start(i, s)
        return plan

    def with_steering(self, i: int, steering: str) -> "CapturePlan":
        """The same plan with burn ``i`` (0-based) flown with another steering law."""
        self._index(i)
        burns = list(self.burns)
        burns[i] = replace(burns[i], steering=steering)
        return replace(self, burns=tuple(burns))

    def with_coasts(self, coasts_s) -> "CapturePlan":
        """The same plan with the coasts after its burns replaced (one per burn, s; None keeps one).

        The coast after an ellipse target is its period (the target's period changes with
        it); after the first burn of a plan with a :class:`Start`, the start's first coast;
        after a circle, its ``coast_s``. An all-burns NLP with free coasts
        (:func:`lunarcap.optim.joint.solve_joint`) reports its optimum as such a plan.
        """
        coasts = list(coasts_s)
        if len(coasts) != self.n_burns:
            raise _err("burns", f"{self.n_burns} coasts expected (one per burn), got "
                                f"{len(coasts)}")
        burns, start = list(self.burns), self.start
        for i, c in enumerate(coasts):
            if c is None:
                continue
            c = _number(f"burns[{i}].coast", float(c) / 60.0, "min") * 60.0
            if i == 0 and start is not None:
                start = replace(start, first_coast_s=c)
            elif burns[i].target == PERILUNE:
                burns[i] = replace(burns[i], period_s=c, apolune_altitude_km=None,
                                   perilune_altitude_km=None, nominal_timing=True)
            else:
                burns[i] = replace(burns[i], coast_s=c)
        return replace(self, burns=tuple(burns), start=start)

    def with_burn_count(self, periods_s, name: str | None = None) -> "CapturePlan":
        """The plan's arrival, engine and last burn, reached through ellipses of these periods.

        ``len(periods_s) + 1`` burns: one into each ellipse (periods in s, longest first),
        then the plan's last burn (its target and coast); every ignition free.
        """
        last = replace(self.burns[-1], start_min="free", start_bounds_min=None)
        burns = tuple(Burn(PERILUNE, period_s=float(p), start_min="free", nominal_timing=True)
                      for p in periods_s)
        n = len(burns) + 1
        return replace(self, burns=burns + (last,), impulsive_loi1_mps=None,
                       name=name or f"{self.name} in {n} burn{'s' * (n > 1)}")

    def resumed(self, i: int, epoch_s: float, state, first_coast_s: float | None = None,
                window_min: tuple = (0.0, 30.0)) -> "CapturePlan":
        """The capture from burn ``i`` (0-based) on, starting from ``state`` at ``epoch_s``.

        Burns i, i+1, ... of this plan; the first ignites within ``window_min`` (min after
        ``epoch_s``, free), the others as in this plan. The first coast ends at
        ``first_coast_s`` after ``epoch_s`` (default: this plan's nominal perilune after
        burn i). The re-plan after a fault (:mod:`lunarcap.runs.missed`) and the impulsive
        limit of a burn from a given state are such plans.
        """
        self._index(i)
        t = self.nominal_perilunes_s
        coast = t[i + 1] - float(epoch_s) if first_coast_s is None else float(first_coast_s)
        first = replace(self.burns[i], start_min="free",
                        start_bounds_min=tuple(float(w) for w in window_min))
        return replace(self, burns=(first,) + self.burns[i + 1:], impulsive_loi1_mps=None,
                       start=Start(float(epoch_s), tuple(np.asarray(state, float)), coast))

    def truncated(self, n: int) -> "CapturePlan":
        """The plan's first ``n`` burns (a prefix: what burn n depends on)."""
        if not 1 <= n <= self.n_burns:
            raise _err("burns", f"a prefix of 1 to {self.n_burns} burns, got {n}")
        return replace(self, burns=self.burns[:n])

    def with_lunar_pole(self, lunar_pole: str) -> "CapturePlan":
        """The plan with another lunar pole fixing M-MME2000 (see physics.frames)."""
        return replace(self, lunar_pole=lunar_pole)

    def ephemeris_model(self) -> Ephemeris:
        """The plan's ephemeris in its M-MME2000 (its ``ephemeris`` and ``lunar_pole``)."""
        return plan_ephemeris(self.ephemeris, self.lunar_pole)

    def key(self, n: int | None = None) -> "CapturePlan":
        """What a solution of burn ``n`` (1-based; default the last) depends on.

        The plan truncated to its first ``n`` burns, with the name and description blanked,
        so equal physics share one cache entry whatever the plans are called.
        """
        plan = self.truncated(self.n_burns if n is None else n)
        return replace(plan, name="", description="")

    def _index(self, i: int) -> None:
        if not isinstance(i, (int, np.integer)) or not 0 <= i < self.n_burns:
            raise _err("burns", f"this plan has burns 1 to {self.n_burns}; "
                                f"burn {i + 1 if isinstance(i, int) else i} does not exist")

    # ------------------------------------------------------------------ (de)serialisation
    @classmethod
    def from_dict(cls, d: dict, base_dir: str | os.PathLike | None = None,
                  default_name: str = "") -> "CapturePlan":
        """A plan from the mapping of a YAML file (every key checked; PlanError names it).

        ``base_dir`` resolves a relative ``ephemeris`` path (the plan file's directory).
        """
        _keys("", d, _TOP_KEYS, {"arrival", "engine", "burns"})
        name = d.get("name", default_name)
        if not isinstance(name, str) or not name.strip():
            raise _err("name", f"must be a non-empty text, got {name!r}")
        a = d["arrival"]
        arrival = _state_arrival_from_dict(a, base_dir)
        if arrival is None:
            arrival = _perilune_arrival_from_dict(a)
        e = d["engine"]
        _keys("engine", e, _ENGINE_KEYS, _ENGINE_KEYS)
        engine = Engine(_number("engine.thrust_N", e["thrust_N"], "N"),
                        _number("engine.isp_s", e["isp_s"], "s"))
        burns_in = d["burns"]
        if not isinstance(burns_in, list) or not burns_in:
            raise _err("burns", "must be a list of at least one burn")
        burns = tuple(_burn_from_dict(f"burns[{i}]", b, arrival.perilune_altitude_km)
                      for i, b in enumerate(burns_in))
        eph = d.get("ephemeris")
        if eph is not None:
            if not isinstance(eph, str):
                raise _err("ephemeris", f"must be the path of an SPK file, got {eph!r}")
            p = Path(eph).expanduser()
            if not p.is_absolute() and base_dir is not None:
                p = Path(base_dir) / p
            eph = str(p.resolve())
        desc = d.get("description", "")
        if not isinstance(desc, str):
            raise _err("description", f"must be a text, got {desc!r}")
        start = d.get("start")
        if start is not None:
            start = _start_from_dict(start)
        return cls(name=name.strip(), arrival=arrival, engine=engine, burns=burns,
                   dynamics=d.get("dynamics", "full"), ephemeris=eph,
                   lunar_pole=d.get("lunar_pole", DEFAULT_LUNAR_POLE),
                   impulsive_loi1_mps=(_number("arrival.impulsive_loi1_mps",
                                               a["impulsive_loi1_mps"], "m/s")
                                       if "impulsive_loi1_mps" in a else None),
                   description=desc.strip(), start=start,
                   formulation=d.get("formulation", "orbit"))

    def to_dict(self) -> dict:
        """The plan as a mapping with the YAML file's keys (round-trips :meth:`from_dict`)."""
        a = self.arrival
        arrival = {"epoch": a.epoch, "perilune_altitude_km": a.perilune_altitude_km,
                   "inclination_deg": a.inclination_deg}
        if self.impulsive_loi1_mps is not None:
            arrival["impulsive_loi1_mps"] = self.impulsive_loi1_mps
        else:
            arrival["v_inf_kmps"] = a.v_inf_kmps
        arrival["hemisphere"] = a.hemisphere
        if a.approach_dir is not None:
            arrival["approach_dir"] = list(a.approach_dir)
        arrival["mass_kg"] = a.mass_kg
        if a.state is not None:   # as given (the perilune is derived again on loading)
            st = a.state
            arrival = ({"opm": st.opm} if st.opm else
                       {"epoch": st.epoch, "frame": st.frame,
                        "position_km": list(st.position_km),
                        "velocity_kmps": list(st.velocity_kmps)}) | {"mass_kg": a.mass_kg}
        burns = []
        for b in self.burns:
            row = {}
            if b.target == CIRCULAR:
                row["target"] = CIRCULAR
                if b.coast_s is not None:
                    row["coast_min"] = b.coast_s / 60.0
            elif b.perilune_altitude_km is not None:
                row["target"] = {"perilune_altitude_km": b.perilune_altitude_km,
                                 "apolune_altitude_km": b.apolune_altitude_km}
            elif b.apolune_altitude_km is not None:
                row["target_apolune_altitude_km"] = b.apolune_altitude_km
            else:
                row["target_period_h"] = b.period_s / 3600.0
            row["start_min"] = b.start_min
            if b.steering != "optimal":
                row["steering"] = b.steering
            if b.start_bounds_min is not None:
                row["start_bounds_min"] = list(b.start_bounds_min)
            burns.append(row)
        out = {"name": self.name}
        if self.description:
            out["description"] = self.description
        out.update(arrival=arrival, engine={"thrust_N": self.engine.thrust_N,
                                            "isp_s": self.engine.isp_s},
                   dynamics=self.dynamics, burns=burns)
        if self.ephemeris is not None:
            out["ephemeris"] = self.ephemeris
        if self.lunar_pole != DEFAULT_LUNAR_POLE:
            out["lunar_pole"] = self.lunar_pole
        if self.formulation != "orbit":
            out["formulation"] = self.formulation
        if self.start is not None:
            out["start"] = {"epoch": calendar_from_seconds(self.start.epoch_s, 6),
                            "mee": list(self.start.state[:6]), "mass_kg": self.start.mass_kg,
                            "first_coast_min": self.start.first_coast_s / 60.0}
        return out

    def to_yaml(self) -> str:
        """YAML text of :meth:`to_dict`."""
        import yaml

        return yaml.safe_dump(self.to_dict(), sort_keys=False, default_flow_style=None)


# ---------------------------------------------------------------------- helpers
def _circle_period_s(r_km: float, mu: float = C.MU_MOON) -> float:
    return float(period_from_semi_major_axis(r_km, mu))


def _period_from_apolune_s(rp_km: float, ra_km: float, mu: float = C.MU_MOON) -> float:
    return float(period_from_semi_major_axis(0.5 * (rp_km + ra_km), mu))


def _start_value(where: str, value):
    if value == "free":
        return "free"
    v = _number(where, value, "min", positive=False)
    if abs(v) > MAX_START_MIN:
        raise _err(where, f"{v:g} min is more than {MAX_START_MIN:g} min from perilune")
    return v


def _ellipse_from_dict(where: str, t) -> tuple:
    """(perilune altitude, apolune altitude, period) of ``target: {perilune_altitude_km, ...}``."""
    keys = {"perilune_altitude_km", "apolune_altitude_km"}
    _keys(where, t, keys, keys)
    rp = _number(f"{where}.perilune_altitude_km", t["perilune_altitude_km"], "km")
    ra = _number(f"{where}.apolune_altitude_km", t["apolune_altitude_km"], "km")
    if not ra > rp:
        raise _err(f"{where}.apolune_altitude_km", f"{ra:g} km is not above the perilune "
                                                   f"altitude {rp:g} km")
    return rp, ra, _period_from_apolune_s(C.R_MOON + rp, C.R_MOON + ra)


def _burn_from_dict(where: str, b, altitude_km: float) -> Burn:
    _keys(where, b, _BURN_KEYS, {"start_min"})
    given = [k for k in ("target_period_h", "target_apolune_altitude_km") if k in b]
    if isinstance(b.get("target"), dict):
        if given or "coast_min" in b:
            raise _err(f"{where}.target", "an ellipse given by both altitudes takes no "
                                          "period, apolune or coast_min of its own")
        rp_alt, ra_alt, period = _ellipse_from_dict(f"{where}.target", b["target"])
        return replace(_burn_from_dict(where, {k: v for k, v in b.items() if k != "target"}
                                       | {"target_period_h": period / 3600.0}, altitude_km),
                       period_s=period, apolune_altitude_km=ra_alt,
                       perilune_altitude_km=rp_alt)
    kind = b.get("target", PERILUNE if given else None)
    if kind not in (PERILUNE, CIRCULAR):
        raise _err(f"{where}.target", f"must be 'circular', an ellipse "
                                      f"{{perilune_altitude_km, apolune_altitude_km}}, or "
                                      f"'perilune' (or give target_period_h / "
                                      f"target_apolune_altitude_km), got {kind!r}")
    period = apo = coast = None
    if kind == CIRCULAR:
        if given:
            raise _err(f"{where}.{given[0]}", "a circular target takes no period or apolune")
        if "coast_min" in b:
            coast = _number(f"{where}.coast_min", b["coast_min"], "min") * 60.0
    else:
        if len(given) != 1:
            raise _err(f"{where}.target_period_h", "give exactly one of target_period_h and "
                                                   "target_apolune_altitude_km")
        if "coast_min" in b:
            raise _err(f"{where}.coast_min", "only a circular target takes coast_min (an "
                                             "ellipse's coast lasts its period)")
        if given[0] == "target_period_h":
            period = _number(f"{where}.target_period_h", b["target_period_h"], "h") * 3600.0
        else:
            apo = _number(f"{where}.target_apolune_altitude_km",
                          b["target_apolune_altitude_km"], "km")
            if apo <= altitude_km:
                raise _err(f"{where}.target_apolune_altitude_km",
                           f"{apo:g} km is not above the perilune altitude {altitude_km:g} km")
            period = _period_from_apolune_s(C.R_MOON + altitude_km, C.R_MOON + apo)
    steering = b.get("steering", "optimal")
    bounds = b.get("start_bounds_min")
    if bounds is not None:
        if not isinstance(bounds, (list, tuple)) or len(bounds) != 2:
            raise _err(f"{where}.start_bounds_min", f"must be [lo, hi] in minutes, got "
                                                    f"{bounds!r}")
        bounds = tuple(_start_value(f"{where}.start_bounds_min[{j}]", x)
                       for j, x in enumerate(bounds))
        if "free" in bounds or not bounds[0] < bounds[1]:
            raise _err(f"{where}.start_bounds_min", f"must be two numbers lo < hi, got "
                                                    f"{list(bounds)!r}")
    return Burn(target=kind, period_s=period,
                start_min=_start_value(f"{where}.start_min", b["start_min"]),
                coast_s=coast, apolune_altitude_km=apo, steering=steering,
                start_bounds_min=bounds)


def _perilune_arrival_from_dict(a) -> ArrivalSpec:
    """The ``arrival`` of a plan given by its perilune (v_inf and the reconstructed geometry)."""
    _keys("arrival", a, _ARRIVAL_KEYS,
          {"epoch", "perilune_altitude_km", "inclination_deg", "mass_kg"})
    if ("v_inf_kmps" in a) == ("impulsive_loi1_mps" in a):
        raise _err("arrival.v_inf_kmps", "give exactly one of v_inf_kmps and "
                                         "impulsive_loi1_mps")
    epoch = a["epoch"]
    if not isinstance(epoch, str):
        raise _err("arrival.epoch", f"must be a text like '2017-02-20 03:41:26 TDB', "
                                    f"got {epoch!r}")
    try:
        seconds_from_calendar(epoch)
    except InputError as exc:
        raise _err("arrival.epoch", str(exc)) from None
    approach = a.get("approach_dir")
    if approach is not None:
        if not isinstance(approach, (list, tuple)) or len(approach) != 3:
            raise _err("arrival.approach_dir", f"must be a list of three numbers "
                                               f"(M-MME2000), got {approach!r}")
        approach = tuple(_number(f"arrival.approach_dir[{j}]", x, "", positive=False)
                         for j, x in enumerate(approach))
    return ArrivalSpec(
        epoch=epoch,
        perilune_altitude_km=_number("arrival.perilune_altitude_km",
                                     a["perilune_altitude_km"], "km", positive=False),
        inclination_deg=_number("arrival.inclination_deg", a["inclination_deg"], "deg",
                                positive=False),
        mass_kg=_number("arrival.mass_kg", a["mass_kg"], "kg"),
        v_inf_kmps=(_number("arrival.v_inf_kmps", a["v_inf_kmps"], "km/s")
                    if "v_inf_kmps" in a else None),
        hemisphere=a.get("hemisphere", "north"),
        approach_dir=approach)


def _state_arrival_from_dict(a, base_dir) -> ArrivalSpec | None:
    """The ``arrival`` of a plan given as a state or an OPM file (None: a perilune arrival).

    The perilune numbers are placeholders until the plan derives them in its dynamics
    (:meth:`CapturePlan._derive_state_arrival`).
    """
    if not isinstance(a, dict) or not ({"opm", "position_km", "velocity_kmps"} & set(a)):
        return None
    mass = a.get("mass_kg")
    if "opm" in a:
        _keys("arrival", a, {"opm", "mass_kg"}, {"opm"})
        from lunarcap.exchange.ccsds import read_opm

        path = a["opm"]
        if not isinstance(path, str):
            raise _err("arrival.opm", f"must be the path of a CCSDS OPM file, got {path!r}")
        p = Path(path).expanduser()
        if not p.is_absolute() and base_dir is not None:
            p = Path(base_dir) / p
        try:
            sv = read_opm(p)
        except InputError as exc:
            raise _err("arrival.opm", str(exc)) from None
        if mass is None:
            if sv.mass_kg is None:
                raise _err("arrival.mass_kg", f"missing: the OPM {p.name} gives no MASS")
            mass = sv.mass_kg
        state = StateArrival(sv.epoch_text, "ICRF", sv.r_km, sv.v_kmps, opm=str(path))
    else:
        unknown = sorted(set(a) - _STATE_ARRIVAL_KEYS)
        if unknown:
            raise _err(f"arrival.{unknown[0]}",
                       f"a state arrival takes {', '.join(sorted(_STATE_ARRIVAL_KEYS))}; "
                       f"{unknown[0]} belongs to an arrival given by its perilune")
        _keys("arrival", a, _STATE_ARRIVAL_KEYS, _STATE_ARRIVAL_KEYS)
        if not isinstance(a["epoch"], str):
            raise _err("arrival.epoch", f"must be a text like '2017-02-20 03:11:26 UTC', "
                                        f"got {a['epoch']!r}")
        try:
            seconds_from_calendar(a["epoch"])
        except InputError as exc:
            raise _err("arrival.epoch", str(exc)) from None
        if a["frame"] not in STATE_FRAMES:
            raise _err("arrival.frame", f"must be one of {', '.join(STATE_FRAMES)}, got "
                                        f"{a['frame']!r}")
        vecs = []
        for key, unit in (("position_km", "km"), ("velocity_kmps", "km/s")):
            val = a[key]
            if not isinstance(val, (list, tuple)) or len(val) != 3:
                raise _err(f"arrival.{key}", f"must be a list of three numbers ({unit}), got "
                                             f"{val!r}")
            vecs.append(tuple(_number(f"arrival.{key}[{j}]", x, unit, positive=False)
                              for j, x in enumerate(val)))
        state = StateArrival(a["epoch"], a["frame"], vecs[0], vecs[1])
    mass = _number("arrival.mass_kg", mass, "kg")
    # placeholders (a valid perilune), replaced by the derivation in the plan's dynamics
    return ArrivalSpec(epoch=state.epoch, perilune_altitude_km=100.0, inclination_deg=90.0,
                       mass_kg=mass, v_inf_kmps=1.0, state=state)


def _start_from_dict(d) -> Start:
    _keys("start", d, _START_KEYS, _START_KEYS)
    if not isinstance(d["epoch"], str):
        raise _err("start.epoch", f"must be a text like '2017-02-20 03:41:26 TDB', got "
                                  f"{d['epoch']!r}")
    try:
        epoch = seconds_from_calendar(d["epoch"])
    except InputError as exc:
        raise _err("start.epoch", str(exc)) from None
    mee = d["mee"]
    if not isinstance(mee, (list, tuple)) or len(mee) != 6:
        raise _err("start.mee", f"must be six numbers (p km, f, g, h, k, L rad), got {mee!r}")
    mee = [_number(f"start.mee[{j}]", x, "", positive=False) for j, x in enumerate(mee)]
    mass = _number("start.mass_kg", d["mass_kg"], "kg")
    coast = _number("start.first_coast_min", d["first_coast_min"], "min") * 60.0
    return Start(epoch, tuple(mee) + (mass,), coast)


def _validate_engine(e: Engine) -> None:
    _number("engine.thrust_N", e.thrust_N, "N")
    _number("engine.isp_s", e.isp_s, "s")


def _validate_arrival(a: ArrivalSpec) -> None:
    alt = _number("arrival.perilune_altitude_km", a.perilune_altitude_km, "km", positive=False)
    if alt <= 0:
        raise _err("arrival.perilune_altitude_km",
                   f"{alt:g} km puts the perilune at or below the lunar surface "
                   f"(radius {C.R_MOON} km): the altitude must be positive")
    inc = _number("arrival.inclination_deg", a.inclination_deg, "deg", positive=False)
    try:
        check_inclination("arrival.inclination_deg", inc)
    except InputError as exc:
        raise PlanError(str(exc)) from None
    _number("arrival.mass_kg", a.mass_kg, "kg")
    if a.v_inf_kmps is not None:
        _number("arrival.v_inf_kmps", a.v_inf_kmps, "km/s")
    if a.hemisphere not in HEMISPHERES:
        raise _err("arrival.hemisphere", f"must be north or south, got {a.hemisphere!r}")
    if a.approach_dir is not None and not np.linalg.norm(a.approach_dir) > 0:
        raise _err("arrival.approach_dir", "must be a non-zero vector")


def _validate_burn(where: str, b: Burn, rp_km: float, period_before_s: float,
                   last: bool) -> None:
    if b.target not in (PERILUNE, CIRCULAR):
        raise _err(f"{where}.target", f"must be 'perilune' or 'circular', got {b.target!r}")
    if b.steering not in STEERING:
        raise _err(f"{where}.steering", f"must be one of {', '.join(STEERING)}, "
                                        f"got {b.steering!r}")
    _start_value(f"{where}.start_min", b.start_min)
    circle = _circle_period_s(rp_km)
    if b.target == CIRCULAR:
        if not last:
            raise _err(f"{where}.target", "a circular target must be the last burn (a burn "
                                          "after it has nothing to lower)")
        if b.coast_s is not None:
            _number(f"{where}.coast_min", b.coast_s / 60.0, "min")
        period_after = circle
    else:
        key = ("target_apolune_altitude_km" if b.apolune_altitude_km is not None
               else "target_period_h")
        p = _number(f"{where}.{key}", b.period_s, "s")
        if p <= circle:
            raise _err(f"{where}.{key}",
                       f"a period of {p / 3600:.4g} h is not longer than the circular orbit's "
                       f"at the perilune radius {rp_km:g} km ({circle / 3600:.4g} h): no "
                       f"ellipse has that perilune and period")
        period_after = p
    if not period_after < period_before_s:
        raise _err(f"{where}.target_period_h" if b.target == PERILUNE else f"{where}.target",
                   f"the orbit reached ({period_after / 3600:.4g} h) is not shorter than the "
                   f"orbit before ({period_before_s / 3600:.4g} h): each capture burn must "
                   f"lower the orbit")
    if not b.free_start and math.isfinite(period_before_s) and \
            abs(b.start_min) * 60.0 > 0.4 * period_before_s:
        raise _err(f"{where}.start_min",
                   f"{b.start_min:g} min from perilune is more than 0.4 of the "
                   f"{period_before_s / 60:.1f} min orbit it starts on")


@lru_cache(maxsize=8)
def plan_ephemeris(path: str | None, lunar_pole: str = DEFAULT_LUNAR_POLE) -> Ephemeris:
    """The ephemeris of a plan's ``ephemeris`` field (None: DE405) for a lunar pole, loaded once."""
    return default_ephemeris(lunar_pole) if path is None else Ephemeris(path, lunar_pole)


# ---------------------------------------------------------------------- files and names
def available_plans() -> list[str]:
    """Names of the packaged plans (``lunarcap plan NAME``)."""
    return sorted(p.stem for p in PLAN_DIR.glob("*.yaml"))


def load_plan(source: str | os.PathLike) -> CapturePlan:
    """A plan from a YAML file or a packaged name (see :func:`available_plans`).

    Raises
    ------
    PlanError
        Unreadable or malformed file (the message names the file and the field).
    """
    import yaml

    path = Path(source).expanduser()
    if not path.is_file():
        packaged = PLAN_DIR / f"{source}.yaml"
        if isinstance(source, str) and os.sep not in source and packaged.is_file():
            path = packaged
        else:
            raise PlanError(f"plan {source}: no such file, and not a packaged plan "
                            f"({', '.join(available_plans())})")
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise PlanError(f"plan {path}: cannot read it: {exc}") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        at = f" (line {mark.line + 1}, column {mark.column + 1})" if mark else ""
        raise PlanError(f"plan {path}: not valid YAML{at}: "
                        f"{getattr(exc, 'problem', None) or exc}") from None
    try:
        return CapturePlan.from_dict(data if data is not None else {}, base_dir=path.parent,
                                     default_name=path.stem)
    except InputError as exc:
        raise PlanError(f"plan {path.name}: {exc}") from None


def paper_plan(thrust_N: float = 150.0, isp_s: float = 200.0, starts=None,
               dynamics: str = "full") -> CapturePlan:
    """Song 2011's capture with any engine.

    For the paper's engines (150 N / 200 s, 300 N / 250 s, 450 N / 300 s) the packaged
    plan with its best ignition offsets (Table B1); for any other engine the 150 N plan
    with that engine and free ignition (``starts`` overrides either).
    """
    name = paper_plan_name(thrust_N, isp_s)
    if name is not None:
        plan = load_plan(name)
    else:
        base = load_plan(PAPER_PLANS[0])
        plan = base.with_engine(thrust_N, isp_s, name=f"song2011-{thrust_N:g}N-{isp_s:g}s")
        plan = plan.with_starts(["free"] * plan.n_burns)
    if starts is not None:
        plan = plan.with_starts(starts)
    return plan if dynamics == plan.dynamics else plan.with_dynamics(dynamics)
