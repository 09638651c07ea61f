"""Tests of lunarcap.physics.frames: the ICRF -> M-MME2000 rotation and the RTN basis (Eq. A5)."""

import numpy as np
import pytest

from lunarcap.physics import frames

# Double-precision round-off on unit vectors built from a few trigonometric calls and
# cross products is a few 1e-16; 1e-14 leaves a margin and still catches any real error.
TOL = 1e-14


def _r1(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1, 0, 0], [0, c, s], [0, -s, c]])


def _r3(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, s, 0], [-s, c, 0], [0, 0, 1]])


C_FULL = frames.icrf_to_mme("iau2009-j2000")
C_CONST = frames.icrf_to_mme("iau-constant")
#: The ecliptic pole of J2000 in ICRF (RA 270 deg, Dec 90 deg - 23.4392911 deg, the IAU 1976
#: obliquity of J2000; the ICRF/J2000 frame bias, 0.02 arcsec, is far below what is tested).
ECLIPTIC_POLE = frames.moon_pole_icrf(270.0, 90.0 - 23.4392911)


def _angle_deg(a, b):
    return float(np.degrees(np.arccos(np.clip(a @ b, -1.0, 1.0))))


@pytest.mark.parametrize("C", [C_FULL, C_CONST])
def test_mme2000_rotation_is_proper_orthonormal(C):
    np.testing.assert_allclose(C @ C.T, np.eye(3), atol=TOL)
    assert np.linalg.det(C) == pytest.approx(1.0, abs=TOL)


def test_default_pole_is_the_whole_iau_expression_at_j2000():
    # The IAU (2009) expression at J2000 (d = T = 0), evaluated term by term here:
    # alpha0 = 269.9949 - 3.8787 sin E1 - 0.1204 sin E2 + 0.0700 sin E3 - 0.0172 sin E4
    #          + 0.0072 sin E6 - 0.0052 sin E10 + 0.0043 sin E13, and likewise delta0.
    s = lambda deg: np.sin(np.radians(deg))  # noqa: E731
    c = lambda deg: np.cos(np.radians(deg))  # noqa: E731
    ra = (269.9949 - 3.8787 * s(125.045) - 0.1204 * s(250.089) + 0.0700 * s(260.008)
          - 0.0172 * s(176.625) + 0.0072 * s(311.589) - 0.0052 * s(15.134) + 0.0043 * s(25.053))
    dec = (66.5392 + 1.5419 * c(125.045) + 0.0239 * c(250.089) - 0.0278 * c(260.008)
           + 0.0068 * c(176.625) - 0.0029 * c(311.589) + 0.0009 * c(134.963)
           + 0.0008 * c(15.134) - 0.0009 * c(25.053))
    got = frames.moon_pole_radec_deg()
    assert got == pytest.approx((ra, dec), abs=1e-12)
    assert got == pytest.approx((266.86, 65.64), abs=0.005)  # the value quoted in issue 10
    pole = frames.moon_pole_icrf(*got)
    np.testing.assert_allclose(C_FULL[2], pole, atol=TOL)
    np.testing.assert_allclose(C_FULL @ pole, [0, 0, 1], atol=TOL)
    # 1.556 deg from the constant-term pole used before
    assert frames.pole_angle_deg("iau2009-j2000", "iau-constant") == pytest.approx(1.556,
                                                                                    abs=0.001)


def test_constant_terms_pole():
    assert frames.moon_pole_radec_deg("iau-constant") == (269.9949, 66.5392)
    a, d = np.radians(269.9949), np.radians(66.5392)
    pole = np.array([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)])
    np.testing.assert_allclose(C_CONST[2], pole, atol=TOL)


def test_lunar_pole_obeys_cassini_law_over_a_nodal_cycle():
    # Cassini: the lunar equator keeps a ~1.54 deg inclination to the ecliptic while its
    # node regresses with the orbit's in 18.6 years. The whole expression must show it
    # (the pole circles the ecliptic pole); the constant terms sit 0.02 deg from it.
    jd = 2451545.0 + np.linspace(0.0, 18.61 * 365.25, 200)
    poles = np.array([frames.moon_pole_icrf(*frames.moon_pole_radec_deg(jd_tdb=j)) for j in jd])
    tilt = np.array([_angle_deg(p, ECLIPTIC_POLE) for p in poles])
    assert np.all(np.abs(tilt - 1.543) < 0.05), (tilt.min(), tilt.max())
    # the pole goes once around the ecliptic pole: its longitude turns through 360 deg
    x = np.cross([0, 0, 1.0], ECLIPTIC_POLE)
    x /= np.linalg.norm(x)
    y = np.cross(ECLIPTIC_POLE, x)
    lon = np.unwrap(np.arctan2(poles @ y, poles @ x))
    assert abs(abs(lon[-1] - lon[0]) - 2 * np.pi) < np.radians(5.0)
    assert _angle_deg(frames.moon_pole_icrf(*frames.moon_pole_radec_deg("iau-constant")),
                      ECLIPTIC_POLE) < 0.03


def test_unknown_pole_is_refused():
    with pytest.raises(ValueError, match="lunar pole must be one of"):
        frames.moon_pole_radec_deg("iau1994")


@pytest.mark.parametrize("pole", frames.LUNAR_POLES)
def test_mme2000_x_axis_is_node_on_icrf_equator(pole):
    C = frames.icrf_to_mme(pole)
    alpha0 = frames.moon_pole_radec_deg(pole)[0]
    x = C[0]
    assert abs(x[2]) < TOL  # in the ICRF equator
    assert abs(x @ C[2]) < TOL  # in the lunar equator
    # the ascending node of the lunar equator on the ICRF equator is at RA = alpha0 + 90 deg
    ra_node = np.degrees(np.arctan2(x[1], x[0])) % 360.0
    assert ra_node == pytest.approx((alpha0 + 90.0) % 360.0, abs=1e-10)


@pytest.mark.parametrize("pole", frames.LUNAR_POLES)
def test_mme2000_equals_euler_sequence(pole):
    # Second formulation: R1(90 deg - delta0) R3(90 deg + alpha0), the classical body-frame
    # rotation from pole coordinates.
    a, d = np.radians(frames.moon_pole_radec_deg(pole))
    expected = _r1(np.pi / 2 - d) @ _r3(np.pi / 2 + a)
    np.testing.assert_allclose(frames.icrf_to_mme(pole), expected, atol=TOL)
    # and for another pole through the function's arguments
    a2, d2 = 40.0, -20.0
    expected2 = _r1(np.radians(90 - d2)) @ _r3(np.radians(90 + a2))
    np.testing.assert_allclose(frames.icrf_to_mme2000(a2, d2), expected2, atol=TOL)


def test_rtn_basis_definition_random_states():
    rng = np.random.default_rng(7)
    r = rng.normal(size=(3, 50)) * 3000.0
    v = rng.normal(size=(3, 50)) * 1.5
    Q = frames.rtn_basis(r, v)
    assert Q.shape == (3, 3, 50)
    for n in range(50):
        q = Q[:, :, n]
        np.testing.assert_allclose(q @ q.T, np.eye(3), atol=TOL)
        assert np.linalg.det(q) == pytest.approx(1.0, abs=TOL)  # right-handed
        rn = r[:, n] / np.linalg.norm(r[:, n])
        h = np.cross(r[:, n], v[:, n])
        np.testing.assert_allclose(q[0], rn, atol=TOL)
        np.testing.assert_allclose(q[2], h / np.linalg.norm(h), atol=TOL)
        # Eq. (A5) as printed: i_t = (r x v) x r / |(r x v) x r|
        t = np.cross(h, r[:, n])
        np.testing.assert_allclose(q[1], t / np.linalg.norm(t), atol=TOL)
        # the velocity has no normal component and a positive tangential one
        assert abs(q[2] @ v[:, n]) < TOL * np.linalg.norm(v[:, n])
        assert q[1] @ v[:, n] > 0
        # the single-state call gives the same matrix as the vectorised one
        np.testing.assert_allclose(frames.rtn_basis(r[:, n], v[:, n]), q, atol=TOL)
