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
