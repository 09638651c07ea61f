"""The one flight (lunarcap.optim.flight): a solved burn re-flown, cut short, spoilt, coasted.

One solve, in two-body dynamics, of a plan that is not the paper's: the first burn of
two-burn-8h with a 300 N / 280 s engine, ignition 4 min before the arrival perilune.
The checks are physical laws the flight must keep whatever the plan:

* the mass flow of a burn does not depend on the state, so the mass and the delta-V at
  any cut-off follow the rocket equation exactly (also with thrust and Isp errors);
* the flight without dense output reaches the verification's (dense) cut-off state;
* a pointing tilt rotates the thrust by the tilt's angle, about an axis normal to the
  burn's mean direction;
* a late ignition coasts first, then flies the whole burn;
* the coast to a perilune (in full dynamics) ends where r.v = 0, on the perilune branch,
  the one nearest the epoch asked.
"""

import math

import numpy as np
import pytest

from lunarcap.capture.chain import arrival_for
from lunarcap.mission.plan import load_plan, plan_ephemeris
from lunarcap.optim.flight import (
    BurnPlan,
    ExecutionErrors,
    coast,
    coast_to_perilune,
    cut_off,
    fly,
    tilt_matrix,
)
from lunarcap.optim.problem import burn_problem
from lunarcap.optim.solve import solve_burn_problem
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mean_motion_and_anomaly, rv_from_mee
from lunarcap.physics.state import State

pytestmark = pytest.mark.slow

THRUST_N, ISP_S = 300.0, 280.0


@pytest.fixture(scope="module")
def sol():
    plan = (load_plan("two-burn-8h").with_dynamics("two-body")
            .with_engine(THRUST_N, ISP_S).with_start(0, -4.0))
    prob = burn_problem(plan, 0, arrival_for(plan.arrival).state, plan_ephemeris(None))
    s = solve_burn_problem(prob)
    assert s.verification.passed, s.verification.failures()
    return s


def _mass_flow_kgps(thrust_N, isp_s):
    return thrust_N / (C.G0_MPS2 * isp_s)


@pytest.mark.parametrize("share", [0.0, 0.3, 0.77, 1.0])
def test_a_cut_off_burns_the_rocket_equations_mass_and_delta_v(sol, share):
    raw = sol.raw
    m0 = float(raw.prob.x0[6])
    fl = cut_off(raw, share * raw.t1_s)
    assert fl.end.t_s == raw.prob.t_ign_s + share * raw.t1_s
    m_expected = m0 - _mass_flow_kgps(THRUST_N, ISP_S) * share * raw.t1_s
    assert fl.end.mass_kg == pytest.approx(m_expected, rel=1e-11)
    dv = C.G0_MPS2 * ISP_S * math.log(m0 / fl.end.mass_kg)
    assert fl.delta_v_mps == pytest.approx(dv, rel=1e-9, abs=1e-9)
    if share == 1.0:   # the same state the verification's dense flight reached
        np.testing.assert_allclose(fl.end.x, sol.flight.cutoff.x, rtol=1e-11, atol=1e-12)
        assert fl.delta_v_mps == pytest.approx(sol.flight.delta_v_mps, rel=1e-12)


def test_thrust_and_isp_errors_change_the_mass_flow_as_the_rocket_equation_says(sol):
    raw = sol.raw
    e = ExecutionErrors(thrust_factor=1.03, isp_factor=0.98)
    fl = fly(BurnPlan.of(raw).with_errors(e), State(raw.prob.t_ign_s, raw.prob.x0))
    m0 = float(raw.prob.x0[6])
    isp = ISP_S * e.isp_factor
    m1 = m0 - _mass_flow_kgps(THRUST_N * e.thrust_factor, isp) * raw.t1_s
    assert fl.end.mass_kg == pytest.approx(m1, rel=1e-11)
    assert fl.delta_v_mps == pytest.approx(C.G0_MPS2 * isp * math.log(m0 / m1), rel=1e-9)
    assert fl.propellant_kg == pytest.approx(m0 - m1, rel=1e-9)


def test_a_tilt_rotates_the_thrust_by_its_angle_about_an_axis_normal_to_the_mean(sol):
    raw = sol.raw
    tilt = (0.004, -0.003)
    R = tilt_matrix(raw.u, tilt)
    np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-15)
    u = raw.u / np.linalg.norm(raw.u, axis=0)
    m = u.mean(axis=1)
    m /= np.linalg.norm(m)
    assert math.acos(min(1.0, float(m @ R @ m))) == pytest.approx(math.hypot(*tilt),
                                                                  rel=1e-6)
    # the flown steering is the nominal one rotated by R, at any state and time
    nominal = BurnPlan.of(raw)
    tilted = nominal.with_errors(ExecutionErrors(tilt_rad=tilt))
    x = np.asarray(raw.prob.x0)
    for t in np.linspace(nominal.t_ign_s, nominal.end_s, 7):
        np.testing.assert_allclose(tilted.direction(t, x), R @ nominal.direction(t, x),
                                   atol=1e-13)


def test_a_late_ignition_coasts_first_then_flies_the_whole_burn(sol):
    raw = sol.raw
    start = State(raw.prob.t_ign_s, raw.prob.x0)
    late = ExecutionErrors(ignition_s=90.0)
    fl = fly(BurnPlan.of(raw).with_errors(late), start)
    assert fl.start.t_s == raw.prob.t_ign_s + 90.0
    assert fl.end.t_s == raw.prob.t_ign_s + 90.0 + raw.t1_s
    coasted = coast(raw.prob.model, start, raw.prob.t_ign_s + 90.0).end
    np.testing.assert_array_equal(fl.start.x, coasted.x)
    # the same burn from the later state, so the same mass but another orbit
    assert fl.end.mass_kg == pytest.approx(sol.flight.cutoff.mass_kg, rel=1e-12)
    assert abs(fl.end.x[5] - sol.flight.cutoff.x[5]) > 1e-3


def test_the_coast_to_a_perilune_ends_where_r_dot_v_vanishes_nearest_the_epoch_asked(
        sol, mission_fit):
    raw = sol.raw
    cut = cut_off(raw, 0.8 * raw.t1_s).end   # a burn cut short misses the planned perilune
    # coasting in full dynamics, where the Kepler jump to the perilune is only a start
    full = Model("full", 0.0, ISP_S, mission_fit)
    peri = coast_to_perilune(full, cut, raw.prob.t_end_s)
    r, v = (np.array(a, float) for a in rv_from_mee(*peri.mee, C.MU_MOON))
    assert abs(r @ v) / (np.linalg.norm(r) * np.linalg.norm(v)) < 1e-8
    f, g, L = peri.x[1], peri.x[2], peri.x[5]
    assert f * math.cos(L) + g * math.sin(L) > 0   # e cos(nu) > 0: a perilune
    n, _ = mean_motion_and_anomaly(peri.x, C.MU_MOON)   # the one nearest the guess
    assert abs(peri.t_s - raw.prob.t_end_s) < math.pi / n
