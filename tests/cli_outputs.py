"""The ``--json`` outputs and CSV tables of the cheap command lines (two-body dynamics).

Shared by tests/test_glossary.py and tests/test_json_schemas.py: each command runs once
per test session (a real ``python -m lunarcap`` process, the solves cached on disk as in
any run), the 450 N engine in two-body dynamics so that every solve takes about a second.
"""

from __future__ import annotations

import functools
import json
import subprocess
import sys
import tempfile
from pathlib import Path

PLAN = ["song2011-450N", "--dynamics", "two-body"]
STUDY = ["--workers", "1", "--no-progress", "--json"]

#: command -> (arguments, CSV table written or None)
COMMANDS = {
    "impulsive": (["impulsive", "--json"], None),
    "solve": (["solve", "--thrust", "450", "--isp", "300", "--burn", "1", "--start", "-3",
               "--dynamics", "two-body", "--json", "--quiet"], None),
    "plan": (["plan", *PLAN, "--json", "--quiet"], None),
    "burns": (["burns", *PLAN, "--counts", "1,2", *STUDY], "burns.csv"),
    "missed": (["missed", *PLAN, "--burn", "1", "--fractions", "0.5", *STUDY], "missed.csv"),
    "dispersions": (["dispersions", *PLAN, "--samples", "2", "--thrust-sigma-pct", "1",
                     *STUDY], "dispersions.csv"),
}


@functools.lru_cache(maxsize=None)
def _dir() -> Path:
    return Path(tempfile.mkdtemp(prefix="lunarcap-cli-outputs-"))


def _run(command: str) -> subprocess.Popen:
    args, csv = COMMANDS[command]
    extra = ["--out", str(_dir() / csv)] if csv else []
    return subprocess.Popen([sys.executable, "-m", "lunarcap", *args, *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


@functools.lru_cache(maxsize=None)
def outputs() -> dict:
    """``{command: (parsed JSON, CSV path or None)}``, the commands run two at a time."""
    out, names = {}, list(COMMANDS)
    for i in range(0, len(names), 2):
        procs = {n: _run(n) for n in names[i:i + 2]}
        for n, p in procs.items():
            stdout, stderr = p.communicate(timeout=900)
            assert p.returncode == 0, f"lunarcap {n} failed ({p.returncode}): {stderr[-2000:]}"
            csv = COMMANDS[n][1]
            out[n] = (json.loads(stdout), _dir() / csv if csv else None)
    return out


def keys(obj, acc: set | None = None) -> set:
    """Every key of every object nested in ``obj``."""
    acc = set() if acc is None else acc
    if isinstance(obj, dict):
        for k, v in obj.items():
            acc.add(k)
            keys(v, acc)
    elif isinstance(obj, list):
        for v in obj:
            keys(v, acc)
    return acc
