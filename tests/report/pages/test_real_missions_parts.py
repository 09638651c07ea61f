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
