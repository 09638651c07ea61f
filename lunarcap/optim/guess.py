"""Initial guess of a burn: thrust opposite the velocity, then the coast, propagated.

The burn duration starts from Eq. (19); for an elliptic target it is tuned so that the
guess coast ends at a perilune at the fixed end epoch, which removes most of the initial
infeasibility of the NLP (in full dynamics, several times fewer IPOPT iterations).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.optim.problem import BurnProblem, anti_velocity_u
from lunarcap.physics import constants as C
from lunarcap.physics.elements import mean_motion_and_anomaly
from lunarcap.physics.propagate import Trajectory, propagate
from lunarcap.physics.rocket import burn_duration_estimate_s
from lunarcap.physics.steering import law

#: Tolerance of the guess propagations (the guess need not be exact: IPOPT corrects it).
GUESS_RTOL = 1e-8
GUESS_ATOL = 1e-10


@dataclass
class Guess:
    """Initial guess: burn duration (s), steering u(t) and the propagated arcs."""

    t1_s: float
    burn_u: object          # callable t -> (3,)
    burn: Trajectory        # dense
    coast: Trajectory | None


def make_guess(prob: BurnProblem, t1_s: float | None = None, tune: bool = True) -> Guess:
    """Initial guess: anti-velocity steering for ``t1_s`` (default Eq. 19), then the coast.

    With ``tune`` (elliptic targets) the duration is adjusted so that the guess coast ends
    at a perilune at ``t_end`` (:func:`tune_duration`).
    """
    t1 = t1_s or prob.eq19_duration_s or 600.0
    t1 = min(t1, 0.9 * (prob.t_end_s - prob.t_ign_s), speed_stop_s(prob))
    if tune and prob.free_end:
        guess = guess_orbit_as_asked(prob, t1)
        if guess is not None:
            return guess
    if tune and not prob.circular:
        t1, guess = tune_duration(prob, t1)
        if guess is not None:
            return guess
    return guess_arcs(prob, t1)


def tune_duration(prob: BurnProblem, t1: float, revs: int = 1):
    """Burn duration for which the anti-velocity guess reaches perilune at t_end.

    The total mean anomaly swept from the burn end to t_end, M(t1) + n(t1) (t_end - t_b),
    is continuous in t1; on the osculating Kepler orbit after the burn it must equal
    2 pi revs. Its root is bracketed on a dense grid of the propagated burn, then
    corrected with numerical coasts (the Earth and Sun shift the timing by minutes).
    Returns the duration and the guess propagated for it (None if not found).
    """
    span = prob.t_end_s - prob.t_ign_s
    tmax = min(2.0 * t1, 0.9 * span, speed_stop_s(prob))
    g = guess_arcs(prob, tmax, coast=False)
    ts = np.linspace(0.3 * t1, tmax, 600)
    xs = g.burn(prob.t_ign_s + ts)
    ok = np.hypot(xs[1], xs[2]) < 1
    ts = ts[ok]
    n, M = mean_motion_and_anomaly(xs[:, ok], C.MU_MOON)
    tot = M + n * (span - ts) - 2 * np.pi * revs
    sign = np.nonzero(np.diff(np.sign(tot)) != 0)[0]
    if sign.size == 0:
        return t1, None
    i = sign[0]
    tk = ts[i] - tot[i] * (ts[i + 1] - ts[i]) / (tot[i + 1] - tot[i])
    slope = (tot[i + 1] - tot[i]) / (ts[i + 1] - ts[i])
    for _ in range(4):  # numerical correction of the Kepler root
        arc = guess_arcs(prob, tk)
        _, Mend = mean_motion_and_anomaly(arc.coast.x[:, -1], C.MU_MOON)
        if abs(Mend) < 1e-5:  # ~0.1 s from perilune on a 12 h orbit: ample for a guess
            return float(tk), arc
        tk = tk - Mend / slope
    return float(tk), None


def speed_stop_s(prob: BurnProblem, share: float = 0.9) -> float:
    """Thrust time that removes ``share`` of the initial speed (rocket equation), s.

    Thrust opposite the velocity for longer would stop the spacecraft and turn it round
    (the orbit degenerates, p -> 0): the guess never burns that long. Matters for a burn
    far from the Moon, where the speed is low (a re-planned capture after a fault).
    """
    from lunarcap.physics.elements import speed_from_mee

    x = prob.x0
    v_mps = float(speed_from_mee(x[0], x[1], x[2], x[5], prob.model.mu)) * 1e3
    return float(burn_duration_estimate_s(x[6], share * v_mps, prob.model.thrust_N,
                                          prob.model.isp_s))


def guess_arcs(prob: BurnProblem, t1: float, coast: bool = True) -> Guess:
    """The anti-velocity burn of ``t1`` s from ``prob.x0`` and (optionally) the coast."""
    model = prob.model
    burn = propagate(model, prob.t_ign_s, prob.x0, None, duration_s=t1,
                     u=law("antivelocity"), rtol=GUESS_RTOL, atol=GUESS_ATOL, dense=True,
                     dense_points=120)
    u_of_t = lambda t: anti_velocity_u(burn(t))  # noqa: E731
    if not coast:
        return Guess(t1, u_of_t, burn, None)
    arc = propagate(model, burn.t[-1], burn.x[:, -1], prob.t_end_s, u=None, dense=True,
                    rtol=GUESS_RTOL, atol=GUESS_ATOL)
    return Guess(t1, u_of_t, burn, arc)


def _trial_burn(prob: BurnProblem, tmax: float, halvings: int = 4) -> tuple:
    """(the anti-velocity burn of ``tmax`` s, tmax), or of the longest tmax / 2^k that flies.

    In a gravity field a trial burn long enough to take the orbit into the Moon does not
    propagate (the field's terms grow as r^-(n+1) below its surface: CVODES stops); the
    semi-major axis asked is reached before that on any orbit that can be flown.
    """
    for _ in range(halvings):
        try:
            return guess_arcs(prob, tmax, coast=False).burn, tmax
        except RuntimeError:
            tmax /= 2.0
    return guess_arcs(prob, tmax, coast=False).burn, tmax


def guess_orbit_as_asked(prob: BurnProblem, t1: float) -> Guess | None:
    """Guess for an ellipse as asked (free end epoch): its semi-major axis, then its perilune.

    The anti-velocity burn lasts until the osculating semi-major axis reaches the target's
    (the first crossing on a dense grid of the propagated burn, refined linearly); the
    coast then runs to the perilune nearest the one the plan predicts (``t_end_s``, within
    the end window), where the NLP's end epoch starts. Timing the guess on the predicted
    perilune instead (the paper's tuning) would ask a short burn to move a perilune
    passage that the lunar J2 and the Earth shift by minutes, and start IPOPT far from any
    solution. Returns None if either step finds nothing.
    """
    a_target = prob.target.semi_major_axis_km
    lo_end = prob.t_end_s + prob.end_window_s[0]
    tmax = min(3.0 * t1, 0.9 * (lo_end - prob.t_ign_s), speed_stop_s(prob))
    burn, tmax = _trial_burn(prob, tmax)
    ts = np.linspace(0.05 * t1, tmax, 400)
    xs = burn(prob.t_ign_s + ts)
    e2 = xs[1] ** 2 + xs[2] ** 2
    a = np.where(e2 < 1, xs[0] / np.maximum(1 - e2, 1e-12), np.inf)
    below = np.nonzero(a <= a_target)[0]
    if below.size == 0 or below[0] == 0:
        return None
    i = below[0]
    t1 = float(ts[i - 1] + (ts[i] - ts[i - 1]) * (a[i - 1] - a_target) /
               (a[i - 1] - a[i] if np.isfinite(a[i - 1]) else 1.0))
    g = guess_arcs(prob, t1, coast=False)
    hi_end = prob.t_end_s + prob.end_window_s[1]
    coast = propagate(prob.model, g.burn.t[-1], g.burn.x[:, -1], hi_end, u=None, dense=True,
                      rtol=GUESS_RTOL, atol=GUESS_ATOL, dense_points=2000)
    tt = np.linspace(max(lo_end, coast.t[0]), hi_end, 4000)
    x = coast(tt)
    radial = x[1] * np.sin(x[5]) - x[2] * np.cos(x[5])      # e sin(nu)
    up = np.nonzero((radial[:-1] < 0) & (radial[1:] >= 0))[0]
    if up.size == 0:
        return None
    j = up[np.argmin(np.abs(tt[up] - prob.t_end_s))]
    t_peri = float(tt[j] - radial[j] * (tt[j + 1] - tt[j]) / (radial[j + 1] - radial[j]))
    arc = propagate(prob.model, g.burn.t[-1], g.burn.x[:, -1], t_peri, u=None, dense=True,
                    rtol=GUESS_RTOL, atol=GUESS_ATOL)
    return Guess(t1, g.burn_u, g.burn, arc)
