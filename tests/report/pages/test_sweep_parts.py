"""The computing parts of the ignition-sweep page, on a hand-made sweep table."""

import math

import pandas as pd
import pytest

from lunarcap.report.pages import sweep as sw


def _sweep(printed=True):
    nan = float("nan")
    df = pd.DataFrame({
        "start_min": [-6.0, -8.0, -10.0], "delta_v_mps": [361.0, 360.0, 360.5],
        "burn_duration_min": [19.6, 19.5, 19.55], "loss_vs_paper_impulse_percent": [2.2, 1.9, 2.0],
        "best": [False, True, False], "paper_best": [False, False, True],
        "delta_v_diff_mps": [0.2, -0.1, 0.4] if printed else [nan] * 3,
        "delta_v_diff_percent": [0.05, -0.03, 0.11] if printed else [nan] * 3,
        "eq19_duration_min": [19.0] * 3, "verified": [True, True, False]})
    df.attrs["impulsive_delta_v_mps"] = 353.0
    return df


def test_median_offsets():
    assert sw.median_offsets(_sweep()) == pytest.approx((0.05, 0.2))
    assert all(math.isnan(x) for x in sw.median_offsets(_sweep(printed=False)))


def test_prose_values_best_row_against_the_paper_best():
    best_p = {"start_min": -10.0, "delta_v_mps": 360.2, "burn_duration_min": 19.5,
              "diff_percent": 2.0}
    v = sw.prose_values(_sweep(), {"delta_v_mps": 353.1}, best_p)
    assert v["best_start_min"] == -8.0 and v["best_loss_mps"] == pytest.approx(7.0)
    assert v["best_diff_mps"] == pytest.approx(-0.2)
    assert v["dv_at_paper_best_mps"] == 360.5
    assert v["impulsive_diff_mps"] == pytest.approx(0.1)
    assert (v["diff_min_percent"], v["diff_max_percent"]) == (-0.03, 0.11)
    assert v["n_verified"] == 2 and v["eq19_half_min"] == 9.5
    v = sw.prose_values(_sweep(printed=False), {"delta_v_mps": 353.1}, None)
    assert math.isnan(v["best_diff_mps"]) and math.isnan(v["diff_median_mps"])
