"""Tests of lunarcap.physics.dynamics: Eqs. (2)-(8) in MEE against independent formulations.

* Eq. (7) J2 in RTN against the finite-difference gradient of the J2 potential.
* The MEE rates (Gauss form, Eqs. 2, A2-A4) against the Cartesian equations of motion,
  mapped through the exact (automatic-differentiation) Jacobian of Eqs. (A6)-(A7).
* The CasADi Function against the numpy evaluation of the same source.
"""

import casadi as ca
import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_engines
from lunarcap.physics import constants as C
from lunarcap.physics import dynamics as dyn
from lunarcap.physics import elements as el
from lunarcap.physics import frames

MU, RM, J2 = C.MU_MOON, C.R_MOON, C.J2_MOON


@pytest.fixture(scope="module")
def fit(mission_fit):
    return mission_fit


def _random_states(rng, n):
    """Random MEE + mass near the Moon: ellipses and hyperbolas, all inclinations < 170 deg."""
    out = []
    for _ in range(n):
        e = rng.uniform(0.0, 0.9) if rng.random() < 0.6 else rng.uniform(1.05, 1.6)
        rp = rng.uniform(RM + 50.0, RM + 3000.0)
        a = rp / (1 - e)
        nu_max = 0.8 * np.arccos(-1 / e) if e > 1 else np.pi
        coe = (a, e, rng.uniform(0, np.radians(170)), rng.uniform(-np.pi, np.pi),
               rng.uniform(-np.pi, np.pi), rng.uniform(-nu_max, nu_max))
        out.append(np.array([*el.mee_from_coe(*coe), rng.uniform(300.0, 600.0)]))
    return out


def _unit(rng):
    u = rng.normal(size=3)
    return u / np.linalg.norm(u)


def _j2_potential(x):
    """U = -mu J2 R^2 / (2 r^3) (3 z^2 / r^2 - 1), with acceleration +grad U."""
    r = np.linalg.norm(x)
    return -MU * J2 * RM ** 2 / (2 * r ** 3) * (3 * x[2] ** 2 / r ** 2 - 1)


def _grad_fd(fun, x, h=1e-2):
    # central differences with h = 10 m at r >~ 1800 km: truncation (h/r)^2 ~ 3e-11 relative,
    # round-off eps |U| / h ~ 2e-16 * 2e-4 / 1e-2 ~ 4e-18 km/s^2 vs |a_J2| ~ 1e-7 km/s^2.
    g = np.zeros(3)
    for j in range(3):
        d = np.zeros(3)
        d[j] = h
        g[j] = (fun(x + d) - fun(x - d)) / (2 * h)
    return g


def test_j2_rtn_equals_gradient_of_potential():
    rng = np.random.default_rng(7)
    for x in _random_states(rng, 200):
        p, f, g, h, k, L, _ = x
        r, v = (np.array(a) for a in el.rv_from_mee(p, f, g, h, k, L, MU))
        a_in = _grad_fd(_j2_potential, r)
        a_rtn_ref = frames.rtn_basis(r, v) @ a_in
        a_rtn = np.array(dyn.j2_rtn(p, f, g, h, k, L, MU, RM, J2))
        # 1e-8 relative: the finite-difference error bound above with a wide margin
        assert np.linalg.norm(a_rtn - a_rtn_ref) <= 1e-8 * np.linalg.norm(a_rtn_ref)


def test_cartesian_j2_equals_gradient_of_potential():
    # the reference Cartesian model (used to check propagation) has the same J2 field
    m2b, mj2 = dyn.Model("two-body"), dyn.Model("j2")
    rng = np.random.default_rng(8)
    for x in _random_states(rng, 50):
        r, v = (np.array(a) for a in el.rv_from_mee(*x[:6], MU))
        s = np.concatenate([r, v, [x[6]]])
        a = dyn.cartesian_rates(0.0, s, mj2)[3:6] - dyn.cartesian_rates(0.0, s, m2b)[3:6]
        ref = _grad_fd(_j2_potential, r)
        assert np.linalg.norm(a - ref) <= 1e-8 * np.linalg.norm(ref)


def test_j2_rtn_closed_form_on_equator_and_pole():
    # On the equator (z = 0) the J2 pull is radial: -3/2 mu J2 R^2 / r^4. Over the pole
    # (z = r) it is +3 mu J2 R^2 / r^4 radially (outward relative to a point mass).
    r = 2000.0
    c = MU * J2 * RM ** 2 / r ** 4
    # equatorial circular orbit: h = k = 0, L arbitrary
    dr, dt, dn = dyn.j2_rtn(r, 0.0, 0.0, 0.0, 0.0, 0.4, MU, RM, J2)
    assert dr == pytest.approx(-1.5 * c, rel=1e-14)
    assert dt == 0.0 and dn == 0.0
    # polar orbit (i = 90 deg: h = tan(45 deg) = 1, k = 0) at the pole (argument of latitude
    # 90 deg: L = raan + 90 deg = 90 deg): the acceleration is radial, 1.5c(1 - 12/4) = +3c.
    dr, dt, dn = dyn.j2_rtn(r, 0.0, 0.0, 1.0, 0.0, np.pi / 2, MU, RM, J2)
    assert dr == pytest.approx(3 * c, rel=1e-14)
    assert abs(dt) < 1e-14 * c and abs(dn) < 1e-14 * c


def test_third_body_accel_closed_form_on_axis():
    # Spacecraft at x on the line to a body at distance D: a = mu (1/(D-x)^2 - 1/D^2) along x.
    D, x, mu = 384_400.0, 1900.0, C.MU_EARTH
    a = dyn.third_body_accel((x, 0.0, 0.0), (D, 0.0, 0.0), mu)
    assert a[0] == pytest.approx(mu * (1 / (D - x) ** 2 - 1 / D ** 2), rel=1e-9)
    assert a[1] == 0.0 and a[2] == 0.0
    # and to first order the tidal term 2 mu x / D^3 (error ~ 3 x / (2 D) ~ 0.75 %)
    assert a[0] == pytest.approx(2 * mu * x / D ** 3, rel=0.01)


def test_third_body_rtn_equals_projected_cartesian():
    # two formulations of Eq. (6) in RTN: from the body's RTN components (what the
    # dynamics use) and the Cartesian acceleration at r i_r projected on i_r, i_t, i_n
    rng = np.random.default_rng(11)
    for x in _random_states(rng, 100):
        rtn = dyn.rtn_from_mee(x[3], x[4], x[5])
        r_sc, _ = el.rv_from_mee(*x[:6], MU)
        r = np.linalg.norm(r_sc)
        for dist, mu in ((384_400.0, C.MU_EARTH), (1.496e8, C.MU_SUN)):
            rj = rng.normal(size=3)
            rj *= dist / np.linalg.norm(rj)
            a = np.array(dyn.third_body_accel(r_sc, rj, mu))
            want = np.array([np.dot(i, a) for i in rtn])
            got = np.array(dyn.third_body_rtn(r, rtn, rj, mu))
            np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * np.abs(a).max())


def test_rtn_from_mee_equals_rtn_basis():
    # two formulations of Eq. (A5): from MEE directly and from the Cartesian state
    rng = np.random.default_rng(9)
    for x in _random_states(rng, 100):
        r, v = (np.array(a) for a in el.rv_from_mee(*x[:6], MU))
        q = np.array(dyn.rtn_from_mee(x[3], x[4], x[5]))
        np.testing.assert_allclose(q, frames.rtn_basis(r, v), rtol=0, atol=1e-14)


def _rv_jacobian():
    """Exact (AD) Jacobian of (r, v) = rv_from_mee(p, f, g, h, k, L), Eq. (A6)-(A7)."""
    y = ca.SX.sym("y", 6)
    r, v = el.rv_from_mee(*[y[j] for j in range(6)], MU)
    rv = ca.vertcat(*r, *v)
    return ca.Function("J", [y], [ca.jacobian(rv, y)])


@pytest.mark.parametrize("mode,thrust", [("two-body", 0.0), ("j2", 0.0), ("full", 0.0),
                                         ("full", 150.0), ("two-body", 450.0)])
def test_mee_rates_equal_cartesian_equations_of_motion(fit, mode, thrust):
    # d(r,v)/dt = d(r,v)/dy . dy/dt must equal the Cartesian r' = v, v' = a. The Kepler part
    # (1e-5 .. 1.5e-3 km/s^2) cancels only to a few ulps, so the tolerance is 1e-14 |a_Kepler|
    # (1e-17 km/s^2 near the Moon) plus 1e-10 of the perturbation (1e-9 .. 1e-3 km/s^2).
    model = dyn.Model(mode, thrust_N=thrust, isp_s=250.0, fit=fit)
    prm = model.params()
    jac = _rv_jacobian()
    rng = np.random.default_rng(10)
    for x in _random_states(rng, 40):
        t = rng.uniform(fit.t0_s, fit.t1_s)
        u = _unit(rng)
        ydot = np.array(dyn.mee_rates(list(x), list(u), t, prm, mode), dtype=float)
        r, v = (np.array(a) for a in el.rv_from_mee(*x[:6], MU))
        s = np.concatenate([r, v, [x[6]]])
        cart = dyn.cartesian_rates(t, s, model, u_rtn=u)
        rvdot = np.asarray(jac(x[:6])) @ ydot[:6]
        kepler = -MU * r / np.linalg.norm(r) ** 3
        np.testing.assert_allclose(rvdot[:3], v, rtol=1e-12, atol=0)
        pert = cart[3:6] - kepler
        tol = 1e-10 * np.linalg.norm(pert) + 1e-14 * np.linalg.norm(kepler)
        assert np.linalg.norm((rvdot[3:] - kepler) - pert) <= tol
        assert ydot[6] == pytest.approx(cart[6], rel=1e-15)


def test_rhs_function_equals_numpy_rates(fit):
    f = dyn.rhs_function("full")
    model = dyn.Model("full", thrust_N=300.0, isp_s=250.0, fit=fit)
    prm = model.params()
    rng = np.random.default_rng(12)
    for x in _random_states(rng, 50):
        t = rng.uniform(fit.t0_s, fit.t1_s)
        u = _unit(rng)
        ref = np.array(dyn.mee_rates(list(x), list(u), t, prm, "full"), dtype=float)
        got = np.asarray(f(x, u, t, prm)).ravel()
        # same formulas, different evaluators: round-off only. Rates span O(1e-3) (L) down
        # to O(1e-9); compare each at 1e-12 relative with a floor of 1e-12 of the largest.
        np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())


def test_two_body_coast_conserves_elements_exactly():
    f = dyn.rhs_function("two-body")
    prm = dyn.Model("two-body").params()
    rng = np.random.default_rng(13)
    for x in _random_states(rng, 50):
        xdot = np.asarray(f(x, np.zeros(3), 5.4e8, prm)).ravel()
        # no perturbation at all: p, f, g, h, k and m are constants of motion, exactly
        assert np.all(xdot[[0, 1, 2, 3, 4, 6]] == 0.0)
        # L' = |r x v| / r^2 (angular rate) from the Cartesian state
        r, v = (np.array(a) for a in el.rv_from_mee(*x[:6], MU))
        assert xdot[5] == pytest.approx(np.linalg.norm(np.cross(r, v)) / (r @ r), rel=1e-12)


@pytest.mark.parametrize("thrust,isp", tuple(paper_engines().items()))
def test_mass_flow_is_thrust_over_exhaust_speed(thrust, isp):
    # Eq. (3): m' = -T / (g0 Isp), g0 = 9.80665 m/s^2; e.g. 150 N / 200 s -> -0.07648 kg/s
    f = dyn.rhs_function("two-body")
    prm = dyn.Model("two-body", thrust_N=thrust, isp_s=isp).params()
    x = np.array([4000.0, 0.5, 0.1, 0.3, -0.2, 1.0, 500.0])
    mdot = float(f(x, [0.0, 1.0, 0.0], 0.0, prm)[6])
    assert mdot == pytest.approx(-thrust / (9.80665 * isp), rel=1e-14)
    # and a tangential push raises p: p' = 2 p/q sqrt(p/mu) T/m > 0
    assert float(f(x, [0.0, 1.0, 0.0], 0.0, prm)[0]) > 0


@pytest.mark.parametrize("kwargs", [dict(mode="nbody"), dict(mode="two-body", thrust_N=-1.0),
                                    dict(mode="two-body", isp_s=0.0),
                                    dict(mode="two-body", thrust_N=float("nan")),
                                    dict(mode="full", fit=None)])
def test_bad_model_is_an_input_error(kwargs):
    with pytest.raises(InputError):
        dyn.Model(**kwargs)
