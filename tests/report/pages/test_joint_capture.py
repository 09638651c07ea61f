"""The joint-capture page (lunarcap.report.pages.joint_capture), built in two-body dynamics.

The page is built as the notebook builds it: the paper's 450 N plan solved with the public
API one burn at a time with every ignition free (``lunarcap.solve``) and as one NLP
(``lunarcap.solve_joint``), both handed to the page's display helper.
"""

import numpy as np
import pytest

import lunarcap
from lunarcap.report.pages import joint_capture

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def solved():
    plan = lunarcap.paper_plan(450.0, 300.0, dynamics="two-body")
    chain = lunarcap.solve(plan.with_starts(["free"] * plan.n_burns), impulsive=False)
    return {(450.0, 300.0): (chain, lunarcap.solve_joint(plan))}


@pytest.fixture(scope="module")
def page(solved):
    return joint_capture.build(solved, "two-body", "t_joint", True)


def test_legs_and_totals_are_consistent(page, solved):
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
    # the same numbers as the public calls themselves: the joint optimum, and the chain
    # solved one burn at a time is the one the joint NLP started from
    chain, joint = solved[450.0, 300.0]
    assert tot.joint_total_delta_v_mps == pytest.approx(joint.total_delta_v_mps, abs=1e-9)
    assert tot.sequential_total_delta_v_mps == pytest.approx(
        chain.totals()["total_delta_v_mps"], abs=1e-9)
    assert tot.sequential_total_delta_v_mps == pytest.approx(
        joint.warm_start_total_delta_v_mps, abs=1e-9)
    assert tot.ipopt_status == joint.ipopt_status


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
