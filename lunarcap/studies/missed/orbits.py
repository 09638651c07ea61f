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


def turn_radius_km(x, thrust_N: float, isp_s: float, mu: float = C.MU_MOON) -> float:
    """The closest radius at which full thrust can stop the outward motion of state ``x``, km.

    The radial equation r'' = -mu / r^2 + h^2 / r^3 + a_r, with the centrifugal term
    (never negative) dropped and the thrust all inward (a_r = -T / m(t), the mass falling
    at T / (g0 Isp)), and gravity at its strongest, mu / r0^2 (the radius only grows until
    the motion stops), bounds r(t) below: r_lb(t) = r0 + int v(t) dt with
    v(t) = v_r0 - mu t / r0^2 - g0 Isp ln(m0 / m(t)). No steering stops the spacecraft
    closer than where v(t) = 0, and a coast (thrust 0) goes farther still. A state moving
    inwards (or not at all) turns where it is: its own radius.
    """
    r, v = (np.array(a, float) for a in rv_from_mee(*np.asarray(x, float)[:6], mu))
    r0 = float(np.linalg.norm(r))
    vr = float(r @ v) / r0 * 1e3   # m/s
    if vr <= 0.0:
        return r0
    m0 = float(np.asarray(x, float)[6])
    ve = C.G0_MPS2 * isp_s
    g = mu / r0 ** 2 * 1e3          # m/s^2

    def speed(t):
        return vr - g * t - ve * np.log(m0 / (m0 - thrust_N / ve * t))
    t_hi = min(vr / g, 0.999 * m0 * ve / thrust_N)
    lo, hi = 0.0, t_hi
    for _ in range(60):   # bisection: speed() falls monotonically from vr > 0
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if speed(mid) > 0 else (lo, mid)
    t = np.linspace(0.0, hi, 401)
    return r0 + float(np.trapezoid(speed(t), t)) * 1e-3


def physical_bound(plan: CapturePlan, i: int, t_s: float, x, window_min: tuple,
                   max_period_s: float, coast: Model) -> str:
    """Why no make-up can be made from ``x`` at ``t_s`` in its window (empty text if one may).

    Checked at the opening and the close of the make-up burn's window: the spacecraft
    outside the Moon's sphere of influence at both, or every orbit with the target's
    perilune radius that reaches where full thrust can first stop the spacecraft's outward
    motion (:func:`turn_radius_km`; where it is, if it moves inwards) longer than
    ``max_period_s`` at both: the make-up would carry the spacecraft beyond the apolune of
    every orbit the bound allows before it could bring it onto one. The latter holds for
    every kind of burn ``i``'s target: the orbit after an intermediate burn is free up to
    ``max_period_s``, and the final orbit (a circle or an ellipse as asked, shorter than
    that) is one of those orbits too. That text names the bound (``--max-period-h``) and
    what lifting it would take: the period needed and an impulsive make-up onto it
    (:func:`aimed_impulse`, two-body, at the window's end nearest to it).
    """
    rp = plan.targets[i].radius_km
    ends = []
    for w in sorted(set(window_min)):
        t = t_s + 60.0 * w
        xw = propagate(coast, t_s, x, t).final if t > t_s else np.asarray(x, float)
        turn = turn_radius_km(xw, plan.engine.thrust_N, plan.engine.isp_s)
        ends.append((xw, make_up_estimate(xw, rp, max_period_s), turn,
                     period_s((turn + rp) / 2), soi_radius_km(t, plan.ephemeris)))
    if all(e["r_km"] > soi for _, e, _, _, soi in ends):
        _, e, _, _, soi = ends[0]
        return (f"the spacecraft is {e['r_km']:,.0f} km from the Moon when the window "
                f"opens, outside its sphere of influence ({soi:,.0f} km)")
    if all(need > max_period_s for *_, need, _ in ends):
        xw, e, turn, need, _ = min(ends, key=lambda end: end[3])
        moving = "" if turn == e["r_km"] else (
            f", moving away; full thrust stops it no closer than {turn:,.0f} km")
        imp = aimed_impulse(xw, rp, need * 1.0001)
        cost = "" if imp is None else \
            f"; an impulsive make-up onto such an orbit: {imp['delta_v_mps']:.0f} m/s"
        return (f"decided by --max-period-h ({max_period_s / 3600:g} h): the spacecraft is "
                f"{e['r_km']:,.0f} km from the Moon when the make-up burn can ignite{moving}; "
                f"every orbit through there with a {rp:,.0f} km perilune radius lasts at least "
                f"{need / 3600:.1f} h (--max-period-h {math.ceil(need / 360.0) / 10:g} or more "
                f"would let a make-up start there{cost})")
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


def aimed_impulse(x, rp_km: float, max_period_s: float, min_period_s: float | None = None,
                  mu: float = C.MU_MOON, n_grid: int = 400) -> dict | None:
    """The cheapest impulse at state ``x`` onto an orbit of perilune radius ``rp_km``.

    Among the orbits in the plane of ``x`` through its position with that perilune radius
    and a period between ``min_period_s`` and ``max_period_s`` (semi-major axis a: the
    speed there from the vis-viva equation, the transverse speed from the angular momentum
    sqrt(mu rp (2 - rp / a)), the radial speed of either sign), the one the smallest
    impulse reaches (a on a grid of ``n_grid``). Unlike :func:`make_up_estimate`'s
    tangential impulse, it keeps the angular momentum a low perilune needs: far from the
    Moon on an outbound leg, an impulse opposite the velocity removes mostly the
    transverse speed and would drop the perilune into the Moon. Returns ``dv_kmps`` (the
    impulse, M-MME2000, km/s), ``delta_v_mps``, ``period_s`` and ``coast_s`` (from the
    impulse to that orbit's next perilune, s); None if no such orbit passes the position
    (it lies below ``rp_km``, or every such orbit is longer than ``max_period_s``).
    """
    r, v = (np.array(a, float) for a in rv_from_mee(*np.asarray(x, float)[:6], mu))
    rn = float(np.linalg.norm(r))
    a_lo = max((rn + rp_km) / 2.0, float(semi_major_axis_from_period(min_period_s, mu))
               if min_period_s else 0.0)
    a_hi = float(semi_major_axis_from_period(max_period_s, mu))
    if rn < rp_km or a_lo > a_hi:
        return None
    r_hat = r / rn
    h_hat = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    t_hat = np.cross(h_hat, r_hat)
    a = np.linspace(a_lo, a_hi, n_grid)
    vt = np.sqrt(mu * rp_km * (2.0 - rp_km / a)) / rn
    vr = np.sqrt(np.maximum(mu * (2.0 / rn - 1.0 / a) - vt ** 2, 0.0))
    best = None
    for sign in (1.0, -1.0):
        new = sign * vr[:, None] * r_hat + vt[:, None] * t_hat
        dv = np.linalg.norm(new - v, axis=1)
        j = int(np.argmin(dv))
        if best is None or dv[j] < best[0]:
            best = (float(dv[j]), new[j], float(a[j]))
    dv, v_new, a_new = best
    n, M = mean_motion_and_anomaly(mee_from_rv(r, v_new, mu), mu)
    return {"dv_kmps": v_new - v, "delta_v_mps": dv * 1e3, "period_s": period_s(a_new, mu),
            "coast_s": float((2 * math.pi - M) / n if M > 0 else -M / n)}


#: The finite burn of :func:`aimed_burn` is tuned until the impulse still missing after it
#: is below this, m/s (a guess: IPOPT corrects the rest), or for at most ``AIM_ITERATIONS``.
AIM_TOL_MPS = 1.0
AIM_ITERATIONS = 8


def aimed_burn(coast: Model, t_s: float, x, rp_km: float, periods_s: tuple, thrust_N: float,
               mu: float = C.MU_MOON) -> dict | None:
    """A finite burn along a fixed direction from ``x`` onto an orbit of :func:`aimed_impulse`.

    The impulse of :func:`aimed_impulse` (periods between ``periods_s`` = (shortest or
    None, longest), s) is flown as a burn of its Eq. (19) duration along its direction
    (fixed in M-MME2000) in ``coast``'s dynamics at ``thrust_N``; the impulse still
    missing at the burn's end (the spacecraft has moved meanwhile) is added to it and the
    burn flown again, until less than :data:`AIM_TOL_MPS` is missing. Returns
    ``dv_kmps`` (the burn's direction times its delta-V, km/s), ``delta_v_mps``,
    ``burn_s`` and ``coast_s`` (from the burn's end to the two-body perilune of the orbit
    it leaves); None if no such orbit passes the start, or the burn's end.
    """
    from lunarcap.physics.steering import law

    x = np.asarray(x, float)
    imp = aimed_impulse(x, rp_km, periods_s[1], periods_s[0], mu)
    if imp is None:
        return None
    dv = np.asarray(imp["dv_kmps"], float)
    for _ in range(AIM_ITERATIONS):
        dv_mps = float(np.linalg.norm(dv)) * 1e3
        burn_s = burn_duration_estimate_s(x[6], dv_mps, thrust_N, coast.isp_s)
        end = propagate(coast, t_s, x, None, duration_s=burn_s, thrust_N=thrust_N,
                        u=law("inertial", dv / np.linalg.norm(dv))).final
        miss = aimed_impulse(end, rp_km, periods_s[1], periods_s[0], mu)
        if miss is None:
            return None
        if miss["delta_v_mps"] < AIM_TOL_MPS:
            break
        dv = dv + miss["dv_kmps"]
    return {"dv_kmps": dv, "delta_v_mps": dv_mps, "burn_s": burn_s,
            "coast_s": time_to_perilune_after_impulse_s(end, 0.0, 0.0, mu)}
