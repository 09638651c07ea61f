"""The computing parts of the capture-plan page, on a hand-made burn table."""

import pandas as pd
import pytest

from lunarcap.report.pages import capture_plan


def _burns(losses):
    n = len(losses)
    return pd.DataFrame({"burn": list(range(1, n + 1)), "delta_v_loss_mps": losses,
                         "objective_loss_mps": [x + 0.2 for x in losses],
                         "verification_passed": [True] * (n - 1) + [False],
                         "verification_rp_error_m": [0.001, -0.004, 0.002][:n]})


def _tot(losses):
    return {"total_delta_v_mps": 900.0, "total_impulsive_limit_mps": 880.0,
            "total_delta_v_loss_mps": sum(losses),
            "total_delta_v_loss_percent": 100 * sum(losses) / 880.0,
            "total_fuel_kg": 200.0, "final_mass_kg": 324.9, "total_burn_duration_min": 40.0,
            "time_to_final_orbit_h": 30.0, "final_rp_altitude_km": 100.0,
            "final_ra_altitude_km": 100.0}


def test_prose_values_name_the_largest_loss_and_its_share():
    losses = [12.0, 6.0, 2.0]
    v = capture_plan.prose_values(3, _burns(losses), _tot(losses))
    assert v["largest_loss_burn"] == 1
    assert v["largest_loss_share_percent"] == pytest.approx(60.0)
    assert v["n_verified"] == 2
    assert v["max_rp_error_m"] == pytest.approx(0.004)


def test_negative_loss_note_names_each_negative_burn():
    assert capture_plan.negative_loss_note(_burns([3.0, 1.0, 0.5])) == \
        "Every burn's loss is positive."
    note = capture_plan.negative_loss_note(_burns([3.0, -0.1, 0.5]))
    assert "burn 2: -0.100 m/s, but +0.100 m/s in the objective" in note
    assert "burn 1" not in note and "burn 3" not in note


def test_the_lro_first_orbit_verdict_follows_the_orbit_reached():
    # was a fixed "not 220 x 3,100 km" that read "220.0 x 3,100.0 km ..., not 220 x 3,100 km
    # (+0.0 min) and an apolune 0 km higher" once the plan met its apolune as asked
    from lunarcap.report.pages.capture_plan import first_orbit_verdict

    met = first_orbit_verdict(220.0, 3100.04, 3.2, 3.2, perilune_timed=False)
    assert "LRO's 220 × 3,100 km, within 1 km" in met and "not 220" not in met
    missed = first_orbit_verdict(220.0, 3183.0, 3.2, 3.26, perilune_timed=True)
    assert "not 220 × 3,100 km" in missed and "83 km higher" in missed
    assert "(+3.6 min)" in missed
    low = first_orbit_verdict(219.0, 3050.0, 3.2, 3.2, perilune_timed=False)
    assert "50 km lower" in low and "perilune -1.0 km" in low
