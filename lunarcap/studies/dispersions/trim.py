"""Dispersions: the trim that returns a sample's final orbit to the plan's.

After the last burn a dispersed capture is on an orbit near the plan's final one, not on
it (the last burn's own errors are not re-planned). An operations team trims it; the
budget must pay for that trim, or a sample that delivered less delta-V than planned (a
weak last burn, an apolune kilometres high) would count as cheaper than the nominal.

**The trim modelled: two impulses, in the plan's dynamics.** Two impulses (the
Hohmann-like pair that corrects the orbit's size and shape), each with any direction (RTN
components), placed and sized for the least total delta-V |dv1| + |dv2|:

1. *Design, two-body, linear.* From the osculating orbit at the end of the plan's last
   coast (epoch ``t0``), an impulse at ``t1`` changes the elements by B(x(t1)) dv (Gauss's
   equations in modified equinoctial elements, Song et al. 2011 Eq. (2) and (A2)-(A4),
   the same as :func:`lunarcap.physics.dynamics.mee_rates`; in two-body only L moves
   between impulses, so the orbit's shape after both impulses is linear in them to first
   order). For ``t1`` at each of :data:`CANDIDATES` epochs over one revolution and ``t2``
   half a revolution later, the least |dv1| + |dv2| that meets the final orbit's
   conditions (a second-order cone problem, :func:`least_delta_v`) is found; the best
   pair's two epochs are then refined together (Nelder-Mead, ``t2`` within a revolution
   of ``t1``). Apsides are the best places for the size and shape alone, but on the
   paper's polar orbit the apsides can lie anywhere, and there a plane change costs
   v di / |cos u| (u the argument of latitude): at an apsis 3 deg from a pole, 20 times
   its cost at a node. Searching the epochs lets the pair move towards the nodes when the
   plane error dominates.
2. *Correction, in the plan's dynamics.* The two impulses are flown (coast from ``t0``,
   impulse, coast, impulse, coast to the check epoch) with the plan's force model and
   CVODES (rtol 1e-13), and corrected by a chord iteration on the design's Jacobian,
   each step the least change of the impulses that cancels the residual to first order
   (a few tenths of m/s, so the pair stays the least delta-V to second order; re-solving
   the split at each step would wander along the cost's flat directions, e.g. one
   impulse shared between two passes of one apsis), until the orbit at the check epoch
   passes the verification gate (:mod:`lunarcap.optim.gate`: perilune and apolune radii
   within 10 m, 50 m for an ellipse's apolune, its period within 0.5 s, the inclination
   within 1e-4 deg), or :data:`MAX_ITERATIONS` steps fail (an error with the residuals,
   never a number).

**What it must reach.** In full dynamics the osculating elements of the nominal's own
final orbit wander over a revolution (about 1 km in perilune radius in the Moon's J2
field) and drift from one revolution to the next (1e-3 deg of inclination in two):
"the plan's final orbit" is therefore the nominal's final state flown on in the plan's
dynamics to the **check epoch** ``t_c``, a whole number of the plan's final-orbit
periods after the nominal's end (its own phase of that wander), the first at least
:data:`CHECK_AFTER_REV` revolutions after ``t0``; the trimmed orbit's osculating
perilune and apolune radii (for a circle: the elements p, f, g) and inclination there
must be the nominal's within the gate. In two-body it is the plan's target itself.
Phase and node are free.

**Not trimmed**: an orbit already within the gate at the end of the plan's last coast
(the target's own conditions, on the shape only: the re-plan was verified there) has a
trim of exactly 0, and the sample's numbers are those of the study without a trim.

Why impulses and not a finite burn: a trim of a few m/s lasts m dv / T, 11 s for 5 m/s
with the 150 N engine at 336 kg, while the orbit turns n t_b = 0.01 rad; the finite
burn's loss over the impulse is second order in that angle (of order 1e-4 of the trim),
and an impulse pair needs no NLP. The trim's propellant is the rocket equation at the plan's
nominal Isp; the trim's own execution errors (a 1 % error of 5 m/s is 5 cm/s) are not
modelled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from lunarcap.mission.targets import CIRCULAR, ELLIPSE, Target
from lunarcap.optim.flight import coast
from lunarcap.optim.gate import target_failures
from lunarcap.physics import constants as C
from lunarcap.physics.elements import mean_motion_and_anomaly, mee_from_rv, rv_from_mee
from lunarcap.physics.rocket import rocket_mass_after
from lunarcap.physics.state import MASS, State

#: Candidate epochs of the first impulse per revolution (the design's grid).
CANDIDATES = 24
#: Chord steps of the correction in the plan's dynamics before the trim is declared failed.
MAX_ITERATIONS = 10
#: Revolutions after the plan's end before which the trimmed orbit is not checked (the
#: impulses fall within two).
CHECK_AFTER_REV = 2.0


class TrimFailed(Exception):
    """The trim did not bring the final orbit within the gate (the message says how far)."""


@dataclass(frozen=True)
class Trim:
    """A sample's trim: its impulses, cost and the orbit it reaches.

    Attributes
    ----------
    delta_v_mps : float
        |dv1| + |dv2|, m/s (0: no trim was needed).
    propellant_kg : float
        Propellant of the impulses (rocket equation, the plan's Isp), kg.
    impulses : tuple of (epoch s, (R, T, N) m/s)
        Each impulse's epoch (TDB s past J2000) and RTN components.
    check_epoch_s : float or None
        Epoch where the trimmed orbit was checked against the plan's final orbit, s.
    errors : dict
        The trimmed orbit's gate errors there (``rp_error_m``, ``ra_error_m``,
        ``inc_error_deg``, ``period_error_s``) against the plan's final orbit; for no trim,
        the errors of the orbit as reached against the plan's target.
    iterations : int
        Chord steps in the plan's dynamics (0: no trim).
    """

    delta_v_mps: float = 0.0
    propellant_kg: float = 0.0
    impulses: tuple = ()
    check_epoch_s: float | None = None
    errors: dict = field(default_factory=dict)
    iterations: int = 0

    def record(self, t_end_s: float) -> list:
        """The impulses as the table stores them: minutes after ``t_end_s`` and m/s."""
        return [{"after_end_min": (t - t_end_s) / 60.0, "delta_v_mps": float(np.linalg.norm(dv)),
                 "radial_mps": float(dv[0]), "transverse_mps": float(dv[1]),
                 "normal_mps": float(dv[2])} for t, dv in self.impulses]


# ====================================================================== conditions
def shape_failures(target: Target, mee) -> list[str]:
    """The gate's conditions on the orbit's shape that ``mee`` fails against ``target``.

    The target's own errors (:meth:`Target.errors`) without those that depend on where
    on the orbit the state is (flight-path angle and perilune branch).
    """
    err = dict(target.errors(mee), gamma_error_deg=None, branch=None)
    return target_failures(err, target.kind == ELLIPSE)


def conditions(mee, ref, circular: bool) -> np.ndarray:
    """The final orbit's conditions against the reference elements ``ref`` (each 0 there).

    A circle: (p - p_ref)/p_ref, f - f_ref, g - g_ref, tan^2(i/2) - its reference (the
    circle's e = 0 makes e^2 flat, so f and g are matched); otherwise (p - p_ref)/p_ref,
    e^2 - e_ref^2, tan^2(i/2) - its reference (the apsidal line free).
    """
    p, f, g, h, k = (float(v) for v in mee[:5])
    pr, fr, gr, hr, kr = (float(v) for v in ref[:5])
    out = [(p - pr) / pr]
    out += [f - fr, g - gr] if circular else [f * f + g * g - fr * fr - gr * gr]
    return np.array(out + [h * h + k * k - hr * hr - kr * kr])


def _condition_gradient(mee, ref, circular: bool) -> np.ndarray:
    """d(conditions)/d(p, f, g, h, k), rows as :func:`conditions`."""
    p, f, g, h, k = (float(v) for v in mee[:5])
    rows = [[1.0 / float(ref[0]), 0, 0, 0, 0]]
    rows += [[0, 1.0, 0, 0, 0], [0, 0, 1.0, 0, 0]] if circular else [[0, 2 * f, 2 * g, 0, 0]]
    return np.array(rows + [[0, 0, 0, 2 * h, 2 * k]], float)


def gate_errors(mee, ref, circular: bool) -> dict:
    """The gate's errors of ``mee`` against the reference orbit ``ref`` (osculating).

    ``rp_error_m``, ``ra_error_m``, ``inc_error_deg``, ``period_error_s`` (None for a
    circle), and ``gamma_error_deg``/``branch`` None: the position on the orbit is free.
    """
    def shape(x):
        p, e = float(x[0]), math.hypot(float(x[1]), float(x[2]))
        a = p / (1 - e * e)
        return (p / (1 + e), p / (1 - e), 2 * math.degrees(math.atan(math.hypot(x[3], x[4]))),
                2 * math.pi * math.sqrt(a ** 3 / C.MU_MOON))

    rp, ra, inc, period = shape(mee)
    rp0, ra0, inc0, period0 = shape(ref)
    return {"rp_error_m": (rp - rp0) * 1e3, "ra_error_m": (ra - ra0) * 1e3,
            "inc_error_deg": inc - inc0,
            "period_error_s": None if circular else period - period0,
            "gamma_error_deg": None, "branch": None}


# ====================================================================== two-body pieces
def gauss_matrix(mee) -> np.ndarray:
    """(6, 3): the change of (p, f, g, h, k, L) per unit RTN velocity impulse (km/s).

    Song et al. (2011) Eq. (2) with (A2)-(A4) (the thrust terms of
    :func:`lunarcap.physics.dynamics.mee_rates` per unit acceleration, times dt).
    """
    p, f, g, h, k, L = (float(v) for v in mee[:6])
    sq = math.sqrt(p / C.MU_MOON)
    cL, sL = math.cos(L), math.sin(L)
    q = 1 + f * cL + g * sL
    s2 = 1 + h * h + k * k
    w = h * sL - k * cL
    return sq * np.array([
        [0.0, 2 * p / q, 0.0],
        [sL, ((q + 1) * cL + f) / q, -w * g / q],
        [-cL, ((q + 1) * sL + g) / q, w * f / q],
        [0.0, 0.0, s2 * cL / (2 * q)],
        [0.0, 0.0, s2 * sL / (2 * q)],
        [0.0, 0.0, w / q]])


def kepler(x, dt_s: float) -> np.ndarray:
    """The state ``x`` (7,) after ``dt_s`` of two-body coast: only L moves (Kepler's equation)."""
    x = np.array(x, float)
    e = math.hypot(x[1], x[2])
    n, M = mean_motion_and_anomaly(x, C.MU_MOON)
    M1 = float(M) + float(n) * dt_s
    E = M1
    for _ in range(30):
        step = (E - e * math.sin(E) - M1) / (1 - e * math.cos(E))
        E -= step
        if abs(step) < 1e-15:
            break
    nu = 2 * math.atan2(math.sqrt(1 + e) * math.sin(E / 2), math.sqrt(1 - e) * math.cos(E / 2))
    x[5] = math.atan2(x[2], x[1]) + nu
    return x


def impulse(x, dv_rtn_mps, isp_s: float) -> np.ndarray:
    """The state ``x`` (7,) after an impulse (R, T, N m/s in its RTN frame).

    The mass drops by the rocket equation at ``isp_s``; L keeps ``x``'s revolution.
    """
    x = np.asarray(x, float)
    dv = np.asarray(dv_rtn_mps, float)
    r, v = (np.array(a, float) for a in rv_from_mee(*x[:6], C.MU_MOON))
    ir = r / np.linalg.norm(r)
    i_n = np.cross(r, v)
    i_n /= np.linalg.norm(i_n)
    Q = np.column_stack([ir, np.cross(i_n, ir), i_n])
    mee = np.asarray(mee_from_rv(r, v + Q @ dv * 1e-3, C.MU_MOON), float).ravel()
    out = np.array([*mee[:6], rocket_mass_after(x[MASS], float(np.linalg.norm(dv)), isp_s)])
    out[5] = x[5] + math.remainder(out[5] - x[5], 2 * math.pi)
    return out


def _period_s(x) -> float:
    """Osculating Kepler period of the state ``x``, s."""
    n, _ = mean_motion_and_anomaly(np.asarray(x, float), C.MU_MOON)
    return 2 * math.pi / float(n)


# ====================================================================== least delta-V
def least_delta_v(A, b):
    """(x, cost): the least |x[:3]| + |x[3:]| (m/s) with A x = b, or (None, inf).

    A second-order cone problem (two impulses) solved on its null space: A x = b is
    x = x_p + N z (x_p its least-squares solution, N a basis of A's null space from the
    SVD), so the cost |y1(z)| + |y2(z)| is a convex function of the few numbers z,
    minimised by Newton's method on the norms smoothed by 1e-6 m/s, with a backtracking
    line search from z = 0. None when A x = b has no solution (a pair that cannot change
    what is asked, e.g. the inclination at two points over the poles).
    """
    A, b = np.asarray(A, float), np.asarray(b, float)
    scale = 1.0 / np.maximum(np.linalg.norm(A, axis=1), 1e-300)
    A, b = A * scale[:, None], b * scale
    U, s, Vt = np.linalg.svd(A)
    if s[-1] < 1e-9 * s[0]:
        return None, math.inf
    xp = Vt[:len(s)].T @ ((U.T @ b) / s)
    N = Vt[len(s):].T
    y0, N0 = xp.reshape(2, 3), N.reshape(2, 3, -1)   # the two impulses' affine maps of z
    z = np.zeros(N.shape[1])
    eps2 = 1e-12

    def cost(z):
        y = y0 + N0 @ z
        return float(np.sqrt((y * y).sum(axis=1) + eps2).sum()), y

    f, y = cost(z)
    for _ in range(60):
        r = np.sqrt((y * y).sum(axis=1) + eps2)
        u = y / r[:, None]
        J = np.einsum("ki,kij->kj", u, N0)                    # d|y_k|/dz
        g = J.sum(axis=0)
        H = np.einsum("kij,kil->jl", N0 / r[:, None, None], N0) - \
            np.einsum("kj,kl,k->jl", J, J, 1.0 / r)
        step = -np.linalg.solve(H + 1e-12 * np.eye(len(g)), g)
        t = 1.0
        while True:
            f1, y1 = cost(z + t * step)
            if f1 <= f + 1e-4 * t * (g @ step) or t < 1e-8:
                break
            t *= 0.5
        done = f - f1 < 1e-13 * max(1.0, f)
        if f1 < f:
            z, f, y = z + t * step, f1, y1
        if done:
            break
    x = y.ravel()
    return x, float(np.linalg.norm(x[:3]) + np.linalg.norm(x[3:]))


def design(x0, ref, circular: bool, half_s: float):
    """The two-body linear design: (dt1, dt2 after x0's epoch s, A (m x 6, per m/s), x m/s).

    ``x0`` the osculating state at the start, ``ref`` the reference elements,
    ``half_s`` the time between the impulses of the first guesses (half a revolution):
    the best of :data:`CANDIDATES` such pairs over a revolution, then both epochs
    refined together (Nelder-Mead on the least delta-V of each pair).
    """
    from scipy.optimize import minimize

    b = -conditions(x0, ref, circular)
    period = _period_s(x0)
    G = _condition_gradient(x0, ref, circular)

    def linear(dt1, dt2):
        return np.hstack([G @ gauss_matrix(kepler(x0, dt1))[:5],
                          G @ gauss_matrix(kepler(x0, dt2))[:5]]) * 1e-3

    def cost(t):
        if not 0.0 <= t[0] < t[1] <= t[0] + period:
            return math.inf
        return least_delta_v(linear(*t), b)[1]

    grid = [np.array([dt, dt + half_s]) for dt in period * np.arange(CANDIDATES) / CANDIDATES]
    costs = [cost(t) for t in grid]
    j = int(np.argmin(costs))
    if not math.isfinite(costs[j]):
        raise TrimFailed("no pair of impulses within a revolution can reach the plan's "
                         "final orbit from the orbit reached")
    step = period / CANDIDATES
    best = minimize(cost, grid[j], method="Nelder-Mead",
                    options={"initial_simplex": [grid[j], grid[j] + [step, 0],
                                                 grid[j] + [0, step]],
                             "xatol": period / 3600, "fatol": 1e-4})
    t = best.x if best.fun < costs[j] else grid[j]
    A = linear(*t)
    return float(t[0]), float(t[1]), A, least_delta_v(A, b)[0]


# ====================================================================== the trim
def _fly(model, s1: State, x_mps, t2_s: float, t_c_s: float, isp_s: float) -> np.ndarray:
    """The state at ``t_c_s`` after the impulses ``x_mps`` at ``s1`` and at ``t2_s``."""
    xa = impulse(s1.x, x_mps[:3], isp_s)
    xb = coast(model, State(s1.t_s, xa), t2_s).end.x
    xc = impulse(xb, x_mps[3:], isp_s)
    return coast(model, State(t2_s, xc), t_c_s).end.x


def trim_orbit(model, target: Target, t0_s: float, x0, reference, isp_s: float) -> Trim:
    """The trim of the orbit ``x0`` (7,) at ``t0_s`` to the plan's final orbit (the module).

    ``model``: the plan's dynamics; ``reference(t_s)``: (t_c, state (7,)), the plan's
    final orbit flown on to its first check epoch at or after ``t_s``; ``isp_s``: the
    engine's. TrimFailed if the correction does not pass the gate.
    """
    x0 = np.asarray(x0, float)
    if not shape_failures(target, x0[:6]):
        err = dict(target.errors(x0[:6]))
        return Trim(errors={k: err[k] for k in ("rp_error_m", "ra_error_m", "inc_error_deg",
                                                "period_error_s")})
    circular = target.kind == CIRCULAR
    p0 = _period_s(x0)
    t_c, ref = reference(t0_s + CHECK_AFTER_REV * p0)
    half_s = 0.25 * (p0 + _period_s(ref))
    dt1, dt2, A, x = design(x0, ref, circular, half_s)
    t1, t2 = t0_s + dt1, t0_s + dt2
    if t2 > t_c:
        raise TrimFailed(f"the trim's impulses ({(t2 - t0_s) / 3600:.2f} h after the plan's "
                         f"end) fall after its check epoch")
    s1 = coast(model, State(t0_s, x0), t1).end
    fails = []
    for it in range(1, MAX_ITERATIONS + 1):
        xc = _fly(model, s1, x, t2, t_c, isp_s)
        err = gate_errors(xc, ref, circular)
        fails = target_failures(err, not circular)
        if not fails:
            return Trim(float(np.linalg.norm(x[:3]) + np.linalg.norm(x[3:])),
                        float(x0[MASS] - xc[MASS]), ((t1, x[:3].copy()), (t2, x[3:].copy())),
                        t_c, {k: err[k] for k in ("rp_error_m", "ra_error_m", "inc_error_deg",
                                                  "period_error_s")}, it)
        x = x + np.linalg.lstsq(A, -conditions(xc, ref, circular), rcond=None)[0]
    raise TrimFailed(f"the trim to the final orbit misses it after {MAX_ITERATIONS} "
                     f"corrections in the plan's dynamics: " + "; ".join(fails))
