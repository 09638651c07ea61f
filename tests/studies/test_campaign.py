"""The studies' shared machinery (lunarcap.studies.campaign) and the distributed path.

* A table path that cannot be written is one InputError before any work, for each study
  (a file where a directory should be; a directory of /proc, where nothing can be made).
* The distributed path: a real ``dask scheduler`` and ``dask worker`` (the shared venv's
  commands) on 127.0.0.1, started here; the burns and missed-thrust studies run through
  them give the same numbers, bit for bit, as through the default local cluster (both with
  the disk cache off, so each solves afresh).
"""

import os
from pathlib import Path

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.mission.plan import load_plan
from lunarcap.studies import campaign
from lunarcap.studies.burn_count import counts as burns
from lunarcap.studies.engine_trade import trade as study
from lunarcap.studies.missed import cases as missed


def _bad_paths(tmp_path):
    blocker = tmp_path / "a_file"
    blocker.write_text("not a directory")
    return [blocker / "table.csv", Path("/proc/lunarcap-test/table.csv")]


def test_unwritable_table_paths_are_input_errors_before_any_work(tmp_path):
    plan = load_plan("song2011-150N").with_dynamics("two-body")
    never = lambda *a: pytest.fail("a case ran")  # noqa: E731
    for bad in _bad_paths(tmp_path):
        with pytest.raises(InputError, match="cannot write"):
            campaign.check_output_path(bad)
        with pytest.raises(InputError, match="cannot write"):
            burns.run_burns([plan], "1", out=bad, task=never, progress=False)
        with pytest.raises(InputError, match="cannot write"):
            missed.run_missed(plan, 1, "0.5", "0", out=bad, task=never, progress=False)
        with pytest.raises(InputError, match="cannot write"):
            study.run_study(study.StudySpec(100, 200, 2, (250,), "two-body"), out=bad,
                            task=never, progress=False)
    assert campaign.check_output_path(tmp_path / "new" / "t.csv") == tmp_path / "new" / "t.csv"


NUMBERS_BURNS = ["total_delta_v_mps", "total_impulsive_limit_mps", "total_fuel_kg",
                 "time_to_final_orbit_h"]
NUMBERS_MISSED = ["partial_delta_v_mps", "cutoff_e", "recovery_delta_v_mps", "penalty_mps"]


@pytest.mark.slow
def test_distributed_path_gives_the_local_numbers(dask_cluster, tmp_path, monkeypatch):
    monkeypatch.setenv("LUNARCAP_NO_CACHE", "1")
    plan = load_plan("song2011-150N").with_dynamics("two-body").with_engine(450.0, 300.0)
    remote = burns.run_burns([plan], "1,2", out=tmp_path / "remote.csv",
                             scheduler=dask_cluster, progress=False)
    local = burns.run_burns([plan], "1,2", out=tmp_path / "local.csv", workers=1,
                            progress=False)
    assert remote.run["scheduler"] == dask_cluster and local.run["scheduler"] == "LocalCluster"
    assert list(remote.table.status) == ["ok", "ok"]
    np.testing.assert_array_equal(remote.table[NUMBERS_BURNS].to_numpy(float),
                                  local.table[NUMBERS_BURNS].to_numpy(float))
    assert list(remote.table.periods_h) == list(local.table.periods_h)
    # the rows were computed in other processes: the scheduler's worker and a local one
    assert remote.table.worker.iloc[0] != local.table.worker.iloc[0]
    remote = missed.run_missed(plan, 1, "0.5", "0", out=tmp_path / "mr.csv",
                               scheduler=dask_cluster, progress=False)
    local = missed.run_missed(plan, 1, "0.5", "0", out=tmp_path / "ml.csv", workers=1,
                              progress=False)
    assert list(remote.table.status) == ["recovered"]
    np.testing.assert_array_equal(remote.table[NUMBERS_MISSED].to_numpy(float),
                                  local.table[NUMBERS_MISSED].to_numpy(float))



def test_a_table_of_other_columns_is_rewritten_not_corrupted(tmp_path):
    fmt_old = campaign.TableFormat(("k",), ("k", "a", "status", "code_version"))
    fmt_new = campaign.TableFormat(("k",), ("k", "a", "b", "status", "code_version"))
    path = tmp_path / "t.csv"
    campaign.append_rows(path, [{"k": 1, "a": 2.0, "status": "ok", "code_version": "v"}],
                         fmt_old.columns)
    campaign.append_rows(path, [{"k": 2, "a": 3.0, "b": 4.0, "status": "ok",
                                 "code_version": "v"}], fmt_new.columns)
    t = campaign.read_table(path, fmt_new)
    assert list(t.k) == [1, 2] and list(t.a) == [2.0, 3.0]
    assert np.isnan(t.b.iloc[0]) and t.b.iloc[1] == 4.0


def test_guarded_turns_a_bug_into_a_row_and_restores_the_cache_setting(monkeypatch):
    from lunarcap.repro import cache

    monkeypatch.delenv("LUNARCAP_NO_CACHE", raising=False)
    env = dict(os.environ)
    seen = []
    r, err = campaign.guarded(lambda: seen.append(cache.location()) or 7, use_cache=False)
    assert (r, err) == (7, None) and seen == [None]       # no disk cache inside the call
    assert cache.enabled() and dict(os.environ) == env    # restored, environment untouched
    r, err = campaign.guarded(lambda: 1 / 0, use_cache=False)
    assert r is None and err == {"status": "error", "error": "ZeroDivisionError: division by zero"}
    assert cache.enabled() and dict(os.environ) == env
    with cache.caching(False):   # None ships the submitting thread's position
        r, _ = campaign.guarded(lambda: cache.enabled())
    assert r is False


#: Calls of the fake burns task below: (n_burns, the cache switch's position in the task).
FAKE_CALLS = []


def _fake_count_row(plan, n, max_period_h, max_days):
    from lunarcap.repro.cache import enabled

    FAKE_CALLS.append((n, enabled()))
    return {"status": "ok", "reason": "", "total_delta_v_mps": 800.0 + n + len(FAKE_CALLS),
            "error": ""}


def test_no_cache_after_an_interrupted_study_replaces_rows_not_duplicates(tmp_path,
                                                                         monkeypatch):
    plan = load_plan("song2011-150N").with_dynamics("two-body")
    out = tmp_path / "burns.csv"
    real = campaign._compute

    def compute_then_ctrl_c(client, task, todo, *args):
        real(client, task, todo[:2], *args)  # counts 1 and 2 finish, then Ctrl-C
        raise KeyboardInterrupt

    kw = dict(out=out, task=_fake_count_row, progress=False, processes=False, workers=1)
    monkeypatch.setattr(campaign, "_compute", compute_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        burns.run_burns([plan], "1,2,3", **kw)
    monkeypatch.setattr(campaign, "_compute", real)
    before = burns.STUDY.table
    assert len(campaign.read_table(out, before)) == 2
    FAKE_CALLS.clear()
    res = burns.run_burns([plan], "1,2,3", use_cache=False, **kw)  # --no-cache
    assert sorted(FAKE_CALLS) == [(1, False), (2, False), (3, False)]
    table = campaign.read_table(out, before)
    assert sorted(table.n_burns) == [1, 2, 3], table[["n_burns", "total_delta_v_mps"]]
    # each row is the recomputed one (its value counts this run's calls, 1 to 3)
    new = dict(zip(res.table.n_burns, res.table.total_delta_v_mps))
    assert dict(zip(table.n_burns, table.total_delta_v_mps)) == new
    assert all(v - 800.0 - n in (1, 2, 3) for n, v in new.items()), new
    # a row of another code version is history, not a duplicate: kept
    text = out.read_text().splitlines()
    old = text[1].replace(res.table.code_version.iloc[0], "older-version")
    out.write_text("\n".join([text[0], old, *text[1:]]) + "\n")
    burns.run_burns([plan], "1,2,3", use_cache=False, **kw)
    table = campaign.read_table(out, before)
    assert len(table) == 4 and list(table.code_version).count("older-version") == 1


def test_a_campaign_uses_the_scheduler_the_environment_names_longest_cases_first(
        tmp_path, monkeypatch):
    """The book's shared cluster (LUNARCAP_DASK_SCHEDULER) and the burns study's order.

    Without ``scheduler``, a campaign joins the cluster the environment variable names
    instead of starting its own; the burns study submits its cases most burns first, so
    a worker does not end the study on the longest one (one worker thread here: the cases
    run in the order they were submitted). The table keeps the order of the counts.
    """
    from dask.distributed import LocalCluster

    plan = load_plan("song2011-150N").with_dynamics("two-body")
    kw = dict(task=_fake_count_row, progress=False, processes=False, workers=1)
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                      dashboard_address=None) as cluster:
        monkeypatch.setenv(campaign.SCHEDULER_ENV, cluster.scheduler_address)
        FAKE_CALLS.clear()
        res = burns.run_burns([plan], "1,2,3", out=tmp_path / "shared.csv", **kw)
    assert res.run["scheduler"] == cluster.scheduler_address
    assert [n for n, _ in FAKE_CALLS] == [3, 2, 1]
    assert list(res.table.n_burns) == [1, 2, 3]
    monkeypatch.delenv(campaign.SCHEDULER_ENV)
    res = burns.run_burns([plan], "1", out=tmp_path / "own.csv", **kw)
    assert res.run["scheduler"] == "LocalCluster"


def test_cases_of_one_nlp_shape_go_to_one_worker_balanced_by_their_cost():
    """assign_workers: a group (same NLP shapes) on one worker; groups, largest first,
    each to the least loaded worker; without affinity or with one worker, anywhere."""

    class Client:
        def __init__(self, *addrs):
            self.addrs = addrs

        def scheduler_info(self):
            return {"workers": {a: {} for a in self.addrs}}

    todo = [({"plan": p, "n_burns": n, "dynamics": "full"}, ()) for p in "ab"
            for n in (1, 2, 3, 4, 5)]
    where = campaign.assign_workers(Client("tcp://w2", "tcp://w1"), todo,
                                    burns._nlp_shapes, lambda k: k["n_burns"])
    home = {}
    for (key, _), addr in zip(todo, where):
        assert home.setdefault(key["n_burns"], addr) == addr  # both plans' n: one worker
    # costs 10 (n=5), 8, 6, 4, 2: w1 takes 5, w2 4 and 3, then w1 2 and 1 (load 16 / 14)
    assert home == {5: "tcp://w1", 4: "tcp://w2", 3: "tcp://w2", 2: "tcp://w1",
                    1: "tcp://w1"}
    assert campaign.assign_workers(Client("tcp://w1", "tcp://w2"), todo) == [None] * 10
    assert campaign.assign_workers(Client("tcp://w1"), todo, burns._nlp_shapes) == \
        [None] * 10


def _one_row(plan, n, *rest):
    """A burns-study task that solves nothing: one infeasible row (fast)."""
    return {"status": "infeasible", "reason": "test", "n_burns": n}


def test_a_stale_table_in_the_cache_is_set_aside_one_elsewhere_refused(tmp_path, monkeypatch,
                                                                        capfd):
    """A study table written by an older lunarcap (its cases had other key columns).

    In lunarcap's cache (the book's tables) it is renamed beside itself and the study
    runs; given by the user as --out elsewhere it is refused, untouched.
    """
    plan = load_plan("song2011-150N").with_dynamics("two-body")
    stale = "plan,status,code_version\nsong2011-150N,ok,old\n"
    cache_dir = tmp_path / "cache"
    monkeypatch.setattr(campaign.paths, "CACHE", cache_dir)
    mine = cache_dir / "study" / "burn_count.csv"
    mine.parent.mkdir(parents=True)
    mine.write_text(stale)
    res = burns.run_burns([plan], "1", out=mine, task=_one_row, progress=False, workers=1,
                          processes=False)
    assert list(res.table.status) == ["infeasible"]
    kept = list(mine.parent.glob("burn_count.stale-*.csv"))
    assert len(kept) == 1 and kept[0].read_text() == stale
    assert "written by an older lunarcap" in capfd.readouterr().err
    theirs = tmp_path / "mine.csv"
    theirs.write_text(stale)
    with pytest.raises(InputError, match="is not a table of this study"):
        burns.run_burns([plan], "1", out=theirs, task=_one_row, progress=False, workers=1,
                        processes=False)
    assert theirs.read_text() == stale
