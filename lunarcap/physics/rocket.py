"""The rocket equation and the finite-burn duration estimate of Eq. (19), Song 2011.

Masses in kg, delta-Vs in m/s, thrust in N, specific impulse in s, durations in s.
"""

from __future__ import annotations

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics import constants as C


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


def _scalar(x):
    """A Python float for a scalar result (the paper's audit compares them as floats)."""
    return float(x) if np.ndim(x) == 0 else x


def exhaust_speed_mps(isp_s: float) -> float:
    """Effective exhaust speed g0 Isp, m/s."""
    return C.G0_MPS2 * isp_s


def rocket_mass_after(m0_kg: float, dv_mps: float, isp_s: float) -> float:
    """Mass after a delta-V by the rocket equation, m0 exp(-dv/(g0 Isp)), kg."""
    return _scalar(m0_kg * np.exp(-dv_mps / exhaust_speed_mps(isp_s)))


def rocket_mass_before(m1_kg: float, dv_mps: float, isp_s: float) -> float:
    """Mass before a delta-V that leaves ``m1_kg``, m1 exp(dv/(g0 Isp)), kg."""
    return _scalar(m1_kg * np.exp(dv_mps / exhaust_speed_mps(isp_s)))


def rocket_propellant_kg(m0_kg: float, dv_mps: float, isp_s: float) -> float:
    """Propellant a delta-V burns from ``m0_kg``, m0 [1 - exp(-dv/(g0 Isp))], kg."""
    return m0_kg - rocket_mass_after(m0_kg, dv_mps, isp_s)


def rocket_delta_v_mps(m0_kg: float, m1_kg: float, isp_s: float) -> float:
    """Delta-V that takes the mass from ``m0_kg`` to ``m1_kg``, g0 Isp ln(m0/m1), m/s.

    >>> round(float(rocket_delta_v_mps(524.895, rocket_mass_after(524.895, 353.272, 200.0),
    ...                                200.0)), 9)
    353.272
    """
    return _scalar(exhaust_speed_mps(isp_s) * np.log(m0_kg / m1_kg))


def burn_duration_estimate_s(m0_kg: float, dv_mps: float, thrust_N: float, isp_s: float) -> float:
    """Finite-burn duration estimate of Eq. (19), s.

    Eq. (19a) as printed, m_f = m0 [1 - exp(-dV/(g0 Isp))], is the propellant mass,
    not the final mass (a typo in Song 2011); Eq. (19b) t1 = (m0 - m_f) g0 Isp / T is
    meant with m_f the mass after the burn. Both readings give
    t1 = m0 [1 - exp(-dV/(g0 Isp))] g0 Isp / T.
    """
    check_engine(thrust_N, isp_s, m0_kg)
    return rocket_propellant_kg(m0_kg, dv_mps, isp_s) * exhaust_speed_mps(isp_s) / thrust_N
