"""Refuse before working (issue 24): an export directory that cannot be written and a UTC
epoch that does not exist get one line, exit status 2, before any solve.

Each case runs as a real ``python -m lunarcap`` process with its own empty cache
directory (``LUNARCAP_CACHE_DIR``). "No solve started" is shown three ways: nothing on
stdout (the plan's header and every burn's progress line are printed before and during the
solves) and no cache entry written.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

from lunarcap.mission.plan import PLAN_DIR, load_plan

PLAN = ["two-burn-8h", "--dynamics", "two-body"]


def _run(argv: list, tmp_path: Path):
    cache = tmp_path / "cache"
    r = subprocess.run([sys.executable, "-m", "lunarcap", *argv], capture_output=True,
                       text=True, timeout=600, cwd=tmp_path,
                       env=dict(os.environ, LUNARCAP_CACHE_DIR=str(cache)))
    return r, cache


def _refused_before_any_solve(r, cache: Path) -> str:
    """The one stderr line of a refusal; asserts exit 2 and that nothing was solved."""
    assert r.returncode == 2, r.stderr
    assert r.stdout == "", r.stdout
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lunarcap: error: "), r.stderr
    assert not cache.exists() or not any(p.is_file() for p in cache.rglob("*")), \
        sorted(cache.rglob("*"))
    return lines[0]


def _cannot_create_a_file_in(d: Path) -> bool:
    try:
        fd = os.open(d / f".lunarcap-test-{os.getpid()}", os.O_CREAT | os.O_EXCL | os.O_WRONLY)
    except OSError:
        return True
    os.close(fd)
    os.unlink(d / f".lunarcap-test-{os.getpid()}")
    return False


def _unwritable_dir(tmp_path: Path) -> Path | None:
    """An existing directory in which this process truly cannot create a file, or None.

    As root, permissions do not stop a write: a read-only mount (/sys in a container)
    does; otherwise a directory made read-only here.
    """
    ro = tmp_path / "read-only"
    ro.mkdir()
    ro.chmod(0o555)
    for d in (ro, Path("/sys"), Path("/sys/fs")):
        if d.is_dir() and _cannot_create_a_file_in(d):
            return d
    return None


@pytest.mark.parametrize("where", ["a file", "under a file", "unwritable"])
def test_export_to_a_directory_that_cannot_be_written_is_refused_first(tmp_path, where):
    blocker = tmp_path / "notes.txt"
    blocker.write_text("a file where a directory is asked\n")
    if where == "a file":
        out, reason = blocker, f"{blocker} is a file, not a directory"
    elif where == "under a file":
        out, reason = blocker / "export", f"{blocker} is a file, not a directory"
    else:
        d = _unwritable_dir(tmp_path)
        if d is None:
            pytest.skip("no directory here refuses a new file to this user")
        out = d if d.name == "read-only" else d / "export"
        reason = ("Permission denied", "Operation not permitted", "Read-only file system")
    r, cache = _run(["plan", *PLAN, "--export", str(out)], tmp_path)
    line = _refused_before_any_solve(r, cache)
    assert line.startswith(f"lunarcap: error: --export {out}: cannot write files there ("), line
    assert any(w in line for w in ((reason,) if isinstance(reason, str) else reason)), line
    assert "Traceback" not in r.stderr


def _plan_with_epoch(tmp_path: Path, epoch: str) -> Path:
    d = yaml.safe_load((PLAN_DIR / "two-burn-8h.yaml").read_text())
    d["arrival"]["epoch"] = epoch
    f = tmp_path / "mine.yaml"
    f.write_text(yaml.safe_dump(d))
    return f


@pytest.mark.parametrize("command", ["plan", "burns", "missed", "dispersions"])
def test_a_utc_second_that_does_not_exist_is_refused_at_load(tmp_path, command):
    # 2026-11-03 ends without a leap second: 23:59:60 was read as 2026-11-04 00:00:00
    f = _plan_with_epoch(tmp_path, "2026-11-03 23:59:60.000 UTC")
    r, cache = _run([command, str(f), "--dynamics", "two-body"], tmp_path)
    line = _refused_before_any_solve(r, cache)
    assert line == ("lunarcap: error: plan mine.yaml: arrival.epoch: epoch '2026-11-03 "
                    "23:59:60.000 UTC' does not exist: 2026-11-03 ends at 23:59:59.999... UTC "
                    "(no leap second that day in IERS's table, valid to "
                    f"{_expires()})"), line


def _expires() -> str:
    from lunarcap.physics.epochs import leap_second_table

    return leap_second_table()["expires"]


def test_hour_24_is_refused_at_load(tmp_path):
    f = _plan_with_epoch(tmp_path, "2026-11-03 24:00:00 UTC")
    r, cache = _run(["plan", str(f)], tmp_path)
    line = _refused_before_any_solve(r, cache)
    assert line.endswith("arrival.epoch: epoch '2026-11-03 24:00:00 UTC' does not exist: its "
                         "hour 24 is not in 00-23"), line


def test_a_real_leap_second_is_an_arrival(tmp_path):
    # 2016-12-31 23:59:60 UTC exists: the plan loads, one second after 23:59:59
    a, b = (load_plan(_plan_with_epoch(tmp_path, f"2016-12-31 23:59:{s} UTC"))
            for s in ("59", "60"))
    assert b.nominal_perilunes_s[0] - a.nominal_perilunes_s[0] == pytest.approx(1.0, abs=2e-6)
