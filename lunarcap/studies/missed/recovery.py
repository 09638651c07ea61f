"""The recovery after a cut-off or a late ignition: where the make-up burn is made.

From the state a fault leaves at ``t_r`` (burn n cut off, after the delay; or burn n's
late ignition), :func:`recovery` answers in one of three ways:

1. **Nothing to make up** (:func:`nothing_to_make_up`): coasting from that state, the
   spacecraft meets burn n's target where the nominal met it, within the verification
   gate's own tolerances (:mod:`lunarcap.optim.gate`). The make-up burn vanishes and is
   **not flown**: the recovery is the nominal's later burns, as verified. Skipping it is
   the honest answer, not gating a burn of next to nothing with tolerances scaled down to
   it: the orbit left is checked with the full gate, and a burn that is not needed is no
   burn (the transcription resolves burns of 0.5 s and more,
   :data:`lunarcap.mission.plan.MIN_BURN_S`).
2. **A make-up burn** at the first of the declared places (:data:`WAITS`, each a
   :class:`Wait`) that gives a verified recovery, solved there from the declared starts
   (:func:`lunarcap.studies.missed.starts.walk`): **in the window** igniting within
   ``window_min`` after ``t_r`` (a late ignition: exactly then); **at the next
   perilune** of the orbit the fault left (a cut-off only), where the window gives no
   verified recovery, is refused, or costs more than the nominal burn itself
   (:func:`dearer_than_the_burn`; the cheaper of the two kept); **at a later perilune**
   (up to :data:`LATER_PERILUNES`) in perturbed dynamics where the one before failed.
   The final orbit passes only through radii between its perilune and apolune: a cut-off
   of the last burn followed by a delay leaves the spacecraft above them until it comes
   back to perilune, where the burn is done again.
3. **No recovery**, every place refused with its reason before any solve: physics (the
   spacecraft outside the Moon's sphere of influence; on an open orbit, with no perilune
   to come back to) or a limit the user sets, named with what lifting it would take
   (``--max-period-h``: :func:`lunarcap.studies.missed.orbits.physical_bound`;
   ``--max-days``: the capture from there cannot end by the deadline, :func:`_too_late`).
   A solver's failure at every place tried is raised, not called "no recovery".
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from lunarcap.mission.plan import MAX_START_MIN, CapturePlan
from lunarcap.optim import flight
from lunarcap.optim.gate import TOL_PERIOD_S, state_failures
from lunarcap.optim.problem import MIN_ORBIT_WINDOW_MIN
from lunarcap.physics.dynamics import Model
from lunarcap.physics.propagate import propagate
from lunarcap.physics.state import State
from lunarcap.studies.missed.makeup import DEADLINE_MARGIN_S, Place
from lunarcap.studies.missed.orbits import (
    classify,
    make_up_estimate,
    period_s,
    physical_bound,
    shortest_free_period_s,
    soi_radius_km,
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


# ---------------------------------------------------------------------- the places
@dataclass(frozen=True)
class Fault:
    """What every place of a recovery sees: the state a fault left and the study's limits.

    Attributes
    ----------
    nplan, legs, i : the nominal's plan and Solutions, the faulty burn (0-based)
    t_s, x : epoch (TDB s past J2000) and state the recovery starts from
    window_min : (float, float)
        The make-up's ignition window after ``t_s``, min.
    max_period_s : float
        Longest period of the orbit after burn ``i``, s (``--max-period-h``).
    deadline_s : float
        Epoch by which the capture must end (its last burn), s: the arrival perilune plus
        ``--max-days``.
    fit_for, coast : the ephemeris fit of a window (min after ``t_s``) and a longest
        make-up orbit (s), the coast's Model
    later : bool
        The make-up may wait for a perilune (a cut-off; not a late ignition).
    remaining_mps : float
        Delta-V of the nominal burn ``i`` not flown, m/s.
    """

    nplan: CapturePlan
    legs: list
    i: int
    t_s: float
    x: object
    window_min: tuple
    max_period_s: float
    deadline_s: float
    fit_for: Callable
    coast: Model
    later: bool
    remaining_mps: float


@dataclass(frozen=True)
class Wait:
    """One place the make-up burn may be made, in the order :func:`recovery` tries them.

    Attributes
    ----------
    name : str
        The place in words ("in the window", "at the next perilune", ...).
    place : callable(Fault) -> Place or str
        The place (:class:`~lunarcap.studies.missed.makeup.Place`), or why it cannot be:
        a text naming what decides it (physics, ``--max-period-h``, ``--max-days``).
    when : callable(found, tried, Fault) -> bool
        Whether it is tried, given the recoveries found so far (``(how, result, estimate)``)
        and the places tried before it (their names).
    """

    name: str
    place: Callable
    when: Callable


def _window(f: Fault):
    """The make-up in its window after the fault: refused by physics or the limits."""
    why = physical_bound(f.nplan, f.i, f.t_s, f.x, f.window_min, f.max_period_s, f.coast) \
        or _too_late(f, f.t_s + 60.0 * f.window_min[0], "in the window")
    if why:
        return why
    longest = _longest_s(f, f.t_s + 60.0 * f.window_min[0])
    return Place(f.t_s, f.x, f.window_min, f.fit_for(f.window_min, longest), f.coast,
                 f.deadline_s, longest)


def _perilune(k: int):
    """The place of a make-up at the ``k``-th perilune after the window (:func:`_at_perilune`)."""
    return lambda f: _at_perilune(f, k)


def _always(found, tried, f: Fault) -> bool:
    return True


def _if_wanted(found, tried, f: Fault) -> bool:
    """A cut-off whose window gave nothing verified, or a recovery dearer than the burn."""
    return f.later and (not found or dearer_than_the_burn(found[0][1], f.legs, f.i,
                                                          f.remaining_mps))


def _if_the_last_failed(found, tried, f: Fault) -> bool:
    """Nothing found yet, the perilune before tried and failed, and perturbed dynamics.

    In two-body dynamics every perilune of the orbit is the same problem shifted in time,
    so a failure at one is a failure at every one.
    """
    return f.later and not found and bool(tried) and tried[-1].startswith("at ") and \
        f.nplan.dynamics != "two-body"


#: The places of a make-up, in order: the window after the fault, then the perilunes of
#: the orbit it left, up to :data:`LATER_PERILUNES` of them (each refused beyond the
#: deadline; a later one tried only where the one before failed: each failure is a whole
#: walk of the starts, minutes in full dynamics).
LATER_PERILUNES = 3
WAITS = (
    Wait("in the window", _window, _always),
    Wait("at the next perilune", _perilune(1), _if_wanted),
) + tuple(Wait(f"at perilune {k} after the window", _perilune(k), _if_the_last_failed)
          for k in range(2, LATER_PERILUNES + 1))


# ---------------------------------------------------------------------- the walk
def recovery(nplan: CapturePlan, legs: list, i: int, t_r: float, x_r, window_min: tuple,
             max_period_s: float, fit_for, coast: Model, later: bool = True,
             remaining_mps: float | None = None, deadline_s: float = math.inf) -> tuple:
    """The recovery from ``x_r`` at ``t_r`` (see the module): ``(how, result, estimate)``.

    ``how``: "none" (nothing to make up: ``result`` None), the name of the place of the
    make-up (a :class:`Wait`'s: "in the window", "at the next perilune", ...; ``result``
    the verified JointResult), or "no recovery" (``result`` the reasons every place gave,
    in order). ``fit_for(window)``: the ephemeris fit of a recovery whose make-up ignites
    in ``window`` (min after ``t_r``). ``later``: the make-up may wait for a perilune (a
    cut-off, not a late ignition). ``deadline_s``: the epoch by which the capture must end
    (s). Where the window's recovery and a perilune's are both verified the cheaper is
    kept (a perilune's estimate then has ``window_delta_v_mps``: the window's recovery
    burns, m/s; and ``window``: why the window's was not kept). ``remaining_mps``: the
    delta-V of the nominal burn not flown (m/s; default all of it). Raises the first
    solver failure if no place gives a recovery and one was tried.
    """
    if nothing_to_make_up(legs, i, t_r, x_r, max_period_s):
        return "none", None, None
    f = Fault(nplan, legs, i, t_r, x_r, window_min, max_period_s, deadline_s, fit_for, coast,
              later, legs[i].delta_v_mps if remaining_mps is None else remaining_mps)
    found, tried, refused, failed = [], [], [], []
    for wait in WAITS:
        if not wait.when(found, tried, f):
            continue
        place = wait.place(f)
        if isinstance(place, str):
            refused.append((wait.name, place))
            if wait.name != "in the window":
                break   # a later perilune is later still
            continue
        tried.append(wait.name)
        longest = min(max_period_s, place.max_period_s)
        try:
            res, est = walk(attempt_at(nplan, legs, i, place, longest, not later,
                                       f.remaining_mps))
        except FAILURES as exc:
            failed.append(exc)
            continue
        est["first_coast_guess_s"] += place.t_s - t_r
        if longest < max_period_s:
            est["deadline_period_h"] = longest / 3600.0
        found.append((wait.name, res, est))
        if wait.name == "in the window" and not _if_wanted(found, tried, f):
            return found[0]
    return _outcome(found, refused, failed)


def _outcome(found: list, refused: list, failed: list) -> tuple:
    """The walk's answer: the cheapest place found, else no recovery or the first failure.

    A recovery away from the window carries why the window's was not kept (its
    estimate's ``window_delta_v_mps``, or the window's refusal as ``window``).
    """
    if found:
        how, res, est = min(found, key=lambda r: r[1].total_delta_v_mps)
        if how != "in the window":
            window = next((r for r in found if r[0] == "in the window"), None)
            if window is not None:
                est["window_delta_v_mps"] = window[1].total_delta_v_mps
            est["window"] = next((why for name, why in refused if name == "in the window"), "")
        return how, res, est
    if failed:
        raise failed[0]
    return "no recovery", "; ".join(
        why if name == "in the window" else f"no make-up {name}: {why}"
        for name, why in refused), None


def _later_s(f: Fault) -> float:
    """The nominal's coasts from the orbit after burn ``i`` to the last burn, s."""
    return sum(f.nplan.coast_s(k) for k in range(f.i + 1, f.nplan.n_burns - 1))


def _longest_s(f: Fault, t_make_s: float) -> float:
    """The longest orbit after a make-up made at ``t_make_s``, s.

    ``--max-period-h``, or shorter where the deadline leaves less: that orbit and the
    nominal's coasts to the last burn must end by it (the NLP then carries the deadline
    itself, :func:`~lunarcap.studies.missed.makeup._solve_recovery`). The last burn's
    make-up orbit is the final orbit: ``--max-period-h``.
    """
    if f.i + 1 >= f.nplan.n_burns:
        return f.max_period_s
    return min(f.max_period_s, f.deadline_s - t_make_s - _later_s(f))


def _too_late(f: Fault, t_make_s: float, where: str) -> str:
    """Why a make-up made at ``t_make_s`` cannot end the capture in time, or "".

    The earliest end of such a capture: the make-up then, the shortest free orbit after
    it (an intermediate burn's, :func:`~lunarcap.studies.missed.orbits.
    shortest_free_period_s`: the next burn is made at that orbit's perilune, one period
    after the make-up's), the nominal's coasts to the last burn; for the last burn, its
    ignition. ``t_make_s``: the window's opening, or the perilune a make-up waits for.
    Refused too where that end leaves less than
    :data:`~lunarcap.studies.missed.makeup.DEADLINE_MARGIN_S` before the deadline: the
    burns (impulses in this count) and the drift of the perilunes need it: with less,
    the make-up orbit is squeezed to within minutes of the shortest and the NLP does not
    converge.
    """
    t0 = f.nplan.nominal_perilunes_s[0]
    end = t_make_s
    if f.i + 1 < f.nplan.n_burns:
        end += shortest_free_period_s(f.nplan, f.i) + _later_s(f)
    if end + DEADLINE_MARGIN_S <= f.deadline_s:
        return ""
    days = (f.deadline_s - t0) / 86400.0
    return (f"a make-up {where} ({(t_make_s - t0) / 3600:.1f} h after the arrival perilune) "
            f"ends the capture at least {(end - t0) / 3600:.1f} h after it, "
            + (f"later than the {days:g} days allowed (--max-days)" if end > f.deadline_s
               else f"less than {DEADLINE_MARGIN_S / 3600:g} h before the {days:g} days "
                    f"allowed run out (--max-days; the burns themselves, minutes each, and "
                    f"the perilunes' drift need that room)"))


def _at_perilune(f: Fault, k: int):
    """The place of a make-up at the ``k``-th perilune after the window, or why none may be.

    The window is +-2 burn durations (at least 30 min) about that perilune, within the 2 h
    a plan's window may span; the recovery resumes where it opens (the coast to there is
    the same coast). Refused where the orbit is open or the spacecraft outside the Moon's
    sphere of influence (it does not come back to a perilune), where the capture could not
    end by the deadline (``--max-days``, :func:`_too_late`), or where physics forbids a
    recovery from there (:func:`physical_bound`).
    """
    x = np.asarray(f.x, float)[:7]
    half = min(max(60.0 * MIN_ORBIT_WINDOW_MIN, 2.0 * f.legs[f.i].raw.t1_s),
               30.0 * MAX_START_MIN)
    window = next_perilune_window(x, 60.0 * f.window_min[1], half, k)
    if window is None:
        return ("on an open orbit (two-body energy >= 0) the spacecraft does not come back to "
                "a perilune")
    soi = soi_radius_km(f.t_s, f.nplan.ephemeris)
    r = classify(x, f.t_s, f.nplan.ephemeris)["r_km"]
    if r > soi:
        return (f"{r:,.0f} km from the Moon, outside its sphere of influence ({soi:,.0f} km), "
                f"the spacecraft's return is the Earth's to decide, not a lunar orbit's")
    t_peri = f.t_s + 30.0 * (window[0] + window[1])   # its centre
    late = _too_late(f, t_peri, f"{(t_peri - f.t_s) / 3600:.1f} h after the fault")
    if late:
        return late + _waiting_cost(f, x, window)
    longest = _longest_s(f, t_peri)
    fit = f.fit_for(window, longest)
    # the window's fit covers a perilune within max_period_s of the fault; a later one
    # is flown with the fit made for its own window
    coast = f.coast if 60.0 * window[1] <= f.max_period_s else replace(f.coast, fit=fit)
    t_b = f.t_s + 60.0 * window[0]
    x_b = propagate(coast, f.t_s, x, t_b).final
    w_b = from_opening(window)
    why = physical_bound(f.nplan, f.i, t_b, x_b, w_b, f.max_period_s, coast)
    if why:
        return why
    return Place(t_b, x_b, w_b, fit, coast, f.deadline_s, longest)


def _waiting_cost(f: Fault, x, window: tuple) -> str:
    """What a make-up at that perilune would cost: the two-body tangential impulse there, text."""
    t_p = 60.0 * 0.5 * (window[0] + window[1])
    x_p = propagate(Model("two-body", 0.0, f.coast.isp_s), 0.0, x, t_p).final
    est = make_up_estimate(x_p, f.nplan.targets[f.i].radius_km, f.max_period_s)
    return (f"; at that perilune an impulsive make-up would cost about "
            f"{est['delta_v_mps']:.0f} m/s")


def next_perilune_window(x, after_s: float, half_width_s: float, k: int = 1) -> tuple | None:
    """The window (min after the state's epoch) around its ``k``-th two-body perilune.

    The ``k``-th perilune later than ``after_s`` of the orbit of ``x`` (1: the first);
    half-width ``half_width_s``, at most :data:`MAX_WINDOW_FRACTION` of the period and
    never before ``after_s``. None if the orbit is open.
    """
    t = time_to_perilune_after_impulse_s(x, 0.0, after_s)
    if not math.isfinite(t):
        return None
    xx = np.asarray(x, float)
    a = xx[0] / (1 - xx[1] ** 2 - xx[2] ** 2)
    t += (k - 1) * period_s(a)
    w = min(half_width_s, MAX_WINDOW_FRACTION * period_s(a), t - after_s)
    return ((t - w) / 60.0, (t + w) / 60.0)


def from_opening(window: tuple) -> tuple:
    """A window (min) counted from its opening, at most the 2 h a plan's window may span.

    Clamped because two half-widths of 60 min may add up to a hair above 120 min in
    floating point, which the plan's checks refuse.
    """
    return (0.0, min(window[1] - window[0], MAX_START_MIN))


def dearer_than_the_burn(res, legs: list, i: int, remaining_mps: float) -> bool:
    """Whether a recovery's penalty exceeds the nominal burn's own delta-V (m/s).

    A make-up that costs more than flying the whole burn again is made where the orbit
    does not suit it (above the final orbit after a delay, say), and the next perilune is
    tried as well. ``remaining_mps``: the delta-V of the nominal burn not flown.
    """
    later = sum(s.delta_v_mps for s in legs[i + 1:])
    return res.total_delta_v_mps - remaining_mps - later > legs[i].delta_v_mps
