"""The computing parts of the joint-capture page, on hand-made leg tables."""

import math

import pandas as pd
import pytest

from lunarcap.report.pages import joint_capture as jc


def _legs(diffs):
    return pd.DataFrame({"loi": [1, 2, 3], "sequential_start_min": [-10.0, -6.0, -5.0],
                         "joint_start_min": [-10.0, -6.1, -4.9],
                         "sequential_burn_duration_min": [19.5, 9.0, 8.0],
                         "joint_burn_duration_min": [19.5, 9.1, 7.9],
                         "sequential_delta_v_mps": [360.0, 256.0, 247.0],
                         "joint_delta_v_mps": [360.0, 256.1, 246.9],
                         "difference_mps": diffs, "joint_verified": [True, True, False]})


def test_legs_frame_labels_every_leg():
    f = jc.legs_frame({"150 N / 200 s": _legs([0.0, -0.1, 0.1]),
                       "300 N / 250 s": _legs([0.0, 0.0, 0.0])})
    assert len(f) == 6 and f.engine.iloc[3] == "300 N / 250 s"
    assert f.joint_verified.tolist()[:3] == ["passed", "passed", "failed"]


def test_prose_values_leg_differences():
    totals = pd.DataFrame({"total_difference_mps": [0.0004, 0.0001],
                           "largest_leg_shift_mps": [0.1, 0.02],
                           "largest_start_shift_s": [6.0, 1.0]})
    v = jc.prose_values({150.0: _legs([0.0, -0.1, 0.1004])}, totals)
    assert v["total_difference_150N_mps"] == pytest.approx(0.0004)
    assert v["leg2_difference_150N_mps"] == -0.1 and v["leg2_extra_150N_mps"] == 0.1
    assert v["leg3_difference_150N_mps"] == 0.1004
    assert math.isnan(v["leg3_difference_300N_mps"])
    assert v["max_start_shift_s"] == 6.0
