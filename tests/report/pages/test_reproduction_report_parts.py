"""The computing parts of the reproduction report, on hand-made tables."""

import numpy as np
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


def _table_b1_long():
    """Table B1's nine rows in the long form of part (a), ours a little off the paper's.

    Ours differ from the paper's by a different amount per engine, so a row holding another
    engine's numbers is caught on either column.
    """
    from lunarcap.paper import printed as paper

    rows = []
    for b in paper.paper_table_b1().itertuples(index=False):
        for qty, printed in (("burn duration", b.burn_duration_min),
                             ("delta-V", b.delta_v_mps),
                             ("difference from impulsive", b.diff_percent)):
            ours = printed + b.thrust_N / 1000.0
            rows.append(dict(source="Table B1", thrust_N=float(b.thrust_N), isp_s=float(b.isp_s),
                             loi=int(b.loi), start_min=float(b.start_min), quantity=qty,
                             unit="", paper=float(printed), ours=ours,
                             difference=ours - float(printed), paper_best=True, ours_best=False,
                             verified=True))
    return pd.DataFrame(rows)


def test_the_wide_table_holds_table_b1s_nine_rows_each_its_engines():
    """Table B1 prints nine rows, three engines by three LOIs; the 300 N and 450 N LOI 3 rows
    both ignite 2 min before perilune. Keyed without the engine, the wide table once had eight:
    the 300 N LOI 3 row showed the 450 N numbers (3.72 min, 245.906 m/s; Table B1 prints 5.32
    min and 246.515 m/s) and the 450 N row was gone."""
    from lunarcap.paper import printed as paper

    wide = rr.tables_wide(_table_b1_long())
    b1 = wide[wide.source.str.startswith("Table B1")]
    assert len(b1) == 9
    printed = paper.paper_table_b1()
    for r in printed.itertuples(index=False):
        row = b1[(b1.thrust_N == r.thrust_N) & (b1.start == f"{r.start_min:g}")
                 & (b1.source == f"Table B1, {r.thrust_N:g} N")]
        row = row[np.isclose(row.paper_delta_v_mps, r.delta_v_mps, rtol=0, atol=1e-9)]
        assert len(row) == 1, (r.thrust_N, r.loi)
        x = row.iloc[0]
        assert x.isp_s == r.isp_s
        assert x.paper_burn_duration_min == pytest.approx(r.burn_duration_min, abs=1e-12)
        assert x.paper_loss_vs_paper_impulse_percent == pytest.approx(r.diff_percent, abs=1e-12)
        # ours beside the paper's of the same engine: offset by that engine's thrust / 1000
        assert x.delta_v_mps - x.paper_delta_v_mps == pytest.approx(r.thrust_N / 1000.0)
        assert x.burn_duration_min - x.paper_burn_duration_min == pytest.approx(
            r.thrust_N / 1000.0)
    # the two engines that ignite LOI 3 at -2 min keep their own rows and numbers, as
    # Table B1 prints them (5.32 min, 246.515 m/s; 3.72 min, 245.906 m/s)
    for thrust, minutes, dv in ((300.0, 5.32, 246.515), (450.0, 3.72, 245.906)):
        row = b1[(b1.source == f"Table B1, {thrust:g} N") & (b1.start == "-2")
                 & np.isclose(b1.paper_burn_duration_min, minutes)]
        assert len(row) == 1 and row.paper_delta_v_mps.iloc[0] == pytest.approx(dv)
