"""The KPLO-class page's parts (lunarcap.report.pages.kplo_capture), against outside facts.

* The plan's intermediate orbits are asked by the periods whose two-body perilune speeds
  at 100 km are KARI's printed ones (S13, Table 2: three decimals, so within 0.5 m/s).
* The arrival's B-plane target: a polar arrival's miss vector lies along R when T is in
  the lunar equator (the orbit plane contains the pole), and its length is the
  hyperbola's impact parameter b = r_p sqrt(1 + 2 mu / (r_p v_inf^2)) in either axes.
* In two-body dynamics each burn's impulsive limit is the tangential impulse between the
  two-body perilune speeds of the orbits before and after it (the closed form), within the
  0.01 m/s the extrapolation of finite burns resolves; the design table's differences are
  ours minus KARI's printed impulses.
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from lunarcap.capture.chain import plan_result
from lunarcap.mission.plan import load_plan
from lunarcap.physics import constants as C
from lunarcap.report.pages import kplo_capture as K
from lunarcap.report.pages.real_missions import KPLO_DV_MPS, KPLO_SPEED_KMPS
from lunarcap.repro.cache import caching


@pytest.fixture(scope="module")
def plan():
    return load_plan("kplo-like-3burn")


def test_the_plans_orbits_are_karis_to_the_printed_digits(plan):
    t = K.sources_table(plan)
    speeds = t[t.quantity.str.startswith("perilune speed")]
    assert len(speeds) == 3
    for kari, ours in zip(KPLO_SPEED_KMPS, speeds.plan_value.astype(float)):
        assert abs(ours - kari) < 5e-4, (ours, kari)
    assumed = set(t.quantity[t.source == "assumed"])
    assert {"specific impulse (s)", "arrival epoch (TDB)"} <= assumed
    assert plan.engine.thrust_N == K.K2_THRUST_N and plan.arrival.mass_kg == K.K1_MASS_KG


def test_the_bplane_target_of_a_polar_arrival(plan):
    b = K.bplane_table(plan)
    eme, lunar = b.iloc[0], b.iloc[1]
    # about the lunar equator a polar orbit's B lies along R: B.T = 0
    assert plan.arrival.inclination_deg == 90.0
    assert abs(lunar.b_t_km) < 1e-6, lunar.b_t_km
    # |B| is the impact parameter of the hyperbola, whatever the axes
    rp, v = plan.perilune_radius_km, plan.arrival.v_inf_kmps
    impact = rp * math.sqrt(1 + 2 * C.MU_MOON / (rp * v ** 2))
    for row in (eme, lunar):
        assert math.hypot(row.b_t_km, row.b_r_km) == pytest.approx(impact, abs=1e-3)
    # EME2000's T is not the lunar equator's: the reference plane matters
    assert abs(eme.b_t_km) > 100.0


def test_perilune_spread_is_the_largest_difference_per_revolution():
    ev = {"a": SimpleNamespace(perilune_altitude_km=np.array([100.0, 99.0, 97.0])),
          "b": SimpleNamespace(perilune_altitude_km=np.array([100.5, 98.0, 97.2, 96.0]))}
    assert K.perilune_spread_km(ev, "a", "b") == pytest.approx(1.0)


@pytest.mark.slow
def test_two_body_limits_are_the_closed_form_impulses(plan):
    two = plan.with_dynamics("two-body")
    with caching(False):
        res = plan_result(two)
    d = K.design_table(res)
    rp = plan.perilune_radius_km
    v = [K.perilune_speed_kmps(plan.arrival.v_inf_kmps, rp)] + \
        [K.ellipse_perilune_speed_kmps(b.period_s, rp) for b in plan.burns[:2]] + \
        [math.sqrt(C.MU_MOON / rp)]
    closed = 1e3 * -np.diff(v)
    assert np.allclose(d.impulsive_limit_mps, closed, atol=0.01), (d.impulsive_limit_mps, closed)
    assert np.allclose(d.delta_v_difference_mps, d.delta_v_mps - np.array(KPLO_DV_MPS))
    assert d.verified.all()
    # a finite burn costs more than its impulse
    assert (d.delta_v_loss_mps > 0).all()


@pytest.mark.slow
def test_the_page_of_a_design_without_studies_or_flight_says_so(tmp_path):
    """The notebook passes None for a study or flight not run: each table says why.

    The design (two-body, cached) is the public API's ``lunarcap.solve``; its values are
    glued, and nothing of the missed-thrust, burns or GMAT sections is computed.
    """
    import lunarcap
    from lunarcap.repro import paths

    res = lunarcap.solve(lunarcap.load_plan("kplo-like-3burn", dynamics="two-body"))
    with paths.using_book(tmp_path):
        page = K.build(res, None, None, None, "t_kplo_none", True,
                       dict(plan="kplo-like-3burn", dynamics="two-body"), after_days=0.5)
    for key in ("missed", "counts", "gmat", "gmat_final"):
        assert page.items[key].df.iloc[0].isna().sum() >= 1, key
        assert "not" in str(page.items[key].df.iloc[0, -1]), key
    for key in ("n_cases", "best_count", "gmat_final_max_m"):
        assert isinstance(page.values[key], str), (key, page.values[key])   # the reason
    assert page.values["total_delta_v_mps"] == pytest.approx(
        res.totals()["total_delta_v_mps"], abs=1e-12)
