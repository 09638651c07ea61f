"""A plan's arrival given as a B-plane target (issue 26): the perilune it defines.

The paper's arrival perilune -> its B-plane (in M-MME2000 and in ICRF axes) -> a plan with
that B-plane arrival -> the plan's arrival perilune: the same state within 1 m and 1 mm/s,
and the plan writes the B-plane back as given. No optimisation.
"""

import numpy as np
import pytest

from lunarcap.mission.arrival import arrival_state
from lunarcap.mission.plan import CapturePlan, PlanError, load_plan
from lunarcap.physics import constants as C
from lunarcap.physics.bplane import bplane_from_rv
from lunarcap.physics.elements import rv_from_mee
from lunarcap.physics.frames import DEFAULT_LUNAR_POLE, icrf_from_mme


def _plan(arrival):
    d = load_plan("song2011-150N").to_dict()
    d["arrival"], d["dynamics"] = arrival, "two-body"
    return CapturePlan.from_dict(d)


def _bplane_arrival(arr, frame):
    r, v = arr.r_km, arr.v_kmps
    if frame == "ICRF":
        r, v = (icrf_from_mme(q, DEFAULT_LUNAR_POLE) for q in (r, v))
    b = bplane_from_rv(r, v, C.MU_MOON)
    return {"epoch": "2017-02-20 03:41:26 TDB", "frame": frame, "b_r_km": b.b_r_km,
            "b_t_km": b.b_t_km, "v_inf_kmps": b.v_inf_kmps,
            "approach_dir": [float(q) for q in b.s_hat], "mass_kg": arr.mass_kg}


@pytest.mark.parametrize("frame", ["M-MME2000", "ICRF"])
@pytest.mark.parametrize("inc, hemi", [(90.0, "north"), (90.0, "south"), (35.0, "north"),
                                       (150.0, "south")])
def test_a_b_plane_arrival_is_the_perilune_it_was_taken_from(frame, inc, hemi):
    arr = arrival_state(inclination_deg=inc, hemisphere=hemi, v_inf_kmps=0.918,
                        approach=[-0.98, 0.17, 0.04])
    p = _plan(_bplane_arrival(arr, frame))
    a = p.arrival
    r, v = (np.array(q) for q in rv_from_mee(*a.perilune_mee, C.MU_MOON))
    assert np.linalg.norm(r - arr.r_km) < 1e-3 and np.linalg.norm(v - arr.v_kmps) < 1e-6
    assert a.hemisphere == hemi
    assert a.inclination_deg == pytest.approx(inc, abs=1e-9)
    assert a.perilune_altitude_km == pytest.approx(100.0, abs=1e-6)
    # the plan writes the arrival back as given, and reads it again to the same perilune
    again = CapturePlan.from_dict(p.to_dict())
    assert again.to_dict()["arrival"] == p.to_dict()["arrival"]
    np.testing.assert_array_equal(again.arrival.perilune_mee, a.perilune_mee)


def test_a_b_plane_arrival_refuses_bad_fields_naming_them():
    good = _bplane_arrival(arrival_state(), "M-MME2000")
    for key, value, said in (("frame", "EME2000", "arrival.frame"),
                             ("approach_dir", [0, 0], "arrival.approach_dir"),
                             ("v_inf_kmps", -1.0, "arrival.v_inf_kmps"),
                             ("b_r_km", 0.0, "arrival.b_r_km")):
        bad = dict(good, **{key: value})
        if key == "b_r_km":
            bad["b_t_km"] = 0.0
        with pytest.raises(PlanError, match=said.replace(".", r"\.")):
            _plan(bad)
