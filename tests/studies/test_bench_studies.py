"""``lunarcap bench --studies`` prints figures (no timing is asserted): its parts run."""

import json

import pytest

from lunarcap.repro import paths
from lunarcap.studies import bench


def test_nlp_builds_reports_each_shape_built_then_loaded():
    lines = []
    rows = bench.nlp_builds("two-body", out=lines.append)
    assert len(rows) == 4 and len(lines) == 5
    assert all(r["build_s"] > 0 and r["hess_l_instructions"] > 0 for r in rows)
    # each shape built in the empty store, then loaded from it (a file per shape)
    assert all(r["loaded"] and r["load_s"] > 0 and r["stored_kB"] > 10 for r in rows)
    # a free start adds the pre-ignition coast: more variables, a larger Hessian
    assert rows[1]["n_vars"] > rows[0]["n_vars"]
    assert rows[1]["hess_l_instructions"] > rows[0]["hess_l_instructions"]


@pytest.mark.slow
def test_derivative_options_solve_to_the_same_optimum():
    """CasADi's AD of the expanded NLP and the node-by-node assembly (in the virtual
    machine, and compiled) are the same exact derivatives: from the same guess IPOPT takes
    the same number of iterations to the same optimum (within 1e-6 m/s; the gate's
    tolerance is 0.01 m/s)."""
    rows = bench.derivative_options(out=lambda line: None)
    assert len(rows) >= 2
    assert len({r["iterations"] for r in rows}) == 1, rows
    dv = [r["delta_v_mps"] for r in rows]
    assert max(dv) - min(dv) < 1e-6 and abs(dv[0] - 367.4) < 2.0, rows


def test_study_walls_reads_the_run_logs(tmp_path, monkeypatch):
    monkeypatch.setattr(paths, "CACHE", tmp_path)
    lines = []
    assert bench.study_walls(out=lines.append) == []
    assert "no study run recorded" in lines[-1]
    (tmp_path / "study").mkdir()
    log = {"started_utc": "2026-11-25 12:00:00 UTC", "wall_s": 218.0, "cases": 90,
           "computed": 90, "reused": 0, "workers": 2}
    (tmp_path / "study" / "engine_trade.runs.json").write_text(json.dumps([log]))
    lines.clear()
    rows = bench.study_walls(out=lines.append)
    assert [r["wall_s"] for r in rows] == [218.0]
    assert "engine_trade" in lines[0] and "218.0 s" in lines[0]


def test_engine_profile_counts_the_solves_it_times():
    """The profile wraps the solver without changing what it solves: every burn of the
    engine is solved through the wrapper (three LOIs and their impulsive limits), so the
    solves and IPOPT iterations it reports are those of a real, successful study engine."""
    lines = []
    (row,) = bench.engine_profile(engines=((300.0, 250.0),), dynamics="two-body",
                                  out=lines.append)
    assert row["solves"] >= 6 and row["iterations"] > row["solves"], row
    assert 0 < row["ipopt_s"] < row["wall_s"]
