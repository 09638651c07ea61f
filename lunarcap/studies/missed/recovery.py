"""The recovery after a cut-off or a late ignition: where the make-up burn is made.

From the state a fault leaves at ``t_r`` (burn n cut off, after the delay; or burn n's
late ignition), :func:`recovery` answers in one of four ways, in this order:

1. **Nothing to make up** (:func:`nothing_to_make_up`): coasting from that state, the
   spacecraft meets burn n's target where the nominal met it, within the verification
   gate's own tolerances (:mod:`lunarcap.optim.gate`). The make-up burn vanishes and is
   **not flown**: the recovery is the nominal's later burns, as verified. Skipping it is
   the honest answer, not gating a burn of next to nothing with tolerances scaled down to
   it: the orbit left is checked with the full gate, and a burn that is not needed is no
   burn (the transcription resolves burns of 0.5 s and more,
   :data:`lunarcap.mission.plan.MIN_BURN_S`).
2. **No recovery**, with the reason physics gives before any solve
   (:func:`lunarcap.studies.missed.orbits.physical_bound`).
3. **A make-up burn in the window** igniting within ``window_min`` after ``t_r`` (a late
   ignition: exactly then), solved from the declared starts
   (:func:`lunarcap.studies.missed.starts.walk`).
4. **The make-up burn at the next perilune** (a cut-off only, when 3 found no verified
   recovery or one dearer than the nominal burn itself, :func:`dearer_than_the_burn`):
   the same re-plan with the make-up window around the spacecraft's next perilune
   (:func:`next_perilune_window`), the cheaper of the two kept. The final orbit passes
   only through radii between its perilune and apolune: a cut-off of the last burn
   followed by a delay leaves the spacecraft above them until it comes back to perilune,
   where the burn is done again.
"""

from __future__ import annotations

import math

import numpy as np

from lunarcap.mission.plan import MAX_START_MIN, CapturePlan
from lunarcap.optim import flight
from lunarcap.optim.gate import TOL_PERIOD_S, state_failures
from lunarcap.optim.problem import MIN_ORBIT_WINDOW_MIN
from lunarcap.physics.dynamics import Model
from lunarcap.physics.propagate import propagate
from lunarcap.physics.state import State
from lunarcap.studies.missed.makeup import Place
from lunarcap.studies.missed.orbits import (
    period_s,
    physical_bound,
    time_to_perilune_after_impulse_s,
)
from lunarcap.studies.missed.starts import FAILURES, attempt_at, walk

#: Longest half-width of the make-up window around the next perilune, as a fraction of
#: the orbit's period (as the plan's free ignitions, :data:`lunarcap.mission.plan_checks`).
MAX_WINDOW_FRACTION = 0.4


# ---------------------------------------------------------------------- 1. nothing to do
def target_misses(target, x_end, max_period_s: float | None = None) -> list[str]:
    """How the state ``x_end`` misses ``target``, against the verification gate's tolerances.

    The gate's target part (:func:`lunarcap.optim.gate.state_failures`), on a state the
    fault left rather than a solution; with ``max_period_s`` also the period bound of a
    free orbit. Empty if none.
    """
    x = np.asarray(x_end, float)
    out = state_failures(target, x[:6])
    if max_period_s is not None:
        e2 = x[1] ** 2 + x[2] ** 2
        a = x[0] / (1 - e2) if e2 < 1 else math.inf
        if not (math.isfinite(a) and period_s(a) <= max_period_s + TOL_PERIOD_S):
            out.append(f"the orbit is longer than {max_period_s / 3600:g} h")
    return out


def nothing_to_make_up(legs: list, i: int, t_r: float, x_r, max_period_s: float) -> bool:
    """True if ``x_r`` at ``t_r``, coasting, meets burn ``i``'s target as the nominal did.

    Flown in the nominal leg's dynamics to the end of its coast (the perilune where its
    target held) and checked with :func:`target_misses` (the orbit of an intermediate burn
    also within ``max_period_s``, the bound the nominal had).
    """
    prob = legs[i].problem
    if not t_r < prob.t_end_s:
        return False
    end = flight.coast(prob.model, State(t_r, np.asarray(x_r, float)), prob.t_end_s).end
    bound = max_period_s if i + 1 < len(legs) else None
    return not target_misses(prob.target, end.x, bound)


# ---------------------------------------------------------------------- the ladder
def recovery(nplan: CapturePlan, legs: list, i: int, t_r: float, x_r, window_min: tuple,
             max_period_s: float, fit_for, coast: Model, later: bool = True,
             remaining_mps: float | None = None) -> tuple:
    """The recovery from ``x_r`` at ``t_r`` (see the module): ``(how, result, estimate)``.

    ``how``: "none" (nothing to make up: ``result`` None), "window" or "next perilune"
    (``result`` the verified JointResult), or "no recovery" (``result`` the physical
    reason of :func:`physical_bound` for the window). ``fit_for(window)``: the ephemeris
    fit of a recovery whose make-up ignites in ``window`` (min after ``t_r``). ``later``:
    the make-up at the next perilune may be tried (a cut-off, not a late ignition), if
    that perilune comes within ``max_period_s``; where both are verified the cheaper is
    kept (a next perilune's estimate then has ``window_delta_v_mps``: the window's
    recovery burns, m/s). ``remaining_mps``: the delta-V of the nominal burn not flown
    (m/s; default all of it). Raises what the window's :func:`walk` raises if the next
    perilune gives nothing either.
    """
    if nothing_to_make_up(legs, i, t_r, x_r, max_period_s):
        return "none", None, None
    why = physical_bound(nplan, i, t_r, x_r, window_min, max_period_s, coast)
    if why:
        return "no recovery", why, None
    remaining = legs[i].delta_v_mps if remaining_mps is None else remaining_mps

    def at(place: Place) -> tuple:
        return walk(attempt_at(nplan, legs, i, place, max_period_s, not later, remaining))

    found, first = None, None
    try:
        found = ("window",) + at(Place(t_r, x_r, window_min, fit_for(window_min), coast))
    except FAILURES as exc:
        first = exc
    if found is not None and not (later and dearer_than_the_burn(found[1], legs, i, remaining)):
        return found
    place = _at_next_perilune(nplan, legs, i, t_r, x_r, window_min, max_period_s, fit_for,
                              coast) if later else None
    if place is None:
        return _found_or_raise(found, first)
    try:
        res, est = at(place)
    except FAILURES:
        return _found_or_raise(found, first)
    if found is not None:
        if found[1].total_delta_v_mps <= res.total_delta_v_mps:
            return found
        est["window_delta_v_mps"] = found[1].total_delta_v_mps
    est["first_coast_guess_s"] += place.t_s - t_r
    return "next perilune", res, est


def _at_next_perilune(nplan: CapturePlan, legs: list, i: int, t_r: float, x_r,
                      window_min: tuple, max_period_s: float, fit_for,
                      coast: Model) -> Place | None:
    """The place of a make-up at the next perilune after the window; None if none may be.

    The window is +-2 burn durations (at least 30 min) about that perilune, within the 2 h
    a plan's window may span; the recovery resumes where it opens (the coast to there is
    the same coast). None if the orbit is open, the window closes later than
    ``max_period_s`` after ``t_r``, or physics forbids a recovery from there.
    """
    half = min(max(60.0 * MIN_ORBIT_WINDOW_MIN, 2.0 * legs[i].raw.t1_s), 30.0 * MAX_START_MIN)
    window = next_perilune_window(x_r, 60.0 * window_min[1], half)
    if window is None or 60.0 * window[1] > max_period_s:
        return None
    t_b = t_r + 60.0 * window[0]
    x_b = propagate(coast, t_r, np.asarray(x_r, float)[:7], t_b).final
    w_b = from_opening(window)
    if physical_bound(nplan, i, t_b, x_b, w_b, max_period_s, coast):
        return None
    return Place(t_b, x_b, w_b, fit_for(window), coast)


def next_perilune_window(x, after_s: float, half_width_s: float) -> tuple | None:
    """The window (min after the state's epoch) around its next two-body perilune.

    The first perilune later than ``after_s`` of the orbit of ``x``; half-width
    ``half_width_s``, at most :data:`MAX_WINDOW_FRACTION` of the period and never before
    ``after_s``. None if the orbit is open.
    """
    t = time_to_perilune_after_impulse_s(x, 0.0, after_s)
    if not math.isfinite(t):
        return None
    xx = np.asarray(x, float)
    a = xx[0] / (1 - xx[1] ** 2 - xx[2] ** 2)
    w = min(half_width_s, MAX_WINDOW_FRACTION * period_s(a), t - after_s)
    return ((t - w) / 60.0, (t + w) / 60.0)


def from_opening(window: tuple) -> tuple:
    """A window (min) counted from its opening, at most the 2 h a plan's window may span.

    Clamped because two half-widths of 60 min may add up to a hair above 120 min in
    floating point, which the plan's checks refuse.
    """
    return (0.0, min(window[1] - window[0], MAX_START_MIN))


def _found_or_raise(found, first):
    """The window's recovery if there is one, else its error (raised)."""
    if found is None:
        raise first
    return found


def dearer_than_the_burn(res, legs: list, i: int, remaining_mps: float) -> bool:
    """Whether a recovery's penalty exceeds the nominal burn's own delta-V (m/s).

    A make-up that costs more than flying the whole burn again is made where the orbit
    does not suit it (above the final orbit after a delay, say), and the next perilune is
    tried as well. ``remaining_mps``: the delta-V of the nominal burn not flown.
    """
    later = sum(s.delta_v_mps for s in legs[i + 1:])
    return res.total_delta_v_mps - remaining_mps - later > legs[i].delta_v_mps
