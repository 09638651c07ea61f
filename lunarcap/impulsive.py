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

from . import constants as C
from .elements import semi_major_axis_from_period, vis_viva_speed
from .errors import InputError

#: Song 2011's impulsive LOI-1 delta-V, m/s (Table 1; from Song et al. 2009c).
PAPER_DV_LOI1_MPS = 353.272


def check_engine(thrust_N: float, isp_s: float, mass_kg: float | None = None) -> None:
    """Raise InputError unless thrust, Isp (and mass) are positive finite numbers."""
    for name, val, unit in (("thrust", thrust_N, "N"), ("specific impulse", isp_s, "s"),
                            ("mass", mass_kg, "kg")):
        if val is None and name == "mass":
            continue
        if not isinstance(val, (int, float, np.floating, np.integer)) or not np.isfinite(val) \
                or val <= 0:
            raise InputError(f"{name} must be a positive number of {unit}, got {val!r}")


def check_perilune_radius(rp_km: float, radius_km: float = C.R_MOON) -> None:
    """Raise InputError if a perilune lies at or below the lunar surface."""
    if not np.isfinite(rp_km) or rp_km <= radius_km:
        raise InputError(f"perilune radius {rp_km} km is at or below the lunar surface "
                         f"({radius_km} km): altitude must be positive")


def rocket_mass_after(m0_kg: float, dv_mps: float, isp_s: float) -> float:
    """Mass after a delta-V by the rocket equation, m0 exp(-dv/(g0 Isp)), kg."""
    return m0_kg * np.exp(-dv_mps / (C.G0_MPS2 * isp_s))


def burn_duration_estimate_s(m0_kg: float, dv_mps: float, thrust_N: float, isp_s: float) -> float:
    """Finite-burn duration estimate of Eq. (19), s.

    Eq. (19a) as printed, m_f = m0 [1 - exp(-dV/(g0 Isp))], is the propellant mass,
    not the final mass (a typo in Song 2011); Eq. (19b) t1 = (m0 - m_f) g0 Isp / T is
    meant with m_f the mass after the burn. Both readings give
    t1 = m0 [1 - exp(-dV/(g0 Isp))] g0 Isp / T.
    """
    check_engine(thrust_N, isp_s, m0_kg)
    fuel = m0_kg - rocket_mass_after(m0_kg, dv_mps, isp_s)
    return fuel * C.G0_MPS2 * isp_s / thrust_N


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
