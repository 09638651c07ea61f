"""The orbit a contingency leaves: its kind, the Moon's sphere of influence, the make-up bound.

Two-body geometry the missed-thrust study uses before any solve: to classify the orbit at
the cut-off (:func:`classify`), to size the make-up burn (:func:`make_up_estimate`), to
answer a case that physics forbids as "no recovery" with its reason
(:func:`physical_bound`), and to bound the free orbit after a burn so that the next burn
keeps a burn to do and room to do it (:func:`shortest_free_period_s`,
:func:`after_free_orbit`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from lunarcap.mission.impulsive import perilune_speed_kmps, period_from_perilune_speed_s
from lunarcap.mission.plan import MIN_BURN_S, CapturePlan, plan_ephemeris
from lunarcap.mission.targets import CIRCULAR
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import (
    mean_motion_and_anomaly,
    mee_from_rv,
    orbit_summary,
    period_from_semi_major_axis,
    rv_from_mee,
    semi_major_axis_from_period,
)
from lunarcap.physics.propagate import propagate
from lunarcap.physics.rocket import burn_duration_estimate_s


def classify(x, t_s: float, ephemeris: str | None = None) -> dict:
    """The orbit of state ``x`` (p, f, g, h, k, L, m) at epoch ``t_s`` about the Moon.

    Returns energy (km^2/s^2), eccentricity, perilune and apolune radii (km, inf if open),
    period (h, inf if open), the sphere-of-influence radius at that epoch (km) and
    ``orbit``: "escape" (energy >= 0), "captured" (apolune inside the sphere of influence)
    or "weakly captured".
    """
    o = orbit_summary(np.asarray(x, float), C.MU_MOON)
    energy = o["v_kmps"] ** 2 / 2 - C.MU_MOON / o["r_km"]
    soi = soi_radius_km(t_s, ephemeris)
    if energy >= 0:
        kind, period_h = "escape", math.inf
    else:
        a = -C.MU_MOON / (2 * energy)
        period_h = period_s(a) / 3600.0
        kind = "captured" if o["ra_km"] < soi else "weakly captured"
    return {"orbit": kind, "energy_km2ps2": energy, "e": o["e"], "rp_km": o["rp_km"],
            "ra_km": o["ra_km"], "period_h": period_h, "r_km": o["r_km"],
            "soi_radius_km": soi}


def soi_radius_km(t_s: float, ephemeris: str | None = None) -> float:
    """Laplace's sphere-of-influence radius of the Moon, a (m_Moon/m_Earth)^(2/5), km.

    ``a``: the Earth-Moon distance at epoch ``t_s`` from the ephemeris.
    """
    rm, _ = plan_ephemeris(ephemeris).moon_geocentric_state(t_s)
    return float(np.linalg.norm(rm[:, 0])) * (C.MU_MOON / C.MU_EARTH) ** 0.4


def period_s(a_km: float, mu: float = C.MU_MOON) -> float:
    """Kepler's third law: the period of an ellipse of semi-major axis ``a_km``, s."""
    return float(period_from_semi_major_axis(a_km, mu))


def time_to_perilune_after_impulse_s(x, dv_mps: float, after_s: float = 0.0,
                                     mu: float = C.MU_MOON) -> float:
    """Two-body time to the first perilune later than ``after_s``, after an impulse ``dv``.

    The impulse is opposite the velocity at the state ``x``; inf if the orbit after it is
    open.
    """
    r, v = (np.array(a, float) for a in rv_from_mee(*np.asarray(x, float)[:6], mu))
    vn = np.linalg.norm(v)
    if dv_mps * 1e-3 >= vn:   # the impulse would stop the spacecraft: no such orbit
        return math.inf
    mee = mee_from_rv(r, v * (vn - dv_mps * 1e-3) / vn, mu)
    if math.hypot(mee[1], mee[2]) >= 1:
        return math.inf
    n, M = mean_motion_and_anomaly(mee, mu)
    t = float((-M if M < 0 else 2 * math.pi - M) / n)
    while t <= after_s:
        t += 2 * math.pi / n
    return t


def make_up_estimate(x, rp_km: float, max_period_s: float, mu: float = C.MU_MOON) -> dict:
    """Two-body delta-V a make-up burn needs at state ``x`` to reach the period bound.

    A tangential impulse opposite the velocity bringing the orbit's period down to
    ``max_period_s`` (0 if it is already shorter). ``min_period_s``: the shortest period
    of any orbit through the position with perilune radius ``rp_km`` (semi-major axis
    (r + rp) / 2): above ``max_period_s``, no recovery is possible from here. Returns
    ``delta_v_mps``, ``min_period_s``, ``r_km``.
    """
    r, v = (np.array(a, float) for a in rv_from_mee(*np.asarray(x, float)[:6], mu))
    rn, vn = float(np.linalg.norm(r)), float(np.linalg.norm(v))
    a_max = float(semi_major_axis_from_period(max_period_s, mu))
    v_max2 = mu * (2 / rn - 1 / a_max)
    dv = vn - math.sqrt(v_max2) if v_max2 > 0 else vn
    return {"delta_v_mps": max(dv, 0.0) * 1e3, "r_km": rn,
            "min_period_s": period_s((rn + min(rp_km, rn)) / 2, mu)}


def physical_bound(plan: CapturePlan, i: int, t_s: float, x, window_min: tuple,
                   max_period_s: float, coast: Model) -> str:
    """Why no recovery can start from ``x`` at ``t_s`` (empty text if one may).

    Checked at the opening and the close of the make-up burn's window: the spacecraft
    outside the Moon's sphere of influence at both, or every orbit through its position
    with the target's perilune radius longer than ``max_period_s`` at both. The latter holds
    for every kind of burn ``i``'s target: the orbit after an intermediate burn is free up
    to ``max_period_s``, and the final orbit (a circle or an ellipse as asked, shorter than
    that) is one of those orbits too.
    """
    rp = plan.targets[i].radius_km
    ends = []
    for w in sorted(set(window_min)):
        t = t_s + 60.0 * w
        xw = propagate(coast, t_s, x, t).final if t > t_s else np.asarray(x, float)
        ends.append((w, make_up_estimate(xw, rp, max_period_s),
                     soi_radius_km(t, plan.ephemeris)))
    if all(e["r_km"] > soi for _, e, soi in ends):
        w, e, soi = ends[0]
        return (f"the spacecraft is {e['r_km']:,.0f} km from the Moon when the window "
                f"opens, outside its sphere of influence ({soi:,.0f} km)")
    if all(e["min_period_s"] > max_period_s for _, e, _ in ends):
        e = min((e for _, e, _ in ends), key=lambda e: e["min_period_s"])
        now = orbit_summary(np.asarray(x, float), C.MU_MOON)
        energy = now["v_kmps"] ** 2 / 2 - C.MU_MOON / now["r_km"]
        still = ""
        if energy < 0:   # bound: it will come back to its perilune
            still = (f"; the spacecraft is still bound (period "
                     f"{period_s(-C.MU_MOON / (2 * energy)) / 3600:.1f} h), so a make-up at a "
                     f"later perilune or a longer --max-period-h could recover it")
        return (f"the spacecraft is {e['r_km']:,.0f} km from the Moon when the make-up burn "
                f"can ignite: every orbit through there with a {rp:,.0f}"
                f" km perilune radius lasts at least {e['min_period_s'] / 3600:.1f} h, more "
                f"than the {max_period_s / 3600:g} h allowed (--max-period-h){still}")
    return ""


def shortest_free_period_s(plan: CapturePlan, i: int) -> float | None:
    """Shortest period of the free orbit after burn ``i`` (0-based) that leaves burn i+1 a burn, s.

    At the plan's perilune radius, the perilune speed of the orbit after burn i+1 (its
    period, or the circle) plus the delta-V that burn needs to last twice the shortest
    burn the transcription resolves (:data:`lunarcap.mission.plan.MIN_BURN_S`, Eq. 19 at
    its mass in the plan's impulsive chain): an orbit after burn i equal to the next one
    would leave a burn of nothing, which no plan may have. None after the last burn.
    """
    if i + 1 >= plan.n_burns:
        return None
    nxt = plan.burns[i + 1]
    rp = plan.perilune_radius_km
    dv_mps = 2 * MIN_BURN_S * plan.engine.thrust_N / plan.impulsive()[i + 1].m_before_kg
    v = perilune_speed_kmps(rp, None if nxt.target == CIRCULAR else nxt.period_s)
    return period_from_perilune_speed_s(rp, v + dv_mps * 1e-3)


def after_free_orbit(prob, plan: CapturePlan, i: int, max_period_s: float):
    """Burn ``i`` + 1's problem with room for any free orbit after burn ``i`` (0-based).

    A burn's duration is bounded by 3 x Eq. (19) of the delta-V its plan gives it
    (:attr:`lunarcap.optim.problem.BurnProblem.burn_bounds_s`); after a free orbit that
    delta-V is the plan's guess of that orbit, not the orbit the NLP chooses. The bound is
    raised to 3 x Eq. (19) of the delta-V from the longest orbit allowed (``max_period_s``,
    at the plan's perilune radius) to the orbit after burn i + 1, from ``prob``'s mass, and
    kept within 0.9 of its ignition-to-end span as the default is: held to the guessed
    orbit's delta-V, the next burn may end on its bound, or make the NLP infeasible.
    """
    nxt = plan.burns[i + 1]
    rp = plan.perilune_radius_km
    dv_mps = 1e3 * (perilune_speed_kmps(rp, max_period_s)
                    - perilune_speed_kmps(rp, None if nxt.target == CIRCULAR else nxt.period_s))
    longest = 3.0 * burn_duration_estimate_s(prob.x0[6], abs(dv_mps), plan.engine.thrust_N,
                                             plan.engine.isp_s)
    hi = min(longest, 0.9 * (prob.t_end_s - prob.t_ign_s))
    if not hi > prob.burn_bounds_s[1]:
        return prob
    return replace(prob, t1_max_s=hi)
