"""The study commands' bad input: one ``lunarcap: error:`` line on stderr, exit status 2.

Each case fails before any solve (the task would fail the test). In process through
``main`` for speed; the trade study's unwritable --out (a FileNotFoundError traceback from
its lock file before) also as a real command line.
"""

import subprocess
import sys
from pathlib import Path

import pytest

from lunarcap.cli import main

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture
def bad_dir(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("x")
    return blocker


CASES = [
    ["burns", "song2011-150N", "--counts", "0,1"],
    ["burns", "song2011-150N", "--counts", "1,2.5"],
    ["burns", "song2011-150N", "--counts", "-1"],
    ["burns", "song2011-150N", "--counts", "one"],
    ["burns", "song2011-150N", "--counts", ""],
    ["burns", "song2011-150N", "--counts", "2,2"],
    ["burns", "song2011-150N", "--max-period-h", "0"],
    ["burns", "song2011-150N", "--max-period-h", "nan"],
    ["burns", "song2011-150N", "--max-days", "-3"],
    ["burns", "song2011-150N", "--workers", "0"],
    ["burns", "no-such-plan"],
    ["burns", "song2011-150N", "--out", "{bad}/t.csv"],
    ["missed", "song2011-150N", "--burn", "4"],
    ["missed", "song2011-150N", "--burn", "0"],
    ["missed", "song2011-150N", "--burn", "x"],
    ["missed", "song2011-150N", "--fractions", "0"],
    ["missed", "song2011-150N", "--fractions", "0.5,1.2"],
    ["missed", "song2011-150N", "--fractions", "-0.5"],
    ["missed", "song2011-150N", "--fractions", "a,b"],
    ["missed", "song2011-150N", "--delays-min", "-30"],
    ["missed", "song2011-150N", "--delays-min", "0,inf"],
    ["missed", "song2011-150N", "--max-period-h", "-1"],
    ["missed", "song2011-150N", "--out", "{bad}/t.csv"],
    ["missed", "song2011-150N", "--out", "/proc/lunarcap-test/t.csv"],
    ["study", "--points", "2", "--out", "{bad}/t.csv"],
    ["study", "--points", "2", "--out", "/proc/lunarcap-test/t.csv"],
]


@pytest.mark.parametrize("args", CASES, ids=[" ".join(c[2:] or c[1:]) for c in CASES])
def test_bad_study_input_is_one_line_and_exit_2(args, bad_dir, capsys, monkeypatch):
    from lunarcap.studies import campaign

    monkeypatch.setattr(campaign, "dask_client",
                        lambda *a, **k: pytest.fail("a cluster was started"))
    code = main([a.replace("{bad}", str(bad_dir)) for a in args])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2
    assert len(err) == 1 and err[0].startswith("lunarcap: error: "), err


def test_study_out_in_an_unwritable_directory_subprocess(bad_dir):
    p = subprocess.run([sys.executable, "-m", "lunarcap", "study", "--points", "2", "--out",
                        str(bad_dir / "t.csv")], capture_output=True, text=True, cwd=ROOT,
                       env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}, timeout=120)
    assert p.returncode == 2
    assert p.stderr.strip().splitlines() == [
        f"lunarcap: error: --out {bad_dir / 't.csv'}: cannot write in {bad_dir} "
        f"(File exists)"], p.stderr
    assert "Traceback" not in p.stderr


@pytest.mark.parametrize("argv, module, func, unit", [
    (["study", "--points", "2"], "lunarcap.studies.engine_trade.trade", "run_study", "engines"),
    (["burns", "song2011-150N", "--counts", "1"], "lunarcap.studies.burn_count.counts",
     "run_burns", "counts"),
    (["missed", "song2011-150N"], "lunarcap.studies.missed.cases", "run_missed", "cases"),
])
def test_ctrl_c_in_a_study_exits_130_with_one_line(argv, module, func, unit, monkeypatch,
                                                     capsys):
    import importlib

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(importlib.import_module(module), func, interrupted)
    assert main(argv) == 130
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"lunarcap: interrupted; finished {unit} are in the table, run the same "
                   "command again to resume"]


@pytest.mark.slow
@pytest.mark.parametrize("argv, expect", [
    (["burns", "song2011-150N", "--counts", "1,2"],
     ["N = 2: total dV", "burn 1: ellipse", "burn 2: circle", "table: "]),
    (["missed", "song2011-150N", "--fractions", "0.5", "--delays-min", "0", "--late-min", "5"],
     ["cut-off", "late ignition", "recovered", "nominal: burns 1..3 need"]),
    (["dispersions", "song2011-150N", "--samples", "2", "--thrust-sigma-pct", "1"],
     ["99 % budget: not estimated (2 samples; its distribution-free 95 % interval needs "
      "368)", "99% | not estimated: its interval needs 368 samples, this run has 2",
      "mean above nominal (captured samples, burns and trim):", "correction failed: 0", "table: "]),
])
def test_study_text_output_names_each_burn(argv, expect, tmp_path, capsys, monkeypatch):
    """The studies' plain-text report (not --json), two-body: exit 0, every line written.

    ``burns`` raised KeyError on each burn's line once its JSON key became
    ``target_orbit``; the JSON tests did not see it.
    """
    monkeypatch.setenv("LUNARCAP_NO_CACHE", "1")
    code = main(argv + ["--dynamics", "two-body", "--workers", "1", "--no-progress",
                        "--out", str(tmp_path / "t.csv")])
    out = capsys.readouterr().out
    assert code == 0, out
    for text in expect:
        assert text in out, (text, out)
