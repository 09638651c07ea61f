"""Reference frames: ICRF/J2000 -> Moon-centred M-MME2000, and RTN unit vectors.

M-MME2000 (Song et al. 2010b; Song 2011, Sec. 1: "Moon centered Moon mean equator and
International Astronomical Union vector of J2000"): origin at the Moon's centre, z along
the lunar pole of the plan (``lunar_pole``, below), x along the IAU vector, the ascending
node of the lunar equator on the ICRF equator, x = z_ICRF x z_Moon / |z_ICRF x z_Moon|,
y = z x x. The frame is inertial, so its one rotation from ICRF, :func:`icrf_to_mme`,
applies to velocities as to positions (:func:`mme_from_icrf`, :func:`icrf_from_mme`);
everything lunarcap exchanges with other tools (:mod:`lunarcap.exchange`) is Moon-centred
ICRF. SPICE's ``J2000`` is taken as ICRF, as NAIF labels the DE ephemerides (the 17 mas
frame bias, 0.2 m at 2,000 km, is not applied).

The lunar poles (:data:`LUNAR_POLES`), from the IAU (2009) orientation model (Archinal et
al. 2011, Table 2):

``iau2009-j2000`` (default)
    The whole expression, with its E1-E13 terms, at J2000: alpha0 = 266.8577 deg,
    delta0 = 65.6411 deg, the Moon's axis at that epoch (1.57 deg from the ecliptic pole,
    by Cassini's laws), so that the lunar J2 acts about it and "90 deg inclination" is
    polar about it.
``iau-constant``
    The constant terms only, alpha0 = 269.9949 deg, delta0 = 66.5392 deg: the centre of
    the pole's 18.6-year precession circle, 1.56 deg from the pole at J2000; kept to show
    what the choice of the pole changes (the book's lunar pole page).
"""

from __future__ import annotations

import numpy as np

from lunarcap.physics import constants as C
from lunarcap.physics.constants import MOON_POLE_DEC_DEG, MOON_POLE_RA_DEG

#: The lunar pole choices of :func:`moon_pole_radec_deg` (first: the default). Besides
#: these names, ``"iau2009@<epoch>"`` (:func:`pole_of_date`) names the whole IAU
#: expression at another epoch: the frame whose z is the Moon's axis of that date.
LUNAR_POLES = ("iau2009-j2000", "iau-constant")
DEFAULT_LUNAR_POLE = LUNAR_POLES[0]
#: Prefix of a pole of date: ``"iau2009@2017-02-20 03:41:26 TDB"``.
POLE_OF_DATE_PREFIX = "iau2009@"


def pole_of_date(epoch: str) -> str:
    """The lunar pole choice of the IAU (2009) pole at a calendar epoch (TDB or UTC).

    The frame it fixes is inertial, like M-MME2000, with z along the Moon's axis of that
    date instead of J2000's (0.79 deg apart in 2017). Plans whose dynamics ask for the
    pole of date measure their inclinations about it (the epoch: their arrival's).

    Examples
    --------
    >>> pole_of_date("2017-02-20 03:41:26 TDB")
    'iau2009@2017-02-20 03:41:26 TDB'
    """
    return POLE_OF_DATE_PREFIX + epoch.strip()


def check_lunar_pole(pole) -> str:
    """``pole`` if it names a lunar pole (a :data:`LUNAR_POLES` name or a pole of date).

    Raises
    ------
    ValueError
        Naming the choices (or the epoch that cannot be read).
    """
    if isinstance(pole, str) and pole.startswith(POLE_OF_DATE_PREFIX):
        _pole_epoch_jd(pole)
        return pole
    if pole not in LUNAR_POLES:
        raise ValueError(f"lunar pole must be one of {', '.join(LUNAR_POLES)} or "
                         f"'{POLE_OF_DATE_PREFIX}<epoch>', got {pole!r}")
    return pole


def _pole_epoch_jd(pole: str) -> float:
    """Julian date (TDB) of a pole of date ``"iau2009@<epoch>"``."""
    from lunarcap.physics.epochs import jd_from_seconds, seconds_from_calendar

    try:
        return jd_from_seconds(seconds_from_calendar(pole[len(POLE_OF_DATE_PREFIX):]))
    except Exception as exc:  # InputError from the calendar parser
        raise ValueError(f"lunar pole {pole!r}: {exc}") from None


def moon_pole_radec_deg(pole: str = DEFAULT_LUNAR_POLE, jd_tdb: float = C.JD_J2000
                        ) -> tuple[float, float]:
    """Right ascension and declination of the lunar pole in ICRF, degrees.

    Parameters
    ----------
    pole : {"iau2009-j2000", "iau-constant"} or "iau2009@<epoch>"
        The whole IAU (2009) expression (Archinal et al. 2011, Table 2) or its constant
        terms only (see the module docstring); a pole of date (:func:`pole_of_date`) is
        the whole expression at its epoch (``jd_tdb`` is then ignored).
    jd_tdb : float
        Epoch of the whole expression, Julian date TDB (M-MME2000: J2000).

    Examples
    --------
    >>> [round(x, 4) for x in moon_pole_radec_deg()]
    [266.8577, 65.6411]
    >>> moon_pole_radec_deg("iau-constant")
    (269.9949, 66.5392)
    """
    if pole == "iau-constant":
        return MOON_POLE_RA_DEG, MOON_POLE_DEC_DEG
    if check_lunar_pole(pole) != "iau2009-j2000":   # a pole of date: at its own epoch
        jd_tdb = _pole_epoch_jd(pole)
    d = jd_tdb - C.JD_J2000
    t = d / 36525.0
    e = np.radians(np.asarray(C.MOON_E_PHASE_DEG) + np.asarray(C.MOON_E_RATE_DEG_PER_DAY) * d)
    ra = MOON_POLE_RA_DEG + C.MOON_POLE_RA_RATE_DEG * t + float(
        np.dot(C.MOON_POLE_RA_AMPL_DEG, np.sin(e)))
    dec = MOON_POLE_DEC_DEG + C.MOON_POLE_DEC_RATE_DEG * t + float(
        np.dot(C.MOON_POLE_DEC_AMPL_DEG, np.cos(e)))
    return ra, dec


def iau_moon_euler_rad(t_s):
    """Euler angles (phi, theta, psi) of the IAU (2009) lunar body-fixed frame, rad.

    The whole expression of Archinal et al. (2011, Table 2) with its E1-E13 terms:
    phi = alpha0 + 90 deg, theta = 90 deg - delta0, psi = W (the prime meridian), so that
    ICRF -> body = R3(psi) R1(theta) R3(phi) (:func:`rotation_313`), the convention of the
    JPL libration angles (:meth:`lunarcap.physics.ephemeris.Ephemeris.librations`). This
    frame approximates the Moon's mean-Earth/polar-axis frame; a gravity field given in
    the principal-axis frame differs from it by about 0.02 deg (see the book).

    Parameters
    ----------
    t_s : float or ndarray
        TDB seconds past J2000.

    Returns
    -------
    phi, theta, psi : float or ndarray, rad (psi not reduced to one turn)
    """
    d = np.asarray(t_s, float) / C.DAY_S
    t = d / 36525.0
    e = np.radians(np.multiply.outer(C.MOON_E_RATE_DEG_PER_DAY, d)
                   + np.reshape(C.MOON_E_PHASE_DEG, (-1,) + (1,) * d.ndim))
    se, ce = np.sin(e), np.cos(e)
    ra = MOON_POLE_RA_DEG + C.MOON_POLE_RA_RATE_DEG * t + np.tensordot(
        C.MOON_POLE_RA_AMPL_DEG, se, axes=1)
    dec = MOON_POLE_DEC_DEG + C.MOON_POLE_DEC_RATE_DEG * t + np.tensordot(
        C.MOON_POLE_DEC_AMPL_DEG, ce, axes=1)
    w = C.MOON_W_DEG + C.MOON_W_RATE_DEG_PER_DAY * d + C.MOON_W_ACCEL_DEG_PER_DAY2 * d * d \
        + np.tensordot(C.MOON_W_AMPL_DEG, se, axes=1)
    return np.radians(ra + 90.0), np.radians(90.0 - dec), np.radians(w)


def rotation_313(phi, theta, psi):
    """Rows of R3(psi) R1(theta) R3(phi): the axes of a body frame in the reference frame.

    Generic over numpy and CasADi (nested tuples of scalars): ``x_body = R x_ref``.
    The third row is the body's pole, (sin theta sin phi, -sin theta cos phi, cos theta).
    """
    from lunarcap.physics._ops import ops

    xp = ops(phi, theta, psi)
    cf, sf, ct, st, cp, sp = (xp.cos(phi), xp.sin(phi), xp.cos(theta), xp.sin(theta),
                              xp.cos(psi), xp.sin(psi))
    return ((cp * cf - sp * ct * sf, cp * sf + sp * ct * cf, sp * st),
            (-sp * cf - cp * ct * sf, -sp * sf + cp * ct * cf, cp * st),
            (st * sf, -st * cf, ct))


def moon_pole_icrf(ra_deg: float = MOON_POLE_RA_DEG, dec_deg: float = MOON_POLE_DEC_DEG
                   ) -> np.ndarray:
    """Unit vector of a pole in ICRF from its right ascension and declination (deg)."""
    a, d = np.radians(ra_deg), np.radians(dec_deg)
    return np.array([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)])


def icrf_to_mme2000(ra_deg: float, dec_deg: float) -> np.ndarray:
    """Rotation matrix C such that ``x_mme = C @ x_icrf``, for a lunar pole (deg).

    Rows are the M-MME2000 axes expressed in ICRF. For a pole (alpha0, delta0) this
    equals R1(90 deg - delta0) R3(90 deg + alpha0).
    """
    z = moon_pole_icrf(ra_deg, dec_deg)
    x = np.cross([0.0, 0.0, 1.0], z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return np.vstack([x, y, z])


def icrf_to_mme(pole: str = DEFAULT_LUNAR_POLE) -> np.ndarray:
    """The rotation ICRF -> M-MME2000 for a lunar pole choice (see :data:`LUNAR_POLES`)."""
    return icrf_to_mme2000(*moon_pole_radec_deg(pole))


def mme_from_icrf(vectors, pole: str = DEFAULT_LUNAR_POLE) -> np.ndarray:
    """Vectors (3,) or (3, N) from Moon-centred ICRF axes to M-MME2000 (positions or velocities).

    Examples
    --------
    >>> v = mme_from_icrf([0.0, 0.0, 1.0])   # the ICRF pole seen from M-MME2000
    >>> round(float(v[2]), 5)                # sin(65.6411 deg), the pole's declination
    0.91098
    """
    return icrf_to_mme(pole) @ np.asarray(vectors, float)


def icrf_from_mme(vectors, pole: str = DEFAULT_LUNAR_POLE) -> np.ndarray:
    """Vectors (3,) or (3, N) from M-MME2000 to Moon-centred ICRF (:func:`mme_from_icrf`)."""
    return icrf_to_mme(pole).T @ np.asarray(vectors, float)


def pole_angle_deg(pole_a: str, pole_b: str) -> float:
    """Angle between two lunar pole choices, degrees."""
    za, zb = (moon_pole_icrf(*moon_pole_radec_deg(p)) for p in (pole_a, pole_b))
    return float(np.degrees(np.arccos(np.clip(za @ zb, -1.0, 1.0))))


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
