"""Tests of lunarcap.physics.propagate: MEE propagation against an independent Cartesian one and
against Kepler's equation.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from lunarcap.errors import InputError
from lunarcap.physics import constants as C
from lunarcap.physics import dynamics as dyn
from lunarcap.physics import elements as el
from lunarcap.physics import propagate as prop

MU = C.MU_MOON


@pytest.fixture(scope="module")
def arrival(paper_arrival):
    return paper_arrival


@pytest.fixture(scope="module")
def fit(mission_fit):
    return mission_fit


def _cartesian(model, t0, x0_mee, t1, u_rtn=(0.0, 0.0, 0.0)):
    """Independent propagation of dynamics.cartesian_rates with DOP853 at rtol 1e-12."""
    r, v = (np.array(a) for a in el.rv_from_mee(*x0_mee[:6], MU))
    s0 = np.concatenate([r, v, [x0_mee[6]]])
    atol = np.r_[np.full(3, 1e-9), np.full(3, 1e-12), 1e-10]  # km, km/s, kg
    res = solve_ivp(lambda t, s: dyn.cartesian_rates(t, s, model, u_rtn), (t0, t1), s0,
                    method="DOP853", rtol=1e-12, atol=atol)
    assert res.success
    return res.y[:, -1]


def _position(x_mee):
    return np.array(el.rv_from_mee(*x_mee[:6], MU)[0])


def test_full_coast_mee_equals_cartesian_after_12h(arrival, fit):
    # The reconstructed arrival hyperbola coasted 12.235 h (the first capture period) under
    # J2 + Earth + Sun: two formulations (MEE Gauss equations vs Cartesian Newton) agree
    # within 1 m; each integrator at rtol 1e-12 contributes ~1e-12 x 4e4 km ~ 4e-8 km.
    model = dyn.Model("full", fit=fit)
    t0 = arrival.epoch_s
    t1 = t0 + C.CAPTURE_PERIODS_S[0]
    traj = prop.propagate(model, t0, arrival.state, t1)
    assert traj.t[-1] == t1
    cart = _cartesian(model, t0, arrival.state, t1)
    r_mee = _position(traj.final)
    assert np.linalg.norm(r_mee) > 20_000.0  # it did leave the Moon on the hyperbola
    assert np.linalg.norm(r_mee - cart[:3]) < 1e-3
    assert traj.final[6] == arrival.mass_kg  # a coast burns nothing
    # the agreement is not vacuous: without perturbations the end point moves > 10 km
    kepler = prop.propagate(dyn.Model("two-body"), t0, arrival.state, t1)
    assert np.linalg.norm(_position(kepler.final) - cart[:3]) > 10.0


def test_full_burn_mee_equals_cartesian(arrival, fit):
    # A 20 min, 150 N / 200 s burn with a constant RTN direction (mostly retrograde, with
    # radial and normal parts) starting 10 min before perilune: positions within 1 m and the
    # mass on the closed form m0 - T t / (g0 Isp).
    model = dyn.Model("full", thrust_N=150.0, isp_s=200.0, fit=fit)
    t_peri = arrival.epoch_s
    back = prop.propagate(model, t_peri, arrival.state, t_peri - 600.0)  # coast back 10 min
    x0 = back.final
    u = np.array([0.2, -0.95, 0.1])
    u /= np.linalg.norm(u)
    t0, t1 = t_peri - 600.0, t_peri + 600.0
    traj = prop.propagate(model, t0, x0, t1, u=u)
    cart = _cartesian(model, t0, x0, t1, u_rtn=u)
    assert np.linalg.norm(_position(traj.final) - cart[:3]) < 1e-3
    m_expected = x0[6] - 150.0 * 1200.0 / (C.G0_MPS2 * 200.0)
    assert traj.final[6] == pytest.approx(m_expected, abs=1e-9)  # linear in t: exact to ~1e-12
    assert cart[6] == pytest.approx(m_expected, abs=1e-9)
    # the retrograde burn bound the spacecraft: the hyperbola became an ellipse
    assert np.hypot(traj.final[1], traj.final[2]) < 1.0


def test_two_body_ellipse_returns_after_one_period():
    # Kepler: after exactly one period the state repeats; L advances by 2 pi. Over ~200
    # steps at rtol 1e-12 the phase error stays far below 1e-9 rad.
    model = dyn.Model("two-body")
    T = C.CAPTURE_PERIODS_S[0]
    a = el.semi_major_axis_from_period(T, MU)
    rp = C.R_MOON + 100.0
    x0 = np.array([*el.mee_from_coe(a, 1 - rp / a, np.radians(90.0), 0.3, 1.2, 0.5), 500.0])
    traj = prop.propagate(model, 0.0, x0, T)
    np.testing.assert_allclose(traj.final[:5], x0[:5], rtol=1e-12, atol=1e-14)
    assert traj.final[5] - x0[5] == pytest.approx(2 * np.pi, abs=1e-9)


def test_two_body_hyperbola_follows_keplers_equation(arrival):
    # From the arrival perilune (nu = 0): e sinh H - H = sqrt(mu / (-a)^3) t; then
    # tan(nu/2) = sqrt((e+1)/(e-1)) tanh(H/2). Compare the true longitude at 0.5, 3, 12 h.
    model = dyn.Model("two-body")
    a_, e, *_ = el.coe_from_mee(*arrival.mee)
    n = np.sqrt(MU / (-a_) ** 3)
    t_eval = arrival.epoch_s + np.array([0.5, 3.0, 12.0]) * 3600.0
    traj = prop.propagate(model, arrival.epoch_s, arrival.state, t_eval[-1], t_eval=t_eval)
    for t, x in zip(traj.t, traj.x.T):
        M = n * (t - arrival.epoch_s)
        H = brentq(lambda H: e * np.sinh(H) - H - M, 0.0, 20.0, xtol=1e-15)
        nu = 2 * np.arctan(np.sqrt((e + 1) / (e - 1)) * np.tanh(H / 2))
        assert x[5] - arrival.mee[5] == pytest.approx(nu, abs=1e-9)


def test_forward_then_backward_returns_to_start(arrival, fit):
    # propagation is reversible: 2 h forward and back recovers the start within 1 cm
    model = dyn.Model("full", fit=fit)
    t0 = arrival.epoch_s
    fwd = prop.propagate(model, t0, arrival.state, t0 + 7200.0)
    bwd = prop.propagate(model, t0 + 7200.0, fwd.final, t0)
    assert np.linalg.norm(_position(bwd.final) - arrival.r_km) < 1e-5


def test_zero_length_propagation_returns_initial_state(arrival):
    traj = prop.propagate(dyn.Model("two-body"), 0.0, arrival.state, 0.0)
    np.testing.assert_array_equal(traj.final, arrival.state)


def test_bad_propagation_input_is_an_input_error(arrival, fit):
    model = dyn.Model("full", fit=fit)
    t0 = arrival.epoch_s
    with pytest.raises(InputError):
        prop.propagate(model, t0, arrival.state[:6], t0 + 60.0)  # no mass
    with pytest.raises(InputError):
        prop.propagate(model, t0, np.r_[arrival.state[:6], 0.0], t0 + 60.0)  # m = 0
    with pytest.raises(InputError):
        prop.propagate(model, t0, np.r_[-1.0, arrival.state[1:]], t0 + 60.0)  # p < 0
    with pytest.raises(InputError):
        prop.propagate(model, t0, np.r_[np.nan, arrival.state[1:]], t0 + 60.0)
    with pytest.raises(InputError, match="ephemeris-fit window"):
        prop.propagate(model, t0, arrival.state, fit.t1_s + 3600.0)
