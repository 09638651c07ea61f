"""The public API's plans and results: a plan changed in code, its targets reached, its
files, its flight in GMAT, and a study added to the registry run with no change to the API.

The plan is a generated one (:mod:`lunarcap.studies.families`, seed 1, its second plan:
494 N / 220 s, 643 kg, 69.5 deg, not the paper's), in two-body dynamics where it is solved.
"""

from __future__ import annotations

from types import SimpleNamespace

import pandas as pd
import pytest

import lunarcap
from lunarcap.physics import constants as C
from lunarcap.studies.families import plan_family, plan_of


@pytest.fixture(scope="module")
def plan():
    return plan_family(1, 2)[0][1]


def test_a_plan_changed_in_code_is_the_plan_file_with_those_values(plan):
    """Two formulations of one plan agree: the changes applied to the generated plan, and a
    plan file's mapping written with the new values by hand (:func:`plan_of`)."""
    changed = lunarcap.load_plan(
        plan, thrust_N=300, isp_s=310, mass_kg=950, dynamics="j2",
        targets=[{"target_period_h": 6.5},
                 {"target": {"perilune_altitude_km": 100, "apolune_altitude_km": 250}}],
        starts=[-7, "free"])
    written = plan_of([{"target_period_h": 6.5, "start_min": -7},
                       {"target": {"perilune_altitude_km": 100, "apolune_altitude_km": 250},
                        "start_min": "free"}], dynamics="j2", inclination=69.5, thrust=300,
                      mass=950, isp=310, name="family-1")
    assert changed == written
    assert changed.key() == written.key()   # the cache's key: the same solves
    # what was not asked for is kept
    assert lunarcap.load_plan(plan, mass_kg=950).burns == plan.burns
    assert lunarcap.load_plan(plan, targets=[None, None]) == plan


@pytest.mark.slow
def test_targets_changed_in_code_are_met_on_the_reflown_capture(plan):
    """The orbits asked in code are those the re-flown burns reach (the verification gate's
    re-propagation): 3000 km apolune after burn 1, a 100 x 250 km ellipse after burn 2,
    each within the gate's 10 m; the loaded plan's 8132.3 km and circle are gone."""
    asked = lunarcap.load_plan(plan, dynamics="two-body", targets=[
        {"target_apolune_altitude_km": 3000},
        {"target": {"perilune_altitude_km": 100, "apolune_altitude_km": 250}}])
    res = lunarcap.solve(asked, impulsive=False)
    assert res.check() is res and res.verified
    rows = res.to_frame()
    for ra_km, r in zip((C.R_MOON + 3000, C.R_MOON + 250), rows.itertuples()):
        assert abs(r.ra_end_km - ra_km) < 0.01
        assert abs(r.rp_end_km - (C.R_MOON + 100)) < 0.01
        assert abs(r.verification_ra_error_m) < 10.0 and abs(r.verification_rp_error_m) < 10.0


@pytest.mark.slow
def test_export_writes_the_formats_asked_and_gmat_flies_it(plan, tmp_path):
    """The writers asked, no others; GMAT flies the exported script within its gates."""
    res = lunarcap.solve(lunarcap.load_plan(plan, dynamics="two-body"), impulsive=False)
    ex = res.export(tmp_path / "two", formats=["maneuvers", "oem"])
    assert list(ex.files) == ["oem", "maneuvers"]   # in the registry's order
    assert sorted(p.name for p in (tmp_path / "two").iterdir()) == [
        "family-1.oem", "family-1_maneuvers.csv"]
    with pytest.raises(lunarcap.InputError, match=r"formats: \['kml'\] not among"):
        res.export(tmp_path / "none", formats=["kml"])
    assert not (tmp_path / "none").exists()   # refused before the directory is made
    flight = res.fly_in_gmat(tmp_path / "gmat")
    assert flight.passed, flight.failures()
    t = flight.to_frame()
    n = res.plan.n_burns
    assert t.flown.value_counts().to_dict() == {"burn": n, "coast": n, "capture": 2 * n + 2}
    assert (t[t.flown == "burn"].position_diff_m < 0.5).all()
    from lunarcap.report.figstyle import legibility_problems

    fig = flight.plot()
    assert legibility_problems(fig) == []
    # the events read in the order they happen (they once came as GMAT's report grouped
    # them: the burns' cut-offs first, the arrival mid-axis)
    ticks = [t.get_text() for t in fig.axes[0].get_xticklabels()]
    assert ticks == ["arrival"] + [f"{k} {e}" for k in range(1, n + 1)
                                   for e in ("ignition", "cut-off")] + ["end"]


def test_a_study_added_to_the_registry_runs_through_the_api_unchanged(plan, monkeypatch,
                                                                       tmp_path):
    """A registered study is an API call by its name, its options by their names with the
    command's defaults, its plan loaded and its Dask options passed as its prepare reads
    them: here a stand-in study whose one case computes Eq. (19)'s first burn duration."""
    from lunarcap.studies import registry

    seen = {}

    def options(p):
        p.add_argument("--burn", default="1")
        p.add_argument("--scale", default="1.0")

    def prepare(args, p):
        seen.update(vars(args), plan=p)
        minutes = p.impulsive()[int(args.burn) - 1].eq19_duration_min * float(args.scale)
        table = pd.DataFrame([{"plan": p.name, "eq19_duration_min": minutes, "status": "ok"}])
        raw = SimpleNamespace(table=table, path=tmp_path / "t.csv", run={"cases": 1})
        return registry.StudyRun(lambda: raw, "cases", lambda r: {"rows": r.table.to_dict(
            "records")}, lambda r: "text", lambda r: True)

    fake = registry.StudyCommand("eq19", "a stand-in", options, prepare, dask="case")
    real = registry.studies
    monkeypatch.setattr(registry, "studies", lambda: real() | {"eq19": fake})
    res = lunarcap.run_study("eq19", "two-burn-8h", scale=2, workers=3)
    first = lunarcap.load_plan("two-burn-8h").impulsive()[0].eq19_duration_min
    assert res.to_dict()["rows"][0]["eq19_duration_min"] == pytest.approx(2 * first, rel=1e-15)
    assert (seen["burn"], seen["scale"], seen["workers"], seen["no_progress"]) == (
        "1", 2, 3, True)
    assert seen["plan"] == lunarcap.load_plan("two-burn-8h")
    assert res.answered and res.text() == "text" and res.name == "eq19"
    with pytest.raises(lunarcap.InputError, match="eq19: needs a plan"):
        lunarcap.run_study("eq19")


def test_a_study_waits_for_its_table_as_long_as_asked(monkeypatch, tmp_path):
    """``lock_wait_s``: a run that finds its table being written by another run (a command
    line run of the same table, another notebook) waits for it as long as asked, as the
    book's trade-study page waits for ``lunarcap study``; by default it is refused at once,
    as the command line is. Here a stand-in study with no case, its table held by a thread
    for a second."""
    import threading
    import time

    from lunarcap.studies import campaign, registry
    from lunarcap.studies.study import Study

    table = tmp_path / "t.csv"
    standin = Study("standin", campaign.TableFormat(key=("case",), columns=("case", "status")),
                    lambda: [], ("ok",), ("ok",), "case", "stand-in")

    def prepare(args, p):
        return registry.StudyRun(lambda: standin.run([], args.out, progress=False), "cases",
                                 lambda r: {}, lambda r: "", lambda r: True)

    fake = registry.StudyCommand("standin", "a stand-in", lambda p: None, prepare, plan=False)
    real = registry.studies
    monkeypatch.setattr(registry, "studies", lambda: real() | {"standin": fake})
    held, release = threading.Event(), threading.Event()

    def other_run():
        with campaign.table_lock(table):
            held.set()
            release.wait(30)

    other = threading.Thread(target=other_run)
    other.start()
    try:
        assert held.wait(10)
        with pytest.raises(lunarcap.InputError, match="being written by another run"):
            lunarcap.run_study("standin", out=table)
        threading.Timer(1.0, release.set).start()
        t0 = time.monotonic()
        res = lunarcap.run_study("standin", out=table, lock_wait_s=30)
        assert time.monotonic() - t0 >= 0.9 and res.campaign.path == table
    finally:
        release.set()
        other.join()


@pytest.mark.slow
def test_all_burns_in_one_nlp_read_as_every_result(tmp_path):
    """``lunarcap.solve_joint``: the joint optimum of a packaged plan (two-body), started from
    the plan solved one burn at a time (``lunarcap.solve``, every ignition free: the same
    numbers, bit for bit), never worse than it; its document strict JSON, its figure
    legible, its files written."""
    import json

    from lunarcap.report.figstyle import legibility_problems

    plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    joint = lunarcap.solve_joint(plan)
    chain = lunarcap.solve(plan.with_starts(["free"] * plan.n_burns), impulsive=False)
    assert joint.verified and joint.ipopt_status == "Solve_Succeeded"
    assert [r["delta_v_mps"] for r in joint.warm_start] == [
        r["delta_v_mps"] for r in chain.rows()]
    assert -1e-3 < joint.warm_start_total_delta_v_mps - joint.total_delta_v_mps < 0.1
    frame = joint.to_frame()
    assert frame.burn.tolist() == [1, 2] and frame.verification_passed.all()
    assert joint.total_delta_v_mps == sum(frame.delta_v_mps)
    doc = json.loads(joint.to_json())
    assert doc["totals"]["total_delta_v_mps"] == joint.total_delta_v_mps
    assert len(doc["legs"]) == len(doc["warm_start"]) == 2 and "u_inertial" not in doc["legs"][0]
    assert legibility_problems(joint.plot()) == []
    files = joint.export(tmp_path)
    assert files["csv"].name == "two-burn-8h_joint.csv" and files["json"].is_file()
    with pytest.raises(lunarcap.InputError, match="plan: a file, a packaged plan"):
        lunarcap.solve_joint(42)
