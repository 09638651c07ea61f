"""The tables beside the paper (lunarcap.studies.sweeps): their data, not their looks.

The arithmetic tests build tables from the paper's own numbers and run in milliseconds.
The tests marked ``slow`` solve a few cases in the two-body model (cached on disk after
the first run) and check the bookkeeping of real tables: units in the column names,
differences that are ours minus the paper's, the best flag on the minimum, the mass
carried through the chain.
"""

import math
import re

import numpy as np
import pandas as pd
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper import printed as paper
from lunarcap.paper.printed import PAPER_BEST_STARTS_MIN, PAPER_IMPULSIVE_DV_MPS
from lunarcap.studies import sweeps as tables

#: Unit suffixes of numeric columns, and the numeric columns that are counts or flags.
UNIT_SUFFIX = re.compile(r"_(min|mps|kmps|percent|kg|m|deg|s|N)$")
UNITLESS = {"loi", "free_start", "verified", "best", "paper_best", "ipopt_iterations",
            "iterations", "passed"}


def _check_units(df):
    numeric = [c for c in df.columns if pd.api.types.is_numeric_dtype(df[c])
               or pd.api.types.is_bool_dtype(df[c])]
    missing = [c for c in numeric if c not in UNITLESS and not UNIT_SUFFIX.search(c)]
    assert not missing, f"numeric columns without a unit suffix: {missing}"


def _paper_chain(thrust_N):
    """A sequence_table-shaped frame from the paper's Table B1 (no solving)."""
    b1 = paper.paper_table_b1()
    pb = b1[b1.thrust_N == thrust_N].reset_index(drop=True)
    return pd.DataFrame({
        "loi": pb.loi, "delta_v_mps": pb.delta_v_mps,
        "paper_impulsive_delta_v_mps": pb.impulsive_delta_v_mps,
        "loss_vs_paper_impulse_mps": pb.delta_v_mps - pb.impulsive_delta_v_mps,
        "loss_vs_paper_impulse_percent": pb.diff_percent, "burn_duration_min": pb.burn_duration_min,
        "m_end_kg": np.nan})


# ------------------------------------------------------------------ arithmetic (fast)
def test_default_previous_is_the_papers_best_prefix():
    assert tables.default_previous(150.0, 1, 200.0) == ()
    assert tables.default_previous(150.0, 2, 200.0) == (-10.0,)
    assert tables.default_previous(300.0, 3, 250.0) == PAPER_BEST_STARTS_MIN[300.0][:2]
    assert tables.default_previous(450, 3, 300) == (-3.0, -2.0)
    # another engine (or another Isp): the earlier burns ignite at their free optima
    assert tables.default_previous(450, 3, 250) == ("free", "free")


def test_sequence_totals_arithmetic_on_a_synthetic_chain():
    df = pd.DataFrame({
        "delta_v_mps": [360.0, 260.0, 250.0],
        "paper_impulsive_delta_v_mps": list(PAPER_IMPULSIVE_DV_MPS),
        "burn_duration_min": [19.0, 11.0, 9.0],
        "m_end_kg": [440.0, 390.0, 340.0],
        "impulsive_limit_mps": [353.0, 254.0, 245.0],
    })
    df["loss_vs_paper_impulse_mps"] = df.delta_v_mps - df.paper_impulsive_delta_v_mps
    df["loss_vs_paper_impulse_percent"] = \
        100 * df.loss_vs_paper_impulse_mps / df.paper_impulsive_delta_v_mps
    df["delta_v_loss_mps"] = df.delta_v_mps - df.impulsive_limit_mps
    df["objective_loss_mps"] = [7.5, 5.0, 5.0]
    t = tables.sequence_totals(df, mass0_kg=500.0)
    imp = sum(PAPER_IMPULSIVE_DV_MPS)
    assert t["total_delta_v_mps"] == pytest.approx(870.0)
    assert t["total_paper_impulsive_delta_v_mps"] == pytest.approx(imp)
    # the sum of the per-LOI losses
    assert t["total_loss_vs_paper_impulse_mps"] == pytest.approx(870.0 - imp)
    assert t["total_loss_vs_paper_impulse_mps"] == pytest.approx(df.loss_vs_paper_impulse_mps.sum())
    assert t["total_loss_vs_paper_impulse_percent"] == pytest.approx(100 * (870.0 - imp) / imp)
    assert t["mean_of_burn_loss_percent"] == pytest.approx(df.loss_vs_paper_impulse_percent.mean())
    assert t["total_fuel_kg"] == pytest.approx(160.0)                 # 500 - 340
    assert t["final_mass_kg"] == pytest.approx(340.0)
    assert t["total_burn_duration_min"] == pytest.approx(39.0)
    assert t["total_delta_v_loss_mps"] == pytest.approx(870.0 - 852.0)
    assert t["total_impulsive_limit_mps"] == pytest.approx(852.0)
    assert t["total_delta_v_loss_percent"] == pytest.approx(100 * 18.0 / 852.0)
    assert t["total_objective_loss_mps"] == pytest.approx(17.5)
    assert t["total_objective_loss_percent"] == pytest.approx(100 * 17.5 / 852.0)
    # the two percentages differ: a mean of ratios is not the ratio of the sums
    assert t["mean_of_burn_loss_percent"] != pytest.approx(
        t["total_loss_vs_paper_impulse_percent"], abs=1e-3)


def test_sequence_totals_without_model_columns_has_no_model_keys():
    df = _paper_chain(150)
    t = tables.sequence_totals(df)
    assert "total_delta_v_loss_mps" not in t
    assert math.isnan(t["total_fuel_kg"]) and math.isnan(t["final_mass_kg"])


@pytest.mark.parametrize("thrust_N", [150, 300, 450])
def test_the_papers_percentages_are_means_of_the_per_burn_percentages(thrust_N):
    """Song 2011 quotes 2.12 / 0.55 / 0.33 %: the mean of Table B1's per-burn %, not the
    total loss over the total impulsive delta-V (which is 2.38 / 0.60 / 0.37 %)."""
    t = tables.sequence_totals(_paper_chain(thrust_N))
    printed = paper.quote(f"loss_total_{thrust_N}N_percent").value
    assert abs(t["mean_of_burn_loss_percent"] - printed) < 0.005
    assert t["total_loss_vs_paper_impulse_percent"] - printed > 0.04
    assert t["total_burn_duration_min"] == pytest.approx(
        paper.quote(f"burn_total_{thrust_N}N_min").value, abs=0.015)


# ------------------------------------------------------------------ solved tables (slow)
@pytest.fixture(scope="module")
def sweep_two_body():
    return tables.sweep_table(150.0, 200.0, 1, [-8.0, -10.0, -12.0], dynamics="two-body")


@pytest.mark.slow
def test_sweep_table_columns_carry_units(sweep_two_body):
    _check_units(sweep_two_body)
    assert len(sweep_two_body) == 3
    assert sweep_two_body.attrs["loi"] == 1 and sweep_two_body.attrs["dynamics"] == "two-body"


@pytest.mark.slow
def test_sweep_table_differences_are_ours_minus_the_paper(sweep_two_body):
    df = sweep_two_body
    printed = paper.paper_table(150, 1).set_index("start_min")
    for r in df.itertuples():
        p = printed.loc[int(r.start_min)]
        assert r.paper_delta_v_mps == p.delta_v_mps
        assert r.paper_burn_duration_min == p.burn_duration_min
        assert r.paper_delta_v_loss_percent == p.diff_percent
    np.testing.assert_allclose(df.delta_v_diff_mps, df.delta_v_mps - df.paper_delta_v_mps)
    np.testing.assert_allclose(df.burn_duration_diff_min,
                               df.burn_duration_min - df.paper_burn_duration_min)
    np.testing.assert_allclose(df.delta_v_diff_percent,
                               100 * df.delta_v_diff_mps / df.paper_delta_v_mps)
    imp = PAPER_IMPULSIVE_DV_MPS[0]
    np.testing.assert_allclose(df.loss_vs_paper_impulse_percent, 100 * (df.delta_v_mps - imp) / imp)


@pytest.mark.slow
def test_sweep_table_best_flag_is_the_minimum(sweep_two_body):
    df = sweep_two_body
    assert df.best.sum() == 1
    assert df.loc[df.best, "delta_v_mps"].iloc[0] == df.delta_v_mps.min()
    assert df.paper_best.sum() == 1
    assert df.loc[df.paper_best, "start_min"].iloc[0] == paper.paper_best(150, 1)["start_min"]
    assert df.verified.all()


@pytest.mark.slow
def test_sequence_table_and_totals_of_a_chain():
    df = tables.sequence_table(150.0, 200.0, dynamics="two-body", with_impulsive_model=False)
    _check_units(df)
    assert list(df.loi) == [1, 2, 3]
    assert tuple(df.start_min) == PAPER_BEST_STARTS_MIN[150.0]
    # the mass carries through the chain
    assert df.m_start_kg.iloc[0] == pytest.approx(paper_scenario().mass_kg)
    np.testing.assert_allclose(df.m_start_kg.iloc[1:], df.m_end_kg.iloc[:-1])
    np.testing.assert_allclose(df.fuel_kg, df.m_start_kg - df.m_end_kg)
    np.testing.assert_allclose(df.loss_vs_paper_impulse_mps,
                               df.delta_v_mps - df.paper_impulsive_delta_v_mps)
    for r in df.itertuples():
        pb = paper.paper_best(150, r.loi)
        assert (r.paper_delta_v_mps, r.paper_start_min) == (pb["delta_v_mps"], pb["start_min"])
    t = tables.sequence_totals(df)
    assert t["total_loss_vs_paper_impulse_mps"] == pytest.approx(df.loss_vs_paper_impulse_mps.sum())
    assert t["total_fuel_kg"] == pytest.approx(df.fuel_kg.sum())
    assert t["final_mass_kg"] == pytest.approx(paper_scenario().mass_kg - t["total_fuel_kg"])
    assert t["total_burn_duration_min"] == pytest.approx(df.burn_duration_min.sum())


@pytest.mark.slow
def test_verification_table_one_row_per_solution():
    from lunarcap.capture.chain import paper_case

    sols = [paper_case(150.0, 200.0, 1, s, (), "two-body") for s in (-8.0, -10.0)]
    v = tables.verification_table(sols)
    _check_units(v.drop(columns=["ra_error_m"]))   # None for non-circular targets
    assert list(v.start_min) == [-8.0, -10.0]
    assert list(v.passed) == [s.verification.passed for s in sols]
    np.testing.assert_allclose(v.delta_v_mps, [s.delta_v_mps for s in sols])
    assert (v.verified_delta_v_diff_mps.abs() < 0.01).all()
