"""The computing parts of the free-ignition page, on hand-made tables."""

import math

import pandas as pd

from lunarcap.report.pages import free_ignition as fi


def _rule(diffs):
    n = len(diffs)
    return pd.DataFrame({"engine": ["150 N / 200 s"] * n, "burn": list(range(1, n + 1)),
                         "start_minus_rule_min": diffs,
                         "eq19_duration_min": [20.0, 9.0, 8.0][:n],
                         "free_start_min": [-11.0, -5.0, -4.5][:n],
                         "rule_start_min": [-10.0, -4.5, -4.0][:n],
                         "rule_objective_cost_mps": [0.02, 0.01, 0.0][:n],
                         "burn_midpoint_min": [-1.0, -0.5, 0.25][:n]})


def test_gate_text_counts():
    assert fi.gate_text(3, 3, "optima", "optimum").startswith("All 3 optima passed")
    assert fi.gate_text(2, 3, "optima", "optimum").startswith("2 of 3 optima passed")
    assert fi.gate_text(0, 1, "optima", "optimum").startswith("The optimum failed")


def test_prose_values_ranges():
    gain = pd.DataFrame({"objective_gain_mps": [0.5, float("nan"), 0.01]})
    v = fi.prose_values(gain, _rule([-1.0, -0.5, -0.25]))
    assert v["max_j_gain_mps"] == 0.5 and v["min_j_gain_mps"] == 0.01
    assert v["max_abs_rule_diff_min"] == 1.0 and v["min_abs_rule_diff_min"] == 0.25
    assert v["max_abs_midpoint_min"] == 1.0
    v = fi.prose_values(gain.iloc[[1]], _rule([-1.0, -0.5, -0.25]))
    assert math.isnan(v["max_j_gain_mps"])


def _rule_note(diffs):
    no_gain = pd.DataFrame({"objective_gain_mps": [], "delta_v_gain_mps": []})
    return fi.notes(no_gain, pd.DataFrame({"delta_v_gain_mps": []}), {}, _rule(diffs))["rule"]


def test_rule_note_names_the_worst_burn_and_the_side():
    note = _rule_note([-1.0, -0.5, -0.25])
    assert "always *earlier*" in note
    assert "The largest difference, -1.00 min, is for the longest burn (150 N, burn 1" in note
    assert "5.0 % of the Eq. (19) duration" in note
    assert "sometimes earlier" in _rule_note([-1.0, 0.5, -0.25])
