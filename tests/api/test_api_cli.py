"""The public API and the command line give the same numbers, bit for bit, on a generated plan.

The plan is drawn by :mod:`lunarcap.studies.families` (seed 1, the second plan: 494 N /
220 s, 643 kg, 69.5 deg, an apolune-altitude ellipse then the circle; not the paper's),
in two-body dynamics so that each run takes seconds. The API is handed the generated
plan object, as a user building a plan in code would; the command line the plan's YAML
file, as a user of the shell would. Every run recomputes (``--no-cache``,
``use_cache=False``) and writes its own table, so both sides solve; the documents must
then agree in every key and every number (``==`` on floats), timings and the table's
path aside. Each API document is also checked against the command's JSON Schema
(``lunarcap/schemas``), and each result's figure against the book's legibility rules.
"""

from __future__ import annotations

import json
import math

import jsonschema
import matplotlib
import pytest

import lunarcap
from lunarcap import schemas
from lunarcap.cli import main
from lunarcap.report.figstyle import legibility_problems
from lunarcap.studies.families import plan_family

matplotlib.use("Agg")

pytestmark = pytest.mark.slow

#: Keys that measure the run rather than the capture (wall and CPU times, where and when).
TIMING = {"solve_wall_s", "nlp_solve_s", "task_wall_s", "task_cpu_s", "worker",
          "completed_utc", "code_version", "run", "table", "wall_s"}


def differences(a, b, path="") -> list:
    """Every place where two documents differ (a key, a length, a value), timings aside."""
    if isinstance(a, dict) and isinstance(b, dict):
        out = [f"{path}.{k}: only in one" for k in sorted(set(a) ^ set(b))]
        for k in sorted((set(a) & set(b)) - TIMING):
            out += differences(a[k], b[k], f"{path}.{k}")
        return out
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{path}: {len(a)} != {len(b)} items"]
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{path}[{i}]")]
    same = a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a)
                      and math.isnan(b))
    return [] if same else [f"{path}: {a!r} != {b!r}"]


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """(the generated plan, the path of its YAML file)."""
    plans, refused = plan_family(1, 2)
    assert not refused
    plan = plans[1]
    path = tmp_path_factory.mktemp("api-cli") / f"{plan.name}.yaml"
    path.write_text(plan.to_yaml(), encoding="utf-8")
    return plan, path


def valid(command: str, result) -> dict:
    """``result.to_dict()``, checked against the command's JSON Schema and its figure drawn."""
    import matplotlib.pyplot as plt

    doc = result.to_dict()
    jsonschema.validate(doc, schemas.load(command), cls=jsonschema.Draft202012Validator)
    fig = result.plot()
    assert legibility_problems(fig) == []
    plt.close(fig)
    return doc


def cli_json(argv, capsys) -> dict:
    """``lunarcap <argv> --json`` run in this process: its document (exit status 0)."""
    code = main([*argv, "--json"])
    out = capsys.readouterr().out
    assert code == 0, out
    return json.loads(out)


def test_the_generated_plan_is_not_the_papers(generated):
    plan, _ = generated
    assert (plan.engine.thrust_N, plan.arrival.mass_kg, plan.arrival.inclination_deg) == (
        494.0, 643.0, 69.5)
    assert [b.describe() for b in plan.burns] == ["ellipse, apolune altitude 8132.3 km",
                                                  "circle"]


def test_plan(generated, capsys):
    plan, path = generated
    cli = cli_json(["plan", str(path), "--no-cache", "--quiet"], capsys)
    api = lunarcap.solve(plan, use_cache=False)
    assert api.verified and cli["complete"]
    assert differences(cli, valid("plan", api)) == []
    assert cli["totals"]["total_delta_v_mps"] == api.totals()["total_delta_v_mps"]


def test_solve(generated, capsys):
    plan, path = generated
    cli = cli_json(["solve", "--plan", str(path), "--burn", "2", "--start", "-4", "--no-cache",
                    "--quiet"], capsys)
    api = lunarcap.solve_burn(plan, 2, start=-4, use_cache=False)
    assert api.verified and cli["start_min"] == -4
    assert differences(cli, valid("solve", api)) == []


def test_missed(generated, tmp_path, capsys):
    plan, path = generated
    cli = cli_json(["missed", str(path), "--fractions", "0.5", "--delays-min", "0",
                    "--workers", "1", "--no-progress", "--no-cache", "--out",
                    str(tmp_path / "cli.csv")], capsys)
    api = lunarcap.missed(plan, fractions=[0.5], delays_min=[0], workers=1, use_cache=False,
                          out=tmp_path / "api.csv")
    assert [c["status"] for c in cli["cases"]] == ["recovered"]
    assert differences(cli, valid("missed", api)) == []
    assert api.to_frame().penalty_mps.tolist() == [c["penalty_mps"] for c in cli["cases"]]


def test_burns(generated, tmp_path, capsys):
    plan, path = generated
    cli = cli_json(["burns", str(path), "--counts", "1,2", "--workers", "1", "--no-progress",
                    "--no-cache", "--out", str(tmp_path / "cli.csv")], capsys)
    api = lunarcap.burns(plan, counts=[1, 2], workers=1, use_cache=False,
                         out=tmp_path / "api.csv")
    assert [c["status"] for c in cli["counts"]] == ["ok", "ok"]
    assert differences(cli, valid("burns", api)) == []


def test_dispersions_on_a_running_cluster(generated, tmp_path, capsys, dask_cluster):
    """Both sides send their samples to one running scheduler (``--scheduler`` / ``scheduler=``)."""
    plan, path = generated
    cli = cli_json(["dispersions", str(path), "--samples", "2", "--seed", "7",
                    "--thrust-sigma-pct", "1", "--pointing-sigma-deg", "0.3", "--scheduler",
                    dask_cluster, "--no-progress", "--no-cache", "--out",
                    str(tmp_path / "cli.csv")], capsys)
    api = lunarcap.dispersions(plan, samples=2, seed=7, thrust_sigma_pct=1,
                               pointing_sigma_deg=0.3, scheduler=dask_cluster, use_cache=False,
                               out=tmp_path / "api.csv")
    assert cli["run"]["scheduler"] == api.campaign.run["scheduler"] != "LocalCluster"
    assert [s["status"] for s in cli["samples"]] == ["ok", "ok"]
    assert differences(cli, valid("dispersions", api)) == []


def test_a_dispersions_sensitivity_with_its_factors_in_antithetic_pairs(generated, tmp_path,
                                                                        capsys):
    """``--sensitivity --factors --antithetic`` and ``sensitivity=, factors=, antithetic=``.

    One source at two multiples of its sigma, one antithetic pair each: the same rows and
    laws on both sides, the pair's second sample the negated draws of its first.
    """
    plan, path = generated
    cli = cli_json(["dispersions", str(path), "--samples", "2", "--seed", "3",
                    "--thrust-sigma-pct", "1", "--sensitivity", "--factors", "1,2",
                    "--antithetic", "--workers", "1", "--no-progress", "--no-cache", "--out",
                    str(tmp_path / "cli.csv")], capsys)
    api = lunarcap.dispersions(plan, samples=2, seed=3, thrust_sigma_pct=1, sensitivity=True,
                               factors=[1, 2], antithetic=True, workers=1, use_cache=False,
                               out=tmp_path / "api.csv")
    assert [(r["source"], r["sigma"]) for r in cli["sensitivity"]] == [
        ("thrust_sigma_pct", 1.0), ("thrust_sigma_pct", 2.0)]
    table = api.campaign.table
    assert len(table) == 4 and table.antithetic.all()
    assert differences(cli, api.to_dict()) == []
