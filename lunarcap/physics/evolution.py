"""The orbit after the capture: days of coasting in a plan's forces, revolution by revolution.

:func:`evolve` propagates a state (the final orbit at the last cut-off) for a number of
days in a force model, in arcs of at most :data:`ARC_DAYS` (each with its own Chebyshev
fit of the ephemeris and the Moon's orientation, whose window is at most 4 days), with
the states sampled every :data:`STEP_S`. Each revolution (a turn of the
true longitude) is read off the samples: its lowest and highest radius (the perilune and
the apolune actually flown, each refined by the parabola through the three samples around
it: the error is of the order of the radius's third derivative times the step cubed,
below a millimetre at 10 s), and its mean osculating inclination, about the z axis of the
plan's frame (the Moon's pole of that frame). In a gravity field the radius has more than
one local minimum per revolution; these are the revolution's extremes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model, fit_for, force_model
from lunarcap.physics.elements import inclination, periapsis_factor
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.propagate import RTOL, Trajectory, propagate

#: Longest arc of one ephemeris fit, days (the fit spans it plus 1 h on each side).
ARC_DAYS = 3.5
#: Sampling step of the states, s.
STEP_S = 10.0
#: Longest evolution asked, days.
MAX_DAYS = 60.0


@dataclass
class Evolution:
    """The final orbit's revolutions over ``days`` from ``t0_s``.

    Attributes
    ----------
    t0_s : float
        Start (the last cut-off), TDB s past J2000.
    days : float
    forces : str
        The model flown (its label).
    perilune_epoch_s, perilune_altitude_km, apolune_altitude_km, inclination_deg : ndarray
        One entry per whole revolution: the epoch and altitude of its lowest point (above
        the mean radius 1738.2 km), the altitude of its highest, and its mean osculating
        inclination (deg, about the frame's pole).
    final_state : ndarray (7,)
        (p, f, g, h, k, L, m) at ``t0_s + days``.
    trajectory : Trajectory
        The sampled states (``t``, ``x``).
    """

    t0_s: float
    days: float
    forces: str
    perilune_epoch_s: np.ndarray
    perilune_altitude_km: np.ndarray
    apolune_altitude_km: np.ndarray
    inclination_deg: np.ndarray
    final_state: np.ndarray
    trajectory: Trajectory

    def summary(self) -> dict:
        """First and last revolution and the extremes (km, deg)."""
        rp, ra, inc = self.perilune_altitude_km, self.apolune_altitude_km, self.inclination_deg
        return {"after_days": self.days, "after_dynamics": self.forces,
                "after_revolutions": int(rp.size),
                "after_min_perilune_altitude_km": float(rp.min()),
                "after_max_apolune_altitude_km": float(ra.max()),
                "after_last_perilune_altitude_km": float(rp[-1]),
                "after_last_apolune_altitude_km": float(ra[-1]),
                "after_inclination_change_deg": float(inc[-1] - inc[0])}

    def to_dict(self) -> dict:
        """JSON-ready: the summary and the per-revolution histories."""
        return self.summary() | {
            "after_start_epoch": calendar_from_seconds(self.t0_s),
            "revolutions": [
                {"perilune_epoch": calendar_from_seconds(t), "perilune_altitude_km": float(a),
                 "apolune_altitude_km": float(b), "mean_inclination_deg": float(i)}
                for t, a, b, i in zip(self.perilune_epoch_s, self.perilune_altitude_km,
                                      self.apolune_altitude_km, self.inclination_deg)]}


def _refined(t, y, i):
    """Epoch and value of the extremum of y at sample i (parabola through i-1, i, i+1)."""
    i = np.clip(i, 1, t.size - 2)
    y0, y1, y2 = y[i - 1], y[i], y[i + 1]
    den = y0 - 2 * y1 + y2
    off = np.where(den != 0, 0.5 * (y0 - y2) / np.where(den != 0, den, 1.0), 0.0)
    off = np.clip(off, -1.0, 1.0)
    return t[i] + off * (t[i + 1] - t[i]), y1 - 0.25 * (y0 - y2) * off


def revolutions(t, x) -> tuple:
    """Per whole revolution of sampled states: perilune epoch and radius, apolune, inclination.

    A revolution is a turn of the true longitude L from its first value; its perilune and
    apolune are its lowest and highest radius (km), its inclination the mean osculating
    one (deg).
    """
    p, f, g, h, k, L = x[:6]
    r = p / (1 + periapsis_factor(f, g, L))
    turn = np.floor((np.unwrap(L) - L[0]) / (2 * np.pi)).astype(int)
    out = []
    for n in range(turn[-1]):   # whole revolutions only
        sel = np.nonzero(turn == n)[0]
        lo, hi = sel[np.argmin(r[sel])], sel[np.argmax(r[sel])]
        tp, rp = _refined(t, r, lo)
        _, ra = _refined(t, -r, hi)
        out.append((tp, rp, -ra, float(np.degrees(inclination(h[sel], k[sel])).mean())))
    return tuple(np.array(c) for c in zip(*out)) if out else (np.array([]),) * 4


def evolve(forces, eph, t0_s: float, x0, days: float, step_s: float = STEP_S,
           rtol: float = RTOL) -> Evolution:
    """Propagate ``x0`` (p, f, g, h, k, L, m at ``t0_s``) for ``days`` in ``forces``.

    Parameters
    ----------
    forces : a preset word, ForceModel or ``dynamics`` mapping
    eph : Ephemeris
        The plan's (its frame: the plan's lunar pole).
    t0_s : float
        TDB s past J2000.
    days : float
        0 < days <= :data:`MAX_DAYS`.
    rtol : float
        Relative (and scaled absolute) tolerance of the propagation (default the
        propagator's, 1e-13). At 1e-10 a 7-day flight of the 100 km polar orbit in LP165P
        20x20 costs half the CPU and its perilunes move by 3 mm.

    Raises
    ------
    InputError
        For a duration out of range, or beyond the ephemeris.
    """
    if not (np.isfinite(days) and 0 < days <= MAX_DAYS):
        raise InputError(f"--after-days: a number of days in (0, {MAX_DAYS:g}], got {days!r}")
    t_end = t0_s + days * C.DAY_S
    eph.check_epochs([t0_s - 3600.0, t_end + 3600.0])
    n_arcs = int(np.ceil(days / ARC_DAYS))
    edges = t0_s + np.linspace(0.0, days * C.DAY_S, n_arcs + 1)
    x = np.asarray(x0, float)
    arcs = []
    for a, b in zip(edges[:-1], edges[1:]):
        model = Model(forces, 0.0, 300.0, fit_for(forces, eph, a - 3600.0, b + 3600.0))
        n = max(2, int(np.ceil((b - a) / step_s)))
        arc = propagate(model, a, x, b, t_eval=a + (b - a) * np.arange(n + 1) / n,
                        rtol=rtol, atol=rtol)
        arcs.append(arc)
        x = arc.final
    traj = Trajectory.join(arcs)
    tp, rp, ra, inc = revolutions(traj.t, traj.x)
    if not tp.size:
        raise InputError(f"--after-days: {days:g} days hold no whole revolution")
    return Evolution(float(t0_s), float(days), force_model(forces).label, tp, rp - C.R_MOON,
                     ra - C.R_MOON, inc, traj.final, traj)
