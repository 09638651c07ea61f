"""Bad input at the command line: one line naming the real culprit, exit status 2.

A plan of one's own (the packaged two-burn-8h, written to a file and spoiled one field at a
time) is given to each command that takes a plan (plan, burns, missed, dispersions). Each
message must name the field as the user wrote it (burns numbered from 1, options as typed),
the value and the reason, on one line of stderr, with nothing on stdout. Run in process
(``cli.main``), so the whole table takes seconds; one case runs as a real subprocess.
"""

from __future__ import annotations

import math
import subprocess
import sys

import pytest
import yaml

from lunarcap import cli
from lunarcap.mission.plan import PLAN_DIR, paper_plan

COMMANDS = ("plan", "burns", "missed", "dispersions")


def _set(*path):
    """A mutation of the plan mapping: the key at ``path[:-1]`` set to ``path[-1]``."""
    def mutate(d):
        node = d
        for k in path[:-2]:
            node = node[k]
        node[path[-2]] = path[-1]
    return mutate


PLAN_CASES = [
    # (id, mutation, field named, words of the reason, the value as printed)
    ("perilune far out", _set("arrival", "perilune_altitude_km", 100000),
     "arrival.perilune_altitude_km", "sphere of influence", "100000"),
    ("perilune below ground", _set("arrival", "perilune_altitude_km", -5),
     "arrival.perilune_altitude_km", "lunar surface", "-5"),
    ("perilune text", _set("arrival", "perilune_altitude_km", "high"),
     "arrival.perilune_altitude_km", "must be a number", "'high'"),
    ("v_inf 800", _set("arrival", "v_inf_kmps", 800), "arrival.v_inf_kmps",
     "above the largest allowed", "800"),
    ("v_inf zero", _set("arrival", "v_inf_kmps", 0), "arrival.v_inf_kmps", "positive", "0"),
    ("v_inf nan", _set("arrival", "v_inf_kmps", math.nan), "arrival.v_inf_kmps", "finite",
     "nan"),
    ("mass 700 t", _set("arrival", "mass_kg", 700000), "arrival.mass_kg",
     "above the largest allowed", "700000"),
    ("mass negative", _set("arrival", "mass_kg", -1), "arrival.mass_kg", "positive", "-1"),
    ("mass text", _set("arrival", "mass_kg", "heavy"), "arrival.mass_kg", "must be a number",
     "'heavy'"),
    ("thrust zero", _set("engine", "thrust_N", 0), "engine.thrust_N", "positive", "0"),
    ("thrust negative", _set("engine", "thrust_N", -150), "engine.thrust_N", "positive",
     "-150"),
    ("thrust text", _set("engine", "thrust_N", "big"), "engine.thrust_N", "must be a number",
     "'big'"),
    ("thrust nan", _set("engine", "thrust_N", math.nan), "engine.thrust_N", "finite", "nan"),
    ("thrust too weak", _set("engine", "thrust_N", 0.5), "engine.thrust_N", "too weak", "0.5"),
    ("isp zero", _set("engine", "isp_s", 0), "engine.isp_s", "positive", "0"),
    ("isp nan", _set("engine", "isp_s", math.nan), "engine.isp_s", "finite", "nan"),
    ("period too short", _set("burns", 0, "target_period_h", 1.0), "burns[1].target_period_h",
     "not longer than the circular orbit", "1 h"),
    ("period negative", _set("burns", 0, "target_period_h", -8), "burns[1].target_period_h",
     "positive", "-8"),
    ("period far out", _set("burns", 0, "target_period_h", 5000), "burns[1].target_period_h",
     "sphere of influence", "5000 h"),
    ("coast negative", _set("burns", 1, "coast_min", -3), "burns[2].coast_min", "positive",
     "-3"),
    ("start text", _set("burns", 1, "start_min", "late"), "burns[2].start_min",
     "must be a number", "'late'"),
    ("unknown key", _set("engine", "thrust_lbf", 30), "engine.thrust_lbf", "unknown key", ""),
]


def _main(argv, capsys) -> tuple:
    """(exit status, stdout, stderr) of ``lunarcap argv`` run in process."""
    try:
        rc = cli.main(argv)
    except SystemExit as exc:   # argparse
        rc = exc.code
    out, err = capsys.readouterr()
    return rc, out, err


def _one_line(err: str) -> str:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    assert lines[0].startswith("lunarcap: error: "), err
    return lines[0]


@pytest.fixture(scope="module")
def own_plan() -> dict:
    return yaml.safe_load((PLAN_DIR / "two-burn-8h.yaml").read_text())


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("case", PLAN_CASES, ids=[c[0] for c in PLAN_CASES])
def test_a_bad_plan_field_is_named(tmp_path, capsys, own_plan, command, case):
    _, mutate, field, words, value = case
    d = yaml.safe_load(yaml.safe_dump(own_plan))
    mutate(d)
    f = tmp_path / "mine.yaml"
    f.write_text(yaml.safe_dump(d, sort_keys=False))
    rc, out, err = _main([command, str(f)], capsys)
    assert rc == 2, err
    line = _one_line(err)
    assert line.startswith(f"lunarcap: error: plan mine.yaml: {field}: "), line
    assert words in line and value in line, line
    assert out == ""


FILE_CASES = [
    ("missing file", lambda d: d / "nope.yaml", "no such file"),
    ("directory", lambda d: d, "is a directory"),
    ("yaml syntax", lambda d: (d / "bad.yaml", (d / "bad.yaml").write_text(
        "name: x\narrival: {epoch: [\n"))[0], "not valid YAML (line"),
]


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("case", FILE_CASES, ids=[c[0] for c in FILE_CASES])
def test_a_bad_plan_file_is_named(tmp_path, capsys, command, case):
    _, make, words = case
    path = make(tmp_path)
    rc, out, err = _main([command, str(path)], capsys)
    assert rc == 2, err
    line = _one_line(err)
    assert line.startswith(f"lunarcap: error: plan {path}") and words in line, line
    assert out == ""


OPTION_CASES = [
    # (argv after the command and the plan, option named, words of the reason)
    (["--thrust", "0"], "--thrust", "must be positive (N), got '0'"),
    (["--thrust", "-5"], "--thrust", "must be positive (N), got '-5'"),
    (["--thrust", "abc"], "--thrust", "must be a number of N, got 'abc'"),
    (["--thrust", "nan"], "--thrust", "must be a finite number of N, got 'nan'"),
    (["--isp", "0"], "--isp", "must be positive (s)"),
    (["--isp", "inf"], "--isp", "must be a finite number of s"),
    (["--mass", "-1"], "--mass", "must be positive (kg)"),
    (["--mass", "700000"], "--mass (arrival.mass_kg)", "above the largest allowed"),
    (["--thrust", "0.5"], "--thrust (engine.thrust_N)", "0.5 N is too weak for 524.895 kg"),
    (["--dynamics", "n-body"], "--dynamics", "invalid choice"),
]


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("case", OPTION_CASES, ids=[" ".join(c[0]) for c in OPTION_CASES])
def test_a_bad_option_is_named(capsys, command, case):
    args, option, words = case
    rc, out, err = _main([command, "song2011-150N", *args], capsys)
    assert rc == 2, err
    line = _one_line(err)
    assert f" {option}: " in line and words in line, line


COMMAND_CASES = [
    (["burns", "song2011-150N", "--max-days", "-1"], "--max-days", "positive"),
    (["burns", "song2011-150N", "--max-period-h", "nan"], "--max-period-h", "finite"),
    (["missed", "song2011-150N", "--burn", "0"], "--burn", "integer >= 1"),
    (["missed", "song2011-150N", "--burn", "x"], "--burn", "must be an integer"),
    (["dispersions", "song2011-150N", "--thrust-sigma-pct", "-1"], "--thrust-sigma-pct",
     "below the smallest allowed"),
    (["solve", "--burn", "0"], "--burn", "must be an integer >= 1"),
    (["missed", "song2011-150N", "--fractions", "0.5,2"], "--fractions",
     "2 is above the largest allowed, 1"),
    (["missed", "song2011-150N", "--fractions", "0"], "--fractions", "must be positive"),
    (["missed", "song2011-150N", "--delays-min", "-5"], "--delays-min",
     "-5 min is below the smallest allowed, 0 min"),
    (["missed", "song2011-150N", "--late-min", "3,3"], "--late-min", "duplicates"),
    (["missed", "song2011-150N", "--late-min", "x"], "--late-min", "must be a number of min"),
    (["dispersions", "song2011-150N", "--samples", "-3"], "--samples", "integer >= 1"),
    (["dispersions", "song2011-150N", "--seed", "1.5"], "--seed", "must be an integer"),
]


@pytest.mark.parametrize("argv,option,words", COMMAND_CASES,
                         ids=[" ".join(c[0][::2]) for c in COMMAND_CASES])
def test_a_bad_study_option_is_named(capsys, argv, option, words):
    rc, out, err = _main(argv, capsys)
    assert rc == 2, err
    line = _one_line(err)
    assert f"{option}: " in line and words in line, line


def test_one_line_and_exit_2_from_a_real_process(tmp_path):
    f = tmp_path / "mine.yaml"
    d = yaml.safe_load((PLAN_DIR / "two-burn-8h.yaml").read_text())
    d["arrival"]["v_inf_kmps"] = 800
    f.write_text(yaml.safe_dump(d))
    r = subprocess.run([sys.executable, "-m", "lunarcap", "plan", str(f)], capture_output=True,
                       text=True, timeout=300)
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.strip().splitlines() == [
        "lunarcap: error: plan mine.yaml: arrival.v_inf_kmps: 800 km/s is above the largest "
        "allowed, 5 km/s (lunarcap's limit; a direct transfer arrives at about 1 km/s)"]


# ---------------------------------------------------------------------- help
def _subparsers():
    parser = cli.build_parser()
    sub = next(a for a in parser._actions if a.choices and isinstance(a.choices, dict))
    return sub.choices


def _options():
    for name, p in _subparsers().items():
        for a in p._actions:
            if a.option_strings and a.help and a.dest != "help":
                yield name, a


def test_help_states_every_real_default():
    """An option's help quotes its argparse default; an override says it is the plan's."""
    for name, a in _options():
        where = f"lunarcap {name} {a.option_strings[0]}: {a.help!r}"
        if a.default in (None, False):
            if a.default is None and a.nargs != 0:
                assert "default" in a.help or a.option_strings[0] in (
                    "--export", "--arrival-cov"), where
            continue
        assert f"default {a.default}" in a.help or f"default: {a.default}" in a.help, where


@pytest.mark.parametrize("command", ["plan", "solve", "impulsive", "plans", "bench", "study",
                                     "burns", "missed", "dispersions"])
def test_every_command_prints_its_help(command, capsys):
    """argparse formats each help with %: a bare '%' in a help text crashed --help."""
    with pytest.raises(SystemExit) as exc:
        cli.main([command, "--help"])
    assert exc.value.code == 0
    assert "usage: lunarcap " + command in capsys.readouterr().out


def test_plan_overrides_say_the_plans_and_the_papers_default():
    """--thrust, --isp, --mass...: "default: the plan's"; without --plan, the paper's values."""
    plan = paper_plan()
    real = {"--thrust": f"{plan.engine.thrust_N:g} N", "--isp": f"{plan.engine.isp_s:g} s",
            "--mass": f"{plan.arrival.mass_kg:g} kg", "--dynamics": plan.dynamics,
            "--hemisphere": plan.arrival.hemisphere, "--lunar-pole": plan.lunar_pole}
    seen = 0
    for name, a in _options():
        opt = a.option_strings[0]
        if opt not in real or name in ("bench", "study"):
            continue
        assert "default: the plan's" in a.help, (name, opt, a.help)
        assert a.default is None, (name, opt)
        if name in ("solve", "impulsive"):   # no PLAN: the paper's capture
            assert f"the paper's {real[opt]} without --plan" in a.help, (name, opt, a.help)
        seen += 1
    assert seen == 6 * len(("plan", "solve", "impulsive", "burns", "missed", "dispersions"))


# ---------------------------------------------------------------------- altitudes
def test_final_orbit_is_printed_as_altitudes(capsys):
    """Plans take altitudes, so the text output's final orbit is in altitudes, not radii."""
    from lunarcap.cli.plan import print_totals
    from lunarcap.physics.constants import R_MOON

    tot = {"total_delta_v_loss_mps": None, "total_delta_v_mps": 800.0,
           "total_burn_duration_min": 30.0,
           "total_fuel_kg": 150.0, "final_mass_kg": 374.9, "final_rp_km": R_MOON + 100.0,
           "final_ra_km": R_MOON + 300.0, "final_inc_deg": 90.0,
           "final_orbit_epoch": "2017-02-21 00:00:00 TDB", "time_to_final_orbit_h": 20.0}
    print_totals(tot)
    out = capsys.readouterr().out
    assert "final orbit 100.0 x 300.0 km altitude" in out, out
