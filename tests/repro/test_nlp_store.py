"""The NLP store: NLPs built once per machine, loaded by every later process.

Each test runs fresh processes on a store of its own (``LUNARCAP_CACHE_DIR``): the first
builds the NLP of the first burn of a plan and solves it, a later one must load it (its
build time reported as a load) and give the same solution bit for bit; a change of the
code's version builds again; a damaged file is built again with one line on stderr;
two processes asking at once for a shape nobody built: one builds, the other waits and
loads it.
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from lunarcap.repro.cache import NLPStore

ROOT = Path(__file__).resolve().parents[2]

#: Solve the first burn of a plan (two-body dynamics unless told) on the first mesh and
#: print what the test compares: where the NLP came from, the solution's bits.
SCRIPT = textwrap.dedent("""
    import json, sys
    import lunarcap.capture.chain as chain   # installs the machine's NLP store
    from lunarcap.optim import nlp as N
    from lunarcap.optim.collocation import Mesh
    from lunarcap.optim.guess import make_guess
    from lunarcap.optim.problem import burn_problem
    from lunarcap.studies.families import plan_of
    from lunarcap.mission.plan import load_plan
    if sys.argv[2] == "other-version":
        import lunarcap.repro.cache as cache
        cache.code_version = lambda *a, **k: "0123456789abcdef"
    if sys.argv[1] == "family":
        plan = plan_of([{"target_period_h": 6.0, "start_min": "free"},
                        {"target": "circular", "start_min": "free"}], inclination=35.0,
                       thrust=260.0, mass=900.0)
    else:
        plan = load_plan(sys.argv[1]).with_dynamics("two-body")
    arrival = chain.arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole)
    prob = burn_problem(plan, 0, arrival.state, plan.ephemeris_model())
    raw = N.solve_nlp(prob, Mesh(8, 16, 5), make_guess(prob))
    nlp = N.nlp_for(prob, Mesh(8, 16, 5))
    print(json.dumps({"origin": nlp.compiled.origin, "build_s": nlp.compiled.build_s,
                      "derivatives": nlp.compiled.derivatives, "status": raw.status,
                      "w": raw.w.tobytes().hex(), "delta_v_mps": raw.delta_v_mps}))
""")


def _solve(store: Path, plan="song2011-150N", version="this", background=False):
    env = dict(os.environ, LUNARCAP_CACHE_DIR=str(store), PYTHONPATH=str(ROOT))
    env.pop("LUNARCAP_NLP_CACHE", None)
    cmd = [sys.executable, "-c", SCRIPT, plan, version]
    if background:
        return subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                text=True)
    r = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return json.loads(r.stdout.splitlines()[-1]), r.stderr


def _files(store: Path) -> list:
    return sorted(store.glob("nlp/*/*.nlp"))


@pytest.mark.parametrize("plan", ["song2011-150N", "family"])
def test_a_later_process_loads_the_nlp_and_solves_bit_for_bit(tmp_path, plan):
    first, _ = _solve(tmp_path, plan)
    assert first["origin"] == "built" and first["status"] == "Solve_Succeeded"
    assert len(_files(tmp_path)) == 1
    second, err = _solve(tmp_path, plan)
    assert second["origin"] == "loaded" and 0 < second["build_s"] < 30
    assert second["w"] == first["w"] and second["delta_v_mps"] == first["delta_v_mps"]
    assert second["derivatives"] == first["derivatives"] != "CasADi's"
    assert "lunarcap:" not in err, err


def test_another_code_version_builds_again(tmp_path):
    first, _ = _solve(tmp_path)
    other, _ = _solve(tmp_path, version="other-version")
    assert other["origin"] == "built" and other["w"] == first["w"]
    assert len(_files(tmp_path)) == 2   # one per version, each in its folder
    again, _ = _solve(tmp_path)
    assert again["origin"] == "loaded"


@pytest.mark.parametrize("damage", ["truncated", "garbage with a valid checksum",
                                    "node library truncated"])
def test_a_damaged_file_is_built_again_with_one_line(tmp_path, damage):
    import hashlib
    import zlib

    first, _ = _solve(tmp_path)
    (path,) = _files(tmp_path)
    raw = path.read_bytes()
    if damage == "truncated":
        path.write_bytes(raw[: len(raw) // 2])
    elif damage == "garbage with a valid checksum":   # no NLP inside
        body = zlib.compress(b"not an NLP")
        path.write_bytes(hashlib.sha256(body).hexdigest().encode() + body)
    else:   # the NLP refers to a compiled node function that no longer loads
        libs = sorted(tmp_path.glob("nlp/nodes/*.so"))
        if not libs:
            pytest.skip("no C compiler: no node library")
        for lib in libs:
            lib.write_bytes(lib.read_bytes()[:100])
    second, err = _solve(tmp_path)
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert second["origin"] == "built" and second["w"] == first["w"]
    assert len(lines) == 1 and lines[0].startswith("lunarcap: the stored NLP") and \
        "is unreadable" in lines[0] and "building it again" in lines[0], err
    third, err3 = _solve(tmp_path)
    assert third["origin"] == "loaded" and not err3.strip()


def test_two_processes_at_once_build_one_nlp(tmp_path):
    procs = [_solve(tmp_path, background=True) for _ in range(2)]
    outs = []
    for p in procs:
        out, err = p.communicate(timeout=600)
        assert p.returncode == 0, err
        outs.append(json.loads(out.splitlines()[-1]))
    assert sorted(o["origin"] for o in outs) == ["built", "loaded"]
    assert outs[0]["w"] == outs[1]["w"]
    assert len(_files(tmp_path)) == 1 and not list(tmp_path.glob("nlp/*/.*.tmp*"))


def test_store_round_trip_and_refusals(tmp_path, capfd):
    store = NLPStore(tmp_path)
    parts = ("burn", "shape", "3.8.2", "vm")
    assert store.load(parts, bytes) is None
    path = store.save(parts, b"payload")
    assert path == store.path(parts) and store.load(parts, bytes) == b"payload"
    assert store.load(("burn", "other shape", "3.8.2", "vm"), bytes) is None

    def refuse(data):
        raise RuntimeError("deserialization failed\nsecond line")

    assert store.load(parts, refuse) is None and not path.exists()
    err = capfd.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "(deserialization failed)" in err[0]


def test_the_store_keeps_the_newest_code_versions(tmp_path, monkeypatch):
    import lunarcap.repro.cache as cache

    store = NLPStore(tmp_path)
    for k in range(cache.NLP_VERSIONS_KEPT + 2):
        monkeypatch.setattr(cache, "code_version", lambda *a, k=k, **kw: f"v{k:015d}")
        store.save(("burn", "shape"), b"x")
        os.utime(store.path(("burn", "shape")).parent, (1e9 + k, 1e9 + k))
    left = sorted(f.name for f in tmp_path.iterdir() if f.is_dir())
    assert left == [f"v{k:015d}" for k in range(2, cache.NLP_VERSIONS_KEPT + 2)]
    assert store.load(("burn", "shape"), bytes) == b"x"   # the current version's file
