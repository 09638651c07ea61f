"""The starts of a recovery's NLP, declared in order, and the one loop that walks them.

The make-up NLP (:func:`lunarcap.studies.missed.makeup.recover`) has local optima and
fails from some guesses, so a recovery from one place is solved from several starts. Each
:class:`Start` declares its guess, its meshes, when it is tried and what it is compared
with; :func:`walk` tries them in order and keeps the cheapest verified recovery:

* two-body dynamics (:data:`TWO_BODY_STARTS`): the first verified recovery is kept. The
  plan's guesses first (the make-up sized from the two-body delta-V actually needed);
  where IPOPT fails from there, the nominal's (a make-up of the delta-V the nominal burn
  had left, its orbit reaching the nominal's next perilune, the later burns flying the
  nominal's steering); where both fail and the nominal's perilune after burn n is still
  ahead, the plan's guesses again with the make-up orbit's coast ending there; where
  those fail too, the aimed make-up (:func:`_aimed`): a burn along the fixed direction of
  the cheapest impulse onto an orbit within the bounds, tuned so that the finite burn
  lands on it. Far from the Moon on an outbound leg (a long fault after a cut-off that
  left a hyperbola) the others thrust against the velocity, which is mostly radial
  there, and remove the transverse speed a low perilune needs; the aimed one keeps it.
  It starts on the second mesh: on the first, where the make-up burn is long and far
  out, a converged solution may fail verification by thousands of km.
* any other dynamics (:data:`STARTS`): first the same recovery solved in two-body
  dynamics and flown in the plan's as the guess (a continuation in the forces), kept at
  once if it costs at most :data:`CONTINUATION_MARGIN` more than that two-body recovery
  (the same optimum, the Earth, the Sun and J2 aside); otherwise the plan's and the
  nominal's starts are solved too (the third and the aimed one as in two-body dynamics),
  and the cheapest verified kept. One still more than the margin above the two-body
  recovery is labelled a possible local optimum (its penalty an upper bound). The meshes
  begin at the second: with the Earth, the Sun and J2 the coarsest mesh's recoveries
  mostly fail verification, and each failure costs that mesh's NLP build.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from lunarcap.errors import SolveError
from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.mission.targets import PERILUNE
from lunarcap.physics.propagate import propagate
from lunarcap.studies.missed.makeup import (
    MIN_FIRST_COAST_S,
    RECOVERY_MESHES,
    Place,
    RecoveryGuess,
    recover,
)
from lunarcap.studies.missed.orbits import aimed_burn, shortest_free_period_s

#: A full-dynamics recovery started from the two-body one is taken as found if it costs at
#: most this fraction more than the two-body recovery; otherwise the other starts are
#: solved too. Where both are the same optimum they differ by the Earth's and the Sun's
#: effect, 0.2-2.5 % where measured; at 5 % a costlier local optimum passed (the tests).
#: One margin for every plan, so a plan whose own nominal costs more than that in full
#: dynamics can have a labelled row that is its true optimum.
CONTINUATION_MARGIN = 0.03

#: Failures :func:`walk` catches and moves on from: a solver's (SolveError), a re-plan the
#: plan's checks refuse (PlanError), a guess whose propagation failed (RuntimeError).
FAILURES = (SolveError, PlanError, RuntimeError)


@dataclass(frozen=True)
class Attempt:
    """A recovery from one place, as every start of :func:`walk` sees it.

    Attributes
    ----------
    nplan : CapturePlan
        The nominal's plan, in the dynamics solved.
    i : int
        The faulty burn, 0-based.
    place : Place
        The state the recovery starts from and the make-up's window.
    max_period_s : float
        Longest period of the free orbit after burn ``i``, s.
    late : bool
        A late ignition: a guess flying a whole burn's steering flies the make-up's too.
    legs : list
        The nominal's Solutions from burn ``i``.
    remaining_mps : float
        Delta-V of the nominal burn ``i`` not flown, m/s.
    nominal_coast_s : float or None
        From ``place`` to the nominal's perilune after burn ``i``, s, where that perilune is
        still ahead of the window and the orbit after burn ``i`` is free; else None.
    """

    nplan: CapturePlan
    i: int
    place: Place
    max_period_s: float
    late: bool
    legs: list
    remaining_mps: float
    nominal_coast_s: float | None


def attempt_at(nplan: CapturePlan, legs: list, i: int, place: Place, max_period_s: float,
               late: bool, remaining_mps: float) -> Attempt:
    """The :class:`Attempt` of a recovery of burn ``i`` from ``place`` (``legs``: the nominal's)."""
    coast_s = nplan.nominal_perilunes_s[i + 1] - place.t_s
    if nplan.targets[i].kind != PERILUNE or \
            coast_s < 60.0 * place.window_min[1] + MIN_FIRST_COAST_S:
        coast_s = None
    return Attempt(nplan, i, place, max_period_s, late, legs[i:], remaining_mps, coast_s)


# ---------------------------------------------------------------------- the starts, declared
@dataclass(frozen=True)
class Start:
    """One start of a recovery's NLP.

    Attributes
    ----------
    name : str
        The start in words.
    guess : callable(Attempt) -> RecoveryGuess or None
        The guess the NLP starts from; None where the start does not apply. It may solve
        (the continuation solves the two-body recovery), and raise what a solve raises.
    meshes : tuple of Mesh
        The meshes it is solved on, in turn (:func:`~lunarcap.studies.missed.makeup.on_meshes`).
    when : callable(found) -> bool
        Whether it is tried, given the verified recoveries of the starts before it.
    enough : callable(result, two_body_mps) -> bool
        Whether its verified recovery is kept at once, compared with the two-body
        recovery's delta-V (m/s, None if none); otherwise the cheapest found is kept.
    reported : bool
        Its failure is the one reported when no start gives a recovery (False: only if no
        reported start failed; the continuation's failure may be its two-body solve's).
    """

    name: str
    guess: Callable
    meshes: tuple
    when: Callable = lambda found: True
    enough: Callable = lambda res, two_body_mps: False
    reported: bool = True


def _nothing_found(found: list) -> bool:
    return not found


def _at_once(res, two_body_mps) -> bool:
    return True


def _plausible(res, two_body_mps) -> bool:
    """At most :data:`CONTINUATION_MARGIN` above the two-body recovery's delta-V."""
    return res.total_delta_v_mps <= (1.0 + CONTINUATION_MARGIN) * two_body_mps


def _plans(a: Attempt) -> RecoveryGuess:
    """The plan's guesses: the make-up sized from the two-body estimate, anti-velocity."""
    return RecoveryGuess(late=a.late)


def _nominals(a: Attempt) -> RecoveryGuess:
    """The nominal's: the delta-V its burn had left, its steering, its next perilune."""
    return RecoveryGuess(legs=a.legs, late=a.late, dv_mps=a.remaining_mps,
                         first_coast_s=a.nominal_coast_s)


def _plans_on_the_nominals_coast(a: Attempt) -> RecoveryGuess | None:
    """The plan's guesses with the make-up orbit ending at the nominal's next perilune."""
    if a.nominal_coast_s is None:
        return None
    return RecoveryGuess(late=a.late, first_coast_s=a.nominal_coast_s)


def _aimed(a: Attempt) -> RecoveryGuess | None:
    """The make-up aimed by the cheapest impulse onto an orbit within the bounds.

    At the window's opening, the finite burn along a fixed direction that
    :func:`~lunarcap.studies.missed.orbits.aimed_burn` tunes onto an orbit with the
    target's perilune radius and a period between the shortest free one and
    ``max_period_s``; the make-up orbit's coast ends at its next perilune. None where the
    make-up's orbit is not free (the final orbit's burn) or no such orbit passes there.
    """
    if a.nplan.targets[a.i].kind != PERILUNE:
        return None
    p = a.place
    t_open = p.t_s + 60.0 * p.window_min[0]
    x = np.asarray(p.x, float)
    x_open = propagate(p.coast, p.t_s, x, t_open).final if t_open > p.t_s else x
    aim = aimed_burn(p.coast, t_open, x_open, a.nplan.targets[a.i].radius_km,
                     (shortest_free_period_s(a.nplan, a.i), a.max_period_s),
                     a.nplan.engine.thrust_N)
    if aim is None:
        return None
    coast = t_open - p.t_s + aim["burn_s"] + aim["coast_s"]
    return RecoveryGuess(late=a.late, dv_mps=aim["delta_v_mps"], aim_kmps=tuple(aim["dv_kmps"]),
                         first_coast_s=max(coast, 60.0 * p.window_min[1] + MIN_FIRST_COAST_S))


def _two_body_recovery(a: Attempt) -> RecoveryGuess:
    """The same recovery solved in two-body dynamics (:data:`TWO_BODY_STARTS`), as a guess.

    Every leg of it (the make-up's ignition, delta-V and steering, its coast, the later
    burns' steering) is flown in the plan's dynamics; its delta-V is what the recovery
    from it is compared with.
    """
    two = replace(a, nplan=a.nplan.with_dynamics("two-body"),
                  place=replace(a.place, coast=replace(a.place.coast, mode="two-body")))
    res2, _ = walk(two)
    legs = res2.legs
    return RecoveryGuess(legs=legs, late=True, dv_mps=legs[0].delta_v_mps,
                         first_coast_s=res2.plan.coast_s(0),
                         ignition_min=(legs[0].problem.t_ign_s - a.place.t_s) / 60.0,
                         two_body_mps=res2.total_delta_v_mps)


#: The starts in two-body dynamics, in order: the first verified recovery is kept.
TWO_BODY_STARTS = (
    Start("the plan's guesses", _plans, RECOVERY_MESHES, enough=_at_once),
    Start("the nominal's", _nominals, RECOVERY_MESHES, enough=_at_once),
    Start("the plan's guesses on the nominal's coast", _plans_on_the_nominals_coast,
          RECOVERY_MESHES, when=_nothing_found, enough=_at_once),
    Start("the aimed make-up", _aimed, RECOVERY_MESHES[1:], when=_nothing_found,
          enough=_at_once),
)

#: The starts in any other dynamics, in order: the continuation from the two-body
#: recovery, kept at once if plausible; else the cheapest verified of all.
STARTS = (
    Start("the two-body recovery", _two_body_recovery, RECOVERY_MESHES[1:],
          enough=_plausible, reported=False),
    Start("the plan's guesses", _plans, RECOVERY_MESHES[1:]),
    Start("the nominal's", _nominals, RECOVERY_MESHES[1:]),
    Start("the plan's guesses on the nominal's coast", _plans_on_the_nominals_coast,
          RECOVERY_MESHES[1:], when=_nothing_found),
    Start("the aimed make-up", _aimed, RECOVERY_MESHES[1:], when=_nothing_found),
)


# ---------------------------------------------------------------------- the walk
def walk(attempt: Attempt) -> tuple:
    """The recovery of ``attempt`` from its dynamics' starts: ``(JointResult, estimate)``.

    Each start in order, when it applies, solved on its meshes
    (:func:`~lunarcap.studies.missed.makeup.recover`); a start's recovery that is
    ``enough`` ends the walk, otherwise the cheapest verified is kept (the first of equal
    ones). Where a two-body recovery was solved, the estimate's ``two_body_delta_v_mps``
    is its delta-V and a kept recovery more than :data:`CONTINUATION_MARGIN` above it has
    a ``doubtful`` reason. Raises the first failure of a reported start (else the first),
    with the two-body recovery's delta-V where it had one.
    """
    starts = TWO_BODY_STARTS if attempt.nplan.dynamics == "two-body" else STARTS
    found, failed, two_body = [], [], None
    for start in starts:
        if not start.when(found):
            continue
        try:
            guess = start.guess(attempt)
            if guess is None:
                continue
            two_body = guess.two_body_mps if guess.two_body_mps is not None else two_body
            res, est = recover(attempt.nplan, attempt.i, attempt.place, attempt.max_period_s,
                               guess, start.meshes)
        except FAILURES as exc:
            failed.append((start, exc))
            continue
        found.append((res, est))
        if start.enough(res, two_body):
            return _compared(res, est, two_body)
    if found:
        return _compared(*min(found, key=lambda r: r[0].total_delta_v_mps), two_body)
    error = next((exc for start, exc in failed if start.reported), failed[0][1])
    raise _with_two_body(error, two_body)


def _compared(res, est: dict, two_body_mps: float | None) -> tuple:
    """``(res, est)`` with the two-body recovery's delta-V, and a doubt if far above it."""
    if two_body_mps is None:
        return res, est
    est["two_body_delta_v_mps"] = two_body_mps
    if not _plausible(res, two_body_mps):
        est["doubtful"] = (
            f"verified, but perhaps a local optimum: the recovery's burns need "
            f"{res.total_delta_v_mps:.1f} m/s, "
            f"{100 * (res.total_delta_v_mps / two_body_mps - 1):.1f} % more than "
            f"the same recovery in two-body dynamics ({two_body_mps:.1f} m/s), "
            f"where the Earth, the Sun and J2 are allowed "
            f"{100 * CONTINUATION_MARGIN:.0f} %; no start found a cheaper one, "
            f"so the penalty is an upper bound")
    return res, est


def _with_two_body(exc: Exception, two_body_mps: float | None) -> Exception:
    """A solver's failure in full dynamics, with what the two-body recovery cost if it had one.

    No start converged to a verified recovery in the plan's dynamics, but the same
    recovery without the Earth, the Sun and J2 was solved and verified: its delta-V is the
    reader's estimate of the answer.
    """
    if two_body_mps is None or not isinstance(exc, SolveError):
        return exc
    return SolveError(f"{str(exc).splitlines()[0]}; the same recovery in two-body dynamics "
                      f"was solved and verified: {two_body_mps:.1f} m/s", status=exc.status,
                      details=exc.details)
