"""Targets met as asked: the orbit the user named, checked on the re-flown state.

Every check here recomputes the orbit from the verified (re-propagated) end state with the
Cartesian state and vis-viva, independently of the target functions the NLP imposes
(:mod:`lunarcap.mission.targets`):

* a 12.235 h ellipse and a final 100 x 300 km ellipse are met within 100 m in apolune and
  1 s in period, in two-body and full dynamics (with the paper's timing-only Eq. 17 target
  the first misses its period by minutes and the second its apolune by ~20 km: this test
  fails if a period or apolune target is imposed as a timing again);
* the same capture at inclinations from 30 to 170 deg ends on its own target inclination
  and apolune (retrograde plans failed with IPOPT Infeasible_Problem_Detected before);
* a seeded family of generated two-body plans: every plan the load-time checks accept
  solves and meets its targets.
"""

import math

import numpy as np
import pytest
from plan_family import plan_family, plan_of

from lunarcap.capture.chain import solve_plan
from lunarcap.mission.plan import PlanError
from lunarcap.physics import constants as C
from lunarcap.physics.elements import rv_from_mee
from lunarcap.repro.cache import caching

pytestmark = pytest.mark.slow


def osculating(x):
    """(perilune radius km, apolune radius km, period s, inclination deg) from a state."""
    r, v = (np.array(a, float) for a in rv_from_mee(*x[:6], C.MU_MOON))
    rn, vn = np.linalg.norm(r), np.linalg.norm(v)
    a = 1.0 / (2.0 / rn - vn * vn / C.MU_MOON)
    h = np.cross(r, v)
    e_vec = np.cross(v, h) / C.MU_MOON - r / rn
    e = np.linalg.norm(e_vec)
    return (a * (1 - e), a * (1 + e), 2 * math.pi * math.sqrt(a ** 3 / C.MU_MOON),
            math.degrees(math.acos(h[2] / np.linalg.norm(h))))


ASKED = [{"target_period_h": 12.235, "start_min": "free"},
         {"target": {"perilune_altitude_km": 100, "apolune_altitude_km": 300},
          "start_min": "free"}]


@pytest.mark.parametrize("dynamics", ["two-body", "full"])
def test_a_period_and_an_ellipse_are_met_as_asked_on_the_reflown_state(dynamics):
    with caching(False):
        sols = solve_plan(plan_of(ASKED, dynamics))
    assert all(s.verification.passed for s in sols)
    rp1, _, period1, _ = osculating(sols[0].end_state)
    rp2, ra2, _, inc2 = osculating(sols[1].end_state)
    assert abs(period1 - 12.235 * 3600.0) < 1.0                    # s
    assert abs(rp1 - (C.R_MOON + 100.0)) < 0.1                     # km
    assert abs(ra2 - (C.R_MOON + 300.0)) < 0.1                     # km (100 m)
    assert abs(rp2 - (C.R_MOON + 100.0)) < 0.1
    assert abs(inc2 - 90.0) < 1e-4
    # the end of each coast is a perilune (the osculating radius is the perilune radius)
    r_end = np.linalg.norm(rv_from_mee(*sols[1].end_state[:6], C.MU_MOON)[0])
    assert abs(r_end - rp2) < 1e-3


def test_the_paper_formulation_meets_a_timing_not_the_orbit():
    """The contrast that makes the test above discriminate: Eq. (17) misses the orbit."""
    burns = [ASKED[0], {"target_apolune_altitude_km": 300, "start_min": "free"}]
    with caching(False):
        sols = solve_plan(plan_of(burns, formulation="song2011"))
    assert all(s.verification.passed for s in sols)   # Eq. (17) holds: it is what it asks
    _, _, period1, _ = osculating(sols[0].end_state)
    _, ra2, _, _ = osculating(sols[1].end_state)
    assert abs(period1 - 12.235 * 3600.0) > 10.0
    assert abs(ra2 - (C.R_MOON + 300.0)) > 1.0


RETRO = [{"target_period_h": 12.0, "start_min": "free"},
         {"target_apolune_altitude_km": 300, "start_min": "free"}]


@pytest.mark.parametrize("dynamics", ["two-body", "full"])
@pytest.mark.parametrize("inclination", [30.0, 60.0, 90.0, 120.0, 150.0, 170.0])
def test_any_inclination_is_met_as_asked(inclination, dynamics):
    with caching(False):
        sols = solve_plan(plan_of(RETRO, dynamics, inclination))
    assert all(s.verification.passed for s in sols)
    rp, ra, _, inc = osculating(sols[-1].end_state)
    assert abs(inc - inclination) < 1e-4
    assert abs(ra - (C.R_MOON + 300.0)) < 0.1 and abs(rp - (C.R_MOON + 100.0)) < 0.1


def test_inclinations_a_plan_cannot_have_are_refused_at_load():
    for bad in (0.0, 176.0, 180.0):
        with pytest.raises(PlanError, match=r"arrival.inclination_deg: .*singular at 180"):
            plan_of(RETRO, inclination=bad)


def test_an_inclination_the_approach_cannot_give_is_refused_at_load():
    # the paper's arrival asymptote lies 2.33 deg from the lunar equator on 2017-02-20
    with pytest.raises(PlanError, match=r"arrival.inclination_deg: 2 deg cannot be reached"):
        plan_of(RETRO, inclination=2.0)
    assert plan_of(RETRO, inclination=3.0).arrival.inclination_deg == 3.0


def test_every_generated_plan_accepted_at_load_solves_and_meets_its_targets():
    plans, refused = plan_family(seed=16, count=10)
    assert len(plans) >= 6, refused
    for plan in plans:
        with caching(False):
            sols = solve_plan(plan)
        assert all(s.verification.passed for s in sols), plan.name
        target = plan.targets[-1]
        rp, ra, _, inc = osculating(sols[-1].end_state)
        assert abs(inc - plan.arrival.inclination_deg) < 1e-4, plan.name
        expected_ra = target.apolune_radius_km if not target.circular else target.radius_km
        assert abs(ra - expected_ra) < 0.1, plan.name


def test_a_small_burn_that_must_also_turn_the_plane_is_not_bounded_by_its_impulse():
    # Family-9 of the full-dynamics family (seed 77): burn 3, 12.446 -> 12.182 h at 584 N,
    # starts from the perilune the Earth left 11.8 km low and 0.215 deg off the asked plane.
    # The same geometry in two-body: from that perilune state to the orbit asked (the
    # two-body impulse, 2.6 m/s, only changes the period). Bounded by 3 x Eq. (19) the
    # burn could give 7.9 m/s and IPOPT reported the problem infeasible on every mesh.
    from lunarcap.optim.problem import burn_problem
    from lunarcap.optim.solve import solve_burn_problem
    from lunarcap.physics.elements import mee_from_coe
    plan = plan_of([{"target_period_h": 12.446, "start_min": "free"},
                    {"target_period_h": 12.182, "start_min": "free"}],
                   inclination=38.2, thrust=584.0, mass=1000.0)
    x = np.array([*mee_from_coe(6293.208, 0.7097802, math.radians(38.415143), -0.1423593,
                                2.4489780, 0.0), 923.25])
    t_peri = plan.nominal_perilunes_s[1]
    prob = burn_problem(plan, 1, x, plan.ephemeris_model(), t_perilune_s=t_peri)
    sol = solve_burn_problem(prob)
    assert sol.verification.passed
    rp, _, period_s, inc = osculating(sol.end_state)
    assert abs(rp - (C.R_MOON + 100)) < 0.01 and abs(inc - 38.2) < 1e-4
    assert abs(period_s - 12.182 * 3600) < 1.0
    # more than three times the two-body impulse: what the old bound cut off
    assert sol.verification.delta_v_mps > 3 * prob.dv_impulsive_mps


def test_a_small_burn_in_full_dynamics_may_ignite_well_away_from_perilune():
    # Family-1 of the seed-24 missed family (266 N, 1,005 kg, the paper's Eq. 17 targets,
    # full dynamics): burn 2, 11.934 -> 10.69 h, is 14.4 m/s in two-body (Eq. 19: 0.8 min).
    # The Earth moves the next perilune, which only a burn away from perilune undoes:
    # within +-2 Eq. (19) durations IPOPT found it infeasible on every mesh.
    from lunarcap.capture.chain import labelled, reuse_earlier_burns, solve_burn
    from lunarcap.physics.rocket import burn_duration_estimate_s
    plans, _ = plan_family(24, 12, dynamics="full", mass_kg=(400, 2000),
                           formulations=("orbit", "song2011"))
    plan = {p.name: p for p in plans}["family-1"]
    with caching(False), reuse_earlier_burns(), labelled(plan):
        sol = solve_burn(plan.key(2))
    assert sol.verification.passed
    x_end = sol.end_state
    r_end = np.linalg.norm(rv_from_mee(*x_end[:6], C.MU_MOON)[0])
    rp, _, _, _ = osculating(x_end)
    assert abs(r_end - (C.R_MOON + 100.0)) < 0.01 and abs(r_end - rp) < 1e-3   # km
    t19_s = burn_duration_estimate_s(sol.problem.x_ref[6], sol.problem.dv_impulsive_mps,
                                     plan.engine.thrust_N, plan.engine.isp_s)
    assert abs(sol.problem.start_min) > 2.0 * t19_s / 60.0   # beyond the old window
