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
    dynamics: full                        # full | j2 | two-body | a mapping (below)
    burns:                                # any number >= 1, in order
      - {target_period_h: 12.235, start_min: -10}
      - {target_period_h: 3.525, start_min: -6}
      - {target: circular, start_min: -5, coast_min: 117.848}

Dynamics
--------
The paper's words: ``full`` (lunar J2, Earth and Sun point masses), ``j2``, ``two-body``,
with J2 about the z axis of the plan's frame (M-MME2000 of ``lunar_pole``, by default the
Moon's pole at J2000): the ``song2011-*`` plans. Or the forces named
(:mod:`lunarcap.physics.forces`)::

    dynamics: {gravity: LP165P, degree: 20, third_bodies: [earth, sun]}
    dynamics: {gravity: j2, pole: of-date, third_bodies: [earth, sun]}

``gravity`` is ``point``, ``j2`` or a field (packaged ``LP165P``, or a ``.cof`` / PDS SHADR
file) of ``degree`` and ``order`` in the Moon's body-fixed ``body_frame`` (``de405``
librations, default, or ``iau2009``); ``pole`` (J2 only, default ``of-date``) is its axis.
A plan that names its forces this way, or names none (the default is the second line
above), measures inclinations about the Moon's axis of date: its ``lunar_pole`` defaults
to ``of-date``, the IAU pole at the arrival epoch (0.79 deg from J2000's in 2017).

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
durations around perilune, at least +-30 min for an ellipse as asked and in any dynamics
beyond a point Moon, within +-120 min and 0.4 of the orbit before the burn).

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

import os
from dataclasses import dataclass, field, replace
from functools import lru_cache
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.arrival import (
    ArrivalSpec,
    perilune_from_bplane_arrival,
    perilune_from_state,
)
from lunarcap.mission.impulsive import ImpulsiveBurn, impulsive_chain, tangential_impulse_mps
from lunarcap.mission.plan_checks import (  # noqa: F401  (the plan's names, re-exported)
    DYNAMICS,
    EPHEMERIS_MARGIN_S,
    FORMULATIONS,
    HEMISPHERES,
    MAX_BURN_FRACTION,
    MAX_START_MIN,
    MIN_BURN_S,
    STEERING,
    PlanError,
    burn_field,
    circle_period_s,
    err,
    num,
    start_value,
    validate,
)
from lunarcap.mission.plan_io import plan_dict, plan_fields
from lunarcap.mission.scenario import PAPER_PLANS, PLAN_DIR, paper_engine_pairs, paper_plan_name
from lunarcap.mission.targets import CIRCULAR, ELLIPSE, PERILUNE, Target
from lunarcap.physics import constants as C
from lunarcap.physics.elements import semi_major_axis_from_period
from lunarcap.physics.ephemeris import Ephemeris, default_ephemeris
from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.physics.frames import DEFAULT_LUNAR_POLE


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
    make_up : bool
        The first burn is a make-up burn after a fault (:mod:`lunarcap.studies.missed.cases`): its
        duration is bounded by its solver, not checked against Eq. (19) (it may need next
        to nothing, and its impulse is tangential where the state is, not at a perilune).
    """

    epoch_s: float
    state: tuple
    first_coast_s: float
    make_up: bool = False

    def __post_init__(self):
        object.__setattr__(self, "state", tuple(self.state))   # checked by the plan

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

    Build one with :func:`lunarcap.load_plan` (a file, a packaged name or a mapping, with
    changes) or :meth:`from_dict`; derive variants with the ``with_*`` methods. A plan is
    immutable: each change returns a new plan, checked as a plan file is, every error a
    :class:`~lunarcap.mission.plan_checks.PlanError` naming the field.

    Attributes
    ----------
    name : str
        Names the plan's results and files.
    arrival : ArrivalSpec
        Epoch of the first perilune (TDB or UTC text), ``perilune_altitude_km`` (km),
        ``inclination_deg`` (deg), ``v_inf_kmps`` (km/s), ``mass_kg`` (kg), hemisphere.
    engine : Engine
        ``thrust_N`` (N) and ``isp_s`` (s), constant.
    burns : tuple of Burn
        In order; each its target orbit and its ignition, ``start_min`` (min from the
        nominal perilune, negative before it; or ``"free"``).
    dynamics : str or ForceModel
        ``"full"`` (lunar J2, Earth, Sun; DE405), ``"j2"``, ``"two-body"`` or named forces.
    formulation : {"orbit", "song2011"}
        How a period or apolune is met (the module's docstring).

    Examples
    --------
    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h")
    >>> plan.n_burns, plan.engine.thrust_N, plan.arrival.mass_kg, plan.dynamics
    (2, 150.0, 524.895, 'full')
    >>> [b.describe() for b in plan.with_engine(440, 320).with_mass(900).burns]
    ['ellipse, 8 h', 'circle']
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
        """The one validation of a plan, whoever built it (:func:`plan_checks.validate`)."""
        object.__setattr__(self, "burns", tuple(self.burns))
        validate(self)

    def _derive_state_arrival(self) -> None:
        """Replace the perilune numbers of a state arrival by those of its propagation."""
        a = self.arrival
        try:
            peri = perilune_from_state(a.state, float(num("arrival.mass_kg", a.mass_kg, "kg")),
                                       self.dynamics, self.ephemeris_model(), self.lunar_pole)
        except InputError as exc:
            where = "arrival.opm" if a.state.opm else "arrival"
            raise err(where, str(exc)) from None
        object.__setattr__(self, "arrival", replace(
            a, epoch=peri["epoch"], perilune_altitude_km=peri["altitude_km"],
            inclination_deg=peri["inclination_deg"], hemisphere=peri["hemisphere"],
            v_inf_kmps=peri["v_inf_kmps"], perilune_mee=peri["mee"],
            approach_dir=peri["approach_dir"]))

    def _derive_bplane_arrival(self) -> None:
        """Replace the perilune numbers of a B-plane arrival by those of its hyperbola."""
        try:
            peri = perilune_from_bplane_arrival(self.arrival.bplane, self.lunar_pole)
        except InputError as exc:
            raise err("arrival.b_r_km", str(exc)) from None
        object.__setattr__(self, "arrival", replace(
            self.arrival, epoch=peri["epoch"], perilune_altitude_km=peri["altitude_km"],
            inclination_deg=peri["inclination_deg"], hemisphere=peri["hemisphere"],
            v_inf_kmps=peri["v_inf_kmps"], perilune_mee=peri["mee"],
            approach_dir=peri["approach_dir"]))

    # ------------------------------------------------------------------ derived numbers
    @property
    def perilune_radius_km(self) -> float:
        """Radius of every perilune and of the final circle, km.

        >>> import lunarcap
        >>> lunarcap.load_plan("two-burn-8h").perilune_radius_km   # 1738.2 + 100 km
        1838.2
        """
        return self.arrival.perilune_radius_km

    @property
    def n_burns(self) -> int:
        """Number of burns.

        >>> import lunarcap
        >>> lunarcap.load_plan("lro-like-5burn").n_burns
        5
        """
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
        return b.coast_s if b.coast_s is not None else circle_period_s(self.perilune_radius_km)

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
        """The same plan with another engine: ``thrust_N`` (N), ``isp_s`` (s).

        ``name``: the new plan's name (default: the plan's, with the engine appended).

        >>> import lunarcap
        >>> p = lunarcap.load_plan("two-burn-8h").with_engine(440, 320)
        >>> p.name, p.engine.thrust_N, p.engine.isp_s
        ('two-burn-8h (440 N / 320 s)', 440.0, 320.0)
        """
        return replace(self, engine=Engine(float(thrust_N), float(isp_s)),
                       name=name or f"{self.name} ({thrust_N:g} N / {isp_s:g} s)")

    def with_dynamics(self, dynamics) -> "CapturePlan":
        """The same plan in other dynamics (a word, a ForceModel or a ``dynamics`` mapping).

        The plan's frame (``lunar_pole``) is kept: a J2 design and its field design measure
        inclinations about the same axis.

        >>> import lunarcap
        >>> p = lunarcap.load_plan("two-burn-8h")
        >>> p.with_dynamics("two-body").dynamics
        'two-body'
        >>> p.with_dynamics({"gravity": "LP165P", "degree": 8}).dynamics.label
        'LP165P 8x8 (de405), Earth, Sun'
        """
        return replace(self, dynamics=dynamics)

    def with_mass(self, mass_kg: float) -> "CapturePlan":
        """The same plan with another mass at the arrival, kg (checked like the file's).

        A plan that starts from a known state (:class:`Start`) keeps that state's mass.

        >>> import lunarcap
        >>> lunarcap.load_plan("two-burn-8h").with_mass(900).arrival.mass_kg
        900.0
        >>> lunarcap.load_plan("two-burn-8h").with_mass(0)
        Traceback (most recent call last):
        ...
        lunarcap.mission.plan_checks.PlanError: arrival.mass_kg: must be positive (kg), got 0
        """
        return replace(self, arrival=replace(self.arrival, mass_kg=mass_kg))

    def with_targets(self, targets) -> "CapturePlan":
        """The same plan with the orbit each burn must reach replaced (one per burn).

        Each target is written as in a plan file's burn, without ``start_min``:
        ``{"target_period_h": 8}``, ``{"target_apolune_altitude_km": 3000}``,
        ``{"target": "circular"}`` (``coast_min`` optional), or ``{"target":
        {"perilune_altitude_km": 100, "apolune_altitude_km": 300}}``; None keeps the burn's.
        Read by the plan file's reader, so an error names the field as a file would
        (``burns[2].target_period_h: ...``); ignitions and steering are kept.

        >>> import lunarcap
        >>> p = lunarcap.load_plan("two-burn-8h")
        >>> q = p.with_targets([{"target_apolune_altitude_km": 3000}, None])
        >>> [b.describe() for b in q.burns]
        ['ellipse, apolune altitude 3000 km', 'circle']
        """
        from lunarcap.mission.plan_io import burn_with_target

        targets = list(targets)
        if len(targets) != self.n_burns:
            raise err("burns", f"{self.n_burns} targets expected (one per burn), got "
                                f"{len(targets)}")
        burns = tuple(b if t is None else burn_with_target(i, b, t)
                      for i, (b, t) in enumerate(zip(self.burns, targets)))
        return replace(self, burns=burns)

    def with_start(self, i: int, start_min) -> "CapturePlan":
        """The same plan with burn ``i`` (0-based) igniting at ``start_min`` (or 'free').

        ``start_min``: minutes from the burn's nominal perilune, negative before it.

        >>> import lunarcap
        >>> lunarcap.load_plan("two-burn-8h").with_start(1, -5).burns[1].start_min
        -5.0
        """
        self._index(i)
        burns = list(self.burns)
        burns[i] = replace(burns[i], start_min=start_value(burn_field(i, "start_min"), start_min))
        return replace(self, burns=tuple(burns))

    def with_starts(self, starts) -> "CapturePlan":
        """The same plan with every burn's ignition offset replaced (one per burn).

        Each offset in minutes from the burn's nominal perilune (negative before it), or
        ``"free"`` (optimised); PlanError if the count differs from the burns'.

        >>> import lunarcap
        >>> p = lunarcap.load_plan("two-burn-8h").with_starts([-4, "free"])
        >>> [b.start_min for b in p.burns]
        [-4.0, 'free']
        >>> lunarcap.load_plan("two-burn-8h").with_starts([-4])  # doctest: +ELLIPSIS
        Traceback (most recent call last):
        ...
        lunarcap.mission.plan_checks.PlanError: burns: 2 ignition offsets expected ..., got 1
        """
        starts = list(starts)
        if len(starts) != self.n_burns:
            raise err("burns", f"{self.n_burns} ignition offsets expected (one per burn), "
                                f"got {len(starts)}")
        plan = self
        for i, s in enumerate(starts):
            plan = plan.with_start(i, s)
        return plan

    def with_steering(self, i: int, steering: str) -> "CapturePlan":
        """The same plan with burn ``i`` (0-based) flown with another steering law.

        ``steering``: ``"optimal"``, ``"inertial"`` (a fixed direction) or
        ``"antivelocity"``.

        >>> import lunarcap
        >>> lunarcap.load_plan("two-burn-8h").with_steering(0, "inertial").burns[0].steering
        'inertial'
        """
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
            raise err("burns", f"{self.n_burns} coasts expected (one per burn), got "
                                f"{len(coasts)}")
        burns, start = list(self.burns), self.start
        for i, c in enumerate(coasts):
            if c is None:
                continue
            c = num(burn_field(i, "coast_min"), float(c) / 60.0, "min") * 60.0
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
                window_min: tuple = (0.0, 30.0), make_up: bool = False) -> "CapturePlan":
        """The capture from burn ``i`` (0-based) on, starting from ``state`` at ``epoch_s``.

        Burns i, i+1, ... of this plan; the first ignites within ``window_min`` (min after
        ``epoch_s``, free), the others as in this plan. The first coast ends at
        ``first_coast_s`` after ``epoch_s`` (default: this plan's nominal perilune after
        burn i). The re-plan after a fault (:mod:`lunarcap.studies.missed.cases`) and the impulsive
        limit of a burn from a given state are such plans. ``make_up``: its first burn is
        a make-up burn (see :class:`Start`).
        """
        self._index(i)
        t = self.nominal_perilunes_s
        coast = t[i + 1] - float(epoch_s) if first_coast_s is None else float(first_coast_s)
        first = replace(self.burns[i], start_min="free",
                        start_bounds_min=tuple(float(w) for w in window_min))
        return replace(self, burns=(first,) + self.burns[i + 1:], impulsive_loi1_mps=None,
                       start=Start(float(epoch_s), tuple(np.asarray(state, float)), coast,
                                   bool(make_up)))

    def truncated(self, n: int) -> "CapturePlan":
        """The plan's first ``n`` burns (a prefix: what burn n depends on)."""
        if not 1 <= n <= self.n_burns:
            raise err("burns", f"a prefix of 1 to {self.n_burns} burns, got {n}")
        return replace(self, burns=self.burns[:n])

    def with_lunar_pole(self, lunar_pole: str) -> "CapturePlan":
        """The plan with another lunar pole fixing M-MME2000 (see physics.frames).

        ``"of-date"``: the IAU pole at the arrival epoch (:func:`plan_io.frame_epoch`);
        ``"iau2009-j2000"``: the IAU 2009 pole at J2000; ``"iau-constant"``.

        >>> import lunarcap
        >>> p = lunarcap.load_plan("two-burn-8h")
        >>> p.lunar_pole, p.with_lunar_pole("of-date").lunar_pole   # resolved at arrival
        ('iau2009-j2000', 'iau2009@2017-02-20 03:41:26 TDB')
        """
        return replace(self, lunar_pole=lunar_pole)   # "of-date" resolved by the checks

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
            raise err("burns", f"this plan has burns 1 to {self.n_burns}; "
                                f"burn {i + 1 if isinstance(i, int) else i} does not exist")

    # ------------------------------------------------------------------ (de)serialisation
    @classmethod
    def from_dict(cls, d: dict, base_dir: str | os.PathLike | None = None,
                  default_name: str = "") -> "CapturePlan":
        """A plan from the mapping of a YAML file (every key checked; PlanError names it).

        ``base_dir`` resolves a relative ``ephemeris`` path (the plan file's directory).
        The mapping's structure is read by :func:`plan_io.plan_fields`; its values are
        checked once, by the plan itself. The keys and units are a plan file's (the
        module's docstring): ``arrival.mass_kg`` in kg, ``engine.thrust_N`` in N, ...

        >>> import lunarcap
        >>> d = lunarcap.load_plan("two-burn-8h").to_dict()
        >>> d["engine"]["thrust_N"] = 440
        >>> lunarcap.CapturePlan.from_dict(d).engine.thrust_N
        440.0
        """
        return cls(**plan_fields(d, base_dir, default_name))

    def to_dict(self) -> dict:
        """The plan as a mapping with the YAML file's keys (round-trips :meth:`from_dict`).

        Units in the keys, as in a plan file (``mass_kg``, ``thrust_N``, ``v_inf_kmps``).

        >>> import lunarcap
        >>> p = lunarcap.load_plan("two-burn-8h")
        >>> d = p.to_dict()
        >>> d["engine"], d["arrival"]["mass_kg"]
        ({'thrust_N': 150.0, 'isp_s': 200.0}, 524.895)
        >>> lunarcap.CapturePlan.from_dict(d) == p
        True
        """
        return plan_dict(self)

    def to_yaml(self) -> str:
        """YAML text of :meth:`to_dict`: a plan file (``lunarcap plan FILE`` solves it).

        >>> import lunarcap
        >>> print(lunarcap.load_plan("two-burn-8h").to_yaml().splitlines()[0])
        name: two-burn-8h
        """
        import yaml

        return yaml.safe_dump(self.to_dict(), sort_keys=False, default_flow_style=None)


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
    if path.is_dir():
        raise PlanError(f"plan {source}: is a directory, not a plan file: give a YAML file "
                        f"in it or a packaged plan ({', '.join(available_plans())})")
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


def paper_plan(thrust_N: float = paper_engine_pairs()[0][0],
               isp_s: float = paper_engine_pairs()[0][1], starts=None,
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
