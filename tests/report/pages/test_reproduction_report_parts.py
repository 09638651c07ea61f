"""The computing parts of the reproduction report, on hand-made tables."""

import pandas as pd
import pytest

from lunarcap.report.pages import reproduction_report as rr


def _dur(t4_diffs, other_diffs):
    n4, no = len(t4_diffs), len(other_diffs)
    return pd.DataFrame({"thrust_N": [300.0] * n4 + [150.0] * no, "loi": [1] * (n4 + no),
                         "difference": list(t4_diffs) + list(other_diffs)})


def test_duration_remark_says_where_the_largest_differences_are():
    assert rr.duration_remark(_dur([], [0.1])) == "Table 4 is not in part (a) of this run"
    assert "0.90 to 1.20 min" in rr.duration_remark(_dur([0.9, -1.2], [0.1, -0.3]))
    assert rr.duration_remark(_dur([0.2], [0.5])).startswith("though")
    assert rr.duration_remark(_dur([0.2, 1.0], [0.5])).startswith("though")


def _long():
    rows = []
    for src, q, paper_v, diff, ver in [
            ("Table 1", "delta-V", 360.0, 0.5, True), ("Table 1", "delta-V", 362.0, -2.0, True),
            ("Table 1", "burn duration", 19.5, 0.05, True),
            ("Table B1", "delta-V", 360.0, 0.36, True),
            ("Tables 1-5, B1 (impulsive)", "delta-V", 353.0, 0.1, True)]:
        rows.append(dict(source=src, quantity=q, paper=paper_v, difference=diff,
                         verified=ver, start_min=-10.0))
    return pd.DataFrame(rows)


def test_part_a_values_worst_and_counts():
    sweep = pd.DataFrame({"start_min": [-8.0, -10.0], "best": [True, False],
                          "paper_best": [False, True]})
    v = rr.part_a_values(_long(), {(150.0, 1): sweep})
    assert v["n_cases"] == 2 and v["n_table_numbers"] == 3 and v["n_numbers_a"] == 5
    assert v["max_dv_diff_mps"] == -2.0
    assert v["median_dv_diff_mps"] == pytest.approx(1.25)
    assert v["n_dv_within_1mps"] == 1 and v["n_best_agree"] == 0
    assert v["b1_max_dv_diff_percent"] == pytest.approx(0.1)
    assert rr.gate_text(_long()).startswith("Every case passed")
