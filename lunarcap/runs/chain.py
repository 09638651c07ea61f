"""The paper's capture chain: LOI problems built from the scenario, solved and cached.

LOI n ignites ``start`` minutes from the nominal perilune epoch of its orbit
(:attr:`lunarcap.mission.arrival.Mission.perilune_epochs_s`) and coasts to the next one. Its
initial state is the arrival perilune state (LOI 1) or the previous LOI's verified
end-of-coast state (LOI 2, 3), propagated backward to the ignition epoch in the same
dynamics (the paper's chain, Song 2011 Sec. 3.1-3.2). Mass carries through the chain.

:func:`solve_case` is cached on disk (joblib, keyed by its arguments and the code
version), so a chain reuses its earlier links and a rerun costs nothing.
"""

from __future__ import annotations

import sys

import numpy as np

from lunarcap.repro.cache import cached
from lunarcap.physics.dynamics import Model
from lunarcap.physics.ephemeris import Ephemeris, default_ephemeris
from lunarcap.errors import InputError
from lunarcap.physics.rocket import burn_duration_estimate_s, check_engine
from lunarcap.optim.nlp import LOIProblem
from lunarcap.physics.propagate import propagate
from lunarcap.mission.arrival import ArrivalSpec, Mission, check_loi, check_start
from lunarcap.optim.solve import solve_loi

#: Song 2011's impulsive delta-Vs (m/s), Table B1 (from Song et al. 2009c).
PAPER_IMPULSIVE_DV_MPS = (353.272, 254.034, 245.363)

_MISSIONS: dict = {}


def mission_for(arrival: ArrivalSpec = ArrivalSpec(), ephemeris: str | None = None) -> Mission:
    """The (memoised) Mission of an arrival spec and ephemeris file (None: DE405)."""
    key = (arrival, ephemeris)
    if key not in _MISSIONS:
        eph = default_ephemeris() if ephemeris is None else Ephemeris(ephemeris)
        _MISSIONS[key] = Mission(arrival.build(eph), eph)
    return _MISSIONS[key]


def loi_problem(mission: Mission, loi: int, thrust_N: float, isp_s: float, start_min,
                x_perilune, dynamics: str = "full", dv_impulsive_mps: float | None = None,
                start_bounds_min: tuple | None = None, steering: str = "optimal") -> LOIProblem:
    """The LOIProblem of LOI ``loi`` igniting ``start_min`` from its nominal perilune.

    ``x_perilune`` is the state (p, f, g, h, k, L, m) at that nominal perilune epoch.
    """
    loi = check_loi(loi)
    check_engine(thrust_N, isp_s)
    model = Model(mode=dynamics, thrust_N=thrust_N, isp_s=isp_s, fit=mission.fit)
    t_peri = mission.perilune_epochs_s[loi - 1]
    if dv_impulsive_mps is None:
        dv_impulsive_mps = PAPER_IMPULSIVE_DV_MPS[loi - 1]
    free = isinstance(start_min, str)
    if free:
        if start_min != "free":
            raise InputError(f"start must be a number of minutes or 'free', got {start_min!r}")
        # guess: ignite half the Eq. (19) duration before perilune (the paper's rule);
        # bounds: +-2 Eq. (19) durations around perilune
        t19 = burn_duration_estimate_s(x_perilune[6], dv_impulsive_mps, thrust_N, isp_s) / 60.0
        guess_min = -0.5 * t19
        bounds = start_bounds_min or (max(-2.0 * t19, -120.0), min(2.0 * t19, 120.0))
    else:
        guess_min = check_start(start_min)
        bounds = (guess_min, guess_min)
    t_ign = t_peri + 60.0 * guess_min
    x0 = propagate(model, t_peri, x_perilune, t_ign).final
    return LOIProblem(x0, t_ign, mission.perilune_epochs_s[loi], model,
                      circular=(loi == 3), dv_impulsive_mps=dv_impulsive_mps, loi=loi,
                      start_min=guess_min, t_perilune_s=t_peri, free_start=free,
                      x_ref=np.asarray(x_perilune, float), t_ref_s=t_peri,
                      start_bounds_min=bounds, steering=steering)


def _log(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


@cached(ignore=["verbose"])
def solve_case(thrust_N: float, isp_s: float, loi: int, start_min: float,
               previous_starts: tuple = (), dynamics: str = "full",
               arrival: ArrivalSpec = ArrivalSpec(), ephemeris: str | None = None,
               verbose: bool = False, steering: str = "optimal"):
    """Solve (or fetch from the cache) one LOI of the chain.

    Parameters
    ----------
    thrust_N, isp_s : engine (N, s)
    loi : 1, 2 or 3
    start_min : ignition offset from the nominal perilune, min (negative: before), or
        "free" to optimise it
    previous_starts : ignition offsets of the earlier LOIs of the chain, min
        (``()`` for LOI 1, ``(s1,)`` for LOI 2, ``(s1, s2)`` for LOI 3)
    dynamics : "full", "j2" or "two-body"
    arrival : ArrivalSpec
    ephemeris : path of an SPK file, or None for DE405
    steering : "optimal" (the paper's), "inertial" (fixed inertial direction, optimised) or
        "antivelocity" (thrust opposite the velocity); applies to this LOI only, the
        earlier LOIs of the chain are the optimal ones

    Returns
    -------
    Solution
    """
    loi = check_loi(loi)
    previous_starts = tuple(s if s == "free" else float(s) for s in previous_starts)
    if len(previous_starts) != loi - 1:
        raise InputError(f"LOI {loi} needs the ignition offsets of the {loi - 1} earlier LOI(s), "
                         f"got {previous_starts}")
    mission, x_peri = _previous_state(thrust_N, isp_s, loi, previous_starts, dynamics, arrival,
                                      ephemeris, verbose)
    prob = loi_problem(mission, loi, thrust_N, isp_s, start_min, x_peri, dynamics,
                       steering=steering)
    if verbose:
        _log(f"LOI {loi}, {thrust_N:g} N / {isp_s:g} s, start {start_min} min, {dynamics}:")
    sol = solve_loi(prob, progress=_log if verbose else None)
    if verbose:
        s = sol.summary()
        _log(f"  -> {s['burn_duration_min']:.2f} min, {s['delta_v_mps']:.3f} m/s "
             f"({s['loss_percent']:+.2f} %), {s['solve_wall_s']:.2f} s")
    return sol


def solve_sequence(thrust_N: float, isp_s: float, starts=(-10.0, -6.0, -5.0), **kw) -> list:
    """The three LOIs of one engine at the given ignition offsets (min), in chain order."""
    starts = tuple(s if s == "free" else float(s) for s in starts)
    if len(starts) != 3:
        raise InputError(f"a capture sequence needs three ignition offsets, got {starts}")
    return [solve_case(thrust_N, isp_s, i + 1, starts[i], starts[:i], **kw) for i in range(3)]


def sweep(thrust_N: float, isp_s: float, loi: int, starts, previous_starts=(), **kw) -> list:
    """Solutions of one LOI for several ignition offsets (the paper's Tables 1-5)."""
    starts = [check_start(s) for s in starts]
    if not starts:
        raise InputError("an ignition-time sweep needs at least one start offset")
    return [solve_case(thrust_N, isp_s, loi, s, tuple(previous_starts), **kw) for s in starts]


def _previous_state(thrust_N, isp_s, loi, previous_starts, dynamics, arrival, ephemeris, verbose):
    """State at the nominal perilune preceding LOI ``loi`` in the finite-burn chain."""
    mission = mission_for(arrival, ephemeris)
    if loi == 1:  # the arrival state carries the spec's mass
        return mission, mission.arrival.state
    prev = solve_case(thrust_N, isp_s, loi - 1, previous_starts[-1], tuple(previous_starts[:-1]),
                      dynamics, arrival, ephemeris, verbose)
    return mission, prev.end_state


#: Burn durations (s) of the two high-thrust solves of :func:`solve_impulsive_case`.
IMPULSIVE_LIMIT_DURATIONS_S = (4.0, 2.0)


@cached(ignore=["verbose"])
def solve_impulsive_case(thrust_N: float, isp_s: float, loi: int, previous_starts: tuple = (),
                         dynamics: str = "full", arrival: ArrivalSpec = ArrivalSpec(),
                         ephemeris: str | None = None, verbose: bool = False) -> dict:
    """Impulsive LOI in the same dynamics, from the same pre-burn orbit as the finite chain.

    One impulse, free epoch (within +-10 min of the nominal perilune) and direction, the
    same terminal conditions and objective (Eq. 9). It is computed as the limit of finite
    burns: the free-start problem is solved with a thrust giving a 4 s burn; a 2 s burn
    centred on the same epoch is then solved; their delta-Vs differ from the impulsive
    one by a loss proportional to the duration squared, and Richardson extrapolation,
    dV_imp = (4 dV(2 s) - dV(4 s)) / 3, removes that term. Both solves are verified.

    Note: the objective dV + v_perilune is nearly flat along the impulse epoch (a later
    impulse needs more dV and leaves a slower perilune), so local optima a few seconds
    apart can differ by ~0.2 m/s in dV while their objectives agree to ~0.003 m/s; the
    sum over the chain is the well-conditioned quantity.

    Returns
    -------
    dict with delta_v_mps (extrapolated), the two finite-limit delta-Vs, impulse epoch
    offset (min) and end speed (km/s).
    """
    loi = check_loi(loi)
    mission, x_peri = _previous_state(thrust_N, isp_s, loi, tuple(previous_starts), dynamics,
                                      arrival, ephemeris, verbose)
    dv_guess = PAPER_IMPULSIVE_DV_MPS[loi - 1]
    d_long, d_short = IMPULSIVE_LIMIT_DURATIONS_S
    big = x_peri[6] * dv_guess / d_long  # N: m * dV / t
    prob = loi_problem(mission, loi, big, isp_s, "free", x_peri, dynamics,
                       start_bounds_min=(-10.0, 10.0))
    s_long = solve_loi(prob, progress=_log if verbose else None)
    # the short burn is centred on the same epoch, so both lie on one t^2 curve
    centre_min = s_long.problem.start_min + s_long.raw.t1_s / 120.0
    big2 = big * d_long / d_short
    t_short_min = s_long.raw.t1_s * d_short / d_long / 60.0
    prob2 = loi_problem(mission, loi, big2, isp_s, centre_min - t_short_min / 2, x_peri, dynamics)
    s_short = solve_loi(prob2, progress=_log if verbose else None)
    dv4, dv2 = s_long.delta_v_mps, s_short.delta_v_mps
    sm = s_short.summary()
    return {"loi": loi, "delta_v_mps": (4 * dv2 - dv4) / 3,
            "delta_v_long_mps": dv4, "delta_v_short_mps": dv2,
            "burn_long_s": s_long.raw.t1_s, "burn_short_s": s_short.raw.t1_s,
            "impulse_offset_min": centre_min, "v_end_kmps": sm["v_end_kmps"],
            "objective_mps": (4 * s_short.raw.objective_kmps - s_long.raw.objective_kmps) / 3 * 1e3,
            "m_before_kg": float(x_peri[6]), "dynamics": dynamics,
            "verification_passed": bool(s_long.verification.passed and s_short.verification.passed)}
