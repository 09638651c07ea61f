"""Tests of lunarcap.mission.targets: the terminal conditions, written once.

States are built here from classical elements with the closed forms of Eq. (A1); the
physical errors of Target.errors must recover the offsets put in (exact inverses of the
residuals, so the tolerances are round-off).
"""

import casadi as ca
import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.mission.targets import CIRCULAR, PERILUNE, Target, conditions
from lunarcap.physics import constants as C
from lunarcap.physics.elements import mee_from_coe

MU = C.MU_MOON
RP = C.R_MOON + 100.0


def _state(rp_km, e, inc_deg, nu_deg, raan_deg=30.0, argp_deg=40.0):
    a = rp_km / (1 - e)
    return np.array(mee_from_coe(a, e, np.radians(inc_deg), np.radians(raan_deg),
                                 np.radians(argp_deg), np.radians(nu_deg)), float)


@pytest.mark.parametrize("inc", [90.0, 60.0, 28.5, 135.0])
def test_perilune_target_is_met_exactly_at_a_perilune(inc):
    t = Target(PERILUNE, RP, inc)
    err = t.errors(_state(RP, 0.6, inc, 0.0))
    assert abs(err["rp_error_m"]) < 1e-8
    assert abs(err["inc_error_deg"]) < 1e-10
    assert abs(err["gamma_error_deg"]) < 1e-10
    assert err["branch"] > 0 and err["ra_error_m"] is None


def test_perilune_errors_recover_the_offsets_put_in():
    t = Target(PERILUNE, RP, 60.0)
    # perilune 25 m high, inclination 0.003 deg off, 0.2 deg of true anomaly past perilune
    x = _state(RP + 0.025, 0.6, 60.003, 0.2)
    err = t.errors(x)
    assert err["rp_error_m"] == pytest.approx(25.0, abs=1e-6)
    assert err["inc_error_deg"] == pytest.approx(0.003, abs=1e-10)
    # tan(gamma) = e sin(nu) / (1 + e cos(nu)) on the conic
    nu = np.radians(0.2)
    gamma = np.degrees(np.arctan2(0.6 * np.sin(nu), 1 + 0.6 * np.cos(nu)))
    assert err["gamma_error_deg"] == pytest.approx(gamma, rel=1e-10)


def test_apolune_is_rejected_by_the_branch_condition():
    # gamma = 0 at apolune too; only e cos(nu) >= 0 tells the perilune apart
    t = Target(PERILUNE, RP, 90.0)
    err = t.errors(_state(RP, 0.6, 90.0, 180.0))
    assert abs(err["gamma_error_deg"]) < 1e-9
    assert err["branch"] == pytest.approx(-0.6, abs=1e-12)


def test_inclination_condition_is_tan_squared_of_half_the_angle():
    # Eq. (18b): tan(i/2) = sqrt(h^2 + k^2). At 60 deg, tan^2(30 deg) = 1/3 differs from
    # tan(30 deg) = 0.577, so a condition written with tan instead of tan^2 would not vanish.
    x = _state(RP, 0.3, 60.0, 0.0)
    eq, _ = conditions(PERILUNE, x, Target(PERILUNE, RP, 60.0).values())
    assert abs(eq[1]) < 1e-14
    assert x[3] ** 2 + x[4] ** 2 == pytest.approx(1.0 / 3.0, rel=1e-13)


def test_circular_target_and_its_radii():
    t = Target(CIRCULAR, RP, 90.0)
    err = t.errors(_state(RP, 0.0, 90.0, 12.0))
    assert abs(err["rp_error_m"]) < 1e-8 and abs(err["ra_error_m"]) < 1e-8
    assert err["gamma_error_deg"] is None and err["branch"] is None
    # an ellipse 20 m low at perilune and 30 m high at apolune
    rp, ra = RP - 0.020, RP + 0.030
    e = (ra - rp) / (ra + rp)
    err = t.errors(_state(rp, e, 90.0, 77.0))
    assert err["rp_error_m"] == pytest.approx(-20.0, abs=1e-6)
    assert err["ra_error_m"] == pytest.approx(30.0, abs=1e-6)


@pytest.mark.parametrize("kind", [PERILUNE, CIRCULAR])
def test_one_definition_serves_numpy_and_casadi(kind):
    x = _state(RP + 0.3, 0.4 if kind == PERILUNE else 0.01, 88.0, 3.0)
    vals = Target(kind, RP, 90.0).values()
    eq, ineq = conditions(kind, x, vals)
    xs = ca.SX.sym("x", 6)
    eq_s, ineq_s = conditions(kind, [xs[i] for i in range(6)], vals)
    f = ca.Function("f", [xs], [ca.vertcat(*eq_s, *ineq_s)])
    np.testing.assert_allclose(f(x).full().ravel(), eq + ineq, rtol=1e-14, atol=1e-16)


@pytest.mark.parametrize("kwargs", [dict(kind="hyperbolic", radius_km=RP, inclination_deg=90.0),
                                    dict(kind=PERILUNE, radius_km=-1.0, inclination_deg=90.0),
                                    dict(kind=PERILUNE, radius_km=RP, inclination_deg=0.0),
                                    dict(kind=PERILUNE, radius_km=RP, inclination_deg=180.0)])
def test_bad_target_is_an_input_error(kwargs):
    with pytest.raises(InputError):
        Target(**kwargs)
