"""One cache switch that every path honours (issue 17, deliverable 2).

``lunarcap plan --no-cache`` turns :func:`lunarcap.repro.cache.caching` off for the whole
command. A burn's earlier burns are solved through the same cached function as the burn
itself (:func:`lunarcap.capture.chain.perilune_epoch_state`), so with the switch off every
burn must be recomputed, each once, and the disk cache neither read nor written. Before
the switch, ``--no-cache`` called ``solve_burn.uncached`` for the last burn only and read
the earlier burns from the cache. Broken on purpose, the test fails: with the cached
wrapper ignoring the switch (0 solves with --no-cache, all read from disk), and without
the in-run memo of earlier burns (5 solves: burns 1 and 2 solved again for later burns).
"""

import json

import joblib
import pytest

from lunarcap import cli
from lunarcap.capture import chain
from lunarcap.repro import cache

pytestmark = pytest.mark.slow

#: A two-body three-burn capture (the paper's 450 N engine): three quick solves.
ARGS = ["plan", "song2011-450N", "--dynamics", "two-body", "--no-impulsive", "--quiet",
        "--json"]


def _files(path) -> set:
    return {p.relative_to(path) for p in path.rglob("*") if p.is_file()}


def _count_solves(monkeypatch) -> list:
    calls = []
    real = chain.solve_burn_problem

    def counting(prob, *args, **kwargs):
        calls.append(prob)
        return real(prob, *args, **kwargs)

    monkeypatch.setattr(chain, "solve_burn_problem", counting)
    return calls


def test_no_cache_recomputes_every_burn_once_and_touches_no_cache(tmp_path, monkeypatch,
                                                                  capsys):
    monkeypatch.delenv("LUNARCAP_NO_CACHE", raising=False)
    monkeypatch.setattr(cache, "memory", joblib.Memory(str(tmp_path), verbose=0))
    calls = _count_solves(monkeypatch)
    assert cli.main(ARGS) == 0                     # cache on: solved and stored
    cached_run = json.loads(capsys.readouterr().out)
    assert len(calls) == 3
    stored = _files(tmp_path)
    assert stored, "the cached run stored nothing"

    calls.clear()
    assert cli.main(ARGS) == 0                     # cache on again: nothing solved
    assert calls == []
    capsys.readouterr()

    reads = []
    real_get = cache.get_memory
    monkeypatch.setattr(cache, "get_memory", lambda: reads.append(1) or real_get())
    assert cli.main(ARGS + ["--no-cache"]) == 0    # switch off: every burn, once each
    fresh = json.loads(capsys.readouterr().out)
    assert len(calls) == 3, f"{len(calls)} burn solves with --no-cache, expected 3"
    assert reads == [], "the disk cache was opened with --no-cache"
    assert _files(tmp_path) == stored, "--no-cache wrote to the cache directory"
    assert [b["delta_v_mps"] for b in fresh["burns"]] == pytest.approx(
        [b["delta_v_mps"] for b in cached_run["burns"]], abs=1e-6)
    assert cache.enabled()                         # the switch is restored after the command


def test_switch_is_restored_and_nests():
    assert cache.position(None) == cache.enabled()
    with cache.caching(False):
        assert not cache.enabled() and cache.location() is None
        with cache.caching(True):
            assert cache.enabled()
        assert not cache.enabled()
        with pytest.raises(ZeroDivisionError):
            with cache.caching(True):
                1 / 0
        assert not cache.enabled()
