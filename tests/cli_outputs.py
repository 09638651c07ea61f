"""The ``--json`` outputs and CSV tables of the command lines, for three kinds of plan.

Shared by tests/test_glossary.py and tests/test_json_schemas.py: each command runs once
per plan and test session (a real ``python -m lunarcap`` process, the solves cached on
disk as in any run), in two-body dynamics and with few cases so that each takes seconds:

* ``song2011-450N``: the paper's formulation, fixed ignitions, the 450 N engine;
* ``two-burn-8h``: the packaged plan, free ignitions, an 8 h ellipse then the circle;
* ``state-arrival``: an arrival given as a state (the paper's hyperbola 2 h before its
  perilune, UTC, ICRF), 450 N / 300 s, free ignitions, into a 100 x 300 km ellipse given
  by both altitudes.
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

#: command -> (arguments, CSV table written or None), for the paper's 450 N plan
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

#: The plans whose outputs are checked (see the module docstring).
PLANS = ("song2011-450N", "two-burn-8h", "state-arrival")


@functools.lru_cache(maxsize=None)
def _dir() -> Path:
    return Path(tempfile.mkdtemp(prefix="lunarcap-cli-outputs-"))


def _state_arrival_plan() -> Path:
    """A plan file whose arrival is a state (written once per session)."""
    import numpy as np
    import yaml

    from lunarcap.mission.arrival import arrival_state
    from lunarcap.mission.scenario import paper_scenario
    from lunarcap.physics import constants as C
    from lunarcap.physics.dynamics import Model
    from lunarcap.physics.elements import rv_from_mee
    from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
    from lunarcap.physics.frames import icrf_from_mme
    from lunarcap.physics.propagate import propagate

    path = _dir() / "state-arrival.yaml"
    if path.exists():
        return path
    arr, t_peri = arrival_state(), seconds_from_calendar(paper_scenario().epoch_tdb)
    t0 = t_peri - 2 * 3600.0
    x0 = propagate(Model("two-body", 0.0, 300.0, None), t_peri,
                   np.concatenate([arr.mee, [arr.mass_kg]]), t0).final
    r, v = (icrf_from_mme(np.array(q)) for q in rv_from_mee(*x0[:6], C.MU_MOON))
    plan = {"name": "state-arrival",
            "arrival": {"epoch": calendar_from_seconds(t0, 9, scale="UTC"), "frame": "ICRF",
                        "position_km": [float(q) for q in r],
                        "velocity_kmps": [float(q) for q in v], "mass_kg": 524.895},
            "engine": {"thrust_N": 450, "isp_s": 300}, "dynamics": "two-body",
            "burns": [{"target_period_h": 8, "start_min": "free"},
                      {"target": {"perilune_altitude_km": 100, "apolune_altitude_km": 300},
                       "start_min": "free"}]}
    path.write_text(yaml.safe_dump(plan, sort_keys=False), encoding="utf-8")
    return path


def commands(plan: str = "song2011-450N") -> dict:
    """``{command: (arguments, CSV table or None)}`` of one of :data:`PLANS`."""
    if plan == "song2011-450N":
        return COMMANDS
    p = ["two-burn-8h", "--dynamics", "two-body"] if plan == "two-burn-8h" else \
        [str(_state_arrival_plan())]
    csv = f"{plan}-{{}}.csv".format
    return {
        "impulsive": (["impulsive", "--plan", *p, "--json"], None),
        "solve": (["solve", "--plan", *p, "--burn", "2", "--json", "--quiet"], None),
        "plan": (["plan", *p, "--json", "--quiet"], None),
        "burns": (["burns", *p, "--counts", "2", *STUDY], csv("burns")),
        "missed": (["missed", *p, "--burn", "1", "--fractions", "0.5", "--delays-min", "0",
                    "--late-min", "1", *STUDY], csv("missed")),
        "dispersions": (["dispersions", *p, "--samples", "2", "--thrust-sigma-pct", "1",
                         *STUDY], csv("dispersions")),
    }


def _run(args: list, csv: str | None) -> subprocess.Popen:
    extra = ["--out", str(_dir() / csv)] if csv else []
    return subprocess.Popen([sys.executable, "-m", "lunarcap", *args, *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


@functools.lru_cache(maxsize=None)
def outputs(plan: str = "song2011-450N") -> dict:
    """``{command: (parsed JSON, CSV path or None)}`` of a plan, run two at a time."""
    cmds = commands(plan)
    out, names = {}, list(cmds)
    for i in range(0, len(names), 2):
        procs = {n: _run(*cmds[n]) for n in names[i:i + 2]}
        for n, p in procs.items():
            stdout, stderr = p.communicate(timeout=900)
            assert p.returncode == 0, \
                f"lunarcap {n} of {plan} failed ({p.returncode}): {stderr[-2000:]}"
            csv = cmds[n][1]
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
