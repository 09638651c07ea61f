"""Two-body impulsive capture sequence and the burn-duration estimate of Eq. (19).

Capture at a fixed perilune radius r_p = R_Moon + 100 km:
hyperbola (v_inf) -> ellipse of period 12.235 h -> ellipse of 3.525 h -> circle,
each impulse tangential at perilune. The arrival hyperbola's v_inf is not printed in
Song 2011; it is derived here from the paper's impulsive LOI-1 delta-V (353.272 m/s),
so LOI 1 reproduces that number by construction and LOI 2-3 are genuine checks.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from lunarcap.physics import constants as C
from lunarcap.physics.elements import semi_major_axis_from_period, vis_viva_speed
from lunarcap.physics.rocket import (
    burn_duration_estimate_s,
    check_engine,
    check_perilune_radius,
    rocket_mass_after,
)
from lunarcap.errors import InputError

#: Song 2011's impulsive LOI-1 delta-V, m/s (Table 1; from Song et al. 2009c).
PAPER_DV_LOI1_MPS = 353.272


def v_inf_from_loi1(dv_loi1_mps: float = PAPER_DV_LOI1_MPS, rp_km: float | None = None,
                    period_s: float = C.CAPTURE_PERIODS_S[0], mu: float = C.MU_MOON) -> float:
    """Hyperbolic excess speed (km/s) whose tangential perilune impulse dv gives the period."""
    rp = C.R_MOON + C.PERILUNE_ALTITUDE_KM if rp_km is None else rp_km
    check_perilune_radius(rp)
    a1 = semi_major_axis_from_period(period_s, mu)
    vp_hyp = vis_viva_speed(rp, a1, mu) + dv_loi1_mps * 1e-3
    vinf2 = vp_hyp ** 2 - 2 * mu / rp
    if vinf2 <= 0:
        raise InputError("the given LOI-1 delta-V leaves the spacecraft bound before LOI")
    return float(np.sqrt(vinf2))


@dataclass
class ImpulsiveBurn:
    """One impulsive LOI at perilune (speeds km/s, delta-V m/s, masses kg, durations min)."""

    loi: int
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


def impulsive_sequence(thrust_N: float = 150.0, isp_s: float = 200.0,
                       mass_kg: float = C.ARRIVAL_MASS_KG, altitude_km: float = 100.0,
                       v_inf_kmps: float | None = None, periods_s=C.CAPTURE_PERIODS_S[:2],
                       mu: float = C.MU_MOON, eq19_masses_kg=None) -> list[ImpulsiveBurn]:
    """The two-body impulsive capture sequence at a fixed perilune radius.

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

    Returns
    -------
    list of three ImpulsiveBurn
    """
    check_engine(thrust_N, isp_s, mass_kg)
    rp = C.R_MOON + altitude_km
    check_perilune_radius(rp)
    if v_inf_kmps is None:
        v_inf_kmps = v_inf_from_loi1(rp_km=rp, period_s=periods_s[0], mu=mu)
    if not np.isfinite(v_inf_kmps) or v_inf_kmps <= 0:
        raise InputError(f"v_inf must be positive (km/s), got {v_inf_kmps}")
    speeds = [np.sqrt(v_inf_kmps ** 2 + 2 * mu / rp)]
    for T in periods_s:
        speeds.append(vis_viva_speed(rp, semi_major_axis_from_period(T, mu), mu))
    speeds.append(np.sqrt(mu / rp))
    periods_h = [np.inf] + [T / 3600 for T in periods_s] + [2 * np.pi * np.sqrt(rp ** 3 / mu) / 3600]
    burns = []
    m = mass_kg
    for i in range(3):
        dv = (speeds[i] - speeds[i + 1]) * 1e3
        m_after = rocket_mass_after(m, dv, isp_s)
        m19 = m if eq19_masses_kg is None else eq19_masses_kg[i]
        t19 = burn_duration_estimate_s(m19, dv, thrust_N, isp_s) / 60
        burns.append(ImpulsiveBurn(i + 1, periods_h[i], periods_h[i + 1], speeds[i],
                                   speeds[i + 1], dv, m, m_after, m - m_after, t19))
        m = m_after
    return burns
