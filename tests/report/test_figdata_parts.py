"""figdata.flown_perilune on a hand-made flight (no solve)."""

import numpy as np
import pytest

from lunarcap.report import figdata


def test_flown_perilune_is_the_least_radius_within_the_window():
    t = np.arange(0.0, 1000.0, 10.0)
    radius = 2000.0 + (t - 400.0) ** 2 / 100.0          # least at t = 400 s
    radius[5] = 1000.0                                   # lower, but outside the window
    angle = np.radians(t / 10.0)
    xy = np.vstack([np.cos(angle), np.sin(angle)])
    r = np.vstack([radius * xy, np.zeros_like(t)])
    t_p, r_p, ang = figdata.flown_perilune(t, r, xy, t_nominal_s=450.0, window_s=200.0)
    assert t_p == 400.0 and r_p == pytest.approx(2000.0)
    assert ang == pytest.approx(40.0)
