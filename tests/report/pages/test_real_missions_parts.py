"""The computing parts of the real-missions page, on hand-made tables."""

import pandas as pd
import pytest

from lunarcap.report.pages import real_missions as rm


def test_prose_values_ratios_and_kplo_differences():
    compare = pd.DataFrame({"ours_paper_spacecraft_min": [9.0, 5.0, 3.0, 2.0],
                            "ours_at_mission_mass_min": [30.0, 20.0, 10.0, 8.0]})
    kplo = pd.DataFrame({"speed_difference_mps": [-40.0, 2.0, -3.0, 1.0],
                         "delta_v_difference_mps": [float("nan"), 1.5, -0.5, 0.25]})
    v = rm.prose_values(compare, kplo, m0_kg=500.0, arrival_speed_kmps=2.4)
    assert v["lro_loi1_scaled_min"] == 30.0
    assert v["lro_mass_ratio"] == pytest.approx(rm.LRO_MASS_KG / 500.0)
    assert v["ce1_loi2_ours_min"] == 3.0
    assert v["ce1_loi3_ratio"] == pytest.approx(rm.CE1_BURNS_MIN[2] / 8.0)
    assert v["kplo_arrival_faster_mps"] == 40.0
    assert v["kplo_max_abs_after_diff_mps"] == 3.0
    assert v["kplo_loi1_dv_diff_mps"] == 1.5
    assert v["kplo_total_dv_diff_mps"] == pytest.approx(1.25)


def test_the_change1_verdict_is_computed_from_the_ratios_it_judges():
    # was a fixed "The order of magnitude agrees." after whatever ratios (also after
    # "nan, nan and nan" in the quick book)
    from lunarcap.report.pages.real_missions import ce1_verdict

    agree = ce1_verdict([0.72, 0.65, 0.58])
    assert agree.startswith("The order of magnitude agrees") and "launch mass" in agree
    shorter = ce1_verdict([1.4, 1.2, 1.1])
    assert shorter.startswith("The order of magnitude agrees") and "launch mass is" not in \
        shorter and "Ours are shorter" in shorter
    far = ce1_verdict([0.05, 0.65, 0.58])
    assert far.startswith("The order of magnitude differs") and "agrees" not in far
    gone = ce1_verdict([float("nan")] * 3, "the SELENE-class engine is not run in the quick book")
    assert gone == ("Not compared in this build (the SELENE-class engine is not run in the "
                    "quick book).")


def test_news_and_encyclopaedia_sources_are_marked_as_not_primary():
    from lunarcap.report.pages.real_missions import NOT_PRIMARY, SOURCES, sources_markdown

    md = sources_markdown()
    for key, what in NOT_PRIMARY.items():
        assert key in SOURCES
        assert f"{key}\n: *Not a primary source: {what}.*" in md
    # the encyclopaedia and the news site the issue named
    assert "Wikipedia" in SOURCES["S12"] and "encyclopaedia" in NOT_PRIMARY["S12"]
    assert "news site" in SOURCES["S10"] and "news site" in NOT_PRIMARY["S10"]
