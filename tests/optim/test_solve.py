"""The second try of a failed solve: a wider free-ignition window (lunarcap.optim.solve).

No solve here: :func:`lunarcap.optim.solve.widened` on problems of the paper's capture,
built as :func:`lunarcap.optim.problem.burn_problem` builds them.
"""

import math
from dataclasses import replace

import numpy as np
import pytest

from lunarcap.capture.chain import arrival_for
from lunarcap.mission.plan import CapturePlan, load_plan
from lunarcap.optim.problem import burn_problem
from lunarcap.optim.solve import widened
from lunarcap.physics import constants as C


def _first_burn(formulation: str, bounds_min=(-30.0, 30.0)):
    """Burn 1 of the paper's 150 N capture with a free ignition in ``bounds_min``."""
    d = load_plan("song2011-150N").to_dict()
    d["formulation"] = formulation
    d["burns"][0].update(start_min="free", start_bounds_min=list(bounds_min))
    plan = CapturePlan.from_dict(d)
    arrival = arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole)
    return burn_problem(plan, 0, arrival.state, plan.ephemeris_model())


def test_a_failed_window_is_widened_three_times_earlier_and_twice_later():
    """An ellipse as asked whose free ignition failed is tried once more in a wider window.

    IPOPT's path depends on the bounds: a generated 149 deg capture whose next perilune
    the Earth lowers by 19 km stalled at the -30 min bound and failed on every mesh; in
    -90 .. +60 min it solved, igniting at -6.4 min. The window grows to 120 min at most
    (from a hyperbola, here), and to 0.4 of the orbit the burn starts on from an ellipse.
    """
    prob = _first_burn("orbit")
    assert prob.target.free_epoch and prob.free_start
    wider = widened(prob)
    assert wider.start_bounds_min == (-90.0, 60.0)
    assert widened(wider).start_bounds_min == (-120.0, 120.0)
    assert widened(widened(wider)) is None                  # nothing wider to try
    # from the paper's 3.525 h orbit: 0.4 of its period, 84.6 min, bounds the window
    a = (C.MU_MOON * (3.525 * 3600.0 / (2 * math.pi)) ** 2) ** (1 / 3)
    e = 1.0 - (C.R_MOON + 100.0) / a
    on_ellipse = replace(prob, x_ref=np.array([a * (1 - e * e), e, 0, 1, 0, 0, 500.0]),
                         start_bounds_min=(-40.0, 40.0))
    lo, hi = widened(on_ellipse).start_bounds_min
    assert lo == pytest.approx(-0.4 * 3.525 * 60.0, rel=1e-12) and hi == 80.0


def test_the_paper_formulation_is_not_widened():
    """The paper's Eq. (17) targets hold at a fixed epoch: no second window."""
    assert widened(_first_burn("song2011")) is None
