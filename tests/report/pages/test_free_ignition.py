"""The free-ignition page (lunarcap.report.pages.free_ignition), built in two-body."""

import numpy as np
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper.printed import PAPER_IMPULSIVE_DV_MPS, PAPER_STARTS_MIN
from lunarcap.physics import constants as C
from lunarcap.report.labels import label
from lunarcap.report.pages import free_ignition

pytestmark = pytest.mark.slow

T_N, ISP_S = 450.0, 300.0


@pytest.fixture(scope="module")
def page():
    """The page as the notebook builds it: every burn solved with the public API."""
    import lunarcap

    capture = lunarcap.paper_plan(T_N, ISP_S, dynamics="two-body")
    free, grid, rule = [], [], {}
    for burn in (1, 2, 3):
        on = dict(previous_starts=["free"] * (burn - 1))
        f = lunarcap.solve_burn(capture, burn, start="free", **on)
        free.append(f)
        grid.append([lunarcap.solve_burn(capture, burn, start=s, impulsive=False, **on)
                     for s in free_ignition.grid_starts(T_N, burn)])
        rule[T_N, burn] = lunarcap.solve_burn(
            capture, burn, start=-f.row()["eq19_duration_min"] / 2, impulsive=False, **on)
    chains = [lunarcap.solve(capture.with_starts(s), impulsive=False)
              for s in (["free"] * 3, free_ignition.best_grid_starts(T_N, ISP_S))]
    return free_ignition.build({T_N: free}, {T_N: grid}, rule, {T_N: chains}, "t_free", True,
                               dict(engines=[[T_N, ISP_S]], dynamics="two-body"))


def test_the_public_solves_are_the_sweeps_free_vs_grid_table(page):
    """The gain table, from lunarcap.solve_burn, is the sweeps' table of paper cases.

    The page computed it with :func:`lunarcap.studies.sweeps.free_vs_grid_table` before the
    notebook solved each burn through the public API: the same numbers, column by column.
    """
    from lunarcap.studies.sweeps import free_vs_grid_table

    g = page.items["gain"].df
    ref = free_vs_grid_table(T_N, ISP_S, "two-body")
    for ours, theirs in (("free_start_min", "free_start_min"),
                         ("free_delta_v_mps", "free_delta_v_mps"),
                         ("free_objective_j_mps", "free_objective_mps"),
                         ("free_objective_loss_mps", "free_objective_loss_mps"),
                         ("grid_start_min", "grid_start_min"),
                         ("objective_gain_mps", "objective_gain_mps"),
                         ("delta_v_gain_mps", "delta_v_gain_mps")):
        np.testing.assert_allclose(g[ours], ref[theirs], rtol=0, atol=1e-9, err_msg=ours)


def test_no_grid_for_an_engine_the_paper_did_not_solve():
    assert free_ignition.grid_starts(200.0, 1) == ()
    assert free_ignition.best_grid_starts(300.0, 300.0) is None
    assert free_ignition.grid_starts(T_N, 2) == PAPER_STARTS_MIN[(T_N, 2)]
    assert free_ignition.best_grid_starts(T_N, ISP_S) == (-3.0, -2.0, -2.0)


def test_free_optimum_never_worse_than_the_grid_in_j(page):
    g = page.items["gain"].df
    assert list(g.burn) == [1, 2, 3] and (g.verified == "passed").all()
    # the grid points are feasible points of the free problem: J cannot be lower there
    assert (g.objective_gain_mps >= -1e-3).all()
    np.testing.assert_allclose(g.delta_v_gain_mps, g.grid_delta_v_mps - g.free_delta_v_mps)
    for r in g.itertuples():
        assert r.grid_start_min in PAPER_STARTS_MIN[(T_N, r.burn)]
    # the loss against the impulse from the same orbit: positive, and J-based
    assert (g.free_objective_loss_mps > 0).all()
    np.testing.assert_allclose(g.free_objective_loss_percent,
                               100 * g.free_objective_loss_mps / g.free_impulsive_limit_mps)
    # the impulse is within a few m/s of the paper's two-body impulsive values
    assert np.abs(g.free_impulsive_limit_mps - np.array(PAPER_IMPULSIVE_DV_MPS)).max() < 2.0


def test_chain_totals_and_propellant(page):
    c = page.items["chain"].df.iloc[0]
    assert c.grid_starts == "-3, -2, -2" and c.verified == "passed"
    assert c.delta_v_gain_mps == pytest.approx(c.grid_total_delta_v_mps
                                               - c.free_total_delta_v_mps)
    assert c.fuel_saved_kg == pytest.approx(c.free_final_mass_kg - c.grid_final_mass_kg)
    # same arrival mass and engine: less delta-V leaves more mass
    assert np.sign(c.fuel_saved_kg) == np.sign(c.delta_v_gain_mps)
    legs = page.data["chain_legs"][T_N]
    assert legs.sum() == pytest.approx(c.delta_v_gain_mps)


def test_eq19_rule_rows(page):
    r = page.items["rule"].df
    g = page.items["gain"].df
    np.testing.assert_allclose(r.rule_start_min, -r.eq19_duration_min / 2)
    np.testing.assert_allclose(r.burn_midpoint_min,
                               g.free_start_min + g.free_burn_duration_min / 2)
    # Eq. (19) for burn 1: the arrival mass and the plan's two-body impulse (353.272 m/s)
    ve = C.G0_MPS2 * ISP_S
    t19 = paper_scenario().mass_kg * (1 - np.exp(-353.272 / ve)) * ve / T_N / 60
    assert r.eq19_duration_min.iloc[0] == pytest.approx(t19, rel=1e-9)
    # igniting at the rule instead of the optimum cannot lower J (1 mm/s)
    assert (r.rule_objective_cost_mps >= -1e-3).all() and (r.verified == "passed").all()
    assert (r.start_minus_rule_min < 0).all()  # the optimum ignites earlier
    page.check()


def test_notes_follow_the_data(page):
    g = page.items["gain"].df
    top = g.loc[g.objective_gain_mps.idxmax()]
    assert f"{top.engine}, burn {top.burn}" in page.notes["largest_gain"]
    neg = g[g.delta_v_gain_mps < 0]
    for r in neg.itertuples():
        assert f"{-r.delta_v_gain_mps:.3f} m/s for {r.engine}, burn {r.burn}" \
            in page.notes["dv_excess"]
    assert f"{page.values['max_abs_rule_diff_min']:.2f} min" in page.notes["rule"]


def test_shown_tables_are_narrow_and_label_their_units(page):
    for key in ("gain", "chain", "rule"):
        t = page.items[key]
        assert len(t.show_columns) <= 7
        for c in t.show_columns:
            lab = (t.columns or {}).get(c, label(c))
            if c.endswith(("_mps", "_min", "_kg", "_percent")):
                assert lab.endswith(("(m/s)", "(min)", "(kg)", "(%)")), (c, lab)
