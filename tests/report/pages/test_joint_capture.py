"""The joint-capture page (lunarcap.report.pages.joint_capture), built in two-body dynamics."""

import numpy as np
import pytest

from lunarcap.capture.joint_plan import chain_summary
from lunarcap.report.pages import joint_capture

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def page():
    return joint_capture.build([[450.0, 300.0]], "two-body", "t_joint", True)


def test_legs_and_totals_are_consistent(page):
    legs = page.items["legs"].df
    np.testing.assert_allclose(legs.difference_mps,
                               legs.sequential_delta_v_mps - legs.joint_delta_v_mps)
    tot = page.items["totals"].df.iloc[0]
    assert tot.sequential_total_delta_v_mps == pytest.approx(legs.sequential_delta_v_mps.sum())
    assert tot.joint_total_delta_v_mps == pytest.approx(legs.joint_delta_v_mps.sum())
    assert tot.total_difference_mps == pytest.approx(
        tot.sequential_total_delta_v_mps - tot.joint_total_delta_v_mps)
    assert tot.largest_start_shift_s == pytest.approx(
        60 * (legs.joint_start_min - legs.sequential_start_min).abs().max())
    # the same numbers as the joint solve itself
    r = chain_summary(450.0, 300.0, "two-body")
    assert tot.joint_total_delta_v_mps == pytest.approx(r["total_delta_v_mps"], abs=1e-9)
    assert tot.sequential_total_delta_v_mps == pytest.approx(
        r["sequential_total_delta_v_mps"], abs=1e-9)


def test_the_joint_optimum_is_never_worse_and_barely_better(page):
    tot = page.items["totals"].df.iloc[0]
    assert -1e-3 <= tot.total_difference_mps < 0.01
    assert (page.items["legs"].df.joint_verified == "passed").all()
    assert page.items["solve"].df.ipopt_status.iloc[0] == "Solve_Succeeded"
    assert page.values["max_total_difference_mps"] == tot.total_difference_mps
    assert page.values["total_difference_450N_mps"] == pytest.approx(tot.total_difference_mps)
    # plain floats: myst-nb's {glue:text} cannot format numpy scalars (np.float64(...))
    assert all(type(v) in (float, str) for v in page.values.values())  # str: a reason or a name
    page.check()


def test_tables_fit_the_page(page):
    for key in ("legs", "timing", "totals", "solve"):
        item = page.items[key]
        assert len(item.show_columns or item.df.columns) <= 7, key
