"""A plan's arrival given as a B-plane target (issue 26): the perilune it defines.

The paper's arrival perilune -> its B-plane (in M-MME2000 and in ICRF axes) -> a plan with
that B-plane arrival -> the plan's arrival perilune: the same state within 1 m and 1 mm/s,
and the plan writes the B-plane back as given. No optimisation.

The B-plane's reference plane is the plan's ``arrival.bplane_reference`` (issue 37):
EME2000 by default, as GMAT's BdotT/BdotR and trajectory teams give it. The cases in
M-MME2000 axes were written when the T axis lay in the frame's own equator (the lunar
equator): they say so now (``bplane_reference: lunar-equator``) and keep their numbers.
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
    """The B-plane target of an arrival perilune about the pole of ``frame`` (its z)."""
    r, v = arr.r_km, arr.v_kmps
    if frame == "ICRF":
        r, v = (icrf_from_mme(q, DEFAULT_LUNAR_POLE) for q in (r, v))
    b = bplane_from_rv(r, v, C.MU_MOON)
    out = {"epoch": "2017-02-20 03:41:26 TDB", "frame": frame, "b_r_km": b.b_r_km,
           "b_t_km": b.b_t_km, "v_inf_kmps": b.v_inf_kmps,
           "approach_dir": [float(q) for q in b.s_hat], "mass_kg": arr.mass_kg}
    if frame == "M-MME2000":   # the frame's pole: the lunar equator, said (not the default)
        out["bplane_reference"] = "lunar-equator"
    return out


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
                             ("b_r_km", 0.0, "arrival.b_r_km"),
                             ("bplane_reference", "ecliptic", "arrival.bplane_reference")):
        bad = dict(good, **{key: value})
        if key == "b_r_km":
            bad["b_t_km"] = 0.0
        with pytest.raises(PlanError, match=said.replace(".", r"\.")):
            _plan(bad)


def _perilune(plan):
    return (np.array(q) for q in rv_from_mee(*plan.arrival.perilune_mee, C.MU_MOON))


def test_the_readme_b_plane_target_is_the_papers_arrival_perilune():
    # the README's example (EME2000, the default, said) is the paper's arrival perilune:
    # 100 km, polar about the lunar pole of J2000, over the north, within 1 m and 1 mm/s
    import re
    from pathlib import Path

    import yaml

    text = (Path(__file__).resolve().parents[2] / "README.md").read_text()
    block = next(b for b in re.findall(r"```yaml\n(.*?)```", text, re.S) if "b_t_km" in b)
    arrival = yaml.safe_load(block)["arrival"]
    assert arrival["bplane_reference"] == "EME2000"
    p = _plan(arrival)
    paper = load_plan("song2011-150N").with_dynamics("two-body").arrival.build()
    r, v = _perilune(p)
    assert np.linalg.norm(r - paper.r_km) < 1e-3 and np.linalg.norm(v - paper.v_kmps) < 1e-6
    assert p.arrival.inclination_deg == pytest.approx(90.0, abs=1e-6)


@pytest.mark.parametrize("inc, hemi, approach", [(90.0, "north", [-0.98, 0.17, 0.04]),
                                                 (35.0, "south", [0.3, -0.9, 0.2]),
                                                 (150.0, "north", [0.6, 0.7, -0.3])])
def test_the_reference_plane_turns_the_b_plane_about_the_asymptote(inc, hemi, approach):
    # the same perilune as a target about EME2000 and about the lunar equator: (B.T, B.R)
    # turned by the angle from the one T axis to the other about S, both T axes built here
    # from the asymptote and the poles (T = S x k / |S x k|); the numbers of one read about
    # the other are another perilune, kilometres away
    from lunarcap.physics.frames import mme_from_icrf

    arr = arrival_state(inclination_deg=inc, hemisphere=hemi, v_inf_kmps=0.918,
                        approach=approach)
    lunar = _bplane_arrival(arr, "M-MME2000")
    s = np.array(lunar["approach_dir"])
    t_l = np.cross(s, [0.0, 0.0, 1.0])
    t_e = np.cross(s, mme_from_icrf([0.0, 0.0, 1.0], DEFAULT_LUNAR_POLE))
    t_l, t_e = t_l / np.linalg.norm(t_l), t_e / np.linalg.norm(t_e)
    ang = np.arctan2(s @ np.cross(t_l, t_e), t_l @ t_e)       # from T_lunar to T_EME2000
    bt, br = lunar["b_t_km"], lunar["b_r_km"]
    eme = dict(lunar, bplane_reference="EME2000",
               b_t_km=bt * np.cos(ang) + br * np.sin(ang),
               b_r_km=-bt * np.sin(ang) + br * np.cos(ang))
    for given in (lunar, eme):
        r, v = _perilune(_plan(given))
        assert np.linalg.norm(r - arr.r_km) < 1e-3 and np.linalg.norm(v - arr.v_kmps) < 1e-6
    misread = dict(lunar, bplane_reference="EME2000")
    r, _ = _perilune(_plan(misread))
    assert np.linalg.norm(r - arr.r_km) > 100.0
    assert abs(np.degrees(ang)) > 5.0


def test_the_plan_writes_its_reference_plane_back():
    # a B-plane arrival always says its reference; any other arrival only when it is not
    # the default (so a plan written before keeps its file and its cache key)
    p = _plan(_bplane_arrival(arrival_state(), "ICRF"))
    assert p.to_dict()["arrival"]["bplane_reference"] == "EME2000"
    d = load_plan("song2011-150N").to_dict()
    assert "bplane_reference" not in d["arrival"]
    d["arrival"]["bplane_reference"] = "lunar-equator"
    again = CapturePlan.from_dict(d)
    assert again.arrival.bplane_reference == "lunar-equator"
    assert again.to_dict()["arrival"]["bplane_reference"] == "lunar-equator"
