"""The missed-thrust page reads a recovery whose make-up waited for a perilune (why it
waited is the row's reason), as it reads a case without recovery."""

import pandas as pd

from lunarcap.report.pages import missed_thrust


def test_a_make_up_that_waited_for_a_perilune_is_read_with_its_reason():
    """The book's 0.9 / 720 min case, recovered at the next perilune since issue 37 (it was
    "no recovery" because the window's bound decided it): the reading says where the
    make-up was made and why, from the row's reason; a recovery in the window with no
    reason adds nothing. Dropping the page's sentence fails it."""
    waited = ("make-up burn at the next perilune (22.4 h after the fault): in the window, "
              "decided by --max-period-h (24 h): the spacecraft is 22,372 km from the Moon")
    rows = [{"contingency": "cut-off", "fraction": f, "delay_min": d, "late_min": 0.0,
             "status": "recovered", "penalty_mps": p, "cutoff_orbit": "captured",
             "make_up_period_h": 24.0, "reason": why}
            for f, d, p, why in ((0.9, 0.0, 0.0, ""), (0.9, 720.0, 35.0, waited))]
    text = missed_thrust.reading(pd.DataFrame(rows), 24.0)
    assert ("Fraction 0.9, 720 min: recovered, the make-up burn at the next perilune "
            "(22.4 h after the fault): in the window, decided by --max-period-h (24 h)") in text
    assert "Fraction 0.9, 0 min" not in text
