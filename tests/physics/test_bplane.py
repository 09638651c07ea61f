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
