"""The computing parts of the steering-laws page, on a hand-made table."""

import math

import pandas as pd
import pytest

from lunarcap.report.pages import steering_laws as sl


def _steer():
    rows = []
    for loi, (dv_i, j_i, j_a, rp) in enumerate([(0.5, 0.9, 4.0, -12.0), (-0.1, 0.2, 2.0, -3.0),
                                                (0.0, -0.02, 1.0, 0.5)], start=1):
        rows += [
            dict(thrust_N=150.0, loi=loi, steering="optimal", delta_v_penalty_mps=0.0,
                 objective_penalty_mps=0.0, rp_miss_km=0.0, inc_miss_deg=0.0,
                 burn_duration_min=20.0 / loi, start_min=-10.0 / loi),
            dict(thrust_N=150.0, loi=loi, steering="inertial", delta_v_penalty_mps=dv_i,
                 objective_penalty_mps=j_i, rp_miss_km=0.0, inc_miss_deg=0.0,
                 burn_duration_min=20.0 / loi, start_min=-9.0 / loi),
            dict(thrust_N=150.0, loi=loi, steering="antivelocity", delta_v_penalty_mps=-1.0,
                 objective_penalty_mps=j_a, rp_miss_km=rp, inc_miss_deg=-0.01 * loi,
                 burn_duration_min=21.0 / loi, start_min=-10.0 / loi)]
    return pd.DataFrame(rows)


def test_prose_values_pick_each_law_and_burn():
    v = sl.prose_values(_steer())
    assert v["inertial_j_loi1_150N_mps"] == 0.9
    assert v["anti_rp_miss_loi2_150N_km"] == -3.0
    assert v["inertial_start_loi2_150N_min"] == pytest.approx(-4.5)
    assert v["duration_loi2_150N_min"] == pytest.approx(10.0)
    assert math.isnan(v["anti_j_loi1_300N_mps"])             # an engine not built
    assert v["max_inertial_j_mps"] == 0.9
    assert v["max_abs_inertial_j_loi3_mps"] == pytest.approx(0.02)
    assert (v["min_anti_j_mps"], v["max_anti_j_mps"]) == (1.0, 4.0)
    assert v["max_anti_rp_miss_km"] == 12.0
    assert v["max_anti_inc_miss_deg"] == pytest.approx(0.03)
