"""A plan's arrival given as a state or an OPM (issue 18): derivation and refusals.

No optimisation: only plan construction (the perilune derived by propagation).
"""

import numpy as np
import pytest

from lunarcap.exchange.ccsds import StateVector, write_opm
from lunarcap.mission.arrival import arrival_state
from lunarcap.mission.plan import CapturePlan, PlanError, load_plan
from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mee_from_rv, rv_from_mee
from lunarcap.physics.ephemeris import ChebyshevFit, default_ephemeris
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.frames import icrf_from_mme
from lunarcap.physics.propagate import propagate

T_PERI = seconds_from_calendar(paper_scenario().epoch_tdb)


def _approach(dynamics="two-body", hours=2.0):
    """The paper's arrival hyperbola ``hours`` before its perilune, ICRF (km, km/s)."""
    arr = arrival_state()
    fit = ChebyshevFit.fit(default_ephemeris(), T_PERI - 6 * 3600, T_PERI + 3600) \
        if dynamics == "full" else None
    x = np.concatenate([arr.mee, [arr.mass_kg]])
    t0 = T_PERI - hours * 3600.0
    x0 = propagate(Model(dynamics, 0.0, 300.0, fit), T_PERI, x, t0).final
    r, v = (icrf_from_mme(np.array(q)) for q in rv_from_mee(*x0[:6], C.MU_MOON))
    return t0, r, v


def _plan(arrival, dynamics="two-body"):
    d = load_plan("song2011-150N").to_dict()
    d["arrival"], d["dynamics"] = arrival, dynamics
    return CapturePlan.from_dict(d)


def _state(t, r, v, scale="TDB", frame="ICRF"):
    return {"epoch": calendar_from_seconds(t, 6 if scale == "TDB" else 9, scale=scale),
            "frame": frame, "position_km": [float(q) for q in r],
            "velocity_kmps": [float(q) for q in v], "mass_kg": 524.895}


@pytest.mark.parametrize("dynamics", ["two-body", "full"])
def test_state_arrival_finds_the_paper_perilune(dynamics):
    # the reconstructed hyperbola 2 h before its perilune, given as a state: the derived
    # perilune is the paper's (epoch within 1 ms, 100 km, 90 deg, north)
    t0, r, v = _approach(dynamics)
    plan = _plan(_state(t0, r, v), dynamics)
    a = plan.arrival
    assert plan.nominal_perilunes_s[0] == pytest.approx(T_PERI, abs=1e-3)
    assert a.perilune_altitude_km == pytest.approx(100.0, abs=1e-5)
    assert a.inclination_deg == pytest.approx(90.0, abs=1e-7)
    assert a.hemisphere == "north"
    assert a.v_inf_kmps == pytest.approx(load_plan("song2011-150N").arrival.v_inf_kmps,
                                         rel=1e-3 if dynamics == "full" else 1e-9)
    assert plan.to_dict()["arrival"]["position_km"] == [float(q) for q in r]


def test_utc_and_tdb_epochs_of_the_same_instant_give_the_same_plan():
    t0, r, v = _approach()
    tdb, utc = _plan(_state(t0, r, v)), _plan(_state(t0, r, v, "UTC"))
    assert utc.arrival.state.epoch.endswith("UTC") and tdb.arrival.state.epoch.endswith("TDB")
    assert utc.nominal_perilunes_s == tdb.nominal_perilunes_s
    assert utc.arrival.perilune_mee == tdb.arrival.perilune_mee


def test_opm_arrival_equals_the_state(tmp_path):
    t0, r, v = _approach()
    write_opm(tmp_path / "approach.opm", StateVector(t0, tuple(r), tuple(v), "ICRF", 524.895),
              "probe", "-310001", "UTC")
    plan = load_plan_from(tmp_path, {"opm": "approach.opm"})
    assert plan.nominal_perilunes_s[0] == pytest.approx(T_PERI, abs=1e-3)
    assert plan.arrival.mass_kg == 524.895
    assert plan.to_dict()["arrival"] == {"opm": "approach.opm", "mass_kg": 524.895}


def load_plan_from(tmp_path, arrival):
    import yaml

    d = load_plan("song2011-150N").to_dict()
    d["arrival"], d["dynamics"] = arrival, "two-body"
    path = tmp_path / "p.yaml"
    path.write_text(yaml.safe_dump(d))
    return load_plan(path)


def _refusal(arrival, dynamics="two-body"):
    with pytest.raises(PlanError) as exc:
        _plan(arrival, dynamics)
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


def test_bad_state_arrivals_name_their_cause(tmp_path):
    t0, r, v = _approach()
    ok = _state(t0, r, v)
    # moving away: the same state with its velocity reversed
    assert "not approaching the Moon: it moves away" in _refusal(ok | {
        "velocity_kmps": [-q for q in ok["velocity_kmps"]]})
    # bound: a third of the speed
    assert "already bound to the Moon" in _refusal(ok | {
        "velocity_kmps": [q / 3 for q in ok["velocity_kmps"]]})
    # on a collision course: aimed at the centre
    rn = np.array(ok["position_km"])
    aimed = list(-rn / np.linalg.norm(rn) * np.linalg.norm(v))
    assert "perilune lies below the lunar surface" in _refusal(ok | {"velocity_kmps": aimed})
    # outside the ephemeris (DE405 ends in 2200)
    assert "outside the ephemeris" in _refusal(ok | {"epoch": "2250-01-01 00:00:00 UTC"})
    # inside the Moon
    assert "inside the Moon" in _refusal(ok | {"position_km": [1000.0, 0.0, 0.0]})
    # an epoch without its scale, a frame or a v_inf key that does not belong
    assert "names no time scale" in _refusal(ok | {"epoch": "2017-02-20T01:41:26"})
    assert "arrival.frame" in _refusal(ok | {"frame": "EME2000"})
    assert "belongs to an arrival given by its perilune" in _refusal(ok | {"v_inf_kmps": 0.9})
    with pytest.raises(PlanError, match="arrival.opm: OPM missing.opm: cannot read it"):
        load_plan_from(tmp_path, {"opm": "missing.opm"})


def test_derived_state_matches_reconstruction_in_mee():
    # the arrival state of a state arrival is the propagated perilune, not a reconstruction
    t0, r, v = _approach()
    plan = _plan(_state(t0, r, v))
    arr = plan.arrival.build()
    ref = arrival_state()
    assert np.linalg.norm(arr.r_km - ref.r_km) < 1e-3   # km
    assert np.allclose(mee_from_rv(arr.r_km, arr.v_kmps, C.MU_MOON), ref.mee, atol=1e-9)


def test_low_inclination_state_arrival_is_judged_by_its_own_asymptote():
    # A 1 deg orbit arriving along the lunar equator: a v_inf arrival on this date could
    # not have it (its anti-lunar-velocity asymptote is 2.33 deg from the equator), but the
    # state's own asymptote lies in its plane, so the plan must load with it.
    arr = arrival_state(inclination_deg=1.0, approach=[1.0, 0.0, 0.0])
    x = np.concatenate([arr.mee, [arr.mass_kg]])
    t0 = T_PERI - 2 * 3600.0
    x0 = propagate(Model("two-body", 0.0, 300.0), T_PERI, x, t0).final
    r, v = (icrf_from_mme(np.array(q)) for q in rv_from_mee(*x0[:6], C.MU_MOON))
    plan = _plan(_state(t0, r, v))
    assert plan.arrival.inclination_deg == pytest.approx(1.0, abs=1e-7)
    assert np.allclose(plan.arrival.approach_dir, [1.0, 0.0, 0.0], atol=1e-9)
