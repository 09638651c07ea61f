"""Reference frames: ICRF/J2000 -> Moon-centred M-MME2000, and RTN unit vectors.

M-MME2000 (Song et al. 2010b; Song 2011, Sec. 1): origin at the Moon's centre,
z along the IAU lunar pole at J2000 (alpha0 = 269.9949 deg, delta0 = 66.5392 deg,
Archinal et al. 2011), x along the IAU node of the lunar equator on the ICRF
equator, x = z_ICRF x z_Moon / |z_ICRF x z_Moon|, y = z x x.
"""

from __future__ import annotations

import numpy as np

from lunarcap.physics.constants import MOON_POLE_DEC_DEG, MOON_POLE_RA_DEG


def moon_pole_icrf(ra_deg: float = MOON_POLE_RA_DEG, dec_deg: float = MOON_POLE_DEC_DEG
                   ) -> np.ndarray:
    """Unit vector of the lunar pole in ICRF from its right ascension and declination (deg)."""
    a, d = np.radians(ra_deg), np.radians(dec_deg)
    return np.array([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)])


def icrf_to_mme2000(ra_deg: float = MOON_POLE_RA_DEG, dec_deg: float = MOON_POLE_DEC_DEG
                    ) -> np.ndarray:
    """Rotation matrix C such that ``x_mme = C @ x_icrf``.

    Rows are the M-MME2000 axes expressed in ICRF. For a pole (alpha0, delta0) this
    equals R1(90 deg - delta0) R3(90 deg + alpha0).
    """
    z = moon_pole_icrf(ra_deg, dec_deg)
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return np.vstack([x, y, z])


#: The constant rotation ICRF -> M-MME2000 used throughout.
C_ICRF_TO_MME = icrf_to_mme2000()


def rtn_basis(r, v, xp=np):
    """Radial, tangential and normal unit vectors of Eq. (A5), Song 2011.

    Parameters
    ----------
    r, v : array_like, shape (3,) or (3, N)
        Position (km) and velocity (km/s) in an inertial frame.
    xp : module
        Array namespace (numpy by default).

    Returns
    -------
    ndarray, shape (3, 3) (or (3, 3, N))
        Rows i_r, i_t, i_n, so ``a_rtn = Q @ a_inertial``.
        i_r = r/|r|; i_n = (r x v)/|r x v|; i_t = i_n x i_r (Eq. A5 writes
        i_t = (r x v) x r / |(r x v) x r|, the same vector).
    """
    r = np.asarray(r, dtype=float)
    v = np.asarray(v, dtype=float)
    ir = r / np.linalg.norm(r, axis=0)
    h = np.cross(r, v, axis=0)
    i_n = h / np.linalg.norm(h, axis=0)
    it = np.cross(i_n, ir, axis=0)
    return np.stack([ir, it, i_n], axis=0)


def thrust_angles_deg(u_rtn):
    """Thrust angles of Eq. (14), Song 2011, from RTN thrust directions, degrees.

    alpha = atan2(u_r, u_t) (Eq. 14a), the in-plane angle from the tangential axis,
    wrapped to [0, 360); beta = asin(u_n / |u|) (Eq. 14b), the out-of-plane angle.
    Vectorised: ``u_rtn`` may have shape (3,) or (3, N).

    Examples
    --------
    >>> a, b = thrust_angles_deg([0.0, -1.0, 0.0])
    >>> float(a), float(b)
    (180.0, 0.0)
    """
    u = np.asarray(u_rtn, dtype=float)
    norm = np.linalg.norm(u, axis=0)
    alpha = np.degrees(np.arctan2(u[0], u[1])) % 360.0
    beta = np.degrees(np.arcsin(np.clip(u[2] / norm, -1.0, 1.0)))
    return alpha, beta


def thrust_direction_rtn(alpha_deg: float, beta_deg: float) -> np.ndarray:
    """Unit thrust direction (u_r, u_t, u_n) from the thrust angles (inverse of Eq. 14).

    ``(cos b sin a, cos b cos a, sin b)`` with a = alpha, b = beta in degrees.
    """
    a, b = np.radians(alpha_deg), np.radians(beta_deg)
    return np.array([np.cos(b) * np.sin(a), np.cos(b) * np.cos(a), np.sin(b)])
