"""Orbital elements: classical, modified equinoctial (MEE) and Cartesian.

Modified equinoctial elements (Walker, Ireland & Owens 1985; Song 2011 Eq. 1):
``y = (p, f, g, h, k, L)`` with p in km and L in radians. They are valid for
circular, elliptic and hyperbolic orbits (p > 0) and singular only at i = 180 deg.

Every function takes the gravitational parameter ``mu`` (km^3/s^2) explicitly and
is written over generic array operations, so it evaluates on numpy arrays (shape
(N,) per element, vectorised) and on CasADi symbols alike.
"""

from __future__ import annotations

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops


# --------------------------------------------------------------------------- classical
def mee_from_coe(a, e, i, raan, argp, nu):
    """MEE from classical elements, Eq. (A1).

    Parameters
    ----------
    a : semi-major axis, km (negative for a hyperbola)
    e : eccentricity
    i, raan, argp, nu : inclination, right ascension of the ascending node,
        argument of periapsis, true anomaly, rad

    Returns
    -------
    tuple (p km, f, g, h, k, L rad)
    """
    xp = ops(a, e, i, raan, argp, nu)
    p = a * (1 - e * e)
    lp = raan + argp
    return (p, e * xp.cos(lp), e * xp.sin(lp),
            xp.sin(i / 2) / xp.cos(i / 2) * xp.cos(raan),
            xp.sin(i / 2) / xp.cos(i / 2) * xp.sin(raan), lp + nu)


def coe_from_mee(p, f, g, h, k, L):
    """Classical elements (a km, e, i, raan, argp, nu rad) from MEE (inverse of Eq. A1).

    For e = 0 the argument of periapsis is undefined and taken as 0 (nu = L - raan);
    for i = 0 the node is undefined and taken as 0. a is negative for a hyperbola
    and infinite for a parabola.
    """
    xp = ops(p, f, g, h, k, L)
    e = xp.sqrt(f * f + g * g)
    i = 2 * xp.arctan(xp.sqrt(h * h + k * k))
    raan = xp.atan2(k, h)
    lp = xp.atan2(g, f)
    with np.errstate(divide="ignore"):
        a = p / (1 - e * e)
    return a, e, i, raan, lp - raan, L - lp


# --------------------------------------------------------------------------- Cartesian
def rv_from_mee(p, f, g, h, k, L, mu):
    """Cartesian position (km) and velocity (km/s) from MEE, Eq. (A6)-(A7).

    Returns
    -------
    r, v : tuples of three components (x, y, z)
    """
    xp = ops(p, f, g, h, k, L)
    cL, sL = xp.cos(L), xp.sin(L)
    alpha2 = h * h - k * k
    s2 = 1 + h * h + k * k
    q = 1 + f * cL + g * sL
    r = p / q
    hk2 = 2 * h * k
    rs = r / s2
    rvec = (rs * (cL + alpha2 * cL + hk2 * sL),
            rs * (sL - alpha2 * sL + hk2 * cL),
            2 * rs * (h * sL - k * cL))
    c = -xp.sqrt(mu / p) / s2
    vvec = (c * (sL + alpha2 * sL - hk2 * cL + g - 2 * f * h * k + alpha2 * g),
            c * (-cL + alpha2 * cL + hk2 * sL - f + 2 * g * h * k + alpha2 * f),
            c * (-2 * (h * cL + k * sL + f * h + g * k)))
    return rvec, vvec


def mee_from_rv(r, v, mu):
    """MEE from Cartesian position (km) and velocity (km/s) (Betts 2010, Sec. 6.3).

    Parameters
    ----------
    r, v : array_like, shape (3,) or (3, N)
    mu : float, km^3/s^2

    Returns
    -------
    ndarray, shape (6,) or (6, N): p km, f, g, h, k, L rad (L in (-pi, pi]).
    """
    r = np.asarray(r, dtype=float)
    v = np.asarray(v, dtype=float)
    hv = np.cross(r, v, axis=0)
    hmag = np.linalg.norm(hv, axis=0)
    rmag = np.linalg.norm(r, axis=0)
    p = hmag ** 2 / mu
    hh = hv / hmag
    if np.any(hh[2] <= -1 + 1e-14):
        raise InputError("modified equinoctial elements are singular for a retrograde "
                         "equatorial orbit (i = 180 deg)")
    k = hh[0] / (1 + hh[2])
    h = -hh[1] / (1 + hh[2])
    s2 = 1 + h * h + k * k
    fhat = np.array([1 - k * k + h * h, 2 * k * h, -2 * k]) / s2
    ghat = np.array([2 * k * h, 1 + k * k - h * h, 2 * h]) / s2
    ev = np.cross(v, hv, axis=0) / mu - r / rmag
    f = np.sum(ev * fhat, axis=0)
    g = np.sum(ev * ghat, axis=0)
    L = np.arctan2(np.sum(r * ghat, axis=0), np.sum(r * fhat, axis=0))
    return np.array([p, f, g, h, k, L])


def rv_from_coe(a, e, i, raan, argp, nu, mu):
    """Cartesian state from classical elements (through MEE), arrays of shape (3,)."""
    r, v = rv_from_mee(*mee_from_coe(a, e, i, raan, argp, nu), mu)
    return np.array(r, dtype=float), np.array(v, dtype=float)


# --------------------------------------------------------------------------- Eq. (18)
def eccentricity(f, g):
    """Eccentricity from MEE, e = sqrt(f^2 + g^2)."""
    return ops(f, g).sqrt(f * f + g * g)


def perilune_radius(p, f, g):
    """Periapsis radius r_p = p / (1 + e), km, Eq. (18a)."""
    return p / (1 + eccentricity(f, g))


def apolune_radius(p, f, g):
    """Apoapsis radius r_a = p / (1 - e), km (ellipses only)."""
    e = eccentricity(f, g)
    if not ops(e).casadi and np.any(np.asarray(e) >= 1):
        raise InputError("an apoapsis radius was asked of a parabola or hyperbola (e >= 1)")
    return p / (1 - e)


def inclination(h, k):
    """Inclination i = 2 atan(sqrt(h^2 + k^2)), rad, Eq. (18b)."""
    xp = ops(h, k)
    return 2 * xp.arctan(xp.sqrt(h * h + k * k))


def radial_factor(f, g, L):
    """F sin L - g cos L = e sin(nu): the radial velocity over sqrt(mu/p)."""
    xp = ops(f, g, L)
    return f * xp.sin(L) - g * xp.cos(L)


def periapsis_factor(f, g, L):
    """F cos L + g sin L = e cos(nu): positive at periapsis, negative at apoapsis."""
    xp = ops(f, g, L)
    return f * xp.cos(L) + g * xp.sin(L)


def flight_path_angle(p, f, g, L):
    """Flight-path angle gamma = asin(r.v / (|r||v|)), rad, Eq. (18c).

    In MEE, tan(gamma) = (f sin L - g cos L) / (1 + f cos L + g sin L).
    """
    xp = ops(p, f, g, L)
    q = 1 + f * xp.cos(L) + g * xp.sin(L)
    return xp.atan2(radial_factor(f, g, L), q)


def speed_from_mee(p, f, g, L, mu):
    """Speed |v| (km/s for p in km) from MEE: v^2 = mu/p (1 + e^2 + 2 e cos(nu))."""
    xp = ops(p, f, g, L)
    return xp.sqrt(mu / p * (1 + f ** 2 + g ** 2 + 2 * (f * xp.cos(L) + g * xp.sin(L))))


def semi_major_axis_from_period(period_s, mu):
    """Semi-major axis (km) of an ellipse of the given period (s)."""
    if np.any(np.asarray(period_s) <= 0):
        raise InputError("an orbital period must be positive")
    return (mu * (np.asarray(period_s) / (2 * np.pi)) ** 2) ** (1.0 / 3.0)


def period_from_semi_major_axis(a_km, mu):
    """Kepler period (s) of an ellipse of semi-major axis ``a_km`` (km) about ``mu`` (km^3/s^2)."""
    return 2 * np.pi * np.sqrt(np.asarray(a_km, float) ** 3 / mu)


def period(p, f, g, mu):
    """Keplerian period (s) of an ellipse from MEE; a hyperbola has none (InputError)."""
    e = np.asarray(eccentricity(f, g))
    if np.any(e >= 1):
        raise InputError(f"an orbital period was asked of a hyperbola or parabola (e = {e})")
    return period_from_semi_major_axis(np.asarray(p) / (1 - e * e), mu)


def vis_viva_speed(r, a, mu):
    """Speed (km/s) at radius r (km) on an orbit of semi-major axis a (km; a < 0 hyperbola)."""
    return np.sqrt(mu * (2.0 / r - 1.0 / a))


def orbit_summary(x, mu) -> dict:
    """Radius, speed and shape of a numeric MEE state (p km, f, g, h, k, L rad, ...).

    Returns
    -------
    dict
        ``rp_km`` and ``ra_km`` (inf for e >= 1), ``inc_deg``, ``gamma_deg``, ``e``,
        ``p_km``, ``v_kmps``, ``r_km``.
    """
    p, f, g, h, k, L = (float(v) for v in x[:6])
    e = float(eccentricity(f, g))
    r, _ = rv_from_mee(p, f, g, h, k, L, mu)
    return {"rp_km": float(perilune_radius(p, f, g)),
            "ra_km": p / (1 - e) if e < 1 else float("inf"),
            "inc_deg": float(np.degrees(inclination(h, k))),
            "gamma_deg": float(np.degrees(flight_path_angle(p, f, g, L))),
            "e": e, "p_km": p, "v_kmps": float(speed_from_mee(p, f, g, L, mu)),
            "r_km": float(np.linalg.norm(r))}


def mean_motion_and_anomaly(x, mu):
    """Osculating mean motion (rad/s) and mean anomaly (rad, in (-pi, pi]) of MEE state(s).

    ``x``: (p km, f, g, h, k, L rad, ...) of one state or of states in columns; ``mu``
    km^3/s^2. An elliptic orbit only (e < 1).
    """
    p, f, g, L = x[0], x[1], x[2], x[5]
    e = np.hypot(f, g)
    a = p / (1 - e * e)
    nu = np.angle(np.exp(1j * (L - np.arctan2(g, f))))  # wrapped to (-pi, pi]
    E = 2 * np.arctan2(np.sqrt(1 - e) * np.sin(nu / 2), np.sqrt(1 + e) * np.cos(nu / 2))
    return np.sqrt(mu / a ** 3), E - e * np.sin(E)
