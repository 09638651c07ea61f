"""Whether an impulse reaches a circle asked at a later epoch (lunarcap.mission.reach).

* Kepler: every member of the circle is at its radius r all along, so the orbit before
  the burn clears it by exactly its perilune height above r (closed form; 1 mm), and a
  perilune below r gives a negative clearance (the impulse exists, off the perilune).
* The member found is the circle asked, checked independently: flown *forward* from where
  it was found to the circle's epoch, its elements are the circle's (p = r, f = g = 0,
  the inclination), and at that point it lies in the direction of the orbit before the
  burn.
* Forces: J2 about the frame's pole (the paper's model) leaves the paper's third burn's
  circle within 1 m of the perilune before it (its impulsive limit exists); LP165P 20x20
  puts it over 100 m below (measured 218 m): no impulse reaches it.

The orbit before the burn is the paper's second capture orbit at its nominal perilune
(the fixture ``third_burn``); the circle is asked one printed period later.
"""

import numpy as np
import pytest

from lunarcap.mission.reach import circle_clearance
from lunarcap.mission.targets import Target
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model, fit_for
from lunarcap.physics.elements import eccentricity, inclination, rv_from_mee
from lunarcap.physics.ephemeris import default_ephemeris
from lunarcap.physics.propagate import propagate

R_T = C.R_MOON + 100.0
CIRCLE = Target("circular", R_T, 90.0)
FIELD = {"gravity": "LP165P", "degree": 20, "third_bodies": ["earth", "sun"]}


def model(dynamics, third_burn) -> Model:
    t0, t_end, _ = third_burn
    return Model(dynamics, 0.0, 300.0,
                 fit_for(dynamics, default_ephemeris(), t0 - 3600.0, t_end + 3600.0))


def position(x) -> np.ndarray:
    return np.array(rv_from_mee(*x[:6], C.MU_MOON)[0], float)


@pytest.mark.parametrize("height_m", [-300.0, 0.0, 500.0])
def test_kepler_clearance_is_the_perilune_height(height_m, third_burn):
    t0, t_end, orbit = third_burn
    c = circle_clearance(model("two-body", third_burn), CIRCLE, t_end, t0, orbit(height_m),
                         600.0)
    assert c.gap_m == pytest.approx(height_m, abs=1e-3)
    assert c.at_offset_s == 0.0 and c.lowest_offset_s == 0.0
    # every member computed is at the circle's radius; the orbit rises away from perilune
    assert np.allclose(c.circle_radius_km, R_T, atol=1e-9)
    assert np.all(np.diff(c.pre_radius_km[c.offsets_s >= 0]) > 0)


@pytest.mark.slow
@pytest.mark.parametrize("dynamics", ["full", "field"])
def test_member_flown_forward_is_the_circle_through_the_orbit(dynamics, third_burn):
    t0, t_end, orbit = third_burn
    m = model(FIELD if dynamics == "field" else dynamics, third_burn)
    x = orbit()
    c = circle_clearance(m, CIRCLE, t_end, t0, x, 600.0)
    t_low = t0 + c.lowest_offset_s
    end = propagate(m, t_low, c.lowest_member, t_end).final
    assert end[0] == pytest.approx(R_T, abs=1e-7)                        # p = r, 0.1 mm
    assert eccentricity(end[1], end[2]) < 1e-10
    assert float(np.degrees(inclination(end[3], end[4]))) == pytest.approx(90.0, abs=1e-8)
    # it passes where the orbit before the burn points at that epoch
    pre = propagate(m, t0, x, t_low).final if c.lowest_offset_s else x
    u, w = position(c.lowest_member), position(pre)
    cos = u @ w / np.linalg.norm(u) / np.linalg.norm(w)
    assert np.degrees(np.arccos(np.clip(cos, -1, 1))) < 1e-6
    # the clearance there is the difference of the two distances
    j = int(np.flatnonzero(c.offsets_s == c.lowest_offset_s)[0])
    assert (np.linalg.norm(w) - np.linalg.norm(u)) * 1e3 == pytest.approx(
        (c.pre_radius_km[j] - c.circle_radius_km[j]) * 1e3, abs=1e-6)


@pytest.mark.slow
def test_field_puts_the_circle_below_the_perilune_j2_does_not(third_burn):
    t0, t_end, orbit = third_burn
    j2 = circle_clearance(model("full", third_burn), CIRCLE, t_end, t0, orbit(), 600.0)
    field = circle_clearance(model(FIELD, third_burn), CIRCLE, t_end, t0, orbit(), 600.0)
    assert abs(j2.gap_m) < 1.0
    assert field.gap_m > 100.0
    assert abs(field.at_offset_s) <= 30.0
