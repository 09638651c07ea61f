"""A capture plan's burns, solved in order, verified and cached.

Burn i ignites ``start_min`` from the nominal perilune epoch before it and coasts to the
next one (:attr:`lunarcap.mission.plan.CapturePlan.nominal_perilunes_s`). Its initial
state is the arrival perilune state (burn 1) or the previous burn's verified end-of-coast
state, propagated backward to the ignition epoch in the same dynamics (the paper's chain,
Song 2011 Sec. 3.1-3.2). Mass carries through the chain.

:func:`solve_burn` is cached on disk (joblib, keyed by the plan's prefix up to that burn,
its name blanked, and the numerical code's version), so a chain reuses its earlier burns
and a rerun costs nothing. :func:`impulsive_limit` gives each burn's impulsive delta-V in
the same dynamics from the same pre-burn orbit, against which :class:`PlanResult`
measures the finite-burn loss.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from lunarcap.errors import InputError, SolveError
from lunarcap.mission.arrival import Arrival, ArrivalSpec
from lunarcap.mission.plan import CapturePlan, paper_plan, plan_ephemeris
from lunarcap.optim.problem import burn_fit, burn_problem
from lunarcap.optim.solution import Solution
from lunarcap.optim.solve import solve_burn_problem, use_nlp_store
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.frames import DEFAULT_LUNAR_POLE
from lunarcap.repro.cache import cached, enabled, nlp_store

use_nlp_store(nlp_store())   # NLPs built once per machine, loaded by every later process


def _log(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


@lru_cache(maxsize=32)
def arrival_for(arrival: ArrivalSpec, ephemeris: str | None = None,
                lunar_pole: str = DEFAULT_LUNAR_POLE) -> Arrival:
    """The reconstructed arrival state of an arrival spec (memoised)."""
    return arrival.build(plan_ephemeris(ephemeris, lunar_pole))


#: In-process memo of earlier burns (see :func:`reuse_earlier_burns`), or None.
_EARLIER: dict | None = None


@contextmanager
def reuse_earlier_burns():
    """Within the block, a burn solved as an earlier link of a chain is solved once.

    With the cache switch off (:func:`lunarcap.repro.cache.caching`), every burn of a chain
    would otherwise be solved again for each later burn that starts from it;
    :func:`plan_result` and ``lunarcap bench`` use this to solve each distinct prefix of a
    chain once per run, in memory (a burn solved in the block is remembered too).
    """
    global _EARLIER
    outer = _EARLIER
    _EARLIER = {} if outer is None else outer
    try:
        yield
    finally:
        _EARLIER = outer


def perilune_state(plan: CapturePlan, i: int, verbose: bool = False) -> np.ndarray:
    """State (p, f, g, h, k, L, m) at the perilune before burn ``i`` (0-based).

    See :func:`perilune_epoch_state` (this is its state).
    """
    return perilune_epoch_state(plan, i, verbose)[1]


def perilune_epoch_state(plan: CapturePlan, i: int, verbose: bool = False) -> tuple:
    """(epoch s, state (p, f, g, h, k, L, m)) at the perilune before burn ``i`` (0-based).

    The chain's start for the first burn (:func:`chain_start`); else the verified end of
    the previous burn's coast: the nominal perilune in the paper's formulation, the
    perilune where the orbit asked holds for an ellipse target.
    """
    if i == 0:
        return _start(plan)
    key = plan.key(i)
    if _EARLIER is not None:
        if key not in _EARLIER:
            sol = solve_burn(key, verbose=verbose)
            _EARLIER[key] = (sol.problem.t_end_s, sol.end_state)
        return _EARLIER[key]
    sol = solve_burn(key, verbose=verbose)
    return sol.problem.t_end_s, sol.end_state


def chain_start(plan: CapturePlan) -> tuple:
    """(epoch s, state (p, f, g, h, k, L, m)) where the first burn's chain starts.

    The arrival perilune (:func:`arrival_for`: the state carries the plan's mass), or for
    a plan with a :class:`lunarcap.mission.plan.Start` the start's epoch and state.
    """
    if plan.start is not None:
        return plan.start.epoch_s, np.array(plan.start.state)
    arr = arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole)
    return plan.nominal_perilunes_s[0], arr.state


def _start_of(plan: CapturePlan) -> tuple:
    """What :func:`chain_start` depends on: the plan's arrival, ephemeris, pole and start."""
    return plan.arrival, plan.ephemeris, plan.lunar_pole, plan.start


@dataclass(frozen=True)
class _Chain:
    """The plan whose burns are being solved (:func:`labelled`), as its solves see it.

    ``n_burns`` counts the progress lines' burns ("burn 2 of 5": a solve sees only the
    plan's prefix up to its burn, :meth:`CapturePlan.key`); ``start`` is
    :func:`chain_start` of the plan, built once for all its solves, and ``start_of`` what
    it depends on (:func:`_start_of`), so that a solve of another plan builds its own.
    """

    n_burns: int
    start_of: tuple
    start: tuple


#: The plan being solved (:func:`labelled`), or None.
_CHAIN: ContextVar = ContextVar("lunarcap_chain", default=None)


def _start(plan: CapturePlan) -> tuple:
    """:func:`chain_start` of ``plan``, the chain's own if ``plan`` shares its start.

    A copy of the state built on entering :func:`labelled`; built here for a plan whose
    arrival, ephemeris, pole or start differ from the chain's (or outside the block).
    """
    chain = _CHAIN.get()
    if chain is not None and chain.start_of == _start_of(plan):
        t, x = chain.start
        return t, np.array(x)
    return chain_start(plan)


@contextmanager
def labelled(plan: CapturePlan):
    """Within the block, ``plan`` is the chain being solved: its start built once, named.

    Its arrival (:func:`chain_start`) is built on entering the block and every solve of
    the block whose plan shares it starts from it; progress lines count burns out of the
    plan's ("burn k of N"), and a SolveError names it (``plan two-burn-8h: burn 2 (...)
    failed ...``): the solves see the plan's key, its name blanked.
    """
    token = _CHAIN.set(_Chain(plan.n_burns, _start_of(plan), chain_start(plan)))
    try:
        yield
    except SolveError as exc:
        if not plan.name or str(exc).startswith(f"plan {plan.name}: "):
            raise
        raise SolveError(f"plan {plan.name}: {exc}", exc.status, exc.details) from None
    finally:
        _CHAIN.reset(token)


def _burn_number(i: int) -> str:
    """'burn 2 of 5' (0-based ``i``; 'burn 2' outside :func:`labelled`)."""
    chain = _CHAIN.get()
    return f"burn {i + 1}" + ("" if chain is None else f" of {chain.n_burns}")


def _burn_label(plan: CapturePlan, i: int) -> str:
    b = plan.burns[i]
    start = "free" if b.free_start else f"{b.start_min:g} min"
    return (f"{_burn_number(i)} ({b.describe()}), {plan.engine.thrust_N:g} N / "
            f"{plan.engine.isp_s:g} s, start {start}, {plan.dynamics}"
            + ("" if b.steering == "optimal" else f", {b.steering} steering"))


@cached(ignore=["verbose"])
def solve_burn(plan: CapturePlan, verbose: bool = False) -> Solution:
    """Solve (or fetch from the cache) the last burn of ``plan``.

    Pass ``plan.key(n)`` to solve burn ``n`` of a plan: the prefix of the plan up to that
    burn, name blanked (what the solution depends on). Earlier burns are solved or fetched
    first; their verified end state starts this one.

    Raises
    ------
    SolveError
        If no mesh gives a converged, verified solution.
    """
    i = plan.n_burns - 1
    t_peri, x_peri = perilune_epoch_state(plan, i, verbose)
    prob = burn_problem(plan, i, x_peri, plan.ephemeris_model(), t_perilune_s=t_peri)
    if verbose:
        _log(f"{_burn_label(plan, i)}:")
    sol = solve_burn_problem(prob, progress=_log if verbose else None)
    if _EARLIER is not None:  # a later burn of the chain starts from its end
        _EARLIER[plan] = (sol.problem.t_end_s, sol.end_state)
    if verbose:
        s = sol.summary()
        _log(f"  -> start {s['start_min']:+.3f} min, {s['burn_duration_min']:.2f} min, "
             f"{s['delta_v_mps']:.3f} m/s, {s['solve_wall_s']:.2f} s")
    return sol


def solve_plan(plan: CapturePlan, verbose: bool = False) -> list:
    """Every burn of a plan in order (a list of Solution), each solved once.

    Cached as the cache switch says (:func:`lunarcap.repro.cache.caching`).
    """
    with reuse_earlier_burns(), labelled(plan):
        return [solve_burn(plan.key(n), verbose=verbose) for n in range(1, plan.n_burns + 1)]


#: Burn durations (s) of the two high-thrust solves of :func:`impulsive_limit`.
IMPULSIVE_LIMIT_DURATIONS_S = (4.0, 2.0)


def impulsive_limit(plan: CapturePlan, verbose: bool = False) -> dict:
    """Impulsive delta-V of the last burn of ``plan`` (see :func:`_impulsive_limit`).

    The result depends on the orbit before the burn and its target, not on the burn's own
    ignition offset or steering law: those are blanked from the cache key, and so is the
    thrust of a first burn (every engine of the same Isp shares its impulsive limit).
    """
    return _impulsive_limit(impulsive_key(plan), verbose=verbose)


def impulsive_key(plan: CapturePlan) -> CapturePlan:
    """The cache key of :func:`impulsive_limit` of the last burn of ``plan``.

    The plan with that burn's ignition free and its steering optimal and, for a first
    burn, the thrust replaced by the one sizing the 4 s burn (see :func:`impulsive_limit`).
    :func:`prebuild_for` asks the cache with this same key.
    """
    i = plan.n_burns - 1
    key = plan.with_start(i, "free").with_steering(i, "optimal")
    if i == 0:  # from the arrival: no earlier burn, so the engine's thrust cannot matter
        m0, dv = plan.arrival.mass_kg, plan.impulsive()[0].delta_v_mps
        key = key.with_engine(round(m0 * dv / IMPULSIVE_LIMIT_DURATIONS_S[0], 3),
                              plan.engine.isp_s)
    return key


#: In a gravity field, a shorter burn whose objective (Eq. 9) exceeds a longer one's by
#: more than this (m/s) shows that the limit of ever shorter burns does not exist (the
#: objective, unlike the delta-V, is settled to ~0.003 m/s among nearby optima; a finite
#: burn's loss only falls as it shortens).
NO_LIMIT_TOL_MPS = 0.01


#: Half-width of the window of the impulse's epoch around the perilune before the burn, min.
IMPULSE_WINDOW_MIN = 10.0
#: In a gravity field, a circle asked that the orbit before its burn clears by more than
#: this (m) is out of reach of every impulse (:func:`lunarcap.mission.reach.
#: circle_clearance`); below it the finite-burn solves decide. A burn of duration tau and
#: delta-V dv thrusting at an angle a inward, then outward, ends dv a tau / 4 below the
#: impulse's point for dv a^2 / 2 more delta-V: a gap g costs about 8 g^2 / (dv tau^2),
#: for 1 m and the 2 s burn of a 245 m/s circularisation 0.008 m/s, within
#: NO_LIMIT_TOL_MPS.
CIRCLE_GAP_TOL_M = 1.0


def _no_impulsive_limit(plan: CapturePlan, why: str, **extra) -> dict:
    """The impulsive limit of a burn in a gravity field that has none, and ``why``.

    In a field an impulse may not reach the orbit asked at all: the circle that the field
    turns into the 100 km circle asked at the coast's end may pass below the perilune of
    the orbit before the burn, where no impulse on that orbit can be
    (:mod:`lunarcap.mission.reach`); a finite burn reaches it by steering partly
    radially, the shorter the dearer. So the limit of finite burns does not exist; the
    burn has no loss. ``extra``: entries added to the result.
    """
    from lunarcap.physics.forces import force_model

    return {"burn": plan.n_burns, "delta_v_mps": None, "objective_j_mps": None,
            "verification_passed": None,
            "reason": f"no impulsive limit in {force_model(plan.dynamics)}: {why}", **extra}


def _unreachable_circle(plan: CapturePlan, i: int, t_peri: float, x_peri, eph, fit
                        ) -> dict | None:
    """The result of a circle no impulse reaches (:func:`_no_impulsive_limit`), else None.

    For a circle asked in a gravity field: how far the orbit before the burn passes above
    the circle flown back to it, within :data:`IMPULSE_WINDOW_MIN` of its perilune
    (:func:`lunarcap.mission.reach.circle_clearance`, a few coast propagations).
    """
    from lunarcap.mission.reach import circle_clearance
    from lunarcap.optim.correction import needs_correction
    from lunarcap.physics.dynamics import Model

    target = plan.targets[i]
    if not target.circular or not needs_correction(plan.dynamics):
        return None
    model = Model(plan.dynamics, 0.0, plan.engine.isp_s, fit)
    t_end = burn_problem(plan, i, x_peri, eph, fit=fit, t_perilune_s=t_peri).t_end_s
    c = circle_clearance(model, target, t_end, t_peri, x_peri, 60.0 * IMPULSE_WINDOW_MIN)
    if not c.gap_m > CIRCLE_GAP_TOL_M:
        return None
    why = (f"the circle asked, flown back to the burn in these forces, lies {c.gap_m:.0f} m "
           f"below the orbit before the burn where that orbit comes closest to it "
           f"({c.at_offset_s:+.0f} s from its perilune), so no impulse from that orbit "
           f"reaches it")
    return _no_impulsive_limit(plan, why, circle_gap_m=c.gap_m)


@cached(ignore=["verbose"])
def _impulsive_limit(plan: CapturePlan, verbose: bool = False) -> dict:
    """Impulsive delta-V of the last burn of ``plan`` in the same dynamics and pre-burn orbit.

    One impulse, free epoch (within +-10 min of the nominal perilune) and direction, the
    same target and objective (Eq. 9), computed as the limit of finite burns: the
    free-start problem is solved with a thrust giving a 4 s burn (sized from the plan's
    two-body impulse), once on each side of the perilune, keeping the lower objective;
    a 2 s burn centred on the same epoch is then solved; their
    delta-Vs differ from the impulsive one by a loss proportional to the duration
    squared, and Richardson extrapolation, dV_imp = (4 dV(2 s) - dV(4 s)) / 3, removes
    that term. Both solves are verified. Pass ``plan.key(n)`` for burn ``n``.

    Note: the objective dV + v_perilune is nearly flat along the impulse epoch (a later
    impulse needs more dV and leaves a slower perilune), so local optima a few seconds
    apart can differ by ~0.2 m/s in dV while their objectives agree to ~0.003 m/s; the
    sum over the chain and the objective are the well-conditioned quantities.

    Returns
    -------
    dict with delta_v_mps (extrapolated), objective_j_mps (likewise), the two finite-limit
    delta-Vs, the impulse's epoch offset (min), end speed (km/s) and the verdicts.
    """
    from lunarcap.optim.correction import needs_correction

    i = plan.n_burns - 1
    t_peri, x_peri = perilune_epoch_state(plan, i, verbose)
    eph = plan.ephemeris_model()
    dv_guess = plan.impulsive()[i].delta_v_mps
    d_long, d_short = IMPULSIVE_LIMIT_DURATIONS_S
    big = x_peri[6] * dv_guess / d_long  # N: m * dV / t
    fit = burn_fit(plan, i, eph, t_peri)
    none = _unreachable_circle(plan, i, t_peri, x_peri, eph, fit)
    if none is not None:   # no impulse reaches the circle: no solve can find a limit
        if verbose:
            _log(f"impulsive limit of {_burn_number(i)}: {none['reason']}")
        return none
    if verbose:
        _log(f"impulsive limit of {_burn_number(i)}: {d_long:g} s burns either side of the "
             f"perilune, then a {d_short:g} s burn, extrapolated to 0 s")

    def progress(what):
        return (lambda line: _log(f"  {what}, {line.strip()}")) if verbose else None
    # The objective is nearly flat along the impulse epoch and has a local optimum on each
    # side of the perilune (a few seconds before and after, differing by ~0.2 m/s in
    # delta-V and ~0.003 m/s in J): solve on each side and keep the lower objective.
    centre = -d_long / 120.0  # ignition (min) of a 4 s burn centred on the perilune
    field = needs_correction(plan.dynamics)   # only a field may have no limit
    try:
        out = _finite_limit(plan, i, x_peri, t_peri, eph, fit, centre, big, progress)
    except SolveError as exc:
        if not field:
            raise
        out = _no_impulsive_limit(plan, f"the finite-burn limit does not converge "
                                        f"({str(exc)[:300]})")
    else:
        short, long_ = out["objective_short_mps"], out["objective_long_mps"]
        if field and short > long_ + NO_LIMIT_TOL_MPS:
            out = _no_impulsive_limit(plan, f"the finite-burn limit does not converge "
                                            f"(the objective of a {d_short:g} s burn, "
                                            f"{short:.3f} m/s, exceeds a {d_long:g} s one's, "
                                            f"{long_:.3f})")
    if verbose and out["delta_v_mps"] is not None:
        dv4, dv2 = out["delta_v_long_mps"], out["delta_v_short_mps"]
        _log(f"  -> {out['delta_v_mps']:.3f} m/s ({d_long:g} s: {dv4:.3f}, {d_short:g} s: "
             f"{dv2:.3f} m/s)")
    elif verbose:
        _log(f"  -> {out['reason']}")
    return out


def _finite_limit(plan, i, x_peri, t_peri, eph, fit, centre, big, progress) -> dict:
    """The two finite burns of :func:`_impulsive_limit` and their extrapolation."""
    d_long, d_short = IMPULSIVE_LIMIT_DURATIONS_S
    sides = []
    w = IMPULSE_WINDOW_MIN
    for side, bounds, guess in (("before", (-w, centre), centre - 0.1),
                                ("after", (centre, w), centre + 0.1)):
        prob = burn_problem(plan, i, x_peri, eph, start_min="free", thrust_N=big,
                            start_bounds_min=bounds, guess_start_min=guess, fit=fit,
                            t_perilune_s=t_peri)
        sides.append(solve_burn_problem(
            prob, progress=progress(f"{d_long:g} s burn {side} the perilune")))
    s_long = min(sides, key=lambda s: s.raw.objective_kmps)
    # the short burn is centred on the same epoch, so both lie on one t^2 curve
    centre_min = s_long.problem.start_min + s_long.raw.t1_s / 120.0
    t_short_min = s_long.raw.t1_s * d_short / d_long / 60.0
    prob2 = burn_problem(plan, i, x_peri, eph, start_min=centre_min - t_short_min / 2,
                         thrust_N=big * d_long / d_short, fit=fit, t_perilune_s=t_peri)
    s_short = solve_burn_problem(prob2, progress=progress(f"{d_short:g} s burn"))
    dv4, dv2 = s_long.delta_v_mps, s_short.delta_v_mps
    return {"burn": i + 1, "delta_v_mps": (4 * dv2 - dv4) / 3,
            "delta_v_long_mps": dv4, "delta_v_short_mps": dv2,
            "burn_long_s": s_long.raw.t1_s, "burn_short_s": s_short.raw.t1_s,
            "impulse_offset_min": centre_min,
            "v_end_kmps": s_short.summary()["v_end_kmps"],
            "objective_j_mps": (4 * s_short.raw.objective_kmps - s_long.raw.objective_kmps) / 3
            * 1e3,
            "m_before_kg": float(x_peri[6]), "dynamics": str(plan.dynamics),
            "objective_long_mps": s_long.raw.objective_kmps * 1e3,
            "objective_short_mps": s_short.raw.objective_kmps * 1e3,
            "verification_passed": bool(s_long.verification.passed
                                        and s_short.verification.passed)}


def time_to_final_orbit_h(t_arrival_s: float, last: Solution) -> float:
    """Time to the final orbit, h: from the arrival perilune to the end of the last burn.

    The one definition every table and page uses: the spacecraft is on its final orbit
    from the last burn's cut-off (the perilune after it is where that orbit's elements are
    measured, one coast later).
    """
    return (last.burn_end_s - t_arrival_s) / 3600.0


def burn_loss(finite: dict, impulsive: dict) -> dict:
    """The loss of a burn against its impulsive limit, in m/s and %, two ways.

    ``finite``: :meth:`Solution.summary` (or any dict with ``delta_v_mps`` and
    ``objective_j_mps``); ``impulsive``: :func:`impulsive_limit` of the same burn. The
    delta-V loss is what the paper tabulates; the objective loss compares Eq. (9),
    delta-V plus the speed at the next perilune, which is nearly flat along the ignition
    epoch: where a per-burn delta-V is uncertain by ~0.2 m/s (see
    :func:`_impulsive_limit`), the objective loss is not, and it is never negative for
    an optimal burn (an impulse from the same orbit does at least as well).
    """
    dv, imp = finite["delta_v_mps"], impulsive["delta_v_mps"]
    if imp is None:   # a burn in a field may have no impulsive limit (its reason is kept)
        return dict.fromkeys(("impulsive_limit_mps", "delta_v_loss_mps", "delta_v_loss_percent",
                              "objective_loss_mps", "objective_loss_percent"))
    jl = finite["objective_j_mps"] - impulsive["objective_j_mps"]
    return {"impulsive_limit_mps": imp, "delta_v_loss_mps": dv - imp,
            "delta_v_loss_percent": 100.0 * (dv - imp) / imp, "objective_loss_mps": jl,
            "objective_loss_percent": 100.0 * jl / imp}


@dataclass
class BurnResult:
    """One verified burn of a plan and its impulsive limit in the same dynamics."""

    solution: Solution
    impulsive: dict | None = None

    def row(self) -> dict:
        """Flat row: the solution's summary, the impulsive limit and the loss (units in keys)."""
        s = self.solution.summary()
        v = s.pop("verification")
        s.pop("u_inertial")
        row = dict(s)
        if self.impulsive is None:
            row.update(dict.fromkeys(("impulsive_limit_mps", "delta_v_loss_mps",
                                      "delta_v_loss_percent",
                                      "objective_loss_mps", "objective_loss_percent")))
        else:
            row.update(burn_loss(s, self.impulsive))
        row["impulsive_verified"] = (None if self.impulsive is None
                                     else self.impulsive["verification_passed"])
        if self.impulsive is not None and self.impulsive.get("reason"):
            row["impulsive_limit_reason"] = self.impulsive["reason"]
        row.update({f"verification_{k}": x for k, x in v.items()})
        return row


@dataclass
class PlanResult:
    """Every burn of a plan, solved and verified, with totals."""

    plan: CapturePlan
    burns: list

    def table(self):
        """One row per burn (pandas DataFrame, units in the column names)."""
        import pandas as pd

        return pd.DataFrame([b.row() for b in self.burns])

    def totals(self) -> dict:
        """Totals of the chain: delta-V, impulsive, loss, fuel, burn time, final orbit."""
        rows = [b.row() for b in self.burns]
        dv = sum(r["delta_v_mps"] for r in rows)
        imps = [r["impulsive_limit_mps"] for r in rows]
        imp = None if any(x is None for x in imps) else sum(imps)
        last = rows[-1]
        # the perilunes reached (an ellipse as asked moves them), not the plan's estimate
        t = (self.plan.nominal_perilunes_s[0], self.burns[-1].solution.problem.t_end_s)
        return {"total_delta_v_mps": dv, "total_impulsive_limit_mps": imp,
                "total_delta_v_loss_mps": None if imp is None else dv - imp,
                "total_delta_v_loss_percent": None if imp is None else 100 * (dv - imp) / imp,
                "total_fuel_kg": self.plan.arrival.mass_kg - last["m_end_kg"],
                "total_burn_duration_min": sum(r["burn_duration_min"] for r in rows),
                "final_mass_kg": last["m_end_kg"],
                "final_rp_km": last["rp_end_km"], "final_ra_km": last["ra_end_km"],
                "final_inc_deg": last["inc_end_deg"],
                "final_perilune_epoch": calendar_from_seconds(t[-1]),
                "final_orbit_epoch": calendar_from_seconds(self.burns[-1].solution.burn_end_s),
                "time_to_final_orbit_h": time_to_final_orbit_h(t[0], self.burns[-1].solution),
                "all_verified": all(r["verification_passed"] for r in rows)
                and all(r["impulsive_verified"] is not False for r in rows)}

    def to_dict(self) -> dict:
        """JSON-ready: the plan, each burn's row, the totals."""
        return {"plan": self.plan.to_dict(), "burns": [b.row() for b in self.burns],
                "totals": self.totals()}


def after_capture(res: PlanResult, days: float, dynamics=None, rtol: float | None = None):
    """The final orbit of a solved plan propagated ``days`` from its last cut-off.

    In the plan's dynamics (or ``dynamics``): :func:`lunarcap.physics.evolution.evolve`,
    from the last burn's verified flight; the :class:`~lunarcap.physics.evolution.Evolution`
    holds each revolution's perilune, apolune and mean inclination and the sampled states.
    ``rtol``: the propagation's tolerance (default the propagator's).
    """
    from lunarcap.physics.evolution import evolve

    burn = res.burns[-1].solution.flight.burn
    kw = {} if rtol is None else {"rtol": rtol}
    return evolve(res.plan.dynamics if dynamics is None else dynamics,
                  res.plan.ephemeris_model(), burn.t[-1], burn.x[:7, -1], days, **kw)


def _in_cache(fn, *args) -> bool:
    """True if a cached function holds a result for ``args`` (False for a plain function)."""
    check = getattr(fn, "is_cached", None)
    return bool(check and check(*args))


def prebuild_for(plan: CapturePlan, burns=None, impulsive: bool = True,
                 verbose: bool = False) -> None:
    """Build at once (two threads) the NLP shapes that solving ``burns`` of ``plan`` needs.

    ``burns``: 1-based burn numbers (default all). Burns (and impulsive limits) already in
    the disk cache need no NLP and are left out. ``verbose``: say what is built, how long.
    """
    from lunarcap.optim.correction import needs_correction
    from lunarcap.optim.solve import prebuild

    shapes = []
    for n in (burns or range(1, plan.n_burns + 1)):
        key, b = plan.key(n), plan.burns[n - 1]
        kind = plan.targets[n - 1].kind
        free_end = plan.targets[n - 1].free_epoch
        if not (enabled() and _in_cache(solve_burn, key)):
            shapes.append((kind, b.free_start, b.steering, plan.dynamics, free_end))
        # a circle in a field: its limit is first checked for reach (no NLP), and its
        # fixed 2 s burn has the burn's own shape; the rest is built if it is needed
        circle_in_field = plan.targets[n - 1].circular and needs_correction(plan.dynamics)
        if impulsive and not circle_in_field:
            if not (enabled() and _in_cache(_impulsive_limit, impulsive_key(key))):
                shapes += [(kind, True, "optimal", plan.dynamics, free_end),
                           (kind, False, "optimal", plan.dynamics, free_end)]
    prebuild(shapes, progress=_log if verbose else None)


def plan_result(plan: CapturePlan, impulsive: bool = True, verbose: bool = False,
                on_burn=None) -> PlanResult:
    """Solve every burn of ``plan`` (and its impulsive limit) in order, each burn once.

    Cached as the cache switch says (:func:`lunarcap.repro.cache.caching`: ``--no-cache``
    recomputes every burn, the earlier ones included). ``on_burn(BurnResult)`` is called as
    each burn completes, so a caller can print what is done even if a later burn fails.
    """
    prebuild_for(plan, impulsive=impulsive, verbose=verbose)
    burns = []
    with reuse_earlier_burns(), labelled(plan):
        for n in range(1, plan.n_burns + 1):
            key = plan.key(n)
            sol = solve_burn(key, verbose=verbose)
            imp = impulsive_limit(key, verbose=verbose) if impulsive else None
            burns.append(BurnResult(sol, imp))
            if on_burn is not None:
                on_burn(burns[-1])
    return PlanResult(plan, burns)


# ---------------------------------------------------------------------- the paper's cases
def paper_case(thrust_N: float, isp_s: float, burn: int, start_min,
               previous_starts: tuple = (), dynamics: str = "full",
               steering: str = "optimal", verbose: bool = False) -> Solution:
    """Burn ``burn`` (1-3) of the paper's capture (:func:`lunarcap.mission.plan.paper_plan`).

    The earlier burns ignite at ``previous_starts`` (min, or "free"); this one at
    ``start_min`` with ``steering``. Cached like every burn.
    """
    plan = paper_plan(thrust_N, isp_s, dynamics=dynamics)
    previous_starts = tuple(previous_starts)
    if not 1 <= burn <= plan.n_burns or len(previous_starts) != burn - 1:
        raise InputError(f"burn {burn} of the paper's {plan.n_burns} needs the ignition "
                         f"offsets of the {burn - 1} earlier burn(s), got {previous_starts}")
    for j, s in enumerate((*previous_starts, start_min)):
        plan = plan.with_start(j, s)
    plan = plan.with_steering(burn - 1, steering)
    with labelled(plan):
        return solve_burn(plan.key(burn), verbose=verbose)
