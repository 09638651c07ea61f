"""The B-plane (lunarcap.physics.bplane): perilune state -> B-plane -> perilune state.

Round trips over arrivals of every kind lunarcap builds (inclinations 0-180 deg, both
hemispheres, v_inf 0.3-3 km/s, approach directions all round), and two independent
checks: the asymptote found from the state is the one the arrival was built along
(:func:`lunarcap.mission.arrival.arrival_state` constructs the hyperbola from it by
another formula), and |B| = h / v_inf.
"""

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.mission.arrival import arrival_state
from lunarcap.physics import constants as C
from lunarcap.physics.bplane import bplane_from_rv, perilune_from_bplane

CASES = [(inc, hemi, vinf, k) for inc, hemi, vinf, k in [
    (90.0, "north", 0.918, 0), (90.0, "south", 0.918, 1), (30.0, "north", 0.3, 2),
    (150.0, "south", 2.0, 3), (60.0, "south", 3.0, 4), (120.0, "north", 1.5, 5),
    (10.0, "north", 0.6, 6), (175.0, "south", 1.1, 7)]]


def _approach(k):
    """A seeded approach direction, latitude within +-5 deg (every inclination here reachable)."""
    rng = np.random.default_rng([26, k])
    lon, lat = rng.uniform(0, 2 * np.pi), np.radians(rng.uniform(-5, 5))
    return np.array([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)])


@pytest.mark.parametrize("inc, hemi, vinf, k", CASES)
def test_perilune_to_bplane_and_back_within_1_m_and_1_mm_per_s(inc, hemi, vinf, k):
    s = _approach(k)
    a = arrival_state(altitude_km=100.0 + 200 * k, inclination_deg=inc, v_inf_kmps=vinf,
                      approach=s, hemisphere=hemi)
    b = bplane_from_rv(a.r_km, a.v_kmps, C.MU_MOON)
    np.testing.assert_allclose(b.s_hat, s, atol=1e-12)   # the asymptote it was built on
    h = np.linalg.norm(np.cross(a.r_km, a.v_kmps))
    assert b.b_km == pytest.approx(h / vinf, rel=1e-12)
    assert b.v_inf_kmps == pytest.approx(vinf, rel=1e-12)
    r, v = perilune_from_bplane(b.b_r_km, b.b_t_km, b.v_inf_kmps, b.s_hat, C.MU_MOON)
    assert np.linalg.norm(r - a.r_km) < 1e-3           # km: 1 m
    assert np.linalg.norm(v - a.v_kmps) < 1e-6         # km/s: 1 mm/s


def test_the_b_plane_axes_and_sign_of_a_polar_arrival():
    # a polar orbit (i = 90 deg about the frame's pole): B lies along -R or +R only, and
    # the north-going and south-going perilunes have B . R of opposite signs
    out = {}
    for hemi in ("north", "south"):
        a = arrival_state(inclination_deg=90.0, v_inf_kmps=0.9, approach=_approach(0),
                          hemisphere=hemi)
        b = bplane_from_rv(a.r_km, a.v_kmps, C.MU_MOON)
        assert abs(b.b_t_km) < 1e-6 * b.b_km
        out[hemi] = b.b_r_km
    assert out["north"] * out["south"] < 0


def test_no_b_plane_for_an_ellipse_or_a_radial_fall():
    a = arrival_state(v_inf_kmps=0.9)
    with pytest.raises(InputError, match="not on a hyperbola"):
        bplane_from_rv(a.r_km, 0.5 * a.v_kmps, C.MU_MOON)
    with pytest.raises(InputError, match="radial fall"):
        perilune_from_bplane(0.0, 0.0, 0.9, [1.0, 0.0, 0.0], C.MU_MOON)


# ---------------------------------------------------------------------- fixed geometry
def _line(b_vec, v=1.0, x0=-1e6):
    """A state on the straight approach along +x offset by ``b_vec`` (km): the limit of a
    hyperbola as mu -> 0, whose B vector is ``b_vec`` itself (Kizner's definition: the
    miss vector from the centre to the asymptote, perpendicular to it)."""
    return np.array([x0, 0.0, 0.0]) + np.asarray(b_vec, float), np.array([v, 0.0, 0.0])


#: A gravitational parameter small enough that the trajectory is its asymptote: the
#: bending over 1e6 km at 1 km/s is mu / (r v^2) = 1e-15 rad.
MU_TINY = 1e-9


@pytest.mark.parametrize("b", [10.0, 4975.0])
def test_b_plane_axes_in_the_standard_convention_against_fixed_geometry(b):
    # T = S x k / |S x k|, R = S x T, k the reference pole (+z): an approach along +x offset
    # by b along +y has B.T = -b and B.R = 0; offset along +z, B.R = -b (the axes of GMAT's
    # BdotT/BdotR and of trajectory teams). The mutant T = k x S flips both signs.
    along_y = bplane_from_rv(*_line([0.0, b, 0.0]), MU_TINY)
    np.testing.assert_allclose(along_y.s_hat, [1.0, 0.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(along_y.t_hat, [0.0, -1.0, 0.0], atol=1e-12)
    np.testing.assert_allclose(along_y.r_hat, [0.0, 0.0, -1.0], atol=1e-12)
    assert along_y.b_t_km == pytest.approx(-b, rel=1e-9)
    assert abs(along_y.b_r_km) < 1e-9 * b
    along_z = bplane_from_rv(*_line([0.0, 0.0, b]), MU_TINY)
    assert along_z.b_r_km == pytest.approx(-b, rel=1e-9)
    assert abs(along_z.b_t_km) < 1e-9 * b
    # the inverse, same limit: the closest approach lies at the miss vector, moving along S
    r, v = perilune_from_bplane(0.0, -b, 1.0, [1.0, 0.0, 0.0], MU_TINY)
    np.testing.assert_allclose(r, [0.0, b, 0.0], atol=1e-9 * b)
    np.testing.assert_allclose(v, [1.0, 0.0, 0.0], atol=1e-9)   # bent by mu / (b v^2)
    r, v = perilune_from_bplane(-b, 0.0, 1.0, [1.0, 0.0, 0.0], MU_TINY)
    np.testing.assert_allclose(r, [0.0, 0.0, b], atol=1e-9 * b)


def test_the_reference_pole_sets_the_t_axis():
    # the same straight approach (along +x, offset b along +y) about other poles: about
    # k = -z the axes turn over (T = +y, B.T = +b); about k = +y, T = S x y = +z and B lies
    # along R = S x T = -y (B.R = -b, B.T = 0)
    b = 300.0
    turned = bplane_from_rv(*_line([0.0, b, 0.0]), MU_TINY, pole=(0.0, 0.0, -1.0))
    assert turned.b_t_km == pytest.approx(b, rel=1e-9)
    about_y = bplane_from_rv(*_line([0.0, b, 0.0]), MU_TINY, pole=(0.0, 1.0, 0.0))
    np.testing.assert_allclose(about_y.t_hat, [0.0, 0.0, 1.0], atol=1e-12)
    assert about_y.b_r_km == pytest.approx(-b, rel=1e-9)
    assert abs(about_y.b_t_km) < 1e-9 * b


def test_reference_poles_of_the_two_planes_in_both_axes():
    # EME2000's pole is ICRF's z; the lunar equator's is M-MME2000's z; each seen from the
    # other axes is the other frame's pole, at the lunar pole's declination (65.64 deg at
    # J2000: the ICRF pole is 24.36 deg from the lunar pole), the lunar pole at its right
    # ascension and declination (Archinal et al. 2011)
    from lunarcap.physics.bplane import check_reference, reference_pole
    from lunarcap.physics.frames import moon_pole_radec_deg

    pole = "iau2009-j2000"
    ra_deg, dec_deg = moon_pole_radec_deg(pole)
    np.testing.assert_array_equal(reference_pole("EME2000", "ICRF", pole), [0, 0, 1])
    np.testing.assert_array_equal(reference_pole("lunar-equator", "M-MME2000", pole), [0, 0, 1])
    k_e = reference_pole("EME2000", "M-MME2000", pole)
    k_l = reference_pole("lunar-equator", "ICRF", pole)
    assert np.degrees(np.arccos(k_e[2])) == pytest.approx(90.0 - dec_deg, abs=1e-9)
    assert abs(dec_deg - 65.64) < 0.01
    assert k_l[2] == pytest.approx(k_e[2], abs=1e-15)
    dec, ra = np.radians(dec_deg), np.radians(ra_deg)
    np.testing.assert_allclose(k_l, [np.cos(dec) * np.cos(ra), np.cos(dec) * np.sin(ra),
                                     np.sin(dec)], atol=1e-15)
    with pytest.raises(InputError, match="bplane_reference must be one of EME2000, "
                                         "lunar-equator"):
        check_reference("ecliptic")
