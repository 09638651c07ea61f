"""The verification gate's tolerances and its target checks, on any state.

:mod:`lunarcap.optim.verify` gates a solution re-flown from its initial state: the end of
its coast against the collocation's (position, speed, objective) and the target on the
re-flown state. The target part is written here once, so that a state reached otherwise
(a fault's orbit, coasting, :mod:`lunarcap.studies.missed.recovery`) is held to the same
tolerances: |r_p - target| < 10 m, |i - target| < 1e-4 deg, |gamma| < 1e-4 deg and the
perilune branch; an ellipse as asked also its apolune within 50 m and its period within
0.5 s; a circle its radii within 10 m.
"""

from __future__ import annotations

from lunarcap.mission.targets import ELLIPSE

#: Gate tolerances: objective (m/s), radii (m), angles (deg), end position (m), end speed (m/s).
TOL_DV_MPS = 0.01
TOL_RP_M = 10.0
TOL_ANGLE_DEG = 1e-4
TOL_POSITION_M = 50.0
TOL_SPEED_MPS = 1e-3
#: Gate of an ellipse target's apolune (m) and period (s): an end speed error of 1 mm/s at
#: the perilune of a 12 h orbit moves the apolune by ~70 m.
TOL_RA_M = 50.0
TOL_PERIOD_S = 0.5


def target_failures(err: dict, ellipse: bool, released=()) -> list[str]:
    """Which target conditions of the gate fail, with the numbers.

    ``err``: the errors of :meth:`lunarcap.mission.targets.Target.errors` (``rp_error_m``,
    ``ra_error_m``, ``period_error_s``, ``inc_error_deg``, ``gamma_error_deg``,
    ``branch``); ``ellipse``: an ellipse as asked (apolune within :data:`TOL_RA_M`, else
    :data:`TOL_RP_M`); ``released``: the residuals a steering law leaves free.
    """
    out, free = [], set(released)
    if not abs(err["rp_error_m"]) < TOL_RP_M and not {"p", "rp"} & free:
        out.append(f"perilune radius off by {err['rp_error_m']:.4g} m")
    tol_ra = TOL_RA_M if ellipse else TOL_RP_M
    ra = err["ra_error_m"]
    if ra is not None and not abs(ra) < tol_ra and not {"p", "e2"} & free:
        out.append(f"apolune radius off by {ra:.4g} m")
    period = err["period_error_s"]
    if period is not None and not abs(period) < TOL_PERIOD_S and "e2" not in free:
        out.append(f"period off by {period:.4g} s")
    if not abs(err["inc_error_deg"]) < TOL_ANGLE_DEG and "inc" not in free:
        out.append(f"inclination off by {err['inc_error_deg']:.3g} deg")
    gamma = err["gamma_error_deg"]
    if gamma is not None and not abs(gamma) < TOL_ANGLE_DEG:
        out.append(f"flight-path angle off by {gamma:.3g} deg")
    if err["branch"] is not None and not err["branch"] >= 0:
        out.append(f"the coast ends at an apolune (e cos(nu) = {err['branch']:.3g}), "
                   "not a perilune")
    return out


def state_failures(target, mee_km) -> list[str]:
    """:func:`target_failures` of a state (p km, f, g, h, k, L rad) against ``target``."""
    return target_failures(target.errors(mee_km), target.kind == ELLIPSE)
