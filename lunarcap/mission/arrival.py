"""The arrival hyperbola at its first perilune, reconstructed from a few numbers.

The paper's arrival (Song 2011, Sec. 3.2.1): first perilune on 2017-02-20 03:41:26 TDB at 100 km
altitude, 90 deg inclination in M-MME2000, mass 524.895 kg. The paper does not print
the hyperbola's speed or orientation. We reconstruct them:

* **Speed.** v_inf is chosen so that a tangential impulse at perilune into the 12.235 h
  ellipse costs the paper's impulsive 353.272 m/s
  (:func:`lunarcap.mission.impulsive.v_inf_from_loi1`),
  giving v_inf = 0.918 km/s.
* **Direction.** The paper's transfer (Song et al. 2009c, 2010a) is a direct,
  Hohmann-like trans-lunar trajectory. Such a trajectory arrives near its geocentric
  apogee with a geocentric speed (about 0.2 km/s) far below the Moon's (about 1.0 km/s)
  and nearly parallel to it, so the Moon-relative velocity on the approach asymptote is
  nearly anti-parallel to the Moon's geocentric velocity. We take the incoming asymptote
  exactly anti-parallel to the Moon's geocentric velocity at the perilune epoch (from
  DE405): the approach direction parameter ``approach="anti-lunar-velocity"``; an
  explicit unit vector (M-MME2000) may be given instead.
* **Plane.** The orbit plane contains the asymptote and has the requested inclination
  (90 deg); of the two such planes, ``hemisphere`` picks the one whose perilune lies over
  the northern or southern lunar hemisphere.

An arrival may instead be a **state** (:class:`StateArrival`: a Moon-centred position and
velocity at an epoch, in ICRF or M-MME2000, as a navigation team or a CCSDS OPM gives it).
:func:`perilune_from_state` then derives the arrival perilune by propagating the state in
the plan's dynamics to its next perilune (the first zero of the radial velocity); its
epoch, altitude, inclination, hemisphere and the two-body v_inf of the perilune state
replace the reconstruction, and the arrival state is that propagated perilune state.

An arrival may also be a **B-plane target** (:class:`BPlaneArrival`: B.R and B.T in km,
v_inf, the incoming asymptote and the epoch of closest approach, the asymptote in ICRF or
M-MME2000, as a trans-lunar trajectory team hands it over). Its perilune is that of the
two-body hyperbola it defines (:func:`lunarcap.physics.bplane.perilune_from_bplane`), at
the epoch of closest approach. The B-plane's T axis is S x k / |S x k| with k the pole of
its reference plane, ``bplane_reference``: ``EME2000`` by default (the Earth's mean
equator of J2000, as GMAT's BdotT/BdotR and trajectory teams give it), ``lunar-equator``
on request (the plan's M-MME2000 equator); :attr:`ArrivalSpec.bplane_reference` is the
same choice for any arrival (the reference of a B-plane covariance in the dispersions
study).
"""


from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.impulsive import v_inf_from_loi1
from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics.elements import inclination, mee_from_rv, rv_from_mee
from lunarcap.physics.ephemeris import Ephemeris, default_ephemeris
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.rocket import check_engine, check_perilune_radius

#: Frames a state arrival may be given in.
STATE_FRAMES = ("ICRF", "M-MME2000")
#: The longest a state may precede its perilune (the ephemeris fit's 4 days, less margins).
MAX_TO_PERILUNE_S = 3.5 * 86400.0

#: The paper's scenario (its packaged plans): the defaults of an arrival.
_PAPER = paper_scenario()


@dataclass(frozen=True)
class StateArrival:
    """An arrival given as a Moon-centred state (the ``arrival`` of a plan with a state).

    Attributes
    ----------
    epoch : str
        Calendar epoch with its scale (``"2017-02-20 03:11:26 UTC"`` or TDB).
    frame : {"ICRF", "M-MME2000"}
    position_km, velocity_kmps : tuple of 3 floats
    opm : str or None
        The CCSDS OPM file the state was read from, if any.
    """

    epoch: str
    frame: str
    position_km: tuple
    velocity_kmps: tuple
    opm: str | None = None

    @property
    def epoch_s(self) -> float:
        """TDB seconds past J2000 of the epoch."""
        return seconds_from_calendar(self.epoch)


@dataclass(frozen=True)
class BPlaneArrival:
    """An arrival given as its B-plane target (the ``arrival`` of a plan with ``b_r_km``).

    Attributes
    ----------
    epoch : str
        Calendar epoch of closest approach (the perilune), with its scale.
    frame : {"ICRF", "M-MME2000"}
        Axes of ``approach_dir``.
    b_r_km, b_t_km : float
        The miss vector's components along R and T, km.
    v_inf_kmps : float
        Hyperbolic excess speed, km/s.
    approach_dir : tuple of 3 floats
        The incoming asymptote S (the approach velocity's direction at infinity), unit.
    reference : {"EME2000", "lunar-equator"}
        The plane the T axis lies in (:data:`lunarcap.physics.bplane.REFERENCE_PLANES`):
        T = S x k / |S x k|, R = S x T, k its pole.
    """

    epoch: str
    frame: str
    b_r_km: float
    b_t_km: float
    v_inf_kmps: float
    approach_dir: tuple
    reference: str = "EME2000"

    def perilune_rv(self, lunar_pole: str) -> tuple:
        """(r km, v km/s) of the perilune in M-MME2000 (InputError if it has none)."""
        from lunarcap.physics.bplane import perilune_from_bplane, reference_pole
        from lunarcap.physics.frames import mme_from_icrf

        k = reference_pole(self.reference, self.frame, lunar_pole)
        r, v = perilune_from_bplane(float(self.b_r_km), float(self.b_t_km),
                                    float(self.v_inf_kmps), self.approach_dir, C.MU_MOON, k)
        if self.frame == "ICRF":
            r, v = mme_from_icrf(r, lunar_pole), mme_from_icrf(v, lunar_pole)
        return np.asarray(r, float), np.asarray(v, float)


def perilune_from_bplane_arrival(b: BPlaneArrival, lunar_pole: str) -> dict:
    """The perilune numbers of a B-plane arrival (the keys of :func:`perilune_from_state`)."""
    r, v = b.perilune_rv(lunar_pole)
    mee = mee_from_rv(r, v, C.MU_MOON)
    s = np.asarray(b.approach_dir, float)
    s = s / np.linalg.norm(s)
    if b.frame == "ICRF":
        from lunarcap.physics.frames import mme_from_icrf

        s = mme_from_icrf(s, lunar_pole)
    return {"epoch": b.epoch, "mee": tuple(float(q) for q in np.asarray(mee).ravel()[:6]),
            "altitude_km": float(np.linalg.norm(r) - C.R_MOON),
            "inclination_deg": float(np.degrees(inclination(mee[3], mee[4]))),
            "hemisphere": "north" if r[2] >= 0 else "south",
            "v_inf_kmps": float(b.v_inf_kmps),
            "approach_dir": tuple(float(q) for q in s)}


@dataclass(frozen=True)
class ArrivalSpec:
    """Hashable parameters of the arrival reconstruction (see :func:`arrival_state`).

    The ``arrival`` section of a capture plan (:mod:`lunarcap.mission.plan`). ``v_inf_kmps``
    is the hyperbolic excess speed, km/s (``None``: derived from the paper's impulsive
    LOI 1); ``approach_dir`` a unit 3-vector in M-MME2000 (``None``: anti-parallel to the
    Moon's geocentric velocity); ``bplane_reference`` the plane the arrival's B-plane T
    axis lies in (:data:`lunarcap.physics.bplane.REFERENCE_PLANES`; a B-plane target's
    and a B-plane covariance's).
    """

    epoch: str = _PAPER.epoch_tdb
    perilune_altitude_km: float = _PAPER.perilune_altitude_km
    inclination_deg: float = _PAPER.inclination_deg
    mass_kg: float = _PAPER.mass_kg
    v_inf_kmps: float | None = None
    hemisphere: str = "north"
    approach_dir: tuple | None = None
    state: StateArrival | None = None     # a state arrival (the rest derived from it)
    bplane: BPlaneArrival | None = None   # a B-plane arrival (the rest derived from it)
    perilune_mee: tuple | None = None     # derived: (p, f, g, h, k, L) at ``epoch``
    bplane_reference: str = "EME2000"     # the B-plane's reference plane (target, covariance)

    @property
    def perilune_radius_km(self) -> float:
        """R_Moon + perilune altitude, km."""
        return C.R_MOON + self.perilune_altitude_km

    def approach_direction(self, eph: Ephemeris | None = None) -> np.ndarray:
        """Unit velocity direction of the incoming asymptote, M-MME2000 (see the module)."""
        if self.approach_dir is not None:
            s = np.asarray(self.approach_dir, float)
            return s / np.linalg.norm(s)
        eph = eph or default_ephemeris()
        _, vm = eph.moon_geocentric_state(seconds_from_calendar(self.epoch))
        return -vm[:, 0] / np.linalg.norm(vm[:, 0])

    def build(self, eph: Ephemeris | None = None) -> "Arrival":
        """The Arrival state of these parameters."""
        if self.perilune_mee is not None:   # a state arrival: the propagated perilune
            r, v = (np.array(a, float) for a in rv_from_mee(*self.perilune_mee, C.MU_MOON))
            return Arrival(seconds_from_calendar(self.epoch), r, v, float(self.mass_kg),
                           float(self.v_inf_kmps), np.array(self.approach_direction(eph)),
                           self.hemisphere)
        approach = "anti-lunar-velocity" if self.approach_dir is None else self.approach_dir
        return arrival_state(self.epoch, self.perilune_altitude_km, self.inclination_deg,
                             self.mass_kg, self.v_inf_kmps, approach=approach,
                             hemisphere=self.hemisphere, eph=eph)


@dataclass
class Arrival:
    """The reconstructed arrival hyperbola at its perilune (km, km/s, kg, M-MME2000)."""

    epoch_s: float
    r_km: np.ndarray
    v_kmps: np.ndarray
    mass_kg: float
    v_inf_kmps: float
    approach_dir: np.ndarray
    hemisphere: str

    @property
    def mee(self) -> np.ndarray:
        """(p, f, g, h, k, L) of the arrival state."""
        return mee_from_rv(self.r_km, self.v_kmps, C.MU_MOON)

    @property
    def state(self) -> np.ndarray:
        """(p, f, g, h, k, L, m)."""
        return np.concatenate([self.mee, [self.mass_kg]])


def arrival_state(epoch: str = _PAPER.epoch_tdb, altitude_km: float = _PAPER.perilune_altitude_km,
                  inclination_deg: float = _PAPER.inclination_deg, mass_kg: float = _PAPER.mass_kg,
                  v_inf_kmps: float | None = None, approach="anti-lunar-velocity",
                  hemisphere: str = "north", eph: Ephemeris | None = None,
                  mu: float = C.MU_MOON) -> Arrival:
    """Reconstruct the arrival hyperbola's perilune state (see the module docstring).

    Parameters
    ----------
    epoch : str, TDB calendar epoch of the first perilune
    altitude_km : perilune altitude, km
    inclination_deg : inclination in M-MME2000, deg
    mass_kg : mass at perilune, kg
    v_inf_kmps : hyperbolic excess speed, km/s (default: from the paper's impulsive LOI 1)
    approach : "anti-lunar-velocity" or a unit vector (3,), the incoming asymptote's
        velocity direction in M-MME2000
    hemisphere : "north" or "south", the lunar hemisphere of the perilune
    """
    eph = eph or default_ephemeris()
    t = seconds_from_calendar(epoch)
    eph.check_epochs(t)
    rp = C.R_MOON + altitude_km
    check_perilune_radius(rp)
    check_engine(1.0, 1.0, mass_kg)
    if not 0.0 <= inclination_deg <= 180.0:
        raise InputError(f"inclination must lie in [0, 180] deg, got {inclination_deg}")
    if hemisphere not in ("north", "south"):
        raise InputError(f"hemisphere must be 'north' or 'south', got {hemisphere!r}")
    vinf = v_inf_from_loi1(rp_km=rp) if v_inf_kmps is None else float(v_inf_kmps)
    if not vinf > 0:
        raise InputError(f"v_inf must be positive (km/s), got {vinf}")
    if isinstance(approach, str):
        if approach != "anti-lunar-velocity":
            raise InputError(f"unknown approach {approach!r}")
        _, vm = eph.moon_geocentric_state(t)
        s = -vm[:, 0] / np.linalg.norm(vm[:, 0])
    else:
        s = np.asarray(approach, float)
        if s.shape != (3,) or not np.isfinite(s).all() or np.linalg.norm(s) == 0:
            raise InputError("approach must be a non-zero 3-vector")
        s = s / np.linalg.norm(s)
    z = np.array([0.0, 0.0, 1.0])
    # orbit normals h perpendicular to s with h.z = cos(i)
    zp = z - (z @ s) * s
    if np.linalg.norm(zp) < 1e-12:
        raise InputError("approach along the lunar pole: the inclination cannot be chosen")
    e1 = zp / np.linalg.norm(zp)
    e2 = np.cross(s, e1)
    cphi = np.cos(np.radians(inclination_deg)) / (e1 @ z)
    if abs(cphi) > 1:
        raise InputError(f"inclination {inclination_deg} deg unreachable with this approach "
                         f"direction (asymptote latitude {np.degrees(np.arcsin(s @ z)):.2f} deg)")
    ecc = 1 + rp * vinf ** 2 / mu
    th_inf = np.arccos(-1 / ecc)
    vp = np.sqrt(vinf ** 2 + 2 * mu / rp)
    cands = []
    for sphi in (np.sqrt(1 - cphi ** 2), -np.sqrt(1 - cphi ** 2)):
        hh = cphi * e1 + sphi * e2
        rhat = np.cos(th_inf) * (-s) + np.sin(th_inf) * np.cross(hh, -s)
        cands.append((rhat, np.cross(hh, rhat)))
    north = max(cands, key=lambda c: c[0] @ z)
    south = min(cands, key=lambda c: c[0] @ z)
    rhat, vhat = north if hemisphere == "north" else south
    return Arrival(t, rp * rhat, vp * vhat, float(mass_kg), vinf, s, hemisphere)


# ---------------------------------------------------------------------- state arrivals
def _radial_sign(x):
    """Sign-carrying radial velocity of MEE states: f sin L - g cos L (r.v up to a factor)."""
    return x[1] * np.sin(x[5]) - x[2] * np.cos(x[5])


@lru_cache(maxsize=64)
def perilune_from_state(state: StateArrival, mass_kg: float, dynamics: str,
                        eph: Ephemeris, lunar_pole: str) -> dict:
    """The arrival perilune of a state, propagated in ``dynamics`` (see the module docstring).

    Returns
    -------
    dict
        ``epoch`` (TDB calendar string, microseconds), ``epoch_s``, ``mee`` (6-tuple),
        ``altitude_km``, ``inclination_deg`` (M-MME2000), ``hemisphere``, ``v_inf_kmps``,
        ``approach_dir`` (the incoming asymptote, M-MME2000) and ``hours_to_perilune``.

    Raises
    ------
    InputError
        One line naming the cause: the epoch outside the ephemeris, a state inside the
        Moon, moving away from it, bound to it, a perilune below the surface or too late.
    """
    from lunarcap.physics.dynamics import Model, fit_for

    t0 = state.epoch_s
    r, v, t_peri = _approach(state, eph, lunar_pole)
    horizon = 1.3 * t_peri + 1800.0
    if horizon > MAX_TO_PERILUNE_S:
        raise InputError(f"the perilune is {t_peri / 86400:.1f} days after the state's "
                         f"epoch (two-body): give a state within "
                         f"{MAX_TO_PERILUNE_S / 86400 - 0.5:g} days of it")
    b0 = eph.span_s[1]
    if t0 + horizon > b0 - 3600.0:
        raise InputError(f"the approach from {state.epoch} to its perilune leaves the "
                         f"ephemeris {eph.name} (ends {calendar_from_seconds(b0, 0)})")
    fit = fit_for(dynamics, eph, t0 - 3600.0, t0 + horizon + 3600.0)
    model = Model(dynamics, 0.0, 300.0, fit)
    x0 = np.concatenate([mee_from_rv(r, v, C.MU_MOON), [mass_kg]])
    tp, xp = _flown_perilune(model, t0, x0, horizon, dynamics)
    return _arrival_at_perilune(tp, xp, t0, dynamics)


def _approach(state: StateArrival, eph: Ephemeris, lunar_pole: str) -> tuple:
    """(r km, v km/s in M-MME2000, two-body time to perilune s) of an arrival state, checked.

    InputError for an epoch outside the ephemeris, a state inside the Moon, moving away
    from it, bound to it, or on a two-body collision course.
    """
    from lunarcap.physics.frames import mme_from_icrf

    mu = C.MU_MOON
    a0, b0 = eph.span_s
    if not a0 + 3600.0 <= state.epoch_s <= b0 - 3600.0:
        raise InputError(f"the state's epoch {state.epoch} is outside the ephemeris "
                         f"{eph.name} ({calendar_from_seconds(a0, 0)} to "
                         f"{calendar_from_seconds(b0, 0)})")
    r, v = np.array(state.position_km, float), np.array(state.velocity_kmps, float)
    if state.frame == "ICRF":
        r, v = mme_from_icrf(r, lunar_pole), mme_from_icrf(v, lunar_pole)
    rn, vr = np.linalg.norm(r), float(r @ v) / np.linalg.norm(r)
    if rn <= C.R_MOON:
        raise InputError(f"the state is {rn:.1f} km from the Moon's centre, inside the Moon "
                         f"(radius {C.R_MOON:g} km)")
    energy = v @ v / 2 - mu / rn
    if vr >= 0:
        raise InputError(f"the state is not approaching the Moon: it moves away (radial "
                         f"speed {vr:+.4f} km/s at {rn:.1f} km); an arrival state must "
                         f"precede its perilune")
    if energy <= 0:
        raise InputError(f"the state is already bound to the Moon (specific energy "
                         f"{energy:.4f} km^2/s^2 at {rn:.1f} km): an arrival is a hyperbolic "
                         f"approach")
    # two-body perilune and the time to it (hyperbolic Kepler equation)
    a = -mu / (2 * energy)
    e = np.linalg.norm(((v @ v - mu / rn) * r - (r @ v) * v) / mu)
    rp2 = a * (1 - e)
    if rp2 <= C.R_MOON:
        raise InputError(f"the perilune lies below the lunar surface (two-body altitude "
                         f"{rp2 - C.R_MOON:.1f} km): the state is on a collision course")
    F = np.arccosh((1 + rn / abs(a)) / e)
    return r, v, float((e * np.sinh(F) - F) / np.sqrt(mu / abs(a) ** 3))


def _flown_perilune(model, t0: float, x0, horizon: float, dynamics: str) -> tuple:
    """(epoch s, state) of the first perilune within ``horizon`` s of (t0, x0), flown."""
    from scipy.optimize import brentq

    from lunarcap.physics.propagate import propagate

    traj = propagate(model, t0, x0, t0 + horizon, dense=True, dense_points=400)
    s = _radial_sign(traj.x)
    up = np.flatnonzero((s[:-1] < 0) & (s[1:] >= 0))
    if not up.size:
        raise InputError(f"no perilune within {horizon / 3600:.1f} h of the state in "
                         f"{dynamics} dynamics")
    j = up[0]
    tp = brentq(lambda t: float(_radial_sign(traj(t))), traj.t[j], traj.t[j + 1],
                xtol=1e-7, rtol=1e-15)
    tp = round(tp, 6)
    return tp, (propagate(model, t0, x0, tp).final if tp != t0 else x0)


def _arrival_at_perilune(tp: float, xp, t0: float, dynamics: str) -> dict:
    """:func:`perilune_from_state`'s answer from the flown perilune (tp, xp), checked."""
    mu = C.MU_MOON
    rp_vec, vp_vec = (np.array(q, float) for q in rv_from_mee(*xp[:6], mu))
    rp = np.linalg.norm(rp_vec)
    if rp <= C.R_MOON:
        raise InputError(f"the perilune lies below the lunar surface (altitude "
                         f"{rp - C.R_MOON:.1f} km in {dynamics} dynamics): the state is on a "
                         f"collision course")
    vinf2 = vp_vec @ vp_vec - 2 * mu / rp
    if vinf2 <= 0:
        raise InputError(f"the state reaches its perilune bound to the Moon (v^2 - 2 mu/r "
                         f"= {vinf2:.4f} km^2/s^2 in {dynamics} dynamics): an arrival is a "
                         f"hyperbolic approach")
    # the incoming asymptote of the osculating hyperbola at the perilune (its velocity
    # direction): s = r/(e r) + sqrt(1 - 1/e^2) v/v, rotated back by the asymptote angle
    e_p = 1 + rp * vinf2 / mu
    s_in = rp_vec / rp / e_p + np.sqrt(1 - 1 / e_p ** 2) * vp_vec / np.linalg.norm(vp_vec)
    return {"epoch": calendar_from_seconds(tp, 6), "epoch_s": tp,
            "approach_dir": tuple(float(q) for q in s_in / np.linalg.norm(s_in)),
            "mee": tuple(float(q) for q in xp[:6]), "altitude_km": float(rp - C.R_MOON),
            "inclination_deg": float(np.degrees(inclination(xp[3], xp[4]))),
            "hemisphere": "north" if rp_vec[2] >= 0 else "south",
            "v_inf_kmps": float(np.sqrt(vinf2)), "hours_to_perilune": (tp - t0) / 3600.0}
