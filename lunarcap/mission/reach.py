"""Whether one impulse near a perilune can reach a circle asked at a later, fixed epoch.

The circle a burn must leave (``target: circular``) is asked at the end of its coast, a
fixed epoch ``t_end``: the osculating orbit there is a circle of radius r (``p = r``,
``f = g = 0``) and the inclination asked, its node and phase free
(:func:`lunarcap.mission.targets.circular_conditions`). An impulse at epoch ``t`` keeps
the spacecraft where it is, so it reaches that circle only if some member of the family,
flown back from ``t_end`` to ``t``, passes through the spacecraft's position there: in
the direction of the spacecraft (two angles, the node and the phase, fix that) *and* at
its distance from the Moon. On a Kepler orbit every member is at distance r all along;
the orbit before the burn has its perilune at r (the plans' perilunes are the circle's
radius), so the impulse is tangential at that perilune. In other forces a member flown
back is not at r: within a metre of it in J2 (the paper's model), but a gravity field
to degree 20 may bring it hundreds of metres below the perilune before the burn
(``tests/mission/test_reach.py``). Then the orbit before the burn, whose lowest point is
that perilune, nowhere meets a member: no impulse reaches the circle, and finite burns
reach it only by thrusting partly radially, at a cost that grows as they shorten (the
limit of ever shorter burns does not exist).

:func:`circle_clearance` measures that: over the window of impulse epochs, the distance
of the orbit before the burn from the Moon less that of the member flown back through
its direction. Each member is found by Newton's method on the two angles (each step a
propagation of the coast backward, in the burn's forces), so the test costs a few dozen
coast propagations instead of the finite-burn solves that would fail.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.targets import Target
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import rv_from_mee
from lunarcap.physics.propagate import propagate

#: Step of the orbit before the burn over the window, s.
STEP_S = 30.0
#: Offsets from the orbit's lowest point (s) at which the member's distance is computed;
#: with the window's ends and halves, where the member is also computed, they bound it.
NEAR_OFFSETS_S = (-STEP_S, 0.0, STEP_S)
#: Newton's method on a member's two angles: converged below this (rad: 1.7 mm at 1738
#: km), within this many steps (each a backward propagation of the coast).
ANGLE_TOL_RAD = 1e-9
MAX_STEPS = 12
#: Finite-difference step of the angles, rad.
FD_STEP_RAD = 1e-6
#: Steps with the Jacobian of a neighbouring member (the chord method) before it is
#: recomputed at every step.
CHORD_STEPS = 3


@dataclass(frozen=True)
class Clearance:
    """How far the orbit before a burn passes above the circle asked, flown back to it.

    Attributes
    ----------
    gap_m : float
        The least, over the window, of the orbit's distance from the Moon less the
        member's through its direction (m; > 0: the orbit passes above every member, and
        no impulse in the window reaches the circle).
    at_offset_s : float
        Where it is least, s from the epoch the window is centred on.
    offsets_s, pre_radius_km, circle_radius_km : ndarray
        The epochs where the member was computed (s from the centre), the orbit's
        distance there and the member's (km).
    propagations : int
        Backward propagations of the coast spent.
    lowest_offset_s : float
        Where the orbit before the burn comes closest to the Moon in the window (s from
        the centre; to :data:`STEP_S`).
    lowest_member : ndarray (7,)
        The member through its direction there, at that epoch (MEE; flown forward to the
        circle's epoch it is the circle asked).
    """

    gap_m: float
    at_offset_s: float
    offsets_s: np.ndarray
    pre_radius_km: np.ndarray
    circle_radius_km: np.ndarray
    propagations: int
    lowest_offset_s: float
    lowest_member: np.ndarray


def circle_state(target: Target, node_rad: float, L_rad: float, mass_kg: float = 1.0):
    """The MEE state (7,) of the member of ``target``'s circle with this node and longitude."""
    t = np.tan(np.radians(target.inclination_deg) / 2.0)
    return np.array([target.radius_km, 0.0, 0.0, t * np.cos(node_rad), t * np.sin(node_rad),
                     L_rad, mass_kg])


def _position(x) -> np.ndarray:
    return np.array(rv_from_mee(*x[:6], C.MU_MOON)[0], float)


class _Members:
    """The circle's members flown back from ``t_end_s`` (counts the propagations)."""

    def __init__(self, model: Model, target: Target, t_end_s: float):
        self.model, self.target, self.t_end_s, self.count = model, target, t_end_s, 0

    def state(self, angles, t_s: float) -> np.ndarray:
        """The member of these angles flown back to ``t_s``: its state (7,)."""
        self.count += 1
        x = circle_state(self.target, angles[0], angles[1])
        return propagate(self.model, self.t_end_s, x, t_s).final

    def through(self, t_s: float, direction, guess, jac=None) -> tuple:
        """(angles, state at ``t_s``, Jacobian) of the member through ``direction``."""
        d = np.asarray(direction, float) / np.linalg.norm(direction)
        e1 = np.cross(d, [0.0, 0.0, 1.0]) if abs(d[2]) < 0.9 else np.cross(d, [1.0, 0, 0])
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(d, e1)

        def residual(a):
            x = self.state(a, t_s)
            r = _position(x)
            u = r / np.linalg.norm(r)
            return np.array([u @ e1, u @ e2]), x

        a = np.asarray(guess, float)
        res, x = residual(a)
        for step in range(MAX_STEPS):
            if np.abs(res).max() < ANGLE_TOL_RAD:
                return a, x, jac
            if jac is None or step >= CHORD_STEPS:   # Newton once the chord is slow
                jac = np.column_stack([(residual(a + FD_STEP_RAD * np.eye(2)[j])[0] - res)
                                       / FD_STEP_RAD for j in range(2)])
            a = a - np.linalg.solve(jac, res)
            res, x = residual(a)
        if np.abs(res).max() < ANGLE_TOL_RAD:
            return a, x, jac
        raise InputError(f"no member of the circle asked passes through the direction "
                         f"{np.round(d, 6).tolist()} at {t_s:.3f} s (angles off by "
                         f"{np.abs(res).max():.2g} rad)")


def _first_guess(target: Target, x_pre, direction, t_s: float, t_end_s: float) -> tuple:
    """Two-body angles of the member through ``direction``: the orbit's node, the phase."""
    node = float(np.arctan2(x_pre[4], x_pre[3]))
    inc = np.radians(target.inclination_deg)
    n_hat = np.array([np.cos(node), np.sin(node), 0.0])
    w = np.array([np.sin(node) * np.sin(inc), -np.cos(node) * np.sin(inc), np.cos(inc)])
    u = float(np.arctan2(direction @ np.cross(w, n_hat), direction @ n_hat))
    n = np.sqrt(C.MU_MOON / target.radius_km ** 3)
    return node, node + u + n * (t_end_s - t_s)


def circle_clearance(model: Model, target: Target, t_end_s: float, t_s: float, x,
                     window_s: float) -> Clearance:
    """How far the orbit through ``x`` at ``t_s`` passes above the circle asked (module doc).

    Parameters
    ----------
    model : Model
        The burn's forces (its ephemeris fit spanning the window and ``t_end_s``).
    target : Target
        A circle (``kind`` circular), asked at ``t_end_s`` (TDB s past J2000).
    t_s : float
        Centre of the window of impulse epochs (the perilune before the burn), TDB s.
    x : (7,)
        The state (p, f, g, h, k, L, m) there.
    window_s : float
        Half-width of the window of impulse epochs, s.

    The orbit's distance is sampled every :data:`STEP_S` over the window; the member
    through its direction is computed at :data:`NEAR_OFFSETS_S` around the lowest
    sample (where the orbit comes closest to the circle) and at the window's ends and
    halves; elsewhere the member's distance is taken as the largest computed.
    """
    if not target.circular:
        raise InputError(f"circle_clearance: the target is a {target.kind}, not a circle")
    x = np.asarray(x, float)
    n = int(np.ceil(window_s / STEP_S))
    grid = STEP_S * np.arange(-n, n + 1)
    back = propagate(model, t_s, x, t_s - grid[-1], t_eval=t_s - grid[n + 1:]).x
    ahead = propagate(model, t_s, x, t_s + grid[-1], t_eval=t_s + grid[n + 1:]).x
    states = np.column_stack([back[:, ::-1], x, ahead])
    pos = np.column_stack([_position(states[:, j]) for j in range(grid.size)])
    radius = np.linalg.norm(pos, axis=0)
    low = int(np.argmin(radius))
    near = [low + int(round(o / STEP_S)) for o in NEAR_OFFSETS_S]
    far = [0, n // 2, n + n // 2, 2 * n]
    picks = sorted({j for j in near + far if 0 <= j < grid.size},
                   key=lambda j: abs(j - low))   # outward from the lowest point
    near_set = set(near)
    members = _Members(model, target, t_end_s)
    jac, member_r, solved = None, {}, {}
    for j in picks:
        # from the nearest member solved, moved as a Kepler circle would move
        near = min(solved, key=lambda i: abs(i - j), default=None)
        two_body = np.array(_first_guess(target, x, pos[:, j] / radius[j], t_s + grid[j],
                                         t_end_s))
        guess = two_body if near is None else solved[near][0] + two_body - solved[near][1]
        angles, xm, jac = members.through(t_s + grid[j], pos[:, j], guess,
                                          jac if j in near_set else None)
        solved[j] = (angles, two_body)
        member_r[j] = float(np.linalg.norm(_position(xm)))
        if j == low:
            lowest = (float(grid[low]), xm)
    top = max(member_r.values())
    gaps = np.array([radius[j] - member_r.get(j, top) for j in range(grid.size)])
    k = int(np.argmin(gaps))
    order = sorted(member_r)
    return Clearance(float(gaps[k] * 1e3), float(grid[k]), grid[order], radius[order],
                     np.array([member_r[j] for j in order]), members.count, *lowest)
