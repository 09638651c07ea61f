"""The steering-laws page (lunarcap.report.pages.steering_laws), built in two-body dynamics."""


import numpy as np
import pytest

from lunarcap.report.labels import label
from lunarcap.report.page import is_missing
from lunarcap.report.pages import steering_laws

pytestmark = pytest.mark.slow


def _burns(thrust_N=450.0, isp_s=300.0):
    """As the notebook computes them: each LOI, ignition free, with each law (public API)."""
    import lunarcap

    capture = lunarcap.paper_plan(thrust_N, isp_s, dynamics="two-body")
    return [lunarcap.solve_burn(capture, loi, start="free", previous_starts=["free"] * (loi - 1),
                                steering=law, impulsive=False)
            for loi in (1, 2, 3) for law in ("optimal", "inertial", "antivelocity")]


@pytest.fixture(scope="module")
def page():
    return steering_laws.build(_burns(), "t_steering", True,
                               dict(engines=[[450.0, 300.0]], dynamics="two-body"))


def test_the_public_route_is_steering_tables_case(page):
    """lunarcap.solve_burn(..., steering=law) solves steering_table's cases: same table."""
    from lunarcap.studies import sweeps

    ref = sweeps.steering_table(450.0, 300.0, "two-body")
    ours = page.data["steering"][list(ref.columns)]
    assert ours.equals(ref)


def test_penalties_are_differences_from_the_optimal_steering(page):
    steer = page.data["steering"]
    assert len(steer) == 9 and set(steer.steering) == {"optimal", "inertial", "antivelocity"}
    for loi, rows in steer.groupby("loi"):
        opt = rows[rows.steering == "optimal"].iloc[0]
        np.testing.assert_allclose(rows.delta_v_penalty_mps, rows.delta_v_mps - opt.delta_v_mps)
        np.testing.assert_allclose(rows.objective_penalty_mps,
                                   rows.objective_j_mps - opt.objective_j_mps)
    # the optimal steering is optimal: no simple law beats its J (1 mm/s solver tolerance)
    inert = steer[steer.steering == "inertial"]
    anti = steer[steer.steering == "antivelocity"]
    assert (inert.objective_penalty_mps >= -1e-3).all()
    assert (anti.objective_penalty_mps.to_numpy() > inert.objective_penalty_mps.to_numpy()).all()


def test_antivelocity_releases_targets_and_ends_low(page):
    t = page.items["targets"].df
    anti = t[t.steering == "antivelocity"]
    assert list(anti.released_targets) == ["inc, rp", "inc, rp", "inc"]
    assert (anti[anti.loi < 3].rp_miss_km < 0).all()      # a lower, faster orbit
    kept = t[t.steering != "antivelocity"]
    assert (kept.released_targets == "none").all()
    assert (kept.rp_miss_km == 0).all() and (kept.inc_miss_deg == 0).all()
    assert (t.verified == "passed").all()


def test_values_quote_the_table_and_checks_pass(page):
    steer = page.data["steering"]
    row = steer[(steer.loi == 1) & (steer.steering == "antivelocity")].iloc[0]
    assert page.values["anti_j_loi1_450N_mps"] == row.objective_penalty_mps
    assert page.values["anti_rp_miss_loi1_450N_km"] == row.rp_miss_km
    assert page.values["max_anti_rp_miss_km"] == steer.rp_miss_km.abs().max()
    assert is_missing(page.values["inertial_j_loi1_150N_mps"])  # engine not built
    # plain floats: myst-nb's {glue:text} cannot format numpy scalars (np.float64(...))
    assert all(type(v) in (float, str) for v in page.values.values())  # str: a reason or a name
    page.check()


def test_every_shown_column_has_a_label_with_its_unit(page):
    units = {"_mps": "(m/s)", "_min": "(min)", "_km": "(km)", "_deg": "(deg)"}
    for key in ("penalty", "targets"):
        item = page.items[key]
        shown = item.show_columns or list(item.df.columns)
        assert len(shown) <= 8  # fits the page
        for c in shown:
            lab = (item.columns or {}).get(c, label(c))
            unit = next((u for s, u in units.items() if c.endswith(s)), None)
            assert unit is None or lab.endswith(unit), (c, lab)
