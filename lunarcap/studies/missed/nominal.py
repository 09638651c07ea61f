"""The nominal a missed-thrust penalty is measured against: the plan's all-burns optimum.

Every ignition is free and the orbit after burn n is free (its coast a decision variable)
up to the same longest period ``max_period_s`` the recovery has, whatever the plan's
formulation (:func:`freed`): the same freedoms on both sides, so that a penalty measures
the contingency and not a difference of bounds. The last burn's orbit is the final one (a
circle or an ellipse as asked): nothing to free.

With a free orbit the all-burns NLP has several local optima, so it is solved from
several declared starts (:data:`NOMINAL_STARTS`, :data:`NOMINAL_STARTS_TWO_BODY`), each
on every mesh up to the finest until it passes verification, and the cheapest verified
optimum is kept.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

from lunarcap.capture.chain import solve_plan
from lunarcap.errors import SolveError
from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.mission.targets import PERILUNE
from lunarcap.optim.collocation import DEFAULT_MESHES, sundman_fractions
from lunarcap.optim.joint import solve_joint, warm_start
from lunarcap.repro.cache import cached, code_version
from lunarcap.studies.missed import MODULES
from lunarcap.studies.missed.makeup import MIN_FIRST_COAST_S, ephemeris_fit, on_meshes
from lunarcap.studies.missed.orbits import after_free_orbit, shortest_free_period_s

#: Longest period of the orbit after burn n, in the recovery and in the nominal alike, h:
#: about twice the paper's 12.235 h, so that a recovery has room to re-plan, while that
#: orbit's apolune (about 17,700 km at a 100 km perilune) stays far inside the Moon's sphere
#: of influence (about 63,000 km). Both sides carry the same bound, so a penalty compares
#: like with like (a nominal may press against it: the README's missed-thrust section).
DEFAULT_MAX_PERIOD_H = 24.0
#: Longest time from the arrival perilune to the end of the capture's last burn, in a
#: recovery, days (``--max-days``): the default of ``lunarcap burns`` (one question asked of
#: a capture by both studies). The paper's plans end their nominal capture about 27 h after
#: the arrival perilune; 3 days leaves room for a make-up to wait a whole orbit of what a
#: late cut-off leaves (burn 1 of the 150 N plan cut at 0.9: a 38 h orbit) and then to fly
#: an orbit at the 24 h bound, and stays within the one ephemeris fit (4 days) a recovery
#: is solved with.
DEFAULT_MAX_DAYS = 3.0
#: Two optima whose orbits after burn n differ by at most this fraction of their period
#: end on the same orbit: the nominal's halfway start is then not solved.
SAME_ORBIT = 0.01


def freed(plan: CapturePlan, i: int) -> CapturePlan:
    """The plan with every ignition free and the orbit after burn ``i`` (0-based) free.

    The orbit after an intermediate burn is the paper's perilune target (Eq. 17) at the
    end of a coast the all-burns NLP chooses (:meth:`CapturePlan.with_coasts`), whether
    the plan asks for it by period or apolune (``formulation: orbit``) or by timing
    (``song2011``): the recovery re-plans from that burn with this freedom, so the
    nominal it is measured against has it too. The last burn's target (the final orbit,
    a circle or an ellipse as asked) is kept.
    """
    free_plan = plan.with_starts(["free"] * plan.n_burns)
    if i + 1 < plan.n_burns and free_plan.targets[i].kind != PERILUNE:
        free_plan = free_plan.with_coasts([free_plan.coast_s(i) if k == i else None
                                           for k in range(plan.n_burns)])
    return free_plan


# ---------------------------------------------------------------------- the starts, declared
@dataclass(frozen=True)
class NominalStart:
    """One start of the nominal's all-burns NLP: the orbit after burn n it starts on.

    Attributes
    ----------
    name : str
        The start in words.
    coast_s : callable(free_plan, i, max_period_s, two_body_s) -> float or None
        The coast after burn ``i`` (0-based) the start's plan has, s (``two_body_s``: that
        coast in the two-body nominal, None if not solved); None: the freed plan's own.
    when : callable(found, i) -> bool
        Whether the start is solved, given the verified optima of the starts before it.
    two_body : bool
        The start needs the two-body nominal (solved first, once).
    """

    name: str
    coast_s: Callable
    when: Callable = lambda found, i: True
    two_body: bool = False


def _ends_apart(found: list, i: int) -> bool:
    """Fewer than two optima, or two ending on orbits more than :data:`SAME_ORBIT` apart."""
    return len(found) < 2 or abs(found[0].plan.coast_s(i) / found[1].plan.coast_s(i) - 1) \
        > SAME_ORBIT


#: The plan's own orbit after burn n.
OWN_ORBIT = NominalStart("the plan's orbit", lambda free_plan, i, longest_s, two_s: None)

#: The nominal's starts in two-body dynamics, all solved. The total depends little on the
#: orbit after burn n (only through the finite burns' losses), and from the plan's orbit
#: alone IPOPT may stop where it started: the longest orbit allowed is the other end.
NOMINAL_STARTS_TWO_BODY = (
    OWN_ORBIT,
    NominalStart("the longest orbit allowed", lambda free_plan, i, longest_s, two_s: longest_s),
)

#: The nominal's starts in any other dynamics. A long free coast needs its mesh spaced for
#: the orbit it ends on, so the two-body optimum's orbit (a continuation in the forces) is
#: the second start; where those two end on different orbits, or one fails, their
#: geometric mean is solved too, the ends of a problem with several local optima.
NOMINAL_STARTS = (
    OWN_ORBIT,
    NominalStart("the two-body optimum's orbit",
                 lambda free_plan, i, longest_s, two_s: two_s, two_body=True),
    NominalStart("halfway (geometric mean)",
                 lambda free_plan, i, longest_s, two_s: math.sqrt(free_plan.coast_s(i) * two_s),
                 when=_ends_apart, two_body=True),
)


# ---------------------------------------------------------------------- the walk
@cached
def nominal(plan: CapturePlan, burn: int = 1, max_period_s: float = DEFAULT_MAX_PERIOD_H *
            3600.0, version: str = "") -> dict:
    """The plan's all-burns optimum, the orbit after ``burn`` free up to ``max_period_s``.

    Pass ``plan.key()``. Every ignition free; burn n's coast (from the perilune before it
    to the one after) a decision variable between the next orbit's coast and
    ``max_period_s`` + 2 h, the osculating period at that perilune at most
    ``max_period_s`` (the recovery's bounds), whatever the plan's formulation
    (:func:`freed`). Each start of :data:`NOMINAL_STARTS` (two-body dynamics:
    :data:`NOMINAL_STARTS_TWO_BODY`) is solved in turn when it applies, and the cheapest
    verified optimum kept; the last burn (the final orbit) has no orbit to free and one
    start, the plan's own chain. Returns ``{"plan": CapturePlan (free ignitions, the
    optimal coasts), "legs": [Solution]}``; raises the last start's error if none is
    verified.
    """
    i = burn - 1
    free_plan = freed(plan, i)
    if free_plan.targets[i].kind != PERILUNE:   # the final orbit: nothing to free
        best = _final_orbit_nominal(free_plan)
    else:
        starts = NOMINAL_STARTS_TWO_BODY if plan.dynamics == "two-body" else NOMINAL_STARTS
        two_s = None
        if any(s.two_body for s in starts):
            two = nominal(plan.with_dynamics("two-body"), burn, max_period_s, version)
            two_s = two["plan"].coast_s(i)
        best = _cheapest(free_plan, i, max_period_s, starts, two_s)
    return {"plan": best.plan, "legs": best.legs}


def _cheapest(free_plan: CapturePlan, i: int, max_period_s: float, starts: tuple,
              two_s: float | None):
    """The cheapest verified optimum of ``starts`` (each :func:`_nominal_from`, in order).

    A start whose plan the checks refuse is no start. Every start's plan is made before
    any is solved. Raises the last error if no start gives a verified optimum.
    """
    plans = []
    for start in starts:
        coast_s = start.coast_s(free_plan, i, max_period_s, two_s)
        plans.append(free_plan if coast_s is None else _coasted(free_plan, i, coast_s))
    found, error = [], None
    for start, start_plan in zip(starts, plans):
        if start_plan is None or not start.when(found, i):
            continue
        try:
            found.append(_nominal_from(start_plan, i, max_period_s))
        except (SolveError, PlanError) as exc:
            error = exc
    if not found:
        raise error
    return min(found, key=lambda r: r.total_delta_v_mps)


def _coasted(free_plan: CapturePlan, i: int, coast_s: float) -> CapturePlan | None:
    """``free_plan`` with the coast after burn ``i`` (0-based) ``coast_s`` (s); None if refused."""
    try:
        return free_plan.with_coasts([coast_s if k == i else None
                                      for k in range(free_plan.n_burns)])
    except PlanError:
        return None


def _final_orbit_nominal(free_plan: CapturePlan):
    """:func:`nominal` of the last burn: the all-burns optimum of the plan's own orbits.

    From the plan's one-at-a-time chain, on each mesh until one passes verification, as
    every other nominal.
    """
    return _joint_on_meshes(free_plan, solve_plan(free_plan))


def _nominal_from(free_plan: CapturePlan, i: int, max_period_s: float):
    """:func:`nominal`'s all-burns optimum from one start (the coasts of ``free_plan``)."""
    seq = solve_plan(free_plan)
    flags = tuple(k == i for k in range(free_plan.n_burns))
    hi = max_period_s + 7200.0
    t = free_plan.nominal_perilunes_s
    span = (t[-1] - t[0]) - free_plan.coast_s(i) + hi
    lo = free_plan.coast_s(i + 1) if i + 1 < free_plan.n_burns else MIN_FIRST_COAST_S
    fit = ephemeris_fit(free_plan, t[0], span)
    return _joint_on_meshes(free_plan, seq, lambda w, k: _widened(w, k, free_plan, i, max_period_s),
                            free_coasts=flags, coast_bounds_s=(lo, hi),
                            max_period_s=max_period_s, fit=fit,
                            min_period_s=shortest_free_period_s(free_plan, i))


def _joint_on_meshes(free_plan: CapturePlan, seq: list, widen=None, **bounds):
    """The all-burns NLP of ``free_plan`` from the chain ``seq``, mesh after mesh.

    Each mesh of :data:`~lunarcap.optim.collocation.DEFAULT_MESHES` until one passes
    verification (a long free coast resolved too coarsely fails it). ``widen(warm, k)``:
    leg ``k``'s warm start as the NLP should have it (default as solved); ``bounds``:
    :func:`~lunarcap.optim.joint.solve_joint`'s free coasts and bounds.
    """
    eph = free_plan.ephemeris_model()
    return on_meshes(meshes=DEFAULT_MESHES, solve=lambda mesh: solve_joint(
        free_plan, None, eph, mesh, **bounds,
        warm=[_remeshed(warm_start(s) if widen is None else widen(warm_start(s), k),
                        s.flight.coast, mesh) for k, s in enumerate(seq)]))


def _widened(warm: tuple, k: int, free_plan: CapturePlan, i: int, max_period_s: float) -> tuple:
    """Leg ``k``'s warm start; burn i + 1's with room for any orbit after burn ``i``.

    The recovery's bound (:func:`lunarcap.studies.missed.orbits.after_free_orbit`), so that
    the nominal keeps the same freedom.
    """
    if k != i + 1:
        return warm
    prob, guess, mc = warm
    return after_free_orbit(prob, free_plan, i, max_period_s), guess, mc


def _remeshed(warm: tuple, coast, mesh) -> tuple:
    """A leg's warm start with its coast mesh made for ``mesh`` (Sundman-spaced)."""
    prob, guess, mc = warm
    if len(mc) != mesh.n_coast + 1:
        mc = sundman_fractions(coast.t, coast.x, mesh.n_coast)
    return prob, guess, mc


def nominal_of(plan: CapturePlan, burn: int, max_period_s: float) -> dict:
    """:func:`nominal` of ``plan`` (its key), cached on disk as the cache switch says.

    No memo in the process: a caller that needs it for several cases solves it once and
    passes it on (:func:`lunarcap.studies.missed.cases.case_result`'s ``nominal``).
    """
    return nominal(plan.key(), int(burn), float(max_period_s), code_version(*MODULES))
