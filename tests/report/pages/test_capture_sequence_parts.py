"""The computing parts of the capture-sequence page, on small hand-made data."""

import math

import numpy as np
import pandas as pd
import pytest

from lunarcap.report.pages import capture_sequence as cs


def _burns():
    return pd.DataFrame({"burn": [1, 2], "burn_duration_min": [20.0, 10.0],
                         "perilune_from_ignition_min": [12.0, 4.0],
                         "ignition_from_perilune_deg": [-30.0, -12.0],
                         "cutoff_from_perilune_deg": [16.0, 9.0]})


def test_paper_case_only_for_150N_at_the_paper_offsets():
    assert cs.is_paper_case(150, 200, [-10, -6, -5])
    assert not cs.is_paper_case(150, 200, [-10, -6, -4])
    assert not cs.is_paper_case(300, 250, [-10, -6, -5])
    assert not cs.is_paper_case(150, 250, [-10, -6, -5])


def test_alpha_crossing_interpolates_a_rising_angle():
    t = np.array([0.0, 10.0, 20.0])
    assert cs.alpha_crossing_min([170.0, 190.0, 210.0], t) == pytest.approx(5.0)
    assert math.isnan(cs.alpha_crossing_min([190.0, 200.0, 210.0], t))   # never below 180
    assert math.isnan(cs.alpha_crossing_min([170.0, 200.0, 195.0], t))   # not monotonic


def test_burn_values_per_burn_and_total():
    v = cs.burn_values(_burns())
    assert v["duration_burn2_min"] == 10.0
    assert v["ign_from_peri_burn1_deg"] == -30.0
    assert v["before_peri_burn1_percent"] == pytest.approx(60.0)
    assert v["before_peri_burn2_percent"] == pytest.approx(40.0)
    assert v["total_burn_min"] == pytest.approx(30.0)


def test_sweep_rates_before_and_after_perilune():
    before, after = cs.sweep_rates_deg_per_min(_burns())
    assert before.tolist() == pytest.approx([2.5, 3.0])
    assert after.tolist() == pytest.approx([2.0, 1.5])
