"""CLI tests of `lunarcap plan` and `lunarcap solve` (real solves in two-body for speed) and
of how they answer bad input: exit 2 and one line naming the field.
"""

import json
import math
import subprocess
import sys

import pytest
import yaml

from lunarcap import cli
from lunarcap.errors import SolveError
from lunarcap.mission.plan import load_plan

pytestmark = pytest.mark.slow

REQUIRED = ["delta_v_mps", "impulsive_limit_mps", "delta_v_loss_percent", "burn_duration_min",
            "start_min", "m_start_kg", "m_end_kg", "v_end_kmps", "solve_wall_s"]


def _run(*args):
    return subprocess.run([sys.executable, "-m", "lunarcap", *args], capture_output=True,
                          text=True, timeout=600)


def _one_error_line(stderr: str) -> str:
    lines = [ln for ln in stderr.splitlines() if "error:" in ln]
    assert len(lines) == 1, stderr
    assert "Traceback" not in stderr
    return lines[0]


@pytest.fixture
def plan_file(tmp_path):
    """A two-burn two-body plan: hyperbola -> 8 h ellipse -> 100 km circle, 450 N."""
    d = load_plan("song2011-450N").to_dict()
    d.update(name="two-burn-test", dynamics="two-body",
             burns=[{"target_period_h": 8.0, "start_min": "free"},
                    {"target": "circular", "start_min": "free"}])
    f = tmp_path / "two.yaml"
    f.write_text(yaml.safe_dump(d, sort_keys=False))
    return f


def test_solve_json_keys_and_physics():
    r = _run("solve", "--thrust", "450", "--isp", "300", "--loi", "1", "--start", "-3",
             "--dynamics", "two-body", "--json", "--quiet", "--no-cache")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    for k in REQUIRED:
        assert k in d
    for k in ("delta_v_mps", "rp_error_m", "inc_error_deg", "gamma_error_deg"):
        assert k in d["verification"]
    # the rocket equation ties the printed numbers together
    dv = 300 * 9.80665 * math.log(d["m_start_kg"] / d["m_end_kg"])
    assert abs(dv - d["delta_v_mps"]) < 1e-6
    # two-body: the impulsive limit is the vis-viva 353.272 m/s, the finite burn costs more,
    # by < 1 %
    assert abs(d["impulsive_limit_mps"] - 353.272) < 0.01
    assert 353.272 < d["delta_v_mps"] < 353.272 * 1.01
    assert d["delta_v_loss_mps"] == pytest.approx(d["delta_v_mps"] - d["impulsive_limit_mps"])
    assert d["verification"]["passed"]


def test_plan_json_totals_and_chain(plan_file):
    r = _run("plan", str(plan_file), "--json", "--quiet")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["complete"] and len(d["burns"]) == 2 and d["plan"]["name"] == "two-burn-test"
    tot = d["totals"]
    assert tot["total_delta_v_mps"] == pytest.approx(sum(b["delta_v_mps"] for b in d["burns"]),
                                                     rel=1e-15)
    # mass carries through the chain, the loss is positive, the final orbit is the circle
    a, b = d["burns"]
    assert a["m_end_kg"] == pytest.approx(b["m_start_kg"], abs=1e-9)  # collocation vs flight
    assert tot["total_delta_v_loss_mps"] > 0
    assert tot["final_rp_km"] == pytest.approx(1838.2, abs=0.01)
    assert tot["final_ra_km"] == pytest.approx(1838.2, abs=0.01)
    assert tot["all_verified"]


def test_plan_text_prints_every_burn_and_totals(plan_file):
    r = _run("plan", str(plan_file), "--quiet")
    assert r.returncode == 0, r.stderr
    assert "ellipse, 8 h" in r.stdout and "circle" in r.stdout and "total: dV" in r.stdout


def test_progress_says_what_is_built_and_counts_burns_out_of_the_plan():
    # issue 24: silence while the NLPs were built; "burn 2 of 2", "burn 3 of 3" for a
    # 3-burn plan (each burn is solved from the plan's prefix); unlabelled impulsive solves
    r = _run("plan", "song2011-450N", "--dynamics", "two-body", "--no-cache")
    assert r.returncode == 0, r.stderr
    err = r.stderr.splitlines()
    first = next(i for i, ln in enumerate(err) if ln.startswith("burn "))
    assert err[0].startswith("building 4 NLPs") and err[first - 1].startswith("  NLPs built in")
    built = err[1:first - 1]
    assert len(built) == 4 and all(ln.endswith(" s") and "two-body dynamics, mesh 8x16 LGR-5"
                                   in ln for ln in built), built
    assert [ln.split(" (")[0] for ln in err if ln.startswith("burn ")] == \
        ["burn 1 of 3", "burn 2 of 3", "burn 3 of 3"]
    assert [ln.split(":")[0] for ln in err if ln.startswith("impulsive limit")] == \
        [f"impulsive limit of burn {k} of 3" for k in (1, 2, 3)]
    meshes = [ln for ln in err[first:] if "mesh 8x16 LGR-5:" in ln]
    labels = ("4 s burn before the perilune, mesh", "4 s burn after the perilune, mesh",
              "2 s burn, mesh")
    assert sum(ln.startswith(tuple("  " + x for x in labels)) for ln in meshes) == 9, err
    assert len(meshes) == 12, err   # and one per finite burn


def test_after_days_propagates_the_final_orbit(plan_file, tmp_path):
    # the final 100 km circle (two-body: it stays one) propagated half a day after the last
    # cut-off: every revolution at 100 km, one per circle period, in the JSON's schema;
    # exported, the OEM goes on from the final orbit's revolution to the half day's end
    import jsonschema
    import numpy as np

    from lunarcap.exchange.ccsds import read_oem
    from lunarcap.physics.constants import R_MOON
    from lunarcap.schemas import schemas

    r = _run("plan", str(plan_file), "--json", "--quiet", "--no-impulsive", "--after-days",
             "0.5")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    jsonschema.validate(d["after"], schemas()["plan"]["properties"]["after"])
    after = d["after"]
    assert after["after_days"] == 0.5 and after["after_dynamics"] == "two-body"
    revs = after["revolutions"]
    assert len(revs) == after["after_revolutions"] == int(0.5 * 86400 / (117.868 * 60))
    for rev in revs:
        assert rev["perilune_altitude_km"] == pytest.approx(100.0, abs=0.01)
        assert rev["apolune_altitude_km"] == pytest.approx(100.0, abs=0.01)
        assert rev["mean_inclination_deg"] == pytest.approx(90.0, abs=1e-4)
    out = tmp_path / "out"
    r = _run("plan", str(plan_file), "--quiet", "--after-days", "0.5", "--export", str(out))
    assert r.returncode == 0, r.stderr
    assert "After the capture: 0.5 days in two-body dynamics, 6 revolutions" in r.stdout
    segs = {s.name: s for s in read_oem(out / "two-burn-test.oem")}
    final, after = segs["final orbit"], segs["after capture"]
    assert list(segs)[-1] == "after capture"
    assert after.t_s[0] == final.t_s[-1]                    # the two segments meet
    assert np.abs(after.r_km[:, 0] - final.r_km[:, -1]).max() < 1e-6
    cutoff = segs["burn 2"].t_s[-1]
    assert after.t_s[-1] == pytest.approx(cutoff + 0.5 * 86400, abs=1e-5)
    assert np.allclose(np.diff(after.t_s[1:-1]), 60.0, atol=1e-5)
    # Kepler: the circle stays at 100 km all along
    assert np.abs(np.linalg.norm(after.r_km, axis=0) - R_MOON - 100.0).max() < 1e-3


def test_failed_solve_exits_3_and_keeps_what_was_done(monkeypatch, capsys, plan_file):
    # burn 2 fails: burn 1's row is printed first, then one error line, exit 3
    import lunarcap.capture.chain as chain
    real = chain.solve_burn

    def fail_second(key, verbose=False):
        if key.n_burns == 2:
            raise SolveError("burn 2 failed on every mesh: 8x16 LGR-5: IPOPT "
                             "Infeasible_Problem_Detected", status="Infeasible_Problem_Detected")
        return real(key, verbose=verbose)
    monkeypatch.setattr(chain, "solve_burn", fail_second)
    rc = cli.main(["plan", str(plan_file), "--quiet", "--no-impulsive"])
    out, err = capsys.readouterr()
    assert rc == 3
    assert "ellipse, 8 h" in out and "total" not in out
    # the solve saw the plan's key (name blanked); the message names the plan (issue 24)
    assert _one_error_line(err) == ("lunarcap: error: plan two-burn-test: burn 2 failed on "
                                    "every mesh: 8x16 LGR-5: IPOPT Infeasible_Problem_Detected")


BAD_PLANS = [
    # (mutation of the plan, field named, words of the reason)
    (lambda d: d["engine"].update(thrust_N=-150), "engine.thrust_N", "positive"),
    (lambda d: d["arrival"].pop("mass_kg"), "arrival.mass_kg", "missing"),
    (lambda d: d.update(colour="red"), "colour", "unknown key"),
    (lambda d: d["arrival"].update(perilune_altitude_km=-50), "arrival.perilune_altitude_km",
     "surface"),
    (lambda d: d["burns"][0].update(target_period_h=1.0), "burns[1].target_period_h",
     "circular orbit"),
    (lambda d: d["arrival"].update(epoch="2250-06-01 00:00:00 TDB"), "arrival.epoch",
     "outside the ephemeris"),
    (lambda d: d["engine"].update(thrust_N=1e9), "engine.thrust_N", "too strong"),
    (lambda d: d["engine"].update(isp_s=float("inf")), "engine.isp_s", "finite"),
]


@pytest.mark.parametrize("mutate,field,reason", BAD_PLANS, ids=[b[1] for b in BAD_PLANS])
def test_bad_plan_exits_2_with_one_line_naming_the_field(tmp_path, plan_file, mutate, field,
                                                         reason):
    d = yaml.safe_load(plan_file.read_text())
    mutate(d)
    f = tmp_path / "bad.yaml"
    f.write_text(yaml.safe_dump(d, sort_keys=False))
    r = _run("plan", str(f), "--quiet")
    assert r.returncode == 2
    line = _one_error_line(r.stderr)
    assert line.startswith(f"lunarcap: error: plan bad.yaml: {field}: "), line
    assert reason in line, line
    assert r.stdout == ""


@pytest.mark.parametrize("args,words", [
    (["solve", "--burn", "4"], "has burns 1 to 3"),
    (["solve", "--start", "abc"], "start offsets must be numbers"),
    (["solve", "--thrust", "-1"], "--thrust: must be positive"),
    (["solve", "--start", "500"], "more than 120 min"),
    (["solve", "--thrust", "1e9"], "too strong"),
    (["plan", "song2011-150N", "--starts", "-1,-2"], "3 ignition offsets expected"),
    (["solve", "--loi", "2", "--previous-starts", "-1,-2"], "needs 1 offset(s)"),
    (["plan", "no-such-plan"], "not a packaged plan"),
])
def test_bad_command_lines_exit_2_with_one_message(args, words):
    r = _run(*args, "--quiet")
    assert r.returncode == 2, r.stderr
    assert words in _one_error_line(r.stderr)
