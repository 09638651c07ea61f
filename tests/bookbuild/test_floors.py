"""The full book's floors: every study page at the size its claims need (issue 36).

A page declares, beside its parameters, the least each may be in the full book
(``Execution.floors``, :class:`lunarcap.report.contents.Floor`). Three things hold:

* the registered pages' full parameters meet their floors, and those floors are at least
  the sizes issue 36 asks for, so an edit that lowers a grid, or its floor with it, fails
  here (`make test`);
* the build refuses a full book whose pages run below their floors, before running any
  page, naming the page, the parameter and why; the quick book is exempt;
* a page of the quick book says at its top that it is a reduced run, and which parameters
  it reduced.
"""

import nbformat
import pytest
import yaml

from lunarcap.bookbuild import build as book
from lunarcap.bookbuild import execution, manifest
from lunarcap.report import contents
from lunarcap.repro import paths
from lunarcap.studies.dispersions.summary import samples_needed

PAPER = ["song2011-150N", "song2011-300N", "song2011-450N"]

#: Issue 36, item 1: what each study page of the full book must run, at least.
#: (parameter, kind, value): "at_least" a number, "includes" every element of a list.
ISSUE_36 = {
    "dispersions": [("plans", "includes", PAPER), ("samples", "at_least", 368),
                    ("sensitivity_plans", "includes", PAPER),
                    ("sensitivity_factors", "includes", [0.5, 1.0, 2.0]),
                    # 8 independent draws per level and source: 8 antithetic pairs
                    ("sensitivity_samples", "at_least", 16)],
    "missed_thrust": [("fractions", "includes", [0.25, 0.5, 0.75, 0.9]),
                      ("delays_min", "includes", [0.0, 30.0, 120.0, 720.0]),
                      ("late_min", "includes", [1.0, 5.0, 10.0])],
    "trade_study": [("points", "at_least", 30),
                    ("isp_s", "includes", [200.0, 250.0, 300.0])],
    "burn_count": [("plans", "includes", PAPER + ["lro-like-5burn"]),
                   ("counts", "includes", [1, 2, 3, 4, 5])],
    "real_moon": [("degrees", "includes", ["2x0", 2, 8, 20, 50]),
                  ("evolve_degrees", "includes", [2, 8, 20, 50]),
                  ("redesign_limits", "one_of", [True])],
}


def _executions():
    return {x.name: x for x in contents.executions(contents.registered())}


def _below(kind, value):
    """Parameter values just below an issue floor: each must be refused."""
    if kind == "at_least":
        return [value - 1 if isinstance(value, int) else value * 0.99]
    if kind == "one_of":
        return [not value[0]] if isinstance(value[0], bool) else [None]
    return [[v for v in value if v != gone] for gone in value]   # each element dropped


def test_the_studies_of_the_full_book_meet_their_floors():
    run = _executions()
    for name in ISSUE_36:
        x = run[name]
        assert x.floors, f"{name} declares no floors"
        assert contents.below_floors(x.parameters, x.floors) == [], name


@pytest.mark.parametrize("page", sorted(ISSUE_36))
def test_each_declared_floor_is_at_least_issue_36s(page):
    """Lower any parameter below the issue's size: the page's own floors refuse it.

    Lowering a grid and its floor together (say samples 4, floor 4) fails here too.
    """
    x = _executions()[page]
    for param, kind, value in ISSUE_36[page]:
        assert contents.Floor(kind, value, "issue 36").shortfall(x.parameters[param]) is None, \
            f"{page}: {param} = {x.parameters[param]!r} is below issue 36's {value!r}"
        for lowered in _below(kind, value):
            problems = contents.below_floors(dict(x.parameters, **{param: lowered}), x.floors)
            assert any(p.startswith(f"{param} ") for p in problems), \
                f"{page}: {param} = {lowered!r} passes its declared floors"


def test_the_dispersions_floor_is_the_fewest_samples_that_bound_the_99_percent_point():
    # the two-sided 95 % interval on the 0.99 quantile from order statistics has a finite
    # upper rank once P(every sample below the quantile) = 0.99^n <= 0.025
    assert 0.99 ** 368 <= 0.025 < 0.99 ** 367
    assert samples_needed(0.99) == 368
    assert _executions()["dispersions"].floors["samples"].value == 368


def test_floors_compare_as_the_page_uses_them():
    f = contents.includes([0.5, 1.0, 2.0], "three levels")
    assert f.shortfall([2, 1, 0.5]) is None                  # numbers as floats
    assert f.shortfall([1.0, 2.0]) == "lacks [0.5] (has [1.0, 2.0])"
    assert f.shortfall(None) is not None
    assert contents.includes(["2x0", 2], "").shortfall([2, 8]) == "lacks ['2x0'] (has [2, 8])"
    assert contents.at_least(368, "").shortfall(368) is None
    assert contents.at_least(368, "").shortfall(367.9) is not None
    assert contents.at_most(50.0, "").shortfall(60.0) == "is 60, above its floor <= 50"
    assert contents.one_of([None], "").shortfall("two-body") is not None
    assert contents.one_of([True], "").shortfall(1) is not None  # a switch is a bool
    with pytest.raises(contents.ContentsError, match="unknown floor kind"):
        contents.Floor("more_than", 3, "")
    with pytest.raises(contents.ContentsError, match="needs a number"):
        contents.at_least("368", "")
    assert contents.below_floors({}, {"x": contents.at_least(1, "why")}) == [
        "x is not given, so its floor is not met (why)"]


# ------------------------------------------------------------------ the build's check
def _tree(tmp_path, samples, floor, monkeypatch):
    """A throw-away book: one page whose ``samples`` has a floor, its manifest and toc."""
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Toy"),
                nbformat.v4.new_code_cell("samples = 1\nquick = False\noutput_name = 'toy'")]
    nb.cells[1].metadata["tags"] = ["parameters"]
    nbformat.write(nb, str(tmp_path / "toy.ipynb"))
    entry = {"name": "toy", "title": "Toy", "notebook": "toy.ipynb",
             "parameters": {"samples": samples}, "quick_parameters": {"samples": 2},
             "floors": {"samples": {"at_least": floor, "why": "the 99 % point"}}}
    (tmp_path / "manifest.yml").write_text(yaml.safe_dump({"entries": [entry]}))
    (tmp_path / "_toc.yml").write_text(yaml.safe_dump(
        {"format": "jb-book", "root": "index", "chapters": [{"file": "generated/toy"}]}))
    (tmp_path / "index.md").write_text("# Index\n")
    monkeypatch.setattr(paths, "MANIFEST", tmp_path / "manifest.yml")
    monkeypatch.setattr(paths, "TOC", tmp_path / "_toc.yml")
    ran = []
    monkeypatch.setattr(book, "run_entries", lambda entries, **kw: ran.append(
        ([e.name for e in entries], kw["quick"])) or True)
    return ran


def test_the_build_refuses_a_page_below_its_floors_before_running_anything(
        tmp_path, monkeypatch, capsys):
    ran = _tree(tmp_path, 4, 368, monkeypatch)
    assert book.main(["build", "--only", "toy", "--no-build"]) == 2
    err = capsys.readouterr().err
    assert "pages below their floors" in err
    assert "toy: samples is 4, below its floor >= 368 (the 99 % point)" in err
    assert ran == []                                    # refused before any page ran
    assert book.main(["check"]) == 2                    # `check` says so too


def test_the_quick_book_and_a_page_at_its_floor_run(tmp_path, monkeypatch):
    ran = _tree(tmp_path, 4, 368, monkeypatch)
    monkeypatch.setenv("LUNARCAP_BOOK_DIR", str(tmp_path / "quickbook"))  # no staging
    assert book.main(["build", "--quick", "--only", "toy", "--no-build"]) == 0
    ran_full = _tree(tmp_path, 368, 368, monkeypatch)
    monkeypatch.delenv("LUNARCAP_BOOK_DIR")
    assert book.main(["build", "--only", "toy", "--no-build"]) == 0
    assert ran == [(["toy"], True)] and ran_full == [(["toy"], False)]


def test_a_manifest_floor_must_name_a_parameter_and_a_kind(tmp_path):
    nb = tmp_path / "a.ipynb"
    nbformat.write(nbformat.v4.new_notebook(), str(nb))
    entry = {"name": "a", "title": "A", "notebook": "a.ipynb", "parameters": {"n": 3},
             "floors": {"n": {"more_than": 2, "why": "x"},
                        "m": {"at_least": 1, "why": "y"}}}
    with pytest.raises(manifest.ManifestError) as err:
        manifest.validate_manifest({"entries": [entry]}, tmp_path, check_notebooks=False)
    assert "entry 1 ('a'): floor of 'n': unknown floor kind 'more_than'" in str(err.value)
    assert "entry 1 ('a'): floor of 'm': no such parameter in its parameters" in str(err.value)
    entry["floors"] = {"n": {"at_least": 2, "why": "x"}}
    (e,) = manifest.validate_manifest({"entries": [entry]}, tmp_path, check_notebooks=False)
    assert e.floors == {"n": contents.at_least(2, "x")}


def test_the_registered_floors_reach_the_manifest_the_build_writes():
    entries = {e.name: e for e in manifest.load_manifest(check_notebooks=False)}
    assert entries["dispersions"].floors["samples"] == contents.at_least(
        368, _executions()["dispersions"].floors["samples"].why)
    manifest.check_floors(list(entries.values()))          # the full book: no problem
    written = contents.manifest(contents.registered())
    floors = {e["name"]: e.get("floors") for e in written["entries"]}
    assert floors["missed_thrust"]["late_min"]["includes"] == [1.0, 5.0, 10.0]
    assert yaml.safe_load(yaml.safe_dump(written)) == written


# ------------------------------------------------------------------ the quick book says so
def test_every_page_of_the_quick_book_below_its_floors_says_so_at_its_top():
    for name, x in _executions().items():
        quick = dict(x.parameters, **x.quick_parameters)
        short = contents.below_floors(quick, x.floors)
        note = execution.quick_note(x.parameters, x.quick_parameters)
        if short:
            assert note is not None, name
            for p in short:
                assert f"{p.split(' ')[0]} = " in note, (name, p)


def test_the_quick_note_stands_under_the_title():
    note = execution.quick_note({"samples": 368, "plans": ["a", "b"], "seed": 1},
                                {"samples": 2, "plans": ["a"], "seed": 1})
    assert "samples = 2 (the book: 368)" in note and "plans = [a] (the book: [a, b])" in note
    assert "seed" not in note                               # unchanged: not said
    assert execution.quick_note({"n": 1}, {"n": 1}) is None
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Source title\nThe intro."),
                nbformat.v4.new_code_cell("x = 1")]
    execution.prepare_for_book(nb, "Title", note)
    head = nb.cells[0].source
    assert head.startswith("# Title\n\n```{admonition} Quick book")
    assert head.index("Quick book") < head.index("The intro.")
    plain = nbformat.v4.new_notebook()
    plain.cells = [nbformat.v4.new_markdown_cell("# Source title\nThe intro.")]
    execution.prepare_for_book(plain, "Title")
    assert plain.cells[0].source == "# Title\nThe intro."

