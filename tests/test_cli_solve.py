"""CLI tests of `lunarcap solve` and `lunarcap sequence` (real solves, two-body for speed)."""

import json
import subprocess
import sys

import pytest

from lunarcap import cli
from lunarcap.errors import SolveError

pytestmark = pytest.mark.slow

REQUIRED = ["delta_v_mps", "impulsive_delta_v_mps", "loss_percent", "burn_duration_min",
            "start_min", "m_start_kg", "m_end_kg", "v_end_kmps", "solve_wall_s"]


def _run(*args):
    return subprocess.run([sys.executable, "-m", "lunarcap", *args], capture_output=True,
                          text=True, timeout=600)


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
    import math
    dv = 300 * 9.80665 * math.log(d["m_start_kg"] / d["m_end_kg"])
    assert abs(dv - d["delta_v_mps"]) < 1e-6
    # two-body finite burn costs more than the two-body impulsive 353.272 m/s, by < 1 %
    assert 353.272 < d["delta_v_mps"] < 353.272 * 1.01
    assert d["verification"]["passed"]


def test_sequence_json_totals():
    r = _run("sequence", "--thrust", "450", "--isp", "300", "--starts", "-3,-2,-2",
             "--dynamics", "two-body", "--json", "--quiet")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["complete"] and len(d["lois"]) == 3
    assert abs(d["total_delta_v_mps"] - sum(x["delta_v_mps"] for x in d["lois"])) < 1e-9
    # mass carries through the chain
    for a, b in zip(d["lois"], d["lois"][1:]):
        assert abs(a["m_end_kg"] - b["m_start_kg"]) < 1e-9


def test_failed_solve_exits_3_with_status(monkeypatch, capsys):
    def boom(*a, **k):
        raise SolveError("LOI 1 failed on every mesh: 8x16 LGR-5: IPOPT Infeasible_Problem_Detected",
                         status="Infeasible_Problem_Detected")
    import lunarcap.runs.chain as seq
    monkeypatch.setattr(seq.solve_case, "uncached", boom, raising=False)
    monkeypatch.setattr(seq, "solve_case", boom)
    rc = cli.main(["solve", "--loi", "1", "--start", "-10", "--quiet"])
    err = capsys.readouterr().err
    assert rc == 3 and "Infeasible_Problem_Detected" in err and "Traceback" not in err


@pytest.mark.parametrize("args", [["solve", "--loi", "4"], ["solve", "--start", "abc"],
                                  ["solve", "--thrust", "-1"], ["solve", "--start", "500"],
                                  ["sequence", "--starts", "-1,-2"],
                                  ["solve", "--loi", "2", "--previous-starts", "-1,-2"]])
def test_bad_input_exits_nonzero_with_one_message(args):
    r = _run(*args, "--quiet")
    assert r.returncode != 0
    assert "Traceback" not in r.stderr
    assert sum("error" in line for line in r.stderr.splitlines()) == 1
