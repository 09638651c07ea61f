"""One study shape (lunarcap.studies.study): every study declared once, run and reported by one
runner.

No solve: each study's declaration is checked against the glossary and itself, and the
command line's one runner (``lunarcap.cli.studies.run_study``) is given a finished campaign's
rows, to check the ``--json`` document, the text and the exit status it makes of them.
"""

import json
from types import SimpleNamespace

import pandas as pd
import pytest

from lunarcap import quantities as Q
from lunarcap.cli.studies import run_study
from lunarcap.mission.plan import load_plan
from lunarcap.studies.burn_count import counts as burns
from lunarcap.studies.dispersions import samples as dispersions
from lunarcap.studies.engine_trade import trade as study
from lunarcap.studies.missed import cases as missed
from lunarcap.studies.study import plan_columns, plan_id

STUDIES = {"burns": burns.STUDY, "missed": missed.STUDY, "dispersions": dispersions.STUDY,
           "engine_trade": study.STUDY}


@pytest.mark.parametrize("name", STUDIES)
def test_each_declaration_is_consistent_and_named_from_the_glossary(name):
    s = STUDIES[name]
    cols = set(s.table.columns)
    assert s.name == name and s.default_table_path().name == f"{name}.csv"
    assert set(s.table.key) <= cols and set(s.table.text_columns) <= cols
    assert {"status", "code_version"} <= cols
    assert set(s.ok_statuses) <= set(s.statuses)
    assert not Q.unknown(cols), Q.unknown(cols)
    for col, key, _ in s.decoders:
        assert col in cols and (key == col or key not in cols)


def test_a_plan_is_named_by_the_same_columns_in_every_plan_study():
    plan = load_plan("two-burn-8h")
    cols = plan_columns(plan)
    assert cols["plan_id"] == plan_id(plan) == plan_id(load_plan("two-burn-8h"))
    assert (cols["plan"], cols["thrust_N"], cols["isp_s"], cols["dynamics"]) == (
        plan.name, plan.engine.thrust_N, plan.engine.isp_s, plan.dynamics)
    assert plan_id(plan.with_engine(300.0, 280.0)) != cols["plan_id"]
    for s in (burns.STUDY, missed.STUDY, dispersions.STUDY):
        assert list(s.table.columns[:len(cols)]) == list(cols)


def _result(rows, columns):
    run = dict(computed=len(rows), reused=0, wall_s=1.5, scheduler="LocalCluster",
               workers=1, cache="off")
    return SimpleNamespace(table=pd.DataFrame(rows, columns=list(columns)), path="t.csv",
                           run=run)


def _burns_rows(second_status):
    base = dict.fromkeys(burns.STUDY.table.columns)
    one = dict(base, plan="p", n_burns=1, status="ok", reason="", periods_h="",
               burns_json=json.dumps([{"burn": 1, "delta_v_mps": 800.0}]))
    two = dict(base, plan="p", n_burns=2, status=second_status, reason="why not", error="",
               periods_h="8.000000", burns_json="")
    return [one, two]


@pytest.mark.parametrize("second, code", [("infeasible", 0), ("failed", 3), ("error", 3)])
def test_the_runner_exits_0_only_when_every_case_is_answered(second, code, capsys):
    res = _result(_burns_rows(second), burns.STUDY.table.columns)
    args = SimpleNamespace(json=True)
    assert run_study(args, burns.STUDY, lambda: res, {"plan": "p"}) == code
    doc = json.loads(capsys.readouterr().out)
    assert list(doc)[:3] == ["plan", "table", "run"] and list(doc)[-1] == "counts"
    first, other = doc["counts"]
    assert first["burns"] == [{"burn": 1, "delta_v_mps": 800.0}] and other["burns"] == []
    assert "burns_json" not in first
    assert first["periods_h"] == [] and other["periods_h"] == [8.0]
    # the decoded periods keep their place among the columns; the burns come last
    assert list(first).index("periods_h") == list(burns.STUDY.table.columns).index("periods_h")
    assert list(first)[-1] == "burns"


def test_the_runner_prints_the_studys_own_text_with_the_run_lines(capsys):
    row = dict.fromkeys(missed.STUDY.table.columns)
    row.update(contingency="late ignition", fraction=0.0, delay_min=0.0, late_min=5.0,
               cutoff_orbit="escape", cutoff_e=1.05, cutoff_ra_km=float("inf"),
               status="no recovery", reason="outside the sphere of influence", error="",
               max_period_h=12.0, nominal_remaining_delta_v_mps=800.0,
               nominal_burn_duration_min=15.0, nominal_time_to_final_orbit_h=20.0)
    res = _result([row], missed.STUDY.table.columns)
    plan = load_plan("song2011-150N")
    assert run_study(SimpleNamespace(json=False), missed.STUDY, lambda: res, {}, None,
                     plan=plan, burn=1) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert "no recovery: outside the sphere of influence" in lines[2]
    assert lines[-2].startswith("1 case(s) computed, 0 taken from the table; wall time 1.5 s")
    assert lines[-1] == "table: t.csv"


def test_ctrl_c_in_any_study_is_one_line_naming_its_cases(capsys):
    def interrupted():
        raise KeyboardInterrupt

    for s in STUDIES.values():
        assert run_study(SimpleNamespace(json=False), s, interrupted) == 130
        err = capsys.readouterr().err.strip().splitlines()
        assert err == [f"lunarcap: interrupted; finished {s.unit}s are in the table, run "
                       "the same command again to resume"]
