"""An error the API raises is the command line's: the same message, and its exit status.

Each case is bad input given once to the API (a keyword) and once to the command line
(the option), on a generated plan (:mod:`lunarcap.studies.families`, seed 1, its second
plan): the API raises an InputError whose text is the line the command prints after
``lunarcap: error:``, and the command's exit status is the one its table maps the
exception's type to (:data:`lunarcap.cli.EXIT_STATUS`). Both must refuse before any work:
a Dask cluster started or a burn solved fails the test. A value is given to the API as the
command line's text where the message quotes it (``workers="0"``: a number would be shown
as 0, text as '0').
"""

from __future__ import annotations

import pytest

import lunarcap
from lunarcap.cli import exit_status, main
from lunarcap.studies.families import plan_family


@pytest.fixture(scope="module")
def generated(tmp_path_factory):
    """(the generated plan, its YAML file, a file standing where a directory is asked)."""
    plan = plan_family(1, 2)[0][1]
    where = tmp_path_factory.mktemp("api-errors")
    path = where / f"{plan.name}.yaml"
    path.write_text(plan.to_yaml(), encoding="utf-8")
    blocker = where / "a_file"
    blocker.write_text("x")
    return plan, path, blocker


@pytest.fixture
def no_work(monkeypatch):
    """Fail the test if a Dask cluster is started or a burn is solved."""
    from lunarcap.capture import chain
    from lunarcap.studies import campaign

    monkeypatch.setattr(campaign, "dask_client",
                        lambda *a, **k: pytest.fail("a cluster was started"))
    monkeypatch.setattr(chain, "solve_burn", lambda *a, **k: pytest.fail("a burn was solved"))


#: (the API's call on (plan, blocker), the command line on (plan file, blocker))
CASES = {
    "no such plan": (lambda p, b: lunarcap.load_plan("no-such-plan"),
                     lambda f, b: ["plan", "no-such-plan"]),
    "joint solve of no such plan": (lambda p, b: lunarcap.solve_joint("no-such-plan"),
                                    lambda f, b: ["plan", "no-such-plan"]),
    "missed fraction above 1": (lambda p, b: lunarcap.missed(p, fractions="0.5,1.2"),
                                lambda f, b: ["missed", f, "--fractions", "0.5,1.2"]),
    "missed burn the plan lacks": (lambda p, b: lunarcap.missed(p, burn=4),
                                   lambda f, b: ["missed", f, "--burn", "4"]),
    "missed negative delay": (lambda p, b: lunarcap.missed(p, delays_min="-30"),
                              lambda f, b: ["missed", f, "--delays-min", "-30"]),
    "burns table under a file": (lambda p, b: lunarcap.burns(p, counts=[1], out=b / "t.csv"),
                                 lambda f, b: ["burns", f, "--counts", "1", "--out",
                                               str(b / "t.csv")]),
    "burns duplicate count": (lambda p, b: lunarcap.burns(p, counts="2,2"),
                              lambda f, b: ["burns", f, "--counts", "2,2"]),
    "burns no workers": (lambda p, b: lunarcap.burns(p, counts="1", workers="0"),
                         lambda f, b: ["burns", f, "--counts", "1", "--workers", "0"]),
    "dispersions no sample": (lambda p, b: lunarcap.dispersions(p, samples="0"),
                              lambda f, b: ["dispersions", f, "--samples", "0"]),
    "dispersions negative sigma": (
        lambda p, b: lunarcap.dispersions(p, thrust_sigma_pct="-1"),
        lambda f, b: ["dispersions", f, "--thrust-sigma-pct", "-1"]),
    "dispersions odd antithetic": (
        lambda p, b: lunarcap.dispersions(p, samples=3, antithetic=True),
        lambda f, b: ["dispersions", f, "--samples", "3", "--antithetic"]),
    "dispersions factors without sensitivity": (
        lambda p, b: lunarcap.dispersions(p, factors=[1, 2]),
        lambda f, b: ["dispersions", f, "--factors", "1,2"]),
    "dispersions negative factor": (
        lambda p, b: lunarcap.dispersions(p, sensitivity=True, thrust_sigma_pct=1,
                                          factors="1,-2"),
        lambda f, b: ["dispersions", f, "--sensitivity", "--thrust-sigma-pct", "1",
                      "--factors", "1,-2"]),
    "solve a burn the plan lacks": (lambda p, b: lunarcap.solve_burn(p, 3),
                                    lambda f, b: ["solve", "--plan", f, "--burn", "3"]),
    "solve with too many earlier starts": (
        lambda p, b: lunarcap.solve_burn(p, 2, previous_starts=[-1, -2]),
        lambda f, b: ["solve", "--plan", f, "--burn", "2", "--previous-starts", "-1,-2"]),
    "trade study of one point": (lambda p, b: lunarcap.engine_trade(points="1"),
                                 lambda f, b: ["study", "--points", "1"]),
}


@pytest.mark.parametrize("case", CASES)
def test_the_api_raises_the_command_lines_error(case, generated, no_work, capsys):
    plan, path, blocker = generated
    api, cli = CASES[case]
    with pytest.raises(lunarcap.LunarcapError) as raised:
        api(plan, blocker)
    code = main(cli(str(path), blocker))
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"lunarcap: error: {raised.value}"]
    assert isinstance(raised.value, lunarcap.InputError)
    assert code == exit_status(raised.value) == 2


def test_an_option_the_plan_refuses_is_named_before_the_plans_field(generated, capsys):
    """The API names the plan's field; the command line puts its option first."""
    plan, path, _ = generated
    with pytest.raises(lunarcap.PlanError) as raised:
        lunarcap.load_plan(plan, mass_kg=700000)
    field, reason = str(raised.value).split(": ", 1)
    assert field == "arrival.mass_kg" and "700000 kg is above the largest allowed" in reason
    assert main(["plan", str(path), "--mass", "700000"]) == exit_status(raised.value) == 2
    assert capsys.readouterr().err.strip() == f"lunarcap: error: --mass ({field}): {reason}"


def test_a_failed_solve_is_a_solve_error_and_exit_status_3(generated, monkeypatch, capsys):
    """IPOPT's failure reaches the API's caller as a SolveError, the command line as status 3."""
    from lunarcap.capture import chain

    plan, path, _ = generated

    def failed(*args, **kwargs):
        raise lunarcap.SolveError("burn 1: IPOPT Maximum_Iterations_Exceeded (rp error 3.2 km)",
                                  "Maximum_Iterations_Exceeded", {"rp_error_m": 3200.0})

    monkeypatch.setattr(chain, "plan_result", failed)
    with pytest.raises(lunarcap.SolveError) as raised:
        lunarcap.solve(plan)
    assert raised.value.status == "Maximum_Iterations_Exceeded"
    assert main(["plan", str(path), "--quiet"]) == exit_status(raised.value) == 3
    assert capsys.readouterr().err.strip() == f"lunarcap: error: {raised.value}"


def test_unknown_study_options_are_refused_by_name(generated, no_work):
    plan, _, _ = generated
    with pytest.raises(lunarcap.InputError, match=r"missed: unknown option 'fraction' "
                                                  r"\(options: .*fractions"):
        lunarcap.missed(plan, fraction=[0.5])
    with pytest.raises(lunarcap.InputError, match="dispersions: unknown option 'no_progress'"):
        lunarcap.dispersions(plan, no_progress=True)
