"""The make-up NLP: a recovery's guesses and its solve from one start, mesh after mesh.

After a fault, the rest of the capture is re-planned from the state it left
(:meth:`lunarcap.mission.plan.CapturePlan.resumed`): a make-up burn with burn n's target,
igniting in a window, then burns n+1, ... with free ignitions, to the same final orbit,
re-optimised as one NLP (total delta-V, :func:`lunarcap.optim.joint.solve_joint`) and
verified leg by leg. The orbit after an intermediate burn is free up to ``max_period_s``,
as in the nominal (:func:`lunarcap.studies.missed.nominal.freed`), and bounded below so
that the next burn keeps a burn to do
(:func:`lunarcap.studies.missed.orbits.shortest_free_period_s`); the make-up may be small
(its duration bounded below by :data:`MIN_MAKE_UP_S`, not by Eq. 10).

:func:`recover` solves that NLP from one :class:`RecoveryGuess`, on each mesh until one
passes verification; which guesses are tried, and in which order, is declared in
:mod:`lunarcap.studies.missed.starts`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from lunarcap.errors import InputError, SolveError
from lunarcap.mission.plan import CapturePlan
from lunarcap.mission.targets import CIRCULAR, PERILUNE
from lunarcap.optim import flight
from lunarcap.optim.collocation import DEFAULT_MESHES, Mesh, sundman_fractions
from lunarcap.optim.guess import GUESS_ATOL, GUESS_RTOL, Guess, guess_arcs, make_guess
from lunarcap.optim.joint import solve_joint
from lunarcap.optim.problem import burn_problem
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model, force_model
from lunarcap.physics.elements import mean_motion_and_anomaly
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.propagate import propagate
from lunarcap.physics.rocket import burn_duration_estimate_s
from lunarcap.physics.steering import law
from lunarcap.studies.burn_count.counts import MAX_FIT_SPAN_S
from lunarcap.studies.missed.orbits import (
    after_free_orbit,
    make_up_estimate,
    shortest_free_period_s,
    time_to_perilune_after_impulse_s,
)

#: Shortest coast from the fault's end to the make-up orbit's perilune, s.
MIN_FIRST_COAST_S = 600.0
#: Lower bound of the make-up burn's duration, s: about nothing (0.003 m/s at 150 N and
#: 525 kg), so the optimiser may drop the burn; nonzero so the burn's mesh keeps its size.
MIN_MAKE_UP_S = 0.01
#: Sizing period of the make-up orbit over the shortest free one (:func:`_sized`): a
#: little above it, so that the next burn's Eq. (19) duration is not at the edge.
SHORTEST_PERIOD_MARGIN = 1.001
#: Meshes of a recovery, tried in turn (:func:`on_meshes`): the solver's, then twice the
#: finest's burn intervals, then twice its coast intervals too. A make-up burn may be long
#: and steered hard, which the solver's finest mesh resolves too coarsely to pass the gate.
RECOVERY_MESHES = DEFAULT_MESHES + (Mesh(36, 36, 6), Mesh(36, 72, 6))
#: The last burn's end may pass its perilune by up to this, s: the deadline enters a
#: recovery's NLP where the longest coasts allowed end within it of the deadline.
DEADLINE_MARGIN_S = 3600.0
#: The make-up orbit's coast (from the fault to that orbit's perilune) may exceed the
#: window and the longest period by this, s: the burn and the arc to the perilune.
COAST_SLACK_S = 7200.0


@dataclass(frozen=True)
class Place:
    """Where a recovery starts: a state at an epoch, and the make-up's ignition window.

    Attributes
    ----------
    t_s : float
        Epoch of the state, TDB s past J2000.
    x : array_like, shape (7,)
        The state (p km, f, g, h, k, L rad, m kg).
    window_min : (float, float)
        The make-up burn's ignition window, min after ``t_s``.
    fit : ChebyshevFit or None
        The Earth/Sun fit covering the recovery (:func:`ephemeris_fit`).
    coast : Model
        The dynamics of a coast from ``x`` (no thrust).
    deadline_s : float
        Epoch by which the capture's last burn must end, TDB s past J2000 (the arrival
        perilune plus ``--max-days``); inf: none.
    max_period_s : float
        Longest period of the make-up orbit the deadline leaves from here, s (inf: the
        deadline leaves more than any bound).
    """

    t_s: float
    x: object
    window_min: tuple
    fit: object
    coast: Model
    deadline_s: float = math.inf
    max_period_s: float = math.inf


@dataclass(frozen=True)
class RecoveryGuess:
    """What a recovery's NLP starts from (:func:`recovery_warm_start`); default the plan's.

    Attributes
    ----------
    legs : list or None
        Solutions (or RawSolutions) of the same burns whose steering the later burns fly
        (the nominal's, or another solve's), each igniting as it did after its perilune;
        None: the plan's anti-velocity guesses, each tuned to reach its perilune on time.
    late : bool
        With ``legs``, the make-up flies ``legs[0]``'s steering too (the whole burn,
        ignited late), instead of an anti-velocity burn of the estimated delta-V.
    dv_mps : float or None
        The make-up's delta-V, m/s; None: the two-body estimate of what it needs.
    first_coast_s : float or None
        The make-up leg's coast from the fault to where its target holds, s; None:
        :func:`first_coast_guess_s`.
    ignition_min : float or None
        The make-up's guessed ignition, min after the start; None: the window's opening.
    two_body_mps : float or None
        Where the guess is the same recovery solved in two-body dynamics, its delta-V
        (m/s): what the recovery from it is compared with.
    aim_kmps : tuple of float or None
        The make-up thrusts along this fixed M-MME2000 direction (the impulse of
        :func:`~lunarcap.studies.missed.orbits.aimed_impulse`, km/s) for the Eq. (19)
        duration of ``dv_mps``, instead of opposite the velocity.
    """

    legs: list | None = None
    late: bool = False
    dv_mps: float | None = None
    first_coast_s: float | None = None
    ignition_min: float | None = None
    two_body_mps: float | None = None
    aim_kmps: tuple | None = None


def ephemeris_fit(plan: CapturePlan, t0_s: float, span_s: float):
    """One Earth/Sun fit from ``t0_s`` - 1 h over ``span_s`` + 6 h for every leg and coast.

    Made in every dynamics (a model's epochs are checked against its fit's window);
    InputError beyond the span a fit covers.
    """
    if span_s + 7 * 3600.0 > MAX_FIT_SPAN_S:
        raise InputError(f"the recovery would span {span_s / 3600:.0f} h, more than the 4 "
                         f"days an ephemeris fit covers: shorten the delay or --max-period-h")
    return ChebyshevFit.fit(plan.ephemeris_model(), t0_s - 3600.0, t0_s + span_s + 6 * 3600.0,
                            body_frame=force_model(plan.dynamics).rotation)


def on_meshes(solve, meshes=RECOVERY_MESHES):
    """``solve(mesh)`` on each mesh in turn until its solution passes verification.

    A finer mesh is tried only when the coarse one converged but failed verification (a
    long free coast or a long burn resolved too coarsely); any other failure is raised at
    once, and the last mesh's failure too.
    """
    for j, mesh in enumerate(meshes):
        try:
            return solve(mesh)
        except SolveError as exc:
            if exc.status != "verification failed" or j == len(meshes) - 1:
                raise


# ---------------------------------------------------------------------- the guesses
def _sized(nplan: CapturePlan, i: int) -> CapturePlan:
    """The plan with burn ``i``'s period between its own and the next orbit's (geometric mean).

    A resumed plan's first burn needs a nonzero impulsive delta-V from the start state to
    pass the plan's engine checks (its Eq. 19 duration), but the make-up orbit is free in
    the NLP, so that period only sizes the checks: with the nominal's own period, a
    cut-off at the planned end (nothing to make up) would be refused. Never shorter than
    :func:`~lunarcap.studies.missed.orbits.shortest_free_period_s` (the bound the NLP puts
    on that orbit) times :data:`SHORTEST_PERIOD_MARGIN`: where the nominal's orbit lies
    close to the next one, the mean alone would leave the next burn too short for the
    checks.
    """
    if nplan.targets[i].kind != PERILUNE or i + 1 >= nplan.n_burns:
        return nplan
    period = max(math.sqrt(nplan.coast_s(i) * nplan.coast_s(i + 1)),
                 SHORTEST_PERIOD_MARGIN * shortest_free_period_s(nplan, i))
    burn = replace(nplan.burns[i], period_s=period, apolune_altitude_km=None)
    return replace(nplan, burns=nplan.burns[:i] + (burn,) + nplan.burns[i + 1:])


def _make_up_dv_mps(rec_plan: CapturePlan, x, max_period_s: float) -> float:
    """Two-body delta-V the make-up burn needs at ``x`` (see :func:`recovery_warm_start`)."""
    if rec_plan.targets[0].kind == PERILUNE:   # a free orbit: down to the period bound
        return make_up_estimate(x, rec_plan.perilune_radius_km, max_period_s)["delta_v_mps"]
    return rec_plan.impulsive()[0].delta_v_mps   # the final orbit's energy


def recovery_warm_start(rec_plan: CapturePlan, eph, fit, max_period_s: float,
                        mesh_n_coast: int, guess: RecoveryGuess = RecoveryGuess()) -> tuple:
    """Problems and guesses of a recovery's legs, without solving any.

    The make-up leg ignites at the window's opening (or ``guess.ignition_min``), thrusts
    opposite the velocity for the duration of the two-body delta-V it needs (a free
    orbit: :func:`make_up_estimate`, to the period bound; the final orbit: the tangential
    impulse to its energy; ``guess.dv_mps`` if given; at least 1 s), its lower duration
    bound :data:`MIN_MAKE_UP_S`; each later leg is the plan's guess (anti-velocity, tuned
    to reach its perilune on time) from the end of the leg before, or with
    ``guess.legs`` flies that steering from there, igniting as it did after its perilune
    (:func:`lunarcap.optim.flight.flown_guess`), and with ``guess.late`` so does the
    make-up. Returns (warm list, estimate dict).
    """
    x_r = np.array(rec_plan.start.state)
    lo_min = rec_plan.burns[0].start_bounds_min[0] if guess.ignition_min is None \
        else guess.ignition_min
    prob = burn_problem(rec_plan, 0, x_r, eph, fit=fit, guess_start_min=lo_min)
    est = {"delta_v_mps": _make_up_dv_mps(rec_plan, prob.x0, max_period_s)
           if guess.dv_mps is None else float(guess.dv_mps)}
    t1 = max(burn_duration_estimate_s(prob.x0[6], est["delta_v_mps"], prob.model.thrust_N,
                                      prob.model.isp_s), 1.0)
    span = prob.t_end_s - prob.t_ign_s
    prob = replace(prob, t1_min_s=MIN_MAKE_UP_S,
                   t1_max_s=min(max(3 * t1, prob.burn_bounds_s[1]), 0.9 * span))
    raws = None if guess.legs is None else [getattr(s, "raw", s) for s in guess.legs]
    if raws is not None and guess.late:
        leg_guess = flight.flown_guess(raws[0], prob)
    elif guess.aim_kmps is not None:
        leg_guess = _aimed_guess(prob, t1, guess.aim_kmps)
    else:
        leg_guess = make_guess(prob, t1) if est["delta_v_mps"] > 1.0 else guess_arcs(prob, t1)
    warm = [(prob, leg_guess, sundman_fractions(leg_guess.coast.t, leg_guess.coast.x,
                                                mesh_n_coast))]
    for k in range(1, rec_plan.n_burns):
        x_peri = leg_guess.coast.x[:, -1]
        prob = burn_problem(rec_plan, k, x_peri, eph, fit=fit, guess_start_min=None
                            if raws is None else raws[k].prob.start_min)
        if k == 1 and rec_plan.targets[0].kind == PERILUNE:   # after the free make-up orbit
            prob = after_free_orbit(prob, rec_plan, 0, max_period_s)
        leg_guess = make_guess(prob) if raws is None else flight.flown_guess(raws[k], prob)
        warm.append((prob, leg_guess, sundman_fractions(leg_guess.coast.t, leg_guess.coast.x,
                                                        mesh_n_coast)))
    return warm, est


def _aimed_guess(prob, t1_s: float, aim_kmps) -> Guess:
    """The make-up's guess thrusting ``t1_s`` along the fixed M-MME2000 ``aim_kmps``, then coasting.

    The finite burn of an impulse along its direction (:class:`RecoveryGuess` ``aim_kmps``):
    a direction fixed in inertial space, as the impulse is, rather than one that turns with
    the velocity.
    """
    steer = law("inertial", np.asarray(aim_kmps, float) / np.linalg.norm(aim_kmps))
    burn = propagate(prob.model, prob.t_ign_s, prob.x0, None, duration_s=t1_s, u=steer,
                     rtol=GUESS_RTOL, atol=GUESS_ATOL, dense=True, dense_points=120)
    arc = propagate(prob.model, burn.t[-1], burn.x[:, -1], prob.t_end_s, u=None, dense=True,
                    rtol=GUESS_RTOL, atol=GUESS_ATOL)
    return Guess(t1_s, lambda t: steer(burn(t)), burn, arc)


def _nearest_perilune_s(x, t_s: float, mu: float = C.MU_MOON) -> float:
    """Epoch of the two-body perilune of state ``x`` nearest to ``t_s`` (past or next), s."""
    n, M = mean_motion_and_anomaly(np.asarray(x, float), mu)
    return t_s - float(M) / float(n)


def first_coast_guess_s(nplan: CapturePlan, i: int, place: Place, max_period_s: float,
                        dv_mps: float | None = None) -> float:
    """The make-up leg's coast (from the start to where its target holds) the NLP starts from, s.

    A free orbit: the two-body time to the perilune after the make-up impulse of
    :func:`make_up_estimate` at the window's opening (at least past the window and the
    burn). The final orbit: a circle, the window, twice the Eq. (19) duration and the
    plan's coast after the circle; an ellipse as asked, one of its periods after the
    perilune nearest the burn (its perilune is where the burn leaves it), past the burn.
    ``dv_mps``: the make-up's delta-V instead of the estimate's, m/s.
    """
    t_r, x_r, window_min = place.t_s, place.x, place.window_min
    t_ig = t_r + 60.0 * window_min[0]
    x_ig = propagate(place.coast, t_r, x_r, t_ig).final if t_ig > t_r else np.asarray(x_r, float)
    dv = make_up_estimate(x_ig, nplan.perilune_radius_km, max_period_s)["delta_v_mps"] \
        if dv_mps is None else dv_mps
    accel = nplan.engine.thrust_N / x_ig[6]   # m/s^2
    target = nplan.targets[i]
    if target.kind == PERILUNE:
        after = 60.0 * (window_min[1] - window_min[0]) + 2 * dv / accel
        t = time_to_perilune_after_impulse_s(x_ig, dv, after)
        t = min(t, max_period_s) if math.isfinite(t) else max_period_s
        return max(t + t_ig - t_r, 60.0 * window_min[1] + MIN_FIRST_COAST_S)
    t19 = 2 * nplan.resumed(i, t_ig, x_ig, window_min=(0.0, 0.0), first_coast_s=1e4,
                            make_up=True).impulsive()[0].delta_v_mps / accel
    if target.kind == CIRCULAR:
        return 60.0 * window_min[1] + t19 + nplan.coast_s(i)
    end_burn = t_ig + t19
    t = _nearest_perilune_s(x_ig, t_ig + t19 / 2) if np.hypot(x_ig[1], x_ig[2]) < 1 \
        else end_burn
    t += target.period_s()
    while t < end_burn + MIN_FIRST_COAST_S:
        t += target.period_s()
    return t - t_r


# ---------------------------------------------------------------------- one solve
def recover(nplan: CapturePlan, i: int, place: Place, max_period_s: float,
            guess: RecoveryGuess = RecoveryGuess(), meshes: tuple = RECOVERY_MESHES):
    """Re-plan the capture from burn ``i`` (0-based) at ``place`` from one guess (see the module).

    ``nplan``: the nominal's plan, in the dynamics solved. Each mesh of ``meshes`` in turn
    (:func:`on_meshes`); a solution that converged on a mesh but failed verification is
    the next mesh's start (:func:`_from_flight`: its coasts' mesh spaced for the orbits
    it found, not the guess's). Returns the :class:`~lunarcap.optim.joint.JointResult`
    (verified) and the make-up estimate (the first guess's, with ``first_coast_guess_s``);
    raises SolveError (IPOPT or verification) or PlanError (no such plan).
    """
    first_coast = guess.first_coast_s or first_coast_guess_s(nplan, i, place, max_period_s,
                                                             guess.dv_mps)
    guesses = [replace(guess, first_coast_s=first_coast)]   # the last: the next mesh's
    eph = nplan.ephemeris_model()
    est = {}

    def solve(mesh):
        start = guesses[-1]
        plan = _sized(nplan, i).resumed(i, place.t_s, place.x, first_coast_s=start.first_coast_s,
                                        window_min=place.window_min, make_up=True)
        warm, e = recovery_warm_start(plan, eph, place.fit, max_period_s, mesh.n_coast, start)
        if len(guesses) == 1:   # the make-up's estimate is the first guess's
            est.update(e)
        try:
            return _solve_recovery(plan, nplan.targets[i].kind, i, nplan, eph, mesh, place.fit,
                                   warm, place.window_min, max_period_s, place.deadline_s)
        except SolveError as exc:
            if exc.unverified is not None:
                guesses.append(_from_flight(*exc.unverified, place.t_s))
            raise
    res = on_meshes(solve, meshes)
    est["first_coast_guess_s"] = first_coast
    return res, est


def _from_flight(plan: CapturePlan, raws: list, t_s: float) -> RecoveryGuess:
    """The guess a converged but unverified recovery (its plan, RawSolutions) makes.

    Its own flight, the make-up included (its ignition, delta-V and steering), and its
    first coast.
    """
    return RecoveryGuess(legs=raws, late=True, dv_mps=raws[0].delta_v_mps,
                         first_coast_s=plan.coast_s(0),
                         ignition_min=(raws[0].prob.t_ign_s - t_s) / 60.0)


def _solve_recovery(rec_plan: CapturePlan, kind: str, i: int, nplan: CapturePlan, eph, mesh,
                    fit, warm: list, window_min: tuple, max_period_s: float,
                    deadline_s: float = math.inf):
    """The all-burns NLP of a recovery (:func:`recover`) on ``mesh`` from ``warm``.

    The make-up orbit's coast (a free orbit) is bounded by the window, ``max_period_s``
    and 2 h; where that coast and the plan's later ones could end the capture after
    ``deadline_s`` (s), the NLP also carries the deadline (its time limit, and the coast
    bounded to meet it), and only there: a bound that cannot bind is left out of the NLP.
    """
    if kind != PERILUNE:   # the final orbit: its coast the plan's
        return solve_joint(rec_plan, None, eph, mesh, fit=fit, warm=warm, expand=True)
    free = (True,) + (False,) * (rec_plan.n_burns - 1)
    hi = 60.0 * window_min[1] + max_period_s + COAST_SLACK_S
    t0 = rec_plan.nominal_perilunes_s[0]
    later = sum(rec_plan.coast_s(k) for k in range(1, rec_plan.n_burns - 1))
    max_time_s = None
    if t0 + hi + later + DEADLINE_MARGIN_S > deadline_s:
        max_time_s = deadline_s - t0
        hi = max(min(hi, max_time_s - later), MIN_FIRST_COAST_S)
    return solve_joint(rec_plan, None, eph, mesh, free_coasts=free,
                       coast_bounds_s=(MIN_FIRST_COAST_S, hi), fit=fit,
                       max_period_s=max_period_s, warm=warm, expand=True,
                       min_period_s=shortest_free_period_s(nplan, i), max_time_s=max_time_s)
