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


def test_mme2000_rotation_is_proper_orthonormal():
    C = frames.C_ICRF_TO_MME
    np.testing.assert_allclose(C @ C.T, np.eye(3), atol=TOL)
    assert np.linalg.det(C) == pytest.approx(1.0, abs=TOL)


def test_mme2000_z_axis_is_iau_lunar_pole():
    # IAU (Archinal et al. 2011) lunar pole at J2000: alpha0 = 269.9949, delta0 = 66.5392 deg.
    a, d = np.radians(269.9949), np.radians(66.5392)
    pole = np.array([np.cos(d) * np.cos(a), np.cos(d) * np.sin(a), np.sin(d)])
    np.testing.assert_allclose(frames.C_ICRF_TO_MME[2], pole, atol=TOL)
    # the pole maps to +z of M-MME2000
    np.testing.assert_allclose(frames.C_ICRF_TO_MME @ pole, [0, 0, 1], atol=TOL)


def test_mme2000_x_axis_is_node_on_icrf_equator():
    C = frames.C_ICRF_TO_MME
    x = C[0]
    assert abs(x[2]) < TOL  # in the ICRF equator
    assert abs(x @ C[2]) < TOL  # in the lunar equator
    # the ascending node of the lunar equator on the ICRF equator is at RA = alpha0 + 90 deg
    ra_node = np.degrees(np.arctan2(x[1], x[0])) % 360.0
    assert ra_node == pytest.approx((269.9949 + 90.0) % 360.0, abs=1e-10)


def test_mme2000_equals_euler_sequence():
    # Second formulation: R1(90 deg - delta0) R3(90 deg + alpha0), the classical body-frame
    # rotation from pole coordinates.
    a, d = np.radians(269.9949), np.radians(66.5392)
    expected = _r1(np.pi / 2 - d) @ _r3(np.pi / 2 + a)
    np.testing.assert_allclose(frames.C_ICRF_TO_MME, expected, atol=TOL)
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
