"""Tests of lunarcap.physics.propagate: MEE propagation against an independent Cartesian one and
against Kepler's equation.
"""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_scenario
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
    t1 = t0 + paper_scenario().capture_periods_s[0]
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
    T = paper_scenario().capture_periods_s[0]
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


def _dop853(model, t0, x0, span, u):
    """Reference: scipy DOP853 at rtol 1e-12 on the same right-hand side (time elapsed)."""
    f = dyn.rhs_function(model.mode)
    prm = model.params(model.thrust_N if u is not None else 0.0)

    def rhs(s, x):
        d = u(x) if u is not None else np.zeros(3)
        return np.asarray(f(x, d, t0 + s, prm)).ravel()
    atol = np.array([1e-9, 1e-13, 1e-13, 1e-13, 1e-13, 1e-13, 1e-10])
    res = solve_ivp(rhs, (0.0, span), x0, method="DOP853", rtol=1e-12, atol=atol)
    assert res.success
    return res.y[:, -1]


def test_compiled_propagation_agrees_with_dop853_over_loi1_burn_and_coast(arrival, fit):
    # A whole 150 N LOI 1 in full dynamics: 19.5 min of anti-velocity burn from 10 min
    # before perilune, then the coast to the next perilune (12.235 h). CVODES (Adams,
    # compiled) and scipy's DOP853 (Python right-hand side) at rtol 1e-12 must end within
    # 1 m of each other (measured: ~1 mm).
    from lunarcap.physics.steering import law

    model = dyn.Model("full", 150.0, 200.0, fit)
    t_peri = arrival.epoch_s
    t_ign = t_peri - 600.0
    x0 = prop.propagate(model, t_peri, arrival.state, t_ign).final
    anti = law("antivelocity")
    burn_s = 1170.0
    xb = prop.propagate(model, t_ign, x0, None, u=anti, duration_s=burn_s).final
    xb_ref = _dop853(model, t_ign, x0, burn_s, anti)
    coast = t_peri + 12.235 * 3600.0 - (t_ign + burn_s)
    xc = prop.propagate(model, t_ign + burn_s, xb, None, duration_s=coast).final
    xc_ref = _dop853(model, t_ign + burn_s, xb_ref, coast, None)
    for a, b in ((xb, xb_ref), (xc, xc_ref)):
        ra = np.array(el.rv_from_mee(*a[:6], MU)[0])
        rb = np.array(el.rv_from_mee(*b[:6], MU)[0])
        assert np.linalg.norm(ra - rb) < 1e-3, np.linalg.norm(ra - rb) * 1e3
        assert abs(a[6] - b[6]) < 1e-9
    assert np.linalg.norm(np.array(el.rv_from_mee(*xc[:6], MU)[0])
                          - np.array(el.rv_from_mee(*x0[:6], MU)[0])) > 1e3  # it moved


def test_dense_output_interpolates_the_arc(arrival, fit):
    # the Hermite interpolant through the dense outputs agrees with a direct propagation to
    # an epoch between two knots (to 1 m over a 12.235 h coast)
    model = dyn.Model("full", 0.0, 200.0, fit)
    t0 = arrival.epoch_s
    traj = prop.propagate(model, t0, arrival.state, t0 + 44046.0, dense=True)
    for t in (t0 + 1234.5, t0 + 20000.3, t0 + 44000.0):
        direct = prop.propagate(model, t0, arrival.state, t).final
        ra = np.array(el.rv_from_mee(*traj(t)[:6], MU)[0])
        rb = np.array(el.rv_from_mee(*direct[:6], MU)[0])
        assert np.linalg.norm(ra - rb) < 1e-3


def test_t_eval_at_an_arc_end_rounded_at_epoch_resolution(arrival):
    """An epoch past J2000 carries ~6e-8 s: an arc's end epoch t0 + span may lie a few ulps
    beyond the end (tau 1 + 2.6e-12 for this 2 h arc, the export's final orbit of a state
    arrival); asked for at such an epoch, the state is the end of the arc."""
    model = dyn.Model("two-body")
    t0, span = 540878738.3485222, 7072.076051693657
    t_end = t0 + span
    assert (t_end - t0) / span - 1 > 1e-12   # the rounding this test is about
    x = np.asarray(arrival.state, float)
    tr = prop.propagate(model, t0, x, None, duration_s=span, t_eval=[t0 + 0.5 * span, t_end])
    end = prop.propagate(model, t0, x, None, duration_s=span).final
    np.testing.assert_allclose(tr.x[:, -1], end, rtol=1e-12, atol=1e-12)
