"""The capture-plan page (lunarcap.report.pages.capture_plan), built in two-body dynamics."""

import math

import numpy as np
import pytest

from lunarcap.physics import constants as C
from lunarcap.report.labels import label
from lunarcap.report.pages import capture_plan

pytestmark = pytest.mark.slow


def _page(name: str, output_name: str):
    """The page as the notebook builds it: the plan solved and drawn with the public API."""
    import lunarcap

    plan = lunarcap.load_plan(name, dynamics="two-body")
    res = lunarcap.solve(plan)
    reference = None
    if capture_plan.beside_paper(plan):
        reference = lunarcap.solve(lunarcap.paper_plan(
            plan.engine.thrust_N, plan.engine.isp_s, starts=["free"] * 3, dynamics="two-body"))
    return capture_plan.build(res, res.to_frame(), res.plot(), output_name, True,
                              dict(plan=name, dynamics="two-body"), reference)


@pytest.fixture(scope="module")
def lro():
    return _page("lro-like-5burn", "t_plan_lro")


@pytest.fixture(scope="module")
def two():
    return _page("two-burn-8h", "t_plan_two")


def test_a_paper_variant_needs_its_reference():
    """The two-burn plan is set beside the paper: build refuses to draw it without one."""
    import lunarcap

    plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    assert capture_plan.beside_paper(plan)
    assert not capture_plan.beside_paper(lunarcap.load_plan("lro-like-5burn"))
    assert not capture_plan.beside_paper(lunarcap.load_plan("song2011-150N"))
    res = lunarcap.solve(plan)
    with pytest.raises(ValueError, match="reference"):
        capture_plan.build(res, res.to_frame(), res.plot(), "t_plan_noref", True)


def _totals(page):
    df = page.items["totals"].df
    return dict(zip(df.key, df.value))


@pytest.mark.parametrize("name", ["lro", "two"])
def test_totals_are_the_sums_of_the_burns(name, request):
    page = request.getfixturevalue(name)
    burns = page.items["burns"].df
    tot = _totals(page)
    assert len(burns) == page.data["plan"].n_burns
    assert tot["total_delta_v_mps"] == pytest.approx(burns.delta_v_mps.sum(), abs=1e-9)
    assert tot["total_impulsive_limit_mps"] == pytest.approx(
        burns.impulsive_limit_mps.sum(), abs=1e-9)
    assert tot["total_delta_v_loss_mps"] == pytest.approx(burns.delta_v_loss_mps.sum(), abs=1e-9)
    assert tot["total_burn_duration_min"] == pytest.approx(burns.burn_duration_min.sum())
    # propellant: the rocket equation's mass drop, burn by burn, adds up to the total
    assert tot["total_fuel_kg"] == pytest.approx(burns.fuel_kg.sum(), abs=1e-6)
    np.testing.assert_allclose(burns.m_end_kg.to_numpy()[:-1], burns.m_start_kg.to_numpy()[1:])
    np.testing.assert_allclose(burns.delta_v_loss_mps,
                               burns.delta_v_mps - burns.impulsive_limit_mps)
    # a finite burn costs more than the impulse, in total; every burn passes the gate
    assert tot["total_delta_v_loss_mps"] > 0 and burns.delta_v_loss_mps.iloc[0] > 0
    assert (page.items["verification"].df.verified == "passed").all()
    page.check()


@pytest.mark.parametrize("name", ["lro", "two"])
def test_final_orbit_is_the_plans_circle(name, request):
    page = request.getfixturevalue(name)
    plan = page.data["plan"]
    tot = _totals(page)
    alt = plan.arrival.perilune_altitude_km
    assert tot["final_rp_altitude_km"] == pytest.approx(alt, abs=1e-3)
    assert tot["final_ra_altitude_km"] == pytest.approx(alt, abs=1e-3)
    assert tot["final_inc_deg"] == pytest.approx(plan.arrival.inclination_deg, abs=1e-6)
    # the plan table's last orbit is the same circle (apolune = perilune altitude)
    assert page.items["plan"].df.apolune_altitude_km.iloc[-1] == pytest.approx(alt)


def test_lro_like_plan_beside_the_published_figures(lro):
    plan = lro.data["plan"]
    assert plan.n_burns == 5 and plan.arrival.mass_kg == 1916.0
    assert (plan.engine.thrust_N, plan.engine.isp_s) == (320.0, 200.0)
    # the plan's first target is LRO's first orbit, 220 x 3,100 km (two-body apolune)
    assert lro.items["plan"].df.apolune_altitude_km.iloc[0] == pytest.approx(3100.0)
    comp = lro.items["comparison"].df.set_index("quantity")
    assert comp.published.iloc[0] == 40.0 and comp.published.iloc[3] == 898.0
    burns = lro.items["burns"].df
    assert comp.ours.iloc[0] == burns.burn_duration_min.iloc[0]
    # 40 min of 320 N / 200 s from 1,916 kg: the rocket equation
    mdot = 320.0 / (C.G0_MPS2 * 200.0)
    dv40 = C.G0_MPS2 * 200.0 * math.log(1916.0 / (1916.0 - mdot * 2400.0))
    assert lro.values["lro_dv40_mps"] == pytest.approx(dv40)
    # ours burns longer than 40 min: our burn needs more delta-V than 40 min can give
    assert burns.delta_v_mps.iloc[0] > dv40 and comp.ours.iloc[0] > 40.0
    assert lro.values["lro_ours_fuel_kg"] < 898.0


def test_two_burns_beside_the_papers_three(two):
    comp = two.items["comparison"].df
    ours, paper, diff = (comp.iloc[i] for i in range(3))
    # every burn tangential at one perilune radius: the impulsive totals agree (the
    # two-body chain: exactly), so the difference is the finite-burn loss
    assert abs(diff.total_impulsive_limit_mps) < 0.5
    assert diff.total_delta_v_loss_mps > 0          # two longer burns lose more than three
    # the final orbit is entered at the last burn's cut-off: one 8 h orbit after the
    # arrival perilune, within the second burn's duration (Eq. 19: ~20 min) of it
    assert 8.0 - 0.5 < ours.time_to_final_orbit_h < 8.0 + 0.5
    # the paper's third burn ends a few minutes after the perilune 12.235 + 3.525 h in
    assert 0 < paper.time_to_final_orbit_h - (12.235 + 3.525) < 0.5
    np.testing.assert_allclose(diff.iloc[1:].astype(float),
                               (ours.iloc[1:] - paper.iloc[1:]).astype(float))


def test_every_shown_column_has_a_label_with_its_unit(lro):
    for key in ("plan", "burns", "masses", "verification", "totals"):
        item = lro.items[key]
        for c in item.show_columns or item.df.columns:
            lab = (item.columns or {}).get(c, label(c))
            unit_suffix = c.endswith(("_mps", "_min", "_percent", "_kg", "_km", "_m", "_mm", "_deg",
                                      "_h"))
            assert ("(" in lab) == (unit_suffix or c == "ignition_epoch"), (c, lab)


def test_plan_periods_read_as_the_paper_writes_them(two):
    plan = two.items["plan"].df
    # hours for the ellipses, minutes for the final circle (2 pi sqrt(r^3/mu), r = 1838.2 km)
    circle_min = 2 * np.pi * np.sqrt(1838.2 ** 3 / 4902.8) / 60
    assert list(plan.period) == [f"{8.0:.4f} h", f"{circle_min:.1f} min"]
    assert "period" in two.items["plan"].show_columns
    assert "period_h" not in two.items["plan"].show_columns
