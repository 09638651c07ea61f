"""A solved capture flown open loop (lunarcap.capture.openloop), against what must hold.

* Flown in its own forces, steering held in RTN, the open loop is the design's verified
  flight: every ignition, cut-off and the end within 1 m and 1 mm/s (one continuous flight
  against the chain's burn-by-burn flights). Held in 10 s inertial segments, within the
  segments' own error (a few metres at the end of the 18 h capture).
* Another g0: each burn's propellant is T t / (g0 Isp), so the propellant of the whole
  capture scales as g0 / g0' exactly (closed form, 1e-9).
* Another lunar GM keeps the start's position and velocity (GMAT is handed a Cartesian
  state): at the first ignition, flown from there, nothing differs.
* A lunar field moves the end by kilometres (the field must matter).
"""

import pytest

from lunarcap.capture.chain import plan_result
from lunarcap.capture.openloop import CUTOFF, END, IGNITION, apart, fly_open_loop
from lunarcap.mission.plan import load_plan
from lunarcap.physics import constants as C

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def design():
    return plan_result(load_plan("song2011-150N"), impulsive=False)


def test_open_loop_in_its_own_forces_is_the_design(design):
    ol = fly_open_loop(design, hold="rtn")
    assert [(e["burn"], e["event"]) for e in ol.events] == \
        [(1, IGNITION), (1, CUTOFF), (2, IGNITION), (2, CUTOFF), (3, IGNITION), (3, CUTOFF),
         (3, END)]
    for e in ol.events:
        assert e["position_diff_m"] < 1.0 and e["velocity_diff_mmps"] < 1.0, e
        assert abs(e["mass_diff_kg"]) < 1e-6
    assert ol.final["rp_alt_km"] == pytest.approx(ol.final["design_rp_alt_km"], abs=1e-3)
    seg = fly_open_loop(design, hold="inertial")
    assert 1e-3 < seg.final["miss_km"] < 0.01   # the 10 s segments' error, metres


def test_another_g0_scales_the_propellant_exactly(design):
    ref = fly_open_loop(design, hold="rtn")
    g0 = 9.81
    other = fly_open_loop(design, hold="rtn", g0_mps2=g0)
    m0 = ref.states[(1, IGNITION)].mass_kg
    spent = [m0 - fl.states[(3, CUTOFF)].mass_kg for fl in (ref, other)]
    assert spent[1] / spent[0] == pytest.approx(C.G0_MPS2 / g0, rel=1e-9)
    assert apart(other, ref)["position_diff_m"] > 1e3   # and it matters: kilometres


def test_another_gm_keeps_the_start_state(design):
    other = fly_open_loop(design, hold="rtn", mu=4902.8005821478)
    first = other.events[0]
    assert (first["burn"], first["event"]) == (1, IGNITION)
    assert first["position_diff_m"] < 1e-6 and first["velocity_diff_mmps"] < 1e-6
    assert other.final["miss_km"] > 0.005   # a 1.2e-7 GM moves the end by metres


def test_a_field_moves_the_capture(design):
    field = {"gravity": "LP165P", "degree": 2, "order": 2, "third_bodies": ["earth", "sun"]}
    ol = fly_open_loop(design, field, hold="rtn")
    assert ol.dynamics.startswith("LP165P 2x2")
    assert ol.final["miss_km"] > 1.0
    with pytest.raises(Exception, match="hold"):
        fly_open_loop(design, hold="sideways")
