"""The computing parts of the summary page, on hand-made numbers."""

import math

import pandas as pd
import pytest

from lunarcap.report.pages import summary


def test_check_engines_accepts_the_paper_engines_only():
    assert summary.check_engines([[150, 200], [450, 300]]) == [(150.0, 200.0), (450.0, 300.0)]
    with pytest.raises(ValueError, match="320 N / 200 s is not one of them"):
        summary.check_engines([[150, 200], [320, 200]])


def test_mass_gap_scales_with_the_mass_ratio():
    v = summary.mass_gap_values({150.0: 300.0, 300.0: float("nan")},
                                {150.0: 299.0, 300.0: 310.0},
                                implied_arrival_kg=590.0, arrival_kg=600.0)
    assert v["arrival_mass_gap_kg"] == pytest.approx(10.0)
    assert v["mass_gap_at_end_kg_150N"] == pytest.approx(5.0)       # 10 kg x 300 / 600
    assert v["final_mass_diff_kg_150N"] == pytest.approx(1.0)
    assert math.isnan(v["mass_gap_at_end_kg_300N"])                  # an engine not run


def test_engine_values_are_nan_for_an_engine_not_run():
    seq = pd.DataFrame({"burn_duration_min": [19.5, 9.0, 8.0]})
    tot = {"total_delta_v_mps": 870.0, "final_mass_kg": 330.0}
    v = summary.engine_values({150.0: seq}, {150.0: tot})
    assert v["loi1_burn_min_150N"] == 19.5
    assert v["total_delta_v_mps_150N"] == 870.0
    assert math.isnan(v["total_delta_v_mps_300N"]) and math.isnan(v["loi1_burn_min_450N"])
    assert v["b1_total_delta_v_mps_300N"] > 800.0          # Table B1 is there for every engine
