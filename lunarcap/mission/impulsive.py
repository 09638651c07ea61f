"""Two-body impulsive capture chain and the burn-duration estimate of Eq. (19).

Every burn is an impulse, tangential at a fixed perilune radius r_p: from the arrival
hyperbola (v_inf) through ellipses of given periods, possibly to a circle at r_p. The
speeds are those of vis-viva at r_p, so the delta-Vs are closed forms. For the paper's
chain (12.235 h, 3.525 h, circle at 100 km), :func:`impulsive_sequence`.

The arrival hyperbola's v_inf is not printed in Song 2011; :func:`v_inf_from_loi1` derives
it from an impulsive first burn (the paper's 353.272 m/s), so that burn reproduces the
given delta-V by construction and the later burns are genuine checks.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_engine_pairs, paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics.elements import (
    period_from_semi_major_axis,
    semi_major_axis_from_period,
    vis_viva_speed,
)
from lunarcap.physics.rocket import (
    burn_duration_estimate_s,
    check_engine,
    check_perilune_radius,
    rocket_mass_after,
)

#: The paper's scenario (its packaged plans, :mod:`lunarcap.mission.scenario`).
_PAPER = paper_scenario()

#: Song 2011's impulsive LOI-1 delta-V, m/s (Table 1; from Song et al. 2009c), as the
#: packaged plans give it (``arrival.impulsive_loi1_mps``).
PAPER_DV_LOI1_MPS = _PAPER.impulsive_loi1_mps


def v_inf_from_loi1(dv_loi1_mps: float = PAPER_DV_LOI1_MPS, rp_km: float | None = None,
                    period_s: float = _PAPER.capture_periods_s[0],
                    mu: float = C.MU_MOON) -> float:
    """Hyperbolic excess speed (km/s) whose tangential perilune impulse dv gives the period.

    Parameters
    ----------
    dv_loi1_mps : impulsive delta-V of the first burn, m/s
    rp_km : perilune radius, km (default R_Moon + 100 km)
    period_s : period of the orbit the first burn reaches, s
    mu : gravitational parameter, km^3/s^2
    """
    rp = C.R_MOON + _PAPER.perilune_altitude_km if rp_km is None else rp_km
    check_perilune_radius(rp)
    if not np.isfinite(dv_loi1_mps) or dv_loi1_mps <= 0:
        raise InputError(f"the impulsive first-burn delta-V must be a positive number of m/s, "
                         f"got {dv_loi1_mps!r}")
    a1 = semi_major_axis_from_period(period_s, mu)
    vp_hyp = vis_viva_speed(rp, a1, mu) + dv_loi1_mps * 1e-3
    vinf2 = vp_hyp ** 2 - 2 * mu / rp
    if vinf2 <= 0:
        raise InputError(f"an impulsive first burn of {dv_loi1_mps:g} m/s into that orbit "
                         "leaves the spacecraft bound before it arrives: give a larger delta-V")
    return float(np.sqrt(vinf2))


def perilune_speed_kmps(rp_km: float, period_s: float | None, mu: float = C.MU_MOON) -> float:
    """Speed at perilune r_p of an ellipse of the given period (None: the circle at r_p), km/s."""
    if period_s is None:
        return float(np.sqrt(mu / rp_km))
    return float(vis_viva_speed(rp_km, semi_major_axis_from_period(period_s, mu), mu))


@dataclass
class ImpulsiveBurn:
    """One impulse at perilune (speeds km/s, delta-V m/s, masses kg, duration min)."""

    burn: int
    period_before_h: float  # inf for the hyperbola
    period_after_h: float
    v_before_kmps: float
    v_after_kmps: float
    delta_v_mps: float
    m_before_kg: float
    m_after_kg: float
    fuel_kg: float
    eq19_duration_min: float

    def to_dict(self) -> dict:
        """Plain dict (JSON-friendly)."""
        return asdict(self)


def impulsive_chain(rp_km: float, v_inf_kmps: float, periods_after_s, thrust_N: float,
                    isp_s: float, mass_kg: float, mu: float = C.MU_MOON,
                    eq19_masses_kg=None, first_delta_v_mps: float | None = None
                    ) -> list[ImpulsiveBurn]:
    """Tangential perilune impulses from a hyperbola through orbits of given periods.

    Parameters
    ----------
    rp_km : perilune radius of every orbit, km
    v_inf_kmps : arrival hyperbolic excess speed, km/s
    periods_after_s : sequence, the period (s) of the orbit each burn reaches, ``None`` for
        the circle at r_p
    thrust_N, isp_s : engine for the masses and Eq. (19) (N, s)
    mass_kg : mass at the first perilune, kg
    eq19_masses_kg : optional masses at each burn for Eq. (19) (default: this chain's)
    first_delta_v_mps : optional delta-V of the first impulse, m/s, for a chain that starts
        from a given state rather than the hyperbola (:func:`tangential_impulse_mps`)

    Returns
    -------
    list of ImpulsiveBurn, one per burn
    """
    check_engine(thrust_N, isp_s, mass_kg)
    check_perilune_radius(rp_km)
    if not np.isfinite(v_inf_kmps) or v_inf_kmps <= 0:
        raise InputError(f"v_inf must be positive (km/s), got {v_inf_kmps}")
    speeds = [float(np.sqrt(v_inf_kmps ** 2 + 2 * mu / rp_km))]
    periods_h = [np.inf]
    for T in periods_after_s:
        speeds.append(perilune_speed_kmps(rp_km, T, mu))
        periods_h.append((period_from_semi_major_axis(rp_km, mu) if T is None else T) / 3600)
    if first_delta_v_mps is not None:  # the speed "before" is the equivalent one
        speeds[0] = speeds[1] + float(first_delta_v_mps) * 1e-3
        periods_h[0] = np.nan
    burns, m = [], float(mass_kg)
    for i in range(len(speeds) - 1):
        dv = (speeds[i] - speeds[i + 1]) * 1e3
        m_after = float(rocket_mass_after(m, dv, isp_s))
        m19 = m if eq19_masses_kg is None else eq19_masses_kg[i]
        t19 = burn_duration_estimate_s(m19, dv, thrust_N, isp_s) / 60
        burns.append(ImpulsiveBurn(i + 1, periods_h[i], periods_h[i + 1], speeds[i],
                                   speeds[i + 1], dv, m, m_after, m - m_after, t19))
        m = m_after
    return burns


def impulsive_sequence(thrust_N: float = paper_engine_pairs()[0][0],
                       isp_s: float = paper_engine_pairs()[0][1],
                       mass_kg: float = _PAPER.mass_kg,
                       altitude_km: float = _PAPER.perilune_altitude_km,
                       v_inf_kmps: float | None = None, periods_s=_PAPER.capture_periods_s[:2],
                       mu: float = C.MU_MOON, eq19_masses_kg=None) -> list[ImpulsiveBurn]:
    """The paper's two-body impulsive chain: hyperbola, 12.235 h, 3.525 h, circle.

    Parameters
    ----------
    thrust_N, isp_s : engine for the masses and Eq. (19) (N, s)
    mass_kg : mass at the first perilune, kg
    altitude_km : perilune altitude, km
    v_inf_kmps : arrival v_inf; by default derived from the paper's LOI-1 delta-V
    periods_s : periods of the two intermediate ellipses, s
    eq19_masses_kg : optional masses at the start of each burn for Eq. (19); by default
        those of this impulsive chain. Song 2011 evaluated Eq. (19) with the masses of
        its finite-burn chain (524.895, 434.471, 381.005 kg).
    """
    rp = C.R_MOON + altitude_km
    check_perilune_radius(rp)
    if v_inf_kmps is None:
        v_inf_kmps = v_inf_from_loi1(rp_km=rp, period_s=periods_s[0], mu=mu)
    return impulsive_chain(rp, v_inf_kmps, (*periods_s, None), thrust_N, isp_s, mass_kg, mu,
                           eq19_masses_kg)


# ---------------------------------------------------------------------- any number of burns
def capture_total_mps(rp_km: float, v_inf_kmps: float, mu: float = C.MU_MOON,
                      final_period_s: float | None = None) -> float:
    """Two-body impulsive delta-V from the hyperbola to the final orbit, any number of burns, m/s.

    Through any chain of tangential impulses at the perilune radius r_p, each impulse takes
    the perilune speed from one orbit's vis-viva value to the next one's, so the sum
    telescopes to the first speed minus the last:

        dV_total = sqrt(v_inf^2 + 2 mu / r_p) - v_p(final),

    whatever the number of burns and the periods of the intermediate ellipses. The final
    orbit is the circle at r_p (``final_period_s`` None; ``v_p = sqrt(mu / r_p)``, for the
    paper's arrival at 100 km 852.67 m/s) or the ellipse of period ``final_period_s`` with
    its perilune at r_p (:func:`perilune_speed_kmps`): the same chain as
    :func:`impulsive_chain`, so the total is the sum of a plan's impulsive burns
    (:meth:`lunarcap.mission.plan.CapturePlan.impulsive`, ``lunarcap impulsive --plan``).

    Parameters
    ----------
    rp_km : perilune radius, km
    v_inf_kmps : hyperbolic excess speed of the arrival, km/s
    mu : gravitational parameter, km^3/s^2
    final_period_s : period of a final ellipse, s (None: the circle at r_p)
    """
    check_perilune_radius(rp_km)
    if not np.isfinite(v_inf_kmps) or v_inf_kmps <= 0:
        raise InputError(f"v_inf must be positive (km/s), got {v_inf_kmps}")
    return float((np.sqrt(v_inf_kmps ** 2 + 2 * mu / rp_km)
                  - perilune_speed_kmps(rp_km, final_period_s, mu)) * 1e3)


def period_from_perilune_speed_s(rp_km: float, v_kmps: float, mu: float = C.MU_MOON) -> float:
    """Period (s) of the ellipse with perilune radius r_p and perilune speed v (inf if open)."""
    inv_a = 2.0 / rp_km - v_kmps ** 2 / mu
    if inv_a <= 0:
        return float("inf")
    return float(period_from_semi_major_axis(1.0 / inv_a, mu))


def equal_split_periods_s(rp_km: float, v_inf_kmps: float, n_burns: int,
                          max_period_s: float | None = None, mu: float = C.MU_MOON,
                          final_period_s: float | None = None) -> tuple:
    """Periods (s) of the n-1 intermediate ellipses that share the impulsive total equally.

    The hyperbola-to-final-orbit total (:func:`capture_total_mps`; the final orbit the
    circle at r_p, or the ellipse of period ``final_period_s``) is split into ``n_burns``
    equal tangential perilune impulses; if the first ellipse would then be longer than
    ``max_period_s``, the first impulse reaches ``max_period_s`` and the rest of the total
    is split equally among the other burns. A start for the search of the best periods
    (finite-burn losses grow faster than linearly with each burn's delta-V, so spreading
    the delta-V evenly is the natural first guess), not an optimum.
    """
    if int(n_burns) != n_burns or n_burns < 1:
        raise InputError(f"the number of burns must be an integer >= 1, got {n_burns!r}")
    n_burns = int(n_burns)
    v0 = float(np.sqrt(v_inf_kmps ** 2 + 2 * mu / rp_km))
    vc = perilune_speed_kmps(rp_km, final_period_s, mu)
    if n_burns == 1:
        return ()
    share = (v0 - vc) / n_burns
    v1 = v0 - share
    if max_period_s is not None and period_from_perilune_speed_s(rp_km, v1, mu) > max_period_s:
        v1 = perilune_speed_kmps(rp_km, max_period_s, mu)
        if v1 <= vc:
            final = "circle's" if final_period_s is None else "final orbit's"
            raise InputError(f"a longest period of {max_period_s / 3600:g} h is not longer than "
                             f"the {final} at r_p = {rp_km:g} km")
        share = (v1 - vc) / (n_burns - 1)
    if v1 ** 2 >= 2 * mu / rp_km:
        raise InputError(f"an equal share of {share * 1e3:.1f} m/s per burn leaves the "
                         f"spacecraft on a hyperbola after the first burn: give a longest "
                         f"period")
    speeds = [v1 - k * share for k in range(n_burns - 1)]
    return tuple(period_from_perilune_speed_s(rp_km, v, mu) for v in speeds)


def tangential_impulse_mps(r_km: float, v_kmps: float, a_target_km: float | None,
                           mu: float = C.MU_MOON) -> float:
    """Tangential impulse at radius r that turns speed v into the target orbit's energy, m/s.

    ``a_target_km`` is the target's semi-major axis (None: the circle of radius r). Where
    the target orbit cannot reach radius r (its apolune is below r), the whole speed is
    returned: a rough upper estimate. Sizes the first burn of a plan that starts from a
    given state (:class:`lunarcap.mission.plan.Start`), which need not be at a perilune.
    """
    a = r_km if a_target_km is None else a_target_km
    v2 = mu * (2.0 / r_km - 1.0 / a)
    v_new = float(np.sqrt(v2)) if v2 > 0 else 0.0
    return abs(float(v_kmps) - v_new) * 1e3
