"""Tests of lunarcap.physics.ephemeris against raw DE405 read directly with jplephem.

The reference values are computed here with ``jplephem.ephem.Ephemeris(de405)`` and the
two-part Julian date, independently of lunarcap's wrapper; the only lunarcap piece
used for them is the rotation ``frames.icrf_to_mme()`` of the default lunar pole
(tested in test_frames).
"""

import casadi as ca
import de405
import numpy as np
import pytest
from jplephem.ephem import Ephemeris as RawEphemeris

from lunarcap.errors import EphemerisRangeError, InputError
from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import ephemeris
from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.physics.frames import icrf_to_mme

C_ICRF_TO_MME = icrf_to_mme()  # the default pole's rotation

RAW = RawEphemeris(de405)
T_ARRIVAL = seconds_from_calendar(paper_scenario().epoch_tdb)
#: 1 m, in km: the accuracy the brief asks of every ephemeris path against raw DE405.
ONE_METRE = 1e-3


def _raw_moon_and_sun_icrf(t_s):
    """Geocentric Moon and Moon-centred Sun (ICRF, km) straight from DE405."""
    t = np.atleast_1d(np.asarray(t_s, float))
    days = t / 86400.0
    whole = 2451545.0 + np.floor(days)
    frac = days - np.floor(days)
    moon = RAW.position("moon", whole, frac)
    emb = RAW.position("earthmoon", whole, frac)
    sun = RAW.position("sun", whole, frac)
    # barycentric Moon = EMB + geocentric Moon * EMRAT/(1+EMRAT); EMRAT from the DE405 header
    moon_bary = emb + moon * (RAW.EMRAT / (1.0 + RAW.EMRAT))
    return moon, sun - moon_bary


def test_earth_moon_distance_at_arrival_matches_raw_de405():
    # Direct jplephem call at JD 2457804.5 + 03:41:26: the geocentric Moon distance.
    jd_frac = (3 * 3600 + 41 * 60 + 26) / 86400.0
    moon = np.ravel(RAW.position("moon", 2457804.5, jd_frac))
    d_raw = np.linalg.norm(moon)
    assert 356_000.0 < d_raw < 407_000.0  # between lunar perigee and apogee extremes
    r_earth, _ = ephemeris.default_ephemeris().earth_sun(T_ARRIVAL)
    assert abs(np.linalg.norm(r_earth[:, 0]) - d_raw) < ONE_METRE
    # the vector too: the Earth seen from the Moon is minus the geocentric Moon, rotated
    np.testing.assert_allclose(r_earth[:, 0], C_ICRF_TO_MME @ (-moon), rtol=0, atol=ONE_METRE)


def test_sun_and_moon_velocity_match_raw_de405():
    eph = ephemeris.default_ephemeris()
    t = T_ARRIVAL + np.array([-3600.0, 0.0, 7200.0])
    moon, sun = _raw_moon_and_sun_icrf(t)
    _, r_sun = eph.earth_sun(t)
    np.testing.assert_allclose(r_sun, C_ICRF_TO_MME @ sun, rtol=0, atol=ONE_METRE)
    # geocentric lunar velocity: central difference of raw positions over +-60 s.
    # Truncation |jerk| dt^2/6 ~ 7e-12 km/s^3 * 3600 s^2 / 6 ~ 4e-9 km/s; jplephem's
    # Chebyshev sums carry ~1e-6 km of round-off, /120 s ~ 1e-8 km/s: tolerance 1e-7 km/s.
    _, v_moon = eph.moon_geocentric_state(t)
    m_plus, _ = _raw_moon_and_sun_icrf(t + 60.0)
    m_minus, _ = _raw_moon_and_sun_icrf(t - 60.0)
    v_fd = C_ICRF_TO_MME @ ((m_plus - m_minus) / 120.0)
    np.testing.assert_allclose(v_moon, v_fd, rtol=0, atol=1e-7)
    assert np.all((np.linalg.norm(v_moon, axis=0) > 0.95) & (np.linalg.norm(v_moon, axis=0) < 1.1))


def test_chebyshev_fit_matches_raw_de405_over_mission_window(mission_fit):
    fit = mission_fit
    # the window spans the whole capture chain (first perilune to the end of the last coast)
    assert fit.t0_s <= T_ARRIVAL and fit.t1_s >= T_ARRIVAL + 20 * 3600
    t = np.linspace(fit.t0_s, fit.t1_s, 2001)  # ~1 min spacing, 31x denser than the nodes
    moon, sun = _raw_moon_and_sun_icrf(t)
    r_earth, r_sun = fit(t)
    err_e = np.linalg.norm(r_earth - C_ICRF_TO_MME @ (-moon), axis=0).max()
    err_s = np.linalg.norm(r_sun - C_ICRF_TO_MME @ sun, axis=0).max()
    assert err_e < ONE_METRE and err_s < ONE_METRE
    # the fit's self-reported error is an honest bound of the same order
    assert fit.max_error_km < ONE_METRE


def test_chebyshev_fit_casadi_equals_numpy(mission_fit):
    fit = mission_fit
    prm = ca.SX.sym("prm", 2 + 6 * ephemeris.ChebyshevFit.NCOEF)
    t = ca.SX.sym("t")
    re, rs = ephemeris.earth_sun_from_params([prm[i] for i in range(prm.numel())], t)
    fun = ca.Function("es", [prm, t], [ca.vertcat(*re, *rs)])
    rng = np.random.default_rng(11)
    for tt in rng.uniform(fit.t0_s, fit.t1_s, size=20):
        cas = np.asarray(fun(fit.param_vector(), tt)).ravel()
        ne, ns = fit(tt)
        ref = np.concatenate([np.ravel(ne), np.ravel(ns)])
        # same Clenshaw arithmetic in a different evaluator: only round-off may differ,
        # |r_sun| ~ 1.5e8 km times a few 1e-16 -> tolerance 1e-12 relative
        np.testing.assert_allclose(cas, ref, rtol=1e-12, atol=0)
        # and the numpy call through the parameter vector is the same function
        pe, ps = ephemeris.earth_sun_from_params(fit.param_vector(), tt)
        np.testing.assert_allclose(np.concatenate([pe, ps]), ref, rtol=1e-14, atol=0)


def test_chebyshev_eval_closed_form():
    # sum c_j T_j(tau) with T_j(cos th) = cos(j th): closed form for any coefficients
    rng = np.random.default_rng(3)
    c = rng.normal(size=(2, 9))
    th = np.linspace(0.0, np.pi, 31)
    got = np.array(ephemeris.chebyshev_eval(c, np.cos(th)))
    ref = np.array([[np.sum(row * np.cos(np.arange(9) * x)) for x in th] for row in c])
    np.testing.assert_allclose(got, ref, rtol=0, atol=1e-13)


def test_epoch_outside_ephemeris_raises():
    eph = ephemeris.default_ephemeris()
    t2300 = seconds_from_calendar("2300-01-01 00:00:00 TDB")
    with pytest.raises(EphemerisRangeError, match="outside the ephemeris"):
        eph.earth_sun(t2300)
    with pytest.raises(EphemerisRangeError):
        eph.check_epochs([T_ARRIVAL, np.nan])
    with pytest.raises(EphemerisRangeError):
        ephemeris.ChebyshevFit.fit(eph, t2300, t2300 + 3600.0)
    # DE405 covers JED 2305424.5 (1599-12-09) to 2525008.5 (2201-02-20) (Standish 1998):
    # the ends are usable, 1 s beyond is not
    a, b = eph.span_s
    assert (a, b) == ((2305424.5 - 2451545.0) * 86400.0, (2525008.5 - 2451545.0) * 86400.0)
    eph.earth_sun([a, b])
    for t in (a - 1.0, b + 1.0):
        with pytest.raises(EphemerisRangeError):
            eph.earth_sun(t)
    # and it is a bad-input error for callers that catch InputError / ValueError
    assert issubclass(EphemerisRangeError, InputError)
    assert issubclass(EphemerisRangeError, ValueError)


def test_bad_fit_windows_and_files_raise_input_error(tmp_path):
    eph = ephemeris.default_ephemeris()
    with pytest.raises(InputError):
        ephemeris.ChebyshevFit.fit(eph, T_ARRIVAL, T_ARRIVAL)  # empty window
    with pytest.raises(InputError):
        ephemeris.ChebyshevFit.fit(eph, T_ARRIVAL, T_ARRIVAL + 5 * 86400.0)  # > 4 days
    with pytest.raises(InputError):
        ephemeris.Ephemeris(tmp_path / "missing.bsp")
    junk = tmp_path / "junk.bsp"
    junk.write_bytes(b"not an SPK file" * 100)
    with pytest.raises(InputError):
        ephemeris.Ephemeris(junk)


# ---------------------------------------------------------------------- the Moon's orientation
def _angle_arcsec(a, b):
    """Angle of the rotation between two sets of axes (rows), arcsec."""
    d = np.asarray(a) @ np.asarray(b).T
    return float(np.degrees(np.arccos(np.clip((np.trace(d) - 1) / 2, -1, 1))) * 3600)


def test_de405_librations_read_raw():
    # the libration angles are DE405's own (jplephem's reader, straight from the package)
    raw = RAW.position("librations", 2451545.0, T_ARRIVAL / 86400.0)
    got = ephemeris.default_ephemeris().body_angles(T_ARRIVAL, "de405")
    np.testing.assert_allclose(got[:, 0], raw[:, 0], rtol=0, atol=1e-12)


def test_body_frames_are_100_arcsec_apart():
    # DE405's principal-axis frame and the IAU (2009) model (which approximates the mean-Earth
    # frame) differ by about 100" over 2017 (measured 92-109": 0.8-1.0 km at 100 km altitude);
    # a convention error (a sign, theta = dec, W missing) would be degrees
    from lunarcap.physics.frames import rotation_313

    t = seconds_from_calendar("2017-01-01 00:00:00 TDB") + np.linspace(0, 365 * 86400, 60)
    eph = ephemeris.default_ephemeris()
    a, b = eph.body_angles(t, "de405"), eph.body_angles(t, "iau2009")
    ang = [_angle_arcsec(rotation_313(*a[:, j]), rotation_313(*b[:, j])) for j in range(t.size)]
    assert 85.0 < min(ang) and max(ang) < 115.0


@pytest.mark.parametrize("frame", ["de405", "iau2009"])
def test_fitted_body_axes_equal_the_angles(mission_fit, frame):
    # the fit's axes in M-MME2000 = R313(angles) C^T, to the fit's 1e-9 rad; and the IAU
    # frame's pole is the IAU pole of date (frames.moon_pole_radec_deg)
    from lunarcap.physics.frames import moon_pole_icrf, moon_pole_radec_deg, rotation_313

    eph = ephemeris.default_ephemeris()
    fit = ephemeris.ChebyshevFit.fit(eph, mission_fit.t0_s, mission_fit.t1_s, body_frame=frame)
    C = icrf_to_mme()
    for t in np.linspace(fit.t0_s, fit.t1_s, 7):
        want = np.array(rotation_313(*eph.body_angles(t, frame)[:, 0])) @ C.T
        np.testing.assert_allclose(fit.body_axes(t), want, rtol=0, atol=2e-9)
        if frame == "iau2009":
            pole = C @ moon_pole_icrf(*moon_pole_radec_deg(jd_tdb=2451545.0 + t / 86400.0))
            np.testing.assert_allclose(fit.body_axes(t)[2], pole, rtol=0, atol=2e-9)
