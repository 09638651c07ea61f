"""The Table B1 and totals page (lunarcap.report.pages.summary), one engine in two-body."""

import types

import numpy as np
import pytest

import lunarcap
from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper import printed as paper
from lunarcap.report.page import is_missing
from lunarcap.report.pages import summary

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def page():
    # the chain as the notebook solves it: the paper's plan with Table B1's offsets
    capture = lunarcap.solve(lunarcap.paper_plan(450.0, 300.0, dynamics="two-body"))
    return summary.build([capture], "t_summary", True,
                         dict(engines=[[450.0, 300.0]], starts=None, dynamics="two-body"))


def test_the_public_chain_is_sequence_tables(page):
    """lunarcap.solve of lunarcap.paper_plan reaches sequence_table's cached solves and
    impulsive limits (the same plan keys): the same rows, to the bit."""
    import pandas as pd

    from lunarcap.studies import sweeps

    ref = sweeps.sequence_table(450.0, 300.0, None, "two-body")
    pd.testing.assert_frame_equal(page.data["chains"]["450 N / 300 s"], ref,
                                  check_exact=True)
    assert page.parameters == {"engines": [[450.0, 300.0]], "starts": None,
                               "dynamics": "two-body"}


def test_b1_table_sets_ours_beside_table_b1(page):
    df = page.items["b1"].df
    b1 = paper.paper_table_b1()
    b1 = b1[b1.thrust_N == 450]
    assert list(df.loi) == [1, 2, 3] and (df.engine == "450 N / 300 s").all()
    np.testing.assert_allclose(df.paper_delta_v_mps, b1.delta_v_mps)
    np.testing.assert_allclose(df.start_min, b1.start_min)  # the paper's best offsets
    np.testing.assert_allclose(df.delta_v_diff_mps, df.delta_v_mps - df.paper_delta_v_mps)
    imp = np.array(paper.PAPER_IMPULSIVE_DV_MPS)
    np.testing.assert_allclose(df.loss_vs_paper_impulse_percent, 100 * (df.delta_v_mps - imp) / imp)
    assert (df.verified == "passed").all()
    # a finite burn needs more than the paper's impulse, even in two-body dynamics
    assert (df.delta_v_mps > imp).all()
    assert len(page.items["b1"].show_columns) <= 7
    assert page.items["b1"].paper == "Table B1, delta-V"
    assert page.items["totals"].paper is None


def test_mass_carries_through_the_chain(page):
    d = page.items["duration"].df
    np.testing.assert_allclose(d.fuel_kg.sum(), paper_scenario().mass_kg - d.m_end_kg.iloc[-1])
    # the totals table: ours is the chain's final mass, and ours - printed is consistent
    t = page.items["totals"].df.set_index("quantity")
    final = t.loc["mass after LOI 3 (kg)"]
    assert final.ours == pytest.approx(d.m_end_kg.iloc[-1])
    assert final.paper_printed == "391.722"
    assert final.ours_minus_printed == pytest.approx(final.ours - 391.722)
    assert t.loc["propellant, LOI 1-3 (kg)"].ours == pytest.approx(d.fuel_kg.sum())


def test_totals_apply_the_papers_arithmetic_to_table_b1(page):
    t = page.items["totals"].df.set_index("quantity")
    # Table B1 450 N: losses 2.277 + 0.353 + 0.543 m/s; per-burn 0.64, 0.14, 0.22 %
    assert t.loc["ΔV loss, sum of the three LOIs (m/s)"].paper_from_table_b1 == \
        pytest.approx(3.173)
    mean = t.loc["loss, mean of the three per-burn % (the paper's way) (%)"]
    assert mean.paper_from_table_b1 == pytest.approx(1.0 / 3.0)
    assert mean.paper_printed == "0.33"  # the paper's total is that mean
    share = t.loc["loss as a share of the total impulsive ΔV (%)"]
    total_imp = sum(paper.PAPER_IMPULSIVE_DV_MPS)
    assert share.paper_from_table_b1 == pytest.approx(100 * 3.173 / total_imp)


def test_model_loss_total_row_sums_the_burns(page):
    m = page.items["model_loss"].df
    burns, total = m[m.loi != "total"], m[m.loi == "total"].iloc[0]
    for col in ("paper_impulsive_delta_v_mps", "impulsive_limit_mps", "paper_delta_v_loss_mps",
                "loss_vs_paper_impulse_mps", "delta_v_loss_mps"):
        assert total[col] == pytest.approx(burns[col].sum())
    seq = page.data["chains"]["450 N / 300 s"]
    # against an impulse in the same dynamics the finite burn loses objective (Eq. 9)
    assert (seq.objective_loss_mps > 0).all()
    np.testing.assert_allclose(burns.delta_v_loss_mps,
                               seq.delta_v_mps - seq.impulsive_limit_mps)


def test_values_notes_and_checks(page):
    v = page.values
    assert is_missing(v["total_loss_vs_paper_impulse_mps_150N"])  # engines not run: a reason
    assert v["b1_total_loss_vs_paper_impulse_mps_150N"] == pytest.approx(20.273)
    assert v["paper_loss_total_150N_mps"] == 20.20
    assert v["total_loss_vs_paper_impulse_mps_450N"] == pytest.approx(
        page.items["totals"].df.ours.iloc[0])
    assert "(450 N)" in page.notes["ours_percentages"]   # a subset names its engines
    assert "Burn time" not in page.notes["differs"]       # the 300 N note needs 300 N
    page.check()


def test_glued_totals_are_the_sums_of_the_chain(page):
    # the index page quotes these: our total delta-V, the paper's (Table B1) and the losses
    df = page.items["b1"].df
    v = page.values
    assert v["total_delta_v_mps_450N"] == pytest.approx(df.delta_v_mps.sum())
    assert v["b1_total_delta_v_mps_450N"] == pytest.approx(355.549 + 254.387 + 245.906)
    assert v["total_loss_vs_paper_impulse_mps_450N"] == pytest.approx(
        v["total_delta_v_mps_450N"] - sum(paper.PAPER_IMPULSIVE_DV_MPS))
    assert v["total_delta_v_loss_mps_450N"] == pytest.approx(
        v["total_delta_v_mps_450N"] - v["total_impulsive_limit_mps_450N"])
    assert is_missing(v["total_delta_v_mps_150N"])  # not run


def test_another_engine_is_refused_with_a_clear_message():
    from lunarcap.report.pages import summary

    other = types.SimpleNamespace(plan=lunarcap.paper_plan(320.0, 200.0, dynamics="two-body"))
    with pytest.raises(ValueError, match="320 N / 200 s is not one of them"):
        summary.build([other])
