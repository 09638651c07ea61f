"""The number-of-burns and missed-thrust pages: what they read from a study's table.

Pure data (no solves): synthetic tables with the studies' columns. The pages themselves
run in the quick book build (tests/report/test_notebooks.py).
"""

import json

import pandas as pd

from lunarcap.report.pages import burn_count, missed_thrust


def test_burn_rows_decode_every_burn_and_reading_names_infeasible_counts():
    burns = [{"burn": 1, "target": "ellipse, 8 h", "delta_v_mps": 428.0},
             {"burn": 2, "target": "circle", "delta_v_mps": 462.0}]
    t = pd.DataFrame([
        {"plan": "p", "plan_id": "x", "label": "P", "n_burns": 1, "status": "infeasible",
         "reason": "burn 1 too long", "total_delta_v_loss_mps": None, "time_to_final_orbit_h": None,
         "burns_json": "[]"},
        {"plan": "p", "plan_id": "x", "label": "P", "n_burns": 2, "status": "ok", "reason": "",
         "total_delta_v_loss_mps": 40.0, "time_to_final_orbit_h": 8.5,
         "burns_json": json.dumps(burns)},
        {"plan": "p", "plan_id": "x", "label": "P", "n_burns": 3, "status": "ok", "reason": "",
         "total_delta_v_loss_mps": 20.0, "time_to_final_orbit_h": 16.0,
         "burns_json": json.dumps(burns)},
    ])
    rows = burn_count.burn_rows(t)
    assert list(rows.n_burns) == [2, 2, 3, 3] and list(rows.burn) == [1, 2, 1, 2]
    text = burn_count.reading(t)
    assert "from 2 to 3 burns the loss goes from 40.0 to 20.0 m/s" in text
    assert "-20.00 m/s" in text and "P: N = 1: infeasible (burn 1 too long)" in text


def test_negative_per_burn_losses_are_explained_or_flagged():
    rows = pd.DataFrame({"delta_v_loss_mps": [0.3, -0.057, 2.0]})
    text = burn_count.negative_losses(rows)
    assert "1 burn(s)" in text and "-0.057" in text and "not a gain" in text
    assert "suspect" in burn_count.negative_losses(pd.DataFrame({"delta_v_loss_mps": [-0.5]}))
    assert burn_count.negative_losses(pd.DataFrame({"delta_v_loss_mps": [0.1, 2.0]})) == ""


def test_missed_reading_counts_recoveries_per_delay_and_signs_penalties():
    def case(f, d, status, penalty, orbit="captured", period=24.0, reason=""):
        return {"contingency": "cut-off", "fraction": f, "delay_min": d, "late_min": 0.0,
                "status": status, "penalty_mps": penalty, "cutoff_orbit": orbit,
                "make_up_period_h": period, "reason": reason}
    far = "the spacecraft is 43,688 km from the Moon when the make-up burn can ignite"
    t = pd.DataFrame([case(0.5, 0, "recovered", 0.01, "escape"),
                      case(0.9, 0, "recovered", 0.03, period=20.0),
                      case(0.5, 720, "no recovery", None, "escape", None, far),
                      case(0.9, 720, "recovered", 0.5)])
    text = missed_thrust.reading(t, 24.0)
    assert "With a delay of 0 min every cut-off is recovered, at a penalty of at most " \
           "0.03 m/s (including 1 that left a hyperbola)." in text
    assert "With a delay of 720 min, 1 of 2 cut-offs is recovered (penalty +0.5 m/s); the " \
           "other has no verified recovery" in text
    assert f"Fraction 0.5, 720 min: no recovery, {far}." in text
    t2 = pd.concat([t, pd.DataFrame([case(0.75, 720, "recovered", 12.0),
                                     case(0.25, 720, "failed", None, "escape", None)])])
    assert "With a delay of 720 min, 2 of 4 cut-offs are recovered (penalty +0.5 to +12.0 " \
           "m/s); the others have no verified recovery" in missed_thrust.reading(t2, 24.0)
    assert "In 2 of 3 recoveries with a make-up orbit its period sits at the 24 h bound" in text
    # late ignitions are read apart, and not mixed into the cut-offs' map
    late = pd.DataFrame([dict(case(0, 0, "recovered", p), contingency="late ignition",
                              late_min=m) for m, p in ((1.0, 0.3), (5.0, 8.9), (10.0, 34.8))])
    both = pd.concat([t, late])
    assert len(missed_thrust.cut_offs(both)) == 4
    assert list(missed_thrust.late_ignitions(both).late_min) == [1.0, 5.0, 10.0]
    lt = missed_thrust.late_reading(missed_thrust.late_ignitions(both))
    assert "1 min: +0.30 m/s; 5 min: +8.90 m/s; 10 min: +34.80 m/s" in lt
    assert "The later, the dearer" in lt


def test_the_period_bound_verdict_follows_the_penalties_of_the_cases_at_the_bound():
    # was a fixed "a longer bound would lower the penalty" for every case at the bound,
    # four of which cost 0.00 m/s in the book's full run
    def rec(period, penalty):
        return {"make_up_period_h": period, "penalty_mps": penalty}
    free = pd.DataFrame([rec(24.0, 0.002), rec(24.0, 0.004), rec(20.0, 3.0)])
    text = missed_thrust.bound_verdict(free, 24.0)
    assert text.startswith("In 2 of 3 recoveries") and "none of them costs more" in text
    assert "would lower" not in text
    costly = free.assign(penalty_mps=[0.002, 5.0, 3.0])    # one case at the bound now costs
    text = missed_thrust.bound_verdict(costly, 24.0)
    assert "for the 1 of them with a penalty above 0.01 m/s a longer bound would lower" in text
    assert "the other 1 already cost nothing above the nominal" in text
    away = free.assign(make_up_period_h=[23.0, 22.0, 20.0])  # none at the bound
    assert "the bound shapes none" in missed_thrust.bound_verdict(away, 24.0)


def test_escapes_are_counted_per_fraction_of_the_burn_not_per_case():
    # a cut-off is a fraction; its delays are cases of the same cut-off (the page said
    # "8 of the 16 cut-offs" for 2 fractions)
    t = pd.DataFrame({"fraction": [0.25] * 4 + [0.5] * 4 + [0.9] * 4,
                      "cutoff_orbit": ["escape"] * 8 + ["captured"] * 4})
    text = missed_thrust.escape_sentence(t)
    assert text.startswith("A cut-off after 0.25 or 0.5 of the burn (2 of the 3 fractions "
                           "tried; 8 of the 12 cases")
    assert missed_thrust.escape_fractions(t) == [0.25, 0.5]
    none = t.assign(cutoff_orbit="captured")
    assert missed_thrust.escape_sentence(none).startswith("No cut-off tried")
