"""Tests of lunarcap.mission.arrival: the reconstructed arrival hyperbola.

Every property is computed here from the Cartesian state with elementary vector algebra;
the Moon's velocity comes straight from jplephem (DE405), rotated with frames.icrf_to_mme().
"""

from datetime import datetime

import de405
import numpy as np
import pytest
from jplephem.ephem import Ephemeris as RawEphemeris

from lunarcap.errors import EphemerisRangeError, InputError
from lunarcap.mission import arrival as scenario
from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics import elements as el
from lunarcap.physics.frames import icrf_to_mme

C_ICRF_TO_MME = icrf_to_mme()  # the default pole's rotation

MU = C.MU_MOON
RP = C.R_MOON + 100.0  # 1838.2 km


@pytest.fixture(scope="module", params=["north", "south"])
def arrival(request):
    return scenario.arrival_state(hemisphere=request.param)


def _incoming_asymptote(r, v):
    """Unit velocity direction on the incoming asymptote (t -> -inf) of a hyperbola.

    In the perifocal frame (P along the eccentricity vector, Q = h x P) the velocity at
    true anomaly nu is sqrt(mu/p) (-sin nu, e + cos nu); at nu = -arccos(-1/e) this is
    proportional to (1, sqrt(e^2 - 1)) / e.
    """
    h = np.cross(r, v)
    ev = np.cross(v, h) / MU - r / np.linalg.norm(r)
    e = np.linalg.norm(ev)
    P = ev / e
    Q = np.cross(h / np.linalg.norm(h), P)
    return (P + np.sqrt(e * e - 1) * Q) / e


def _raw_moon_velocity_direction(epoch):
    dt = datetime(2017, 2, 20, 3, 41, 26) - datetime(2017, 2, 20)
    assert epoch == paper_scenario().epoch_tdb
    _, vel = RawEphemeris(de405).position_and_velocity("moon", 2457804.5,
                                                       dt.total_seconds() / 86400.0)
    vm = C_ICRF_TO_MME @ np.ravel(vel)
    return vm / np.linalg.norm(vm)


def test_arrival_perilune_geometry(arrival):
    r, v = arrival.r_km, arrival.v_kmps
    # perilune radius 1838.2 km (100 km altitude) and flight-path angle 0
    assert np.linalg.norm(r) == pytest.approx(RP, rel=1e-14)
    assert abs(r @ v) / (np.linalg.norm(r) * np.linalg.norm(v)) < 1e-14
    # inclination 90 deg in M-MME2000: the angular momentum lies in the lunar equator
    h = np.cross(r, v)
    assert np.degrees(np.arccos(h[2] / np.linalg.norm(h))) == pytest.approx(90.0, abs=1e-10)
    # it is a perilune, not an apolune: the speed exceeds the local escape speed
    assert np.linalg.norm(v) > np.sqrt(2 * MU / RP)


def test_arrival_v_inf_and_paper_loi1(arrival):
    r, v = arrival.r_km, arrival.v_kmps
    energy = v @ v / 2 - MU / np.linalg.norm(r)
    vinf = np.sqrt(2 * energy)
    assert vinf == pytest.approx(arrival.v_inf_kmps, rel=1e-12)
    # v_inf is set so that the tangential perilune burn into the 12.235 h ellipse costs the
    # paper's impulsive 353.272 m/s (Song 2011, Table 1)
    a1 = np.cbrt(MU * (12.235 * 3600 / (2 * np.pi)) ** 2)
    dv = np.linalg.norm(v) - np.sqrt(MU * (2 / RP - 1 / a1))
    assert dv * 1e3 == pytest.approx(353.272, abs=1e-9)
    assert arrival.v_inf_kmps == pytest.approx(0.918, abs=5e-4)  # value quoted in scenario docs


def test_arrival_asymptote_anti_parallel_to_moon_velocity(arrival):
    s_in = _incoming_asymptote(arrival.r_km, arrival.v_kmps)
    moon_dir = _raw_moon_velocity_direction(paper_scenario().epoch_tdb)
    # exact by construction: only round-off separates the state's asymptote from -v_Moon.
    # Components agree to 1e-12 (a few hundred ulps: the eccentricity vector is a difference
    # of O(1) terms); the angle via arccos near 1 resolves only sqrt(2 eps) ~ 2e-8 rad.
    angle = np.arccos(np.clip(s_in @ -moon_dir, -1, 1))
    assert angle < 1e-7
    np.testing.assert_allclose(s_in, -moon_dir, atol=1e-12)
    np.testing.assert_allclose(arrival.approach_dir, -moon_dir, atol=1e-12)


def test_hemisphere_choice_is_honoured():
    north = scenario.arrival_state(hemisphere="north")
    south = scenario.arrival_state(hemisphere="south")
    assert north.r_km[2] > 0 > south.r_km[2]
    # both are perilunes of the same asymptote, in the two planes that reach i = 90 deg
    np.testing.assert_allclose(_incoming_asymptote(north.r_km, north.v_kmps),
                               _incoming_asymptote(south.r_km, south.v_kmps), atol=1e-12)
    assert np.linalg.norm(north.r_km - south.r_km) > 100.0


def test_other_inclination_and_explicit_approach():
    s = np.array([0.3, -0.9, 0.2])
    arr = scenario.arrival_state(inclination_deg=45.0, approach=s, v_inf_kmps=1.2)
    h = np.cross(arr.r_km, arr.v_kmps)
    assert np.degrees(np.arccos(h[2] / np.linalg.norm(h))) == pytest.approx(45.0, abs=1e-10)
    np.testing.assert_allclose(_incoming_asymptote(arr.r_km, arr.v_kmps),
                               s / np.linalg.norm(s), atol=1e-12)
    v2 = arr.v_kmps @ arr.v_kmps
    assert v2 - 2 * MU / RP == pytest.approx(1.2 ** 2, rel=1e-12)


def test_arrival_mee_matches_cartesian_state(arrival):
    r, v = el.rv_from_mee(*arrival.mee, MU)
    np.testing.assert_allclose(r, arrival.r_km, rtol=1e-12)
    np.testing.assert_allclose(v, arrival.v_kmps, rtol=1e-12)
    assert arrival.state[6] == paper_scenario().mass_kg == 524.895
    assert el.perilune_radius(*arrival.mee[:3]) == pytest.approx(RP, rel=1e-12)


@pytest.mark.parametrize("kwargs,exc", [
    (dict(epoch="2300-01-01 00:00:00 TDB"), EphemerisRangeError),
    (dict(epoch="20-Feb-2017 3:41"), InputError),
    (dict(altitude_km=-10.0), InputError),
    (dict(altitude_km=0.0), InputError),
    (dict(mass_kg=0.0), InputError),
    (dict(inclination_deg=200.0), InputError),
    (dict(hemisphere="east"), InputError),
    (dict(approach="sunward"), InputError),
    (dict(approach=[0.0, 0.0, 0.0]), InputError),
    (dict(approach=[0.0, 0.0, 1.0]), InputError),        # along the pole
    (dict(approach=[1.0, 0.0, 0.9], inclination_deg=10.0), InputError),  # unreachable i
    (dict(v_inf_kmps=-1.0), InputError),
])
def test_bad_arrival_input_is_an_input_error(kwargs, exc):
    with pytest.raises(exc):
        scenario.arrival_state(**kwargs)
