"""The paper's capture chain: LOI problems built from the scenario, solved and cached.

LOI n ignites ``start`` minutes from the nominal perilune epoch of its orbit
(:attr:`lunarcap.scenario.Mission.perilune_epochs_s`) and coasts to the next one. Its
initial state is the arrival perilune state (LOI 1) or the previous LOI's verified
end-of-coast state (LOI 2, 3), propagated backward to the ignition epoch in the same
dynamics (the paper's chain, Song 2011 Sec. 3.1-3.2). Mass carries through the chain.

:func:`solve_case` is cached on disk (joblib, keyed by its arguments and the code
version), so a chain reuses its earlier links and a rerun costs nothing.
"""

from __future__ import annotations

import sys

from . import constants as C
from .cache import cached
from .dynamics import Model
from .ephemeris import Ephemeris, default_ephemeris
from .errors import InputError
from .impulsive import check_engine
from .ocp import LOIProblem
from .propagate import propagate
from .scenario import ArrivalSpec, Mission, check_loi, check_start
from .solve import solve_loi

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


def loi_problem(mission: Mission, loi: int, thrust_N: float, isp_s: float, start_min: float,
                x_perilune, dynamics: str = "full", dv_impulsive_mps: float | None = None
                ) -> LOIProblem:
    """The LOIProblem of LOI ``loi`` igniting ``start_min`` from its nominal perilune.

    ``x_perilune`` is the state (p, f, g, h, k, L, m) at that nominal perilune epoch.
    """
    loi = check_loi(loi)
    start_min = check_start(start_min)
    check_engine(thrust_N, isp_s)
    model = Model(mode=dynamics, thrust_N=thrust_N, isp_s=isp_s, fit=mission.fit)
    t_peri = mission.perilune_epochs_s[loi - 1]
    t_ign = t_peri + 60.0 * start_min
    x0 = propagate(model, t_peri, x_perilune, t_ign).final
    if dv_impulsive_mps is None:
        dv_impulsive_mps = PAPER_IMPULSIVE_DV_MPS[loi - 1]
    return LOIProblem(x0, t_ign, mission.perilune_epochs_s[loi], model,
                      circular=(loi == 3), dv_impulsive_mps=dv_impulsive_mps, loi=loi,
                      start_min=start_min, t_perilune_s=t_peri)


def _log(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


@cached(ignore=["verbose"])
def solve_case(thrust_N: float, isp_s: float, loi: int, start_min: float,
               previous_starts: tuple = (), dynamics: str = "full",
               arrival: ArrivalSpec = ArrivalSpec(), ephemeris: str | None = None,
               verbose: bool = False):
    """Solve (or fetch from the cache) one LOI of the chain.

    Parameters
    ----------
    thrust_N, isp_s : engine (N, s)
    loi : 1, 2 or 3
    start_min : ignition offset from the nominal perilune, min (negative: before)
    previous_starts : ignition offsets of the earlier LOIs of the chain, min
        (``()`` for LOI 1, ``(s1,)`` for LOI 2, ``(s1, s2)`` for LOI 3)
    dynamics : "full", "j2" or "two-body"
    arrival : ArrivalSpec
    ephemeris : path of an SPK file, or None for DE405

    Returns
    -------
    Solution
    """
    loi = check_loi(loi)
    previous_starts = tuple(float(s) for s in previous_starts)
    if len(previous_starts) != loi - 1:
        raise InputError(f"LOI {loi} needs the ignition offsets of the {loi - 1} earlier LOI(s), "
                         f"got {previous_starts}")
    mission = mission_for(arrival, ephemeris)
    if loi == 1:
        x_peri = mission.arrival.state
        if arrival.mass_kg != C.ARRIVAL_MASS_KG:
            x_peri[6] = arrival.mass_kg
    else:
        prev = solve_case(thrust_N, isp_s, loi - 1, previous_starts[-1], previous_starts[:-1],
                          dynamics, arrival, ephemeris, verbose)
        x_peri = prev.end_state
    prob = loi_problem(mission, loi, thrust_N, isp_s, start_min, x_peri, dynamics)
    if verbose:
        _log(f"LOI {loi}, {thrust_N:g} N / {isp_s:g} s, start {start_min:+g} min, {dynamics}:")
    sol = solve_loi(prob, progress=_log if verbose else None)
    if verbose:
        s = sol.summary()
        _log(f"  -> {s['burn_duration_min']:.2f} min, {s['delta_v_mps']:.3f} m/s "
             f"({s['loss_percent']:+.2f} %), {s['solve_wall_s']:.2f} s")
    return sol


def solve_sequence(thrust_N: float, isp_s: float, starts=(-10.0, -6.0, -5.0), **kw) -> list:
    """The three LOIs of one engine at the given ignition offsets (min), in chain order."""
    starts = tuple(float(s) for s in starts)
    if len(starts) != 3:
        raise InputError(f"a capture sequence needs three ignition offsets, got {starts}")
    return [solve_case(thrust_N, isp_s, i + 1, starts[i], starts[:i], **kw) for i in range(3)]


def sweep(thrust_N: float, isp_s: float, loi: int, starts, previous_starts=(), **kw) -> list:
    """Solutions of one LOI for several ignition offsets (the paper's Tables 1-5)."""
    starts = [check_start(s) for s in starts]
    if not starts:
        raise InputError("an ignition-time sweep needs at least one start offset")
    return [solve_case(thrust_N, isp_s, loi, s, tuple(previous_starts), **kw) for s in starts]
