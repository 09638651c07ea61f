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
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.impulsive import v_inf_from_loi1
from lunarcap.physics import constants as C
from lunarcap.physics.elements import mee_from_rv
from lunarcap.physics.ephemeris import Ephemeris, default_ephemeris
from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.physics.rocket import check_engine, check_perilune_radius


@dataclass(frozen=True)
class ArrivalSpec:
    """Hashable parameters of the arrival reconstruction (see :func:`arrival_state`).

    The ``arrival`` section of a capture plan (:mod:`lunarcap.mission.plan`). ``v_inf_kmps``
    is the hyperbolic excess speed, km/s (``None``: derived from the paper's impulsive
    LOI 1); ``approach_dir`` a unit 3-vector in M-MME2000 (``None``: anti-parallel to the
    Moon's geocentric velocity).
    """

    epoch: str = C.ARRIVAL_EPOCH_TDB
    perilune_altitude_km: float = C.PERILUNE_ALTITUDE_KM
    inclination_deg: float = 90.0
    mass_kg: float = C.ARRIVAL_MASS_KG
    v_inf_kmps: float | None = None
    hemisphere: str = "north"
    approach_dir: tuple | None = None

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


def arrival_state(epoch: str = C.ARRIVAL_EPOCH_TDB, altitude_km: float = C.PERILUNE_ALTITUDE_KM,
                  inclination_deg: float = 90.0, mass_kg: float = C.ARRIVAL_MASS_KG,
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
