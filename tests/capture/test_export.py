"""Round trips of an exported plan (issue 18): the paper's 150 N capture in two-body dynamics.

The plan is solved once (cached); its export is read back by a third-party CCSDS parser,
by SPICE, by lunarcap's own state arrival, and flown from its attitude and maneuver files.
"""

import numpy as np
import pytest

from lunarcap.capture.chain import plan_result
from lunarcap.capture.export import (
    BURN_STEP_S,
    COAST_STEP_S,
    export_plan,
    flight_arcs,
    segment_of,
)
from lunarcap.exchange import burn_files as xburns
from lunarcap.exchange import ccsds, spk
from lunarcap.mission.plan import CapturePlan, load_plan
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mee_from_rv, orbit_summary, rv_from_mee
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.frames import icrf_from_mme, mme_from_icrf
from lunarcap.physics.propagate import propagate

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def solved():
    plan = load_plan("song2011-150N").with_dynamics("two-body")
    return plan_result(plan, impulsive=False)


@pytest.fixture(scope="module")
def exported(solved, tmp_path_factory):
    out = tmp_path_factory.mktemp("export")
    return export_plan(solved, out), solved


def _oem_states(path):
    return ccsds.read_oem(path)


def test_export_writes_its_files_and_oem_interpolates_within_1_m(exported):
    ex, res = exported
    assert set(ex.files) == {"oem", "spk", "attitude", "maneuvers", "gmat_script",
                             "gmat_gravity", "gmat_moon"}
    assert all(ex.sizes_bytes[k] > 100 for k in ex.files)
    names = [s["name"] for s in ex.segments]
    assert names == ["approach", "burn 1", "coast 1", "burn 2", "coast 2", "burn 3",
                     "final orbit"]
    # the file's own interpolation (Lagrange 7), checked at every mid-step of every segment
    assert ex.max_interpolation_error_m < 1.0
    # and independently at random epochs against the flown arcs
    arcs = flight_arcs([b.solution for b in res.burns])
    rng = np.random.default_rng(18)
    for seg, arc in zip(_oem_states(ex.files["oem"]), arcs):
        tq = np.sort(rng.uniform(seg.t_s[0], seg.t_s[-1], 5))
        guess = ccsds.lagrange_interpolate(seg.t_s, seg.r_km, tq)
        r, _ = rv_from_mee(*arc.states(tq)[:6], C.MU_MOON)
        truth = icrf_from_mme(np.array(r), res.plan.lunar_pole)
        assert np.max(np.linalg.norm(guess - truth, axis=0)) * 1e3 < 1.0, arc.name


def test_exported_arcs_are_the_verified_flights(exported):
    # the arcs re-fly each burn and coast from the flights' own states with the steering
    # the verification flew: at the flights' knots they agree to the integrator's noise
    _, res = exported
    sols = [b.solution for b in res.burns]
    arcs = {a.name: a for a in flight_arcs(sols)}
    worst = 0.0
    for i, s in enumerate(sols, 1):
        coast = arcs[f"coast {i}" if i < len(sols) else "final orbit"]
        for arc, tr in ((arcs[f"burn {i}"], s.flight.burn), (coast, s.flight.coast)):
            lo, hi = arc.span
            sel = (tr.t >= lo) & (tr.t <= hi)
            mine = np.array(rv_from_mee(*arc.states(tr.t[sel])[:6], C.MU_MOON)[0])
            theirs = np.array(rv_from_mee(*tr.x[:6, sel], C.MU_MOON)[0])
            worst = max(worst, np.max(np.linalg.norm(mine - theirs, axis=0)))
    assert worst * 1e3 < 0.01   # m


def test_oem_read_by_third_party_parser_equals_our_states(exported):
    from oem import OrbitEphemerisMessage

    ex, res = exported
    theirs = OrbitEphemerisMessage.open(ex.files["oem"])
    arcs = flight_arcs([b.solution for b in res.burns])
    assert len(theirs.segments) == len(arcs)
    worst = np.zeros(3)
    for seg, arc in zip(theirs.segments, arcs):
        assert (seg.metadata["CENTER_NAME"], seg.metadata["REF_FRAME"],
                seg.metadata["TIME_SYSTEM"]) == ("MOON", "ICRF", "TDB")
        ours, _ = segment_of(arc, res.plan.lunar_pole,
                             BURN_STEP_S if arc.thrust_N else COAST_STEP_S)
        states = list(seg.states)
        t = np.array([(s.epoch.tdb.jd1 - 2451545.0 + s.epoch.tdb.jd2) * 86400.0
                      for s in states])
        r = np.array([s.position for s in states]).T
        v = np.array([s.velocity for s in states]).T
        worst = np.maximum(worst, [np.max(np.abs(t - ours.t_s)),
                                   np.max(np.abs(r - ours.r_km)),
                                   np.max(np.abs(v - ours.v_kmps))])
    print("OEM via oem: epochs, positions, velocities off by at most", worst)
    # what was written: epochs to 1 us, km to 6 decimals, km/s to 9 (plus float noise)
    assert worst[0] < 1e-6 and worst[1] < 0.6e-6 and worst[2] < 0.6e-9


def test_spk_read_through_spice_equals_oem_within_1_m(exported):
    ex, _ = exported
    assert spk.coverage(ex.files["spk"])[0][0] == pytest.approx(
        _oem_states(ex.files["oem"])[0].t_s[0], abs=1e-6)
    worst = 0.0
    for seg in _oem_states(ex.files["oem"]):
        # at the states and half-way between them (SPICE's own Lagrange interpolation
        # against the OEM's), inside the segment so no neighbour takes over
        mid = 0.5 * (seg.t_s[1:] + seg.t_s[:-1])
        x_spk = spk.read_spk(ex.files["spk"], np.concatenate([seg.t_s[1:-1], mid]))
        x_oem = np.hstack([seg.states[:, 1:-1],
                           np.vstack([ccsds.lagrange_interpolate(seg.t_s, seg.r_km, mid),
                                      ccsds.lagrange_interpolate(seg.t_s, seg.v_kmps, mid)])])
        worst = max(worst, np.max(np.linalg.norm(x_spk[:3] - x_oem[:3], axis=0)) * 1e3)
    print("SPK via SPICE against the OEM: at most", worst, "m")
    assert worst < 1.0


def _daf_comments(path) -> list:
    """The comment lines of a DAF file (an SPK), as SPICE reads them."""
    import spiceypy as sp

    handle = sp.dafopr(str(path))
    try:
        return list(sp.dafec(handle, 50, 100)[1])
    finally:
        sp.dafcls(handle)


def test_every_exported_file_states_the_moons_gm_and_radius(exported, tmp_path):
    # issue 24: a tool with the IAU radius 1,737.4 km reads every altitude 0.8 km off;
    # each file says which GM and radius lunarcap's numbers use, at its head
    import pandas as pd

    ex, res = exported
    first = "Moon GM 4902.800 km^3/s^2, mean radius 1738.2 km (Song et al. 2011, Sec. 3.1)."
    assert (C.MU_MOON, C.R_MOON) == (4902.800, 1738.2)   # what the dynamics use
    lines = ccsds.reference_comments()
    assert lines[0] == first and "1737.4 km" in lines[1] and "0.8 km higher" in lines[2]
    oem = ex.files["oem"].read_text().splitlines()
    assert oem[:4] == ["CCSDS_OEM_VERS = 2.0", *[f"COMMENT {c}" for c in lines]]
    created = next(i for i, ln in enumerate(oem) if ln.startswith("CREATION_DATE = "))
    assert all(ln.startswith("COMMENT ") for ln in oem[1:created])   # where CCSDS puts them
    assert _daf_comments(ex.files["spk"])[:3] == lines
    for kind in ("attitude", "maneuvers"):
        text = ex.files[kind].read_text().splitlines()
        assert text[:3] == [f"# {c}" for c in lines], kind
        assert list(pd.read_csv(ex.files[kind], comment="#").columns) == \
            list(xburns.ATTITUDE_COLUMNS if kind == "attitude" else xburns.MANEUVER_COLUMNS)
    assert ex.reference == lines
    # the GMAT script, its gravity file (GMAT skips lines starting with C) and Moon kernel
    script = ex.files["gmat_script"].read_text().splitlines()
    assert script[:3] == [f"% {c}" for c in lines]
    cof = ex.files["gmat_gravity"].read_text().splitlines()
    assert cof[1:4] == [f"C {c}" for c in lines]
    assert _daf_comments(ex.files["gmat_moon"])[:3] == lines
    state = ccsds.StateVector(0.0, (1838.2, 0.0, 0.0), (0.0, 1.6, 0.0))
    opm = ccsds.write_opm(tmp_path / "x.opm", state, "probe", "-310001")
    assert opm.read_text().splitlines()[1] == f"COMMENT {first}"
    assert ccsds.read_opm(opm).r_km == state.r_km
    # and it is the radius behind the altitudes: the final orbit's 100 km is |r| - 1738.2 km
    final = _oem_states(ex.files["oem"])[-1]
    alt = np.linalg.norm(final.r_km, axis=0) - C.R_MOON
    assert alt.min() == pytest.approx(res.plan.arrival.perilune_altitude_km, abs=0.01)


def _arrival_plan(plan, t_s, r, v, m, epoch_text):
    d = plan.to_dict()
    d["name"] = "from-oem"
    d["arrival"] = {"epoch": epoch_text, "frame": "ICRF", "position_km": [float(q) for q in r],
                    "velocity_kmps": [float(q) for q in v], "mass_kg": float(m)}
    return CapturePlan.from_dict(d)


def test_state_from_oem_as_arrival_reproduces_the_burns_and_utc_equals_tdb(exported):
    ex, res = exported
    approach = _oem_states(ex.files["oem"])[0]
    man = xburns.read_maneuvers(ex.files["maneuvers"])
    t, r, v = approach.t_s[0], approach.r_km[:, 0], approach.v_kmps[:, 0]
    tdb = _arrival_plan(res.plan, t, r, v, man[0]["m_start_kg"], calendar_from_seconds(t, 6))
    utc = _arrival_plan(res.plan, t, r, v, man[0]["m_start_kg"],
                        calendar_from_seconds(t, 9, scale="UTC"))
    assert utc.arrival.state.epoch.endswith("UTC")
    # the perilune derived from the state is the plan's own (epoch to 1 ms, altitude 1 mm)
    assert tdb.nominal_perilunes_s[0] == pytest.approx(res.plan.nominal_perilunes_s[0],
                                                       abs=1e-3)
    assert tdb.arrival.perilune_altitude_km == pytest.approx(100.0, abs=1e-6)
    assert tdb.arrival.inclination_deg == pytest.approx(90.0, abs=1e-7)
    again = plan_result(tdb, impulsive=False)
    dv0 = [b.solution.delta_v_mps for b in res.burns]
    dv1 = [b.solution.delta_v_mps for b in again.burns]
    print("state arrival: perilune epoch off by",
          tdb.nominal_perilunes_s[0] - res.plan.nominal_perilunes_s[0], "s; delta-Vs off by",
          np.subtract(dv1, dv0), "m/s")
    assert np.max(np.abs(np.subtract(dv1, dv0))) < 0.05
    # the same instant written in UTC: the same numbers, bit for bit
    assert utc.nominal_perilunes_s == tdb.nominal_perilunes_s
    same = plan_result(utc, impulsive=False)
    assert [b.solution.delta_v_mps for b in same.burns] == dv1


def test_attitude_and_maneuver_files_fly_to_the_final_orbit(exported):
    ex, res = exported
    pole = res.plan.lunar_pole
    att = xburns.read_attitude(ex.files["attitude"])
    man = xburns.read_maneuvers(ex.files["maneuvers"])
    segs = _oem_states(ex.files["oem"])
    assert len(man) == len(att) == res.plan.n_burns
    # the state at the first ignition, from the OEM (end of the approach segment)
    r, v = mme_from_icrf(segs[0].r_km[:, -1], pole), mme_from_icrf(segs[0].v_kmps[:, -1], pole)
    x = np.concatenate([mee_from_rv(r, v, C.MU_MOON), [man[0]["m_start_kg"]]])
    t = segs[0].t_s[-1]
    for i, m in enumerate(man, 1):
        assert m["ignition_et_s"] == pytest.approx(t, abs=1e-6)
        model = Model("two-body", m["thrust_N"], m["isp_s"])
        x = xburns.fly_attitude(model, x, att[i], pole)
        assert x[6] == pytest.approx(m["m_end_kg"], abs=1e-6)
        t_next = man[i]["ignition_et_s"] if i < len(man) else segs[-1].t_s[-1]
        t_cut = att[i]["t_s"][-1]
        x = propagate(model, t_cut, x, t_next).final
        t = t_next
    rf, vf = (np.array(q) for q in rv_from_mee(*x[:6], C.MU_MOON))
    r_oem = mme_from_icrf(segs[-1].r_km[:, -1], pole)
    v_oem = mme_from_icrf(segs[-1].v_kmps[:, -1], pole)
    o = orbit_summary(x, C.MU_MOON)
    o_oem = orbit_summary(np.concatenate([mee_from_rv(r_oem, v_oem, C.MU_MOON), [1.0]]),
                          C.MU_MOON)
    print("attitude flown: end position off by", np.linalg.norm(rf - r_oem) * 1e3, "m,",
          "speed", np.linalg.norm(vf - v_oem) * 1e3, "m/s; rp",
          (o["rp_km"] - o_oem["rp_km"]) * 1e3, "m; ra", (o["ra_km"] - o_oem["ra_km"]) * 1e3)
    assert abs(o["rp_km"] - o_oem["rp_km"]) * 1e3 < 5.0
    assert abs(o["ra_km"] - o_oem["ra_km"]) * 1e3 < 5.0
    assert np.linalg.norm(rf - r_oem) * 1e3 < 50.0
    assert np.linalg.norm(vf - v_oem) * 1e3 < 0.05
    # the maneuver file's delta-V is the rocket equation of its masses
    for m in man:
        assert m["delta_v_mps"] == pytest.approx(
            C.G0_MPS2 * m["isp_s"] * np.log(m["m_start_kg"] / m["m_end_kg"]), abs=1e-3)


def test_export_from_a_plan_solves_it_first(exported, tmp_path):
    ex, res = exported
    again = export_plan(res.plan, tmp_path)   # the solutions come from the cache
    assert again.sizes_bytes["spk"] == ex.sizes_bytes["spk"]
    assert (tmp_path / "song2011-150N_maneuvers.csv").read_text() == \
        ex.files["maneuvers"].read_text()


def test_cli_export_in_utc(exported, tmp_path, capsys):
    from lunarcap.cli import main

    rc = main(["plan", "song2011-150N", "--dynamics", "two-body", "--no-impulsive", "--quiet",
               "--export", str(tmp_path), "--time-system", "utc"])
    assert rc == 0
    out = capsys.readouterr().out
    assert "Exported in" in out and "song2011-150N.bsp" in out
    assert "  Moon GM 4902.800 km^3/s^2, mean radius 1738.2 km" in out   # the summary
    text = (tmp_path / "song2011-150N.oem").read_text()
    assert "TIME_SYSTEM = UTC" in text and "TIME_SYSTEM = TDB" not in text
    # the same instants as the TDB file: 69.18 s earlier on the UTC clock
    tdb = ccsds.read_oem(exported[0].files["oem"])
    utc = ccsds.read_oem(tmp_path / "song2011-150N.oem")
    assert np.max(np.abs(utc[0].t_s - tdb[0].t_s)) < 1.2e-6
    assert "START_TIME = 2017-02-20T02:30:16.814761" in text   # 02:31:26 TDB
