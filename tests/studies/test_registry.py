"""The studies' registry (lunarcap.studies.registry): a study is one file and one line.

A toy study, written here into a temporary package (one file, ``toy_study.py``, on
``sys.path``) and registered by one line added to ``registry.STUDIES``, must reach
everything a packaged study reaches without any other file touched: ``lunarcap --help``
lists it, ``lunarcap toy --help`` shows its options and the shared plan and Dask ones,
``lunarcap toy PLAN --json`` runs its trivial task on a generated two-body plan, and the
schema generated from the records it declares (its run key, its own quantities) validates
that output. The same file without the line reaches nothing.

The packaged studies' declarations are checked against their commands and schemas too.
"""

from __future__ import annotations

import importlib
import json
import sys
import textwrap
from pathlib import Path

import jsonschema
import pytest

from lunarcap import cli, schemas
from lunarcap import quantities as Q
from lunarcap.mission.plan import paper_plan
from lunarcap.studies import registry

TOY = '''
"""A toy study: the plan's two-body impulsive total scaled by each factor asked."""

from lunarcap.errors import number_list
from lunarcap.studies.campaign import TableFormat
from lunarcap.studies.registry import StudyCommand, StudyRun
from lunarcap.studies.study import Study, plan_columns

KEY = ("plan_id", "toy_factor")
COLUMNS = ("plan", "plan_id", "thrust_N", "isp_s", "dynamics", "toy_factor",
           "toy_scaled_delta_v_mps", "status", "error", "task_wall_s", "worker",
           "code_version", "completed_utc")


def scaled(total_mps, factor):
    return {"toy_scaled_delta_v_mps": total_mps * factor, "status": "ok"}


def text(result, plan):
    rows = result.table.to_dict("records")
    return "\\n".join([f"toy study of {plan.name}"] + [
        f"x{r['toy_factor']:g}: {r['toy_scaled_delta_v_mps']:.3f} m/s" for r in rows]
        + STUDY.run_lines(result))


STUDY = Study("toy", TableFormat(KEY, COLUMNS, text_columns=("plan", "plan_id", "dynamics")),
              scaled, ("ok", "error"), ("ok",), "factor", "toy study", rows_key="toy_cases",
              text=text)


def options(p):
    p.add_argument("--factors", default="1,2", metavar="F1,F2,...",
                   help="factors of the impulsive total (default 1,2)")


def prepare(args, plan):
    factors = number_list("--factors", args.factors, "", positive=True)
    total = sum(b.delta_v_mps for b in plan.impulsive())
    cases = [({**plan_columns(plan), "toy_factor": f}, (total, f)) for f in factors]
    return StudyRun.of(STUDY, lambda: STUDY.run(
        cases, args.out, workers=int(args.workers), progress=not args.no_progress,
        processes=False, describe={"study": "toy", "toy_factors": list(factors)}),
        {"plan": plan.to_dict()}, plan=plan)


COMMAND = StudyCommand(
    "toy", "a toy study: the impulsive total scaled", options, prepare, dask="factor",
    signed=("--factors",),
    records={"toy": [{"plan": "plan_file"}, "table", {"run": "run"},
                     {"toy_cases": "toy_case"}],
             "toy_case": list(COLUMNS)},
    arrays=frozenset({"toy_case"}), run_keys=("toy_factors",),
    glossary={"toy_factor": {"label": "factor", "definition": "A toy's scale factor."},
              "toy_scaled_delta_v_mps": {"label": "scaled ΔV",
                                         "definition": "The impulsive total times a factor."},
              "toy_factors": {"label": "factors", "kind": "array",
                              "definition": "The factors of a toy run."},
              "toy_cases": {"label": "cases", "kind": "array",
                            "definition": "One record per factor."}})
'''


@pytest.fixture
def toy(tmp_path, monkeypatch):
    """The toy study's package on sys.path (not registered); the glossary restored after."""
    pkg = tmp_path / "toypkg"
    pkg.mkdir()
    (pkg / "toy_study.py").write_text(textwrap.dedent(TOY), encoding="utf-8")
    monkeypatch.syspath_prepend(str(pkg))
    monkeypatch.setattr(Q, "GLOSSARY", dict(Q.GLOSSARY))
    monkeypatch.setattr(Q, "_Q", list(Q._Q))
    monkeypatch.setattr(Q, "_SOURCES", dict(Q._SOURCES))
    plan = tmp_path / "two-body.yaml"
    plan.write_text(paper_plan(450.0, 300.0).with_dynamics("two-body").to_yaml(),
                    encoding="utf-8")
    sys.modules.pop("toy_study", None)
    yield plan
    sys.modules.pop("toy_study", None)


def _register(monkeypatch):
    """The one registration line of the toy study."""
    monkeypatch.setattr(registry, "STUDIES", [*registry.STUDIES, "toy_study:COMMAND"])


def _main(argv, capsys) -> tuple:
    try:
        rc = cli.main(argv)
    except SystemExit as exc:   # --help, argparse errors
        rc = exc.code
    out, err = capsys.readouterr()
    return rc, out, err


def test_a_registered_toy_study_reaches_the_cli_and_the_schemas(toy, tmp_path, monkeypatch,
                                                                  capsys):
    _register(monkeypatch)
    rc, out, _ = _main(["--help"], capsys)
    assert rc == 0 and "a toy study: the impulsive total scaled" in out
    assert out.index("dispersions") < out.index("toy")   # after the packaged studies

    rc, out, _ = _main(["toy", "--help"], capsys)
    assert rc == 0 and "usage: lunarcap toy" in out
    for option in ("PLAN", "--factors", "factors of the impulsive total", "--thrust",
                   "--dynamics", "--json", "--workers", "--out", "--no-cache"):
        assert option in out, option

    rc, out, err = _main(["toy", str(toy), "--factors", "1,2.5", "--workers", "1",
                          "--no-progress", "--json", "--out", str(tmp_path / "toy.csv")],
                         capsys)
    assert rc == 0, err
    doc = json.loads(out)
    total = sum(b.delta_v_mps for b in paper_plan(450.0, 300.0).impulsive())
    assert [c["toy_scaled_delta_v_mps"] for c in doc["toy_cases"]] == [total, 2.5 * total]
    assert doc["run"]["toy_factors"] == [1.0, 2.5] and doc["plan"]["dynamics"] == "two-body"

    assert "toy" in schemas.COMMANDS and not schemas.path("toy").exists()
    schema = schemas.schemas()["toy"]
    jsonschema.Draft202012Validator.check_schema(schema)
    jsonschema.validate(doc, schema, cls=jsonschema.Draft202012Validator)
    assert schema["properties"]["toy_cases"]["items"]["properties"][
        "toy_scaled_delta_v_mps"]["x-unit"] == "m/s"
    stray = json.loads(out)
    stray["toy_cases"][0]["toy_stray_mps"] = 1.0   # a key its records do not declare
    with pytest.raises(jsonschema.ValidationError, match="toy_stray_mps"):
        jsonschema.validate(stray, schema, cls=jsonschema.Draft202012Validator)
    # bad input: one line, exit 2, before any work
    rc, out, err = _main(["toy", str(toy), "--factors", "-1"], capsys)
    assert rc == 2 and err.strip().splitlines() == [
        "lunarcap: error: --factors: must be positive (a number), got '-1'"]


def test_the_toy_study_without_its_registration_reaches_nothing(toy, capsys):
    rc, out, _ = _main(["--help"], capsys)
    assert rc == 0 and "toy" not in out
    rc, _, err = _main(["toy", str(toy), "--json"], capsys)
    assert rc == 2 and "invalid choice: 'toy'" in err
    assert "toy" not in schemas.COMMANDS and not Q.is_known("toy_scaled_delta_v_mps")


def test_a_study_redefining_a_quantity_or_a_name_is_refused(toy, monkeypatch, capsys):
    import toy_study

    monkeypatch.setattr(toy_study, "COMMAND", registry.StudyCommand(
        "toy", "h", toy_study.options, toy_study.prepare,
        glossary={"delta_v_mps": {"label": "ΔV", "definition": "Mine."}}))
    _register(monkeypatch)
    with pytest.raises(ValueError, match="delta_v_mps .* defined twice"):
        schemas.schemas()
    monkeypatch.setattr(toy_study, "COMMAND", registry.StudyCommand(
        "missed", "h", toy_study.options, toy_study.prepare))
    with pytest.raises(ValueError, match="two studies are registered as 'missed'"):
        registry.studies()


def test_every_packaged_study_is_registered_with_its_records_and_glossary():
    studies = registry.studies()
    assert list(studies) == ["study", "burns", "missed", "dispersions"]
    assert list(schemas.COMMANDS)[3:] == ["burns", "missed", "dispersions"]
    for name, s in studies.items():
        assert set(s.arrays) <= set(s.records), name
        if s.records:
            assert name in s.records, name
        assert all(opt.startswith("--") for opt in s.signed), name
        if isinstance(s.glossary, str):   # read with the glossary, found by its place
            folder = Path(importlib.import_module(s.prepare.__module__).__file__).parent
            assert (folder / s.glossary).resolve() in Q.STUDY_FILES, name
