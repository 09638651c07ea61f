"""The computing parts of the other-engines page, on hand-made sequence tables."""

import math

import pandas as pd
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.report.pages import other_engines as oe

M0 = paper_scenario().mass_kg  # the paper's arrival mass, kg


def _seq(scale: float, model: bool = True) -> pd.DataFrame:
    """A three-burn sequence table whose numbers scale with ``scale``."""
    df = pd.DataFrame({
        "loi": [1, 2, 3], "start_min": [-5.0, -3.0, -2.0],
        "burn_duration_min": [10.0 * scale, 6.0 * scale, 5.0 * scale],
        "delta_v_mps": [360.0, 256.0, 246.0], "fuel_kg": [80.0, 50.0, 40.0],
        "m_end_kg": [M0 - 80.0, M0 - 130.0, M0 - 170.0],
        "verified": [True, True, True],
        "paper_impulsive_delta_v_mps": [353.0, 254.0, 245.0],
        "loss_vs_paper_impulse_mps": [7.0 * scale, 2.0 * scale, 1.0 * scale],
        "loss_vs_paper_impulse_percent": [2.0, 0.8, 0.4]})
    if model:
        df = df.assign(impulsive_limit_mps=[353.1, 254.0, 245.2],
                       delta_v_loss_mps=df.loss_vs_paper_impulse_mps + 0.1,
                       delta_v_loss_percent=1.0,
                       objective_loss_mps=df.loss_vs_paper_impulse_mps * 2,
                       objective_loss_percent=1.5)
    return df


def _case():
    rows = oe.engine_rows([(320.0, 200.0)], ["LRO-class"], [(150.0, 200.0), (320.0, 200.0)])
    seqs = {rows[0][3]: _seq(1.0), rows[1][3]: _seq(2.0)}
    return rows, seqs


def test_engine_rows_leave_out_a_paper_engine_already_cited():
    rows, _ = _case()
    assert [(t, o) for t, _, o, _ in rows] == [(320.0, "LRO-class"), (150.0, oe.PAPER_ENGINE)]
    with pytest.raises(ValueError, match="engine_names"):
        oe.engine_rows([(320.0, 200.0)], [], [])


def test_burns_frame_keeps_the_cited_engines_only():
    rows, seqs = _case()
    burns = oe.burns_frame(seqs, rows, model_loss=True)
    assert burns.engine.unique().tolist() == ["LRO-class, 320 N / 200 s"]
    assert burns.verified.tolist() == ["passed"] * 3
    assert "objective_loss_mps" in burns
    assert "objective_loss_mps" not in oe.burns_frame(seqs, rows, model_loss=False)


def test_totals_frame_sorted_by_thrust_with_sums():
    rows, seqs = _case()
    tot = oe.totals_frame(seqs, rows, model_loss=True)
    assert tot.thrust_N.tolist() == [150.0, 320.0]
    assert tot.total_loss_vs_paper_impulse_mps.tolist() == pytest.approx([20.0, 10.0])
    assert tot.burn_duration_min_loi1.tolist() == pytest.approx([20.0, 10.0])
    assert tot.total_objective_loss_mps.tolist() == pytest.approx([40.0, 20.0])
    assert tot.total_fuel_kg.tolist() == pytest.approx([170.0, 170.0])


def test_prose_values_ratios_and_missing_engines():
    rows, seqs = _case()
    tot = oe.totals_frame(seqs, rows, model_loss=True)
    v = oe.prose_values(tot, seqs, rows, model_loss=True)
    assert v["plotted_loss_mps_320N"] == pytest.approx(20.0)      # objective loss
    assert v["total_paper_loss_mps_150N"] == pytest.approx(20.0)
    assert v["burn_loi2_150N_min"] == pytest.approx(12.0)
    assert v["loss_ratio_150_320"] == pytest.approx(2.0)
    assert v["duration_ratio_sq_150_320"] == pytest.approx(4.0)
    assert math.isnan(v["plotted_loss_mps_500N"]) and math.isnan(v["dv_loi1_450N_mps"])
    v = oe.prose_values(tot, seqs, rows, model_loss=False)
    assert v["plotted_loss_mps_320N"] == pytest.approx(10.0)      # loss vs paper
