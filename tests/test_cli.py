"""Tests of the command line: ``lunarcap impulsive`` output and its handling of bad input.

Bad input must give exit status != 0 and exactly one ``error:`` line on stderr (argparse's
``lunarcap impulsive: error: ...`` or lunarcap's ``lunarcap: error: ...``), never a traceback.
"""

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from lunarcap import cli
from lunarcap.errors import InputError, SolveError
from lunarcap.mission import impulsive as imp
from lunarcap.mission.plan import CapturePlan
from lunarcap.physics import rocket

ROOT = Path(__file__).resolve().parents[1]
UNIT_SUFFIXES = ("_mps", "_kmps", "_kg", "_h", "_min", "_s", "_N")
UNITLESS_KEYS = {"burn", "burns", "plan"}
SNAKE = re.compile(r"^[a-z][a-z0-9]*(_[a-z0-9]+)*(_N)?$")  # N: the SI symbol of the newton


def _run(*args):
    return subprocess.run([sys.executable, "-m", "lunarcap", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=60)


def _strict_json(text):
    def reject(c):
        raise ValueError(f"non-standard JSON constant {c}")
    return json.loads(text, parse_constant=reject)


def _assert_one_clean_error(stderr):
    lines = [ln for ln in stderr.splitlines() if "error:" in ln]
    assert len(lines) == 1, stderr
    assert re.match(r"^lunarcap( impulsive)?: error: ", lines[0]), stderr
    assert "Traceback" not in stderr


def _keys(obj):
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield k
            yield from _keys(v)
    elif isinstance(obj, list):
        for v in obj:
            yield from _keys(v)


def test_impulsive_json_subprocess():
    res = _run("impulsive", "--json")
    assert res.returncode == 0, res.stderr
    out = _strict_json(res.stdout)  # inf periods must be null, not 'Infinity'
    for key in _keys(out):
        assert SNAKE.match(key), key
        assert key in UNITLESS_KEYS or key.endswith(UNIT_SUFFIXES), f"{key} names no unit"
    burns = out["burns"]
    assert [b["burn"] for b in burns] == [1, 2, 3]
    # by construction
    assert burns[0]["impulsive_delta_v_two_body_mps"] == pytest.approx(353.272, abs=1e-9)
    # JSON carries the full double: the same numbers as the library call
    lib = imp.impulsive_sequence(150.0, 200.0, 524.895)
    for b, ref in zip(burns, lib):
        assert b["impulsive_delta_v_two_body_mps"] == ref.delta_v_mps
        assert b["m_after_kg"] == ref.m_after_kg
    assert out["total_impulsive_delta_v_two_body_mps"] == pytest.approx(
        sum(b["impulsive_delta_v_two_body_mps"] for b in burns), rel=1e-15)
    assert burns[0]["period_before_h"] is None
    assert out["thrust_N"] == 150.0 and out["isp_s"] == 200.0 and out["mass_kg"] == 524.895


def test_impulsive_table_in_process(capsys):
    assert cli.main(["impulsive", "--thrust", "300", "--isp", "250"]) == 0
    out = capsys.readouterr().out
    assert "300 N / 250 s" in out
    assert "353.272" in out  # LOI 1 at 3 decimals
    # Eq. (19) at 300 N / 250 s from the impulsive chain's own first mass
    t19 = rocket.burn_duration_estimate_s(524.895, 353.272, 300.0, 250.0) / 60
    assert f"{t19:9.2f}" in out


@pytest.mark.parametrize("args", [
    ["impulsive", "--thrust", "0"],
    ["impulsive", "--thrust", "-150"],
    ["impulsive", "--isp", "0"],
    ["impulsive", "--mass", "-1"],
    ["impulsive", "--thrust", "abc"],
    ["impulsive", "--isp", "nan"],
    ["impulsive", "--mass", "inf"],
    [],                                  # no subcommand
    ["orbit"],                           # unknown subcommand
])
def test_bad_arguments_in_process(args, capsys):
    with pytest.raises(SystemExit) as info:
        cli.main(args)
    assert info.value.code != 0
    _assert_one_clean_error(capsys.readouterr().err)


@pytest.mark.parametrize("args", [["impulsive", "--thrust", "-150"],
                                  ["impulsive", "--isp", "0", "--json"],
                                  ["impulsive", "--mass", "0"]])
def test_bad_arguments_subprocess(args):
    res = _run(*args)
    assert res.returncode != 0
    assert res.stdout == ""
    _assert_one_clean_error(res.stderr)


@pytest.mark.parametrize("exc,code", [(InputError("epoch 2300-01-01 is outside"), 2),
                                      (SolveError("IPOPT did not converge"), 3)])
def test_library_errors_become_one_line(monkeypatch, capsys, exc, code):
    # errors raised below the argument parser (bad physics input, failed solves) must also
    # come out as one 'lunarcap: error:' line and a non-zero status
    def boom(*a, **k):
        raise exc
    monkeypatch.setattr(CapturePlan, "impulsive", boom)
    assert cli.main(["impulsive"]) == code
    err = capsys.readouterr().err
    _assert_one_clean_error(err)
    assert err.startswith("lunarcap: error: ") and str(exc) in err
