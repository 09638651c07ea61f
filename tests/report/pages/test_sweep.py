"""The ignition-sweep page (lunarcap.report.pages.sweep), built in two-body dynamics."""

import numpy as np
import pytest

from lunarcap.paper import printed as paper
from lunarcap.report.labels import label
from lunarcap.report.pages import sweep

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def page():
    # as the notebook computes it: the paper's plan, burn 1 at each offset (public API)
    import lunarcap

    capture = lunarcap.paper_plan(150.0, 200.0, dynamics="two-body")
    burns = [lunarcap.solve_burn(capture, 1, start=s) for s in (-8.0, -10.0)]
    return sweep.build(burns, "t_sweep", True)


def test_delta_v_table_sets_ours_beside_the_paper(page):
    df = page.items["dv"].df
    assert list(df.burn) == [sweep.IMPULSE_ROW_LIMIT, "finite", "finite"]
    # one row label per impulse: the reproduction report's row holds the two-body impulse
    from lunarcap.report.reproduction import IMPULSE_ROW_TWO_BODY
    assert IMPULSE_ROW_TWO_BODY != sweep.IMPULSE_ROW_LIMIT
    fin = df[df.burn == "finite"]
    printed = paper.paper_table(150.0, 1).set_index("start_min")
    np.testing.assert_allclose(fin.paper_delta_v_mps,
                               printed.loc[fin.start_min, "delta_v_mps"].to_numpy())
    np.testing.assert_allclose(fin.delta_v_diff_mps, fin.delta_v_mps - fin.paper_delta_v_mps)
    # loss against the paper's impulsive 353.272 m/s, as the paper's Tables 1-5
    np.testing.assert_allclose(fin.loss_vs_paper_impulse_percent,
                               100 * (fin.delta_v_mps - 353.272) / 353.272)
    assert (df.verified == "passed").all()
    # the smallest delta-V is flagged (ours, and the paper's best -10 min is "both")
    best = fin.loc[fin.delta_v_mps.idxmin()]
    assert best.best in ("ours", "both")
    # the paper's Table 1 carries the paper's number, not a book number
    assert page.items["dv"].paper == "Table 1, delta-V"
    assert page.items["duration"].paper == "Table 1, burn durations"
    assert page.items["dv_figure"].paper is None   # our plot, not one of the paper's


def test_values_and_checks(page):
    v = page.values
    assert v["n_cases"] == 2 and v["n_verified"] == 2
    assert v["paper_best_delta_v_mps"] == 367.415
    assert v["best_diff_mps"] == pytest.approx(v["best_delta_v_mps"] - 367.415)
    page.check()  # two-body: the Table B1 comparison is not asserted, the rest is


def test_every_shown_column_has_a_label_with_its_unit(page):
    for key in ("dv", "duration"):
        for c in page.items[key].df.columns:
            lab = (page.items[key].columns or {}).get(c, label(c))
            unit_suffix = c.endswith(("_mps", "_min", "_percent"))
            assert ("(" in lab) == unit_suffix, (c, lab)


def test_the_public_route_is_the_papers_case():
    """lunarcap.solve_burn on lunarcap.paper_plan solves sweep_table's case: same solution.

    Same plan key (the paper's formulation and model), so the same cached solve: the
    shaped table and the impulsive limit are identical, bit for bit.
    """
    import lunarcap
    from lunarcap.studies import sweeps

    capture = lunarcap.paper_plan(150.0, 200.0, dynamics="two-body")
    burns = [lunarcap.solve_burn(capture, 2, start=s) for s in (-6.0, -3.0)]
    ours, imp = sweep.sweep_of(burns)
    ref = sweeps.sweep_table(150.0, 200.0, 2, [-6.0, -3.0], dynamics="two-body")
    cols = [c for c in ref.columns if c != "solve_wall_s"]
    assert ours[cols].equals(ref[cols])
    assert ours.attrs == ref.attrs
    assert imp == sweeps.paper_impulsive_case(150.0, 200.0, 2, (-10.0,), "two-body")
