"""The book machinery: manifest validation, scheduling, stamps, paths and cache (fast).

One test (marked ``notebooks``) runs the real executor on a throw-away tree with a
failing notebook.
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import nbformat
import pytest
import yaml

from lunarcap.bookbuild import build as book
from lunarcap.bookbuild.build import ManifestError, validate_manifest
from lunarcap.repro import cache, paths


def _notebook(path: Path, params: str = "x = 1\nquick = False\noutput_name = 'n'",
              body: str = "print(x)", n_param_cells: int = 1) -> Path:
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3",
                                 "language": "python"}
    nb.cells = [nbformat.v4.new_markdown_cell("# Source title")]
    for _ in range(n_param_cells):
        c = nbformat.v4.new_code_cell(params)
        c.metadata["tags"] = ["parameters"]
        nb.cells.append(c)
    nb.cells.append(nbformat.v4.new_code_cell(body))
    nbformat.write(nb, str(path))
    return path


def _entry(name, notebook="a.ipynb", **kw):
    return {"name": name, "title": name.title(), "notebook": notebook, **kw}


@pytest.fixture
def nbdir(tmp_path):
    _notebook(tmp_path / "a.ipynb")
    _notebook(tmp_path / "b.ipynb")
    return tmp_path


# ------------------------------------------------------------------ manifest validation
def test_valid_manifest_returns_entries_in_order(nbdir):
    entries = validate_manifest({"entries": [
        _entry("one", parameters={"x": 2}, quick_parameters={"x": 3}, outputs=["tables/o.csv"]),
        _entry("two", "b.ipynb", depends_on=["one"]),
    ]}, nbdir)
    assert [e.name for e in entries] == ["one", "two"]
    one = entries[0]
    assert one.effective_parameters(quick=False) == {"x": 2, "quick": False, "output_name": "one"}
    assert one.effective_parameters(quick=True) == {"x": 3, "quick": True, "output_name": "one"}
    assert entries[1].depends_on == ("one",)


def test_cycle_is_one_clear_error(nbdir):
    with pytest.raises(ManifestError) as err:
        validate_manifest({"entries": [_entry("a", depends_on=["c"]), _entry("b", depends_on=["a"]),
                                       _entry("c", depends_on=["b"])]}, nbdir)
    msg = str(err.value)
    assert "dependency cycle" in msg
    assert "a -> c -> b -> a" in msg or "c -> b -> a -> c" in msg or "b -> a -> c -> b" in msg


def test_self_dependency_is_reported(nbdir):
    with pytest.raises(ManifestError, match="depends on itself"):
        validate_manifest({"entries": [_entry("a", depends_on=["a"])]}, nbdir)


def test_unknown_notebook_is_reported(nbdir):
    with pytest.raises(ManifestError, match=r"notebook 'missing\.ipynb' not found"):
        validate_manifest({"entries": [_entry("a", "missing.ipynb")]}, nbdir)


def test_unknown_key_is_reported(nbdir):
    with pytest.raises(ManifestError, match=r"unknown key\(s\) \['paramters'\]"):
        validate_manifest({"entries": [_entry("a", paramters={"x": 1})]}, nbdir)


def test_all_problems_are_listed_at_once(nbdir):
    with pytest.raises(ManifestError) as err:
        validate_manifest({"entries": [_entry("a", colour="red"), _entry("b", "nope.ipynb"),
                                       _entry("c", depends_on=["zzz"]), {"name": "d"}]}, nbdir)
    msg = str(err.value)
    for needle in ("colour", "nope.ipynb", "unknown entry 'zzz'", "missing key(s)"):
        assert needle in msg, needle


@pytest.mark.parametrize("data", [None, [], {"entries": {}}, {"entries": [], "extra": 1}])
def test_bad_top_level(data, nbdir):
    with pytest.raises(ManifestError, match="one key 'entries'"):
        validate_manifest(data, nbdir)


def test_duplicate_and_invalid_names(nbdir):
    with pytest.raises(ManifestError, match="duplicate name 'a'"):
        validate_manifest({"entries": [_entry("a"), _entry("a")]}, nbdir)
    with pytest.raises(ManifestError, match="invalid output name"):
        validate_manifest({"entries": [_entry("../escape")]}, nbdir)


def test_parameters_must_exist_in_the_notebook(nbdir):
    with pytest.raises(ManifestError, match=r"parameter\(s\) \['y'\] are not defined"):
        validate_manifest({"entries": [_entry("a", quick_parameters={"y": 1})]}, nbdir)


def test_injected_parameters_may_not_be_set(nbdir):
    with pytest.raises(ManifestError, match="may not set"):
        validate_manifest({"entries": [_entry("a", parameters={"quick": True})]}, nbdir)


def test_notebook_needs_one_parameters_cell_with_quick_and_output_name(tmp_path):
    _notebook(tmp_path / "two.ipynb", n_param_cells=2)
    _notebook(tmp_path / "none.ipynb", n_param_cells=0)
    _notebook(tmp_path / "noquick.ipynb", params="x = 1\noutput_name = 'n'")
    with pytest.raises(ManifestError) as err:
        validate_manifest({"entries": [_entry("a", "two.ipynb"), _entry("b", "none.ipynb"),
                                       _entry("c", "noquick.ipynb")]}, tmp_path)
    msg = str(err.value)
    assert "exactly one cell tagged 'parameters' (found 2)" in msg
    assert "(found 0)" in msg
    assert "must define 'quick'" in msg


def test_outputs_must_stay_below_generated(nbdir):
    with pytest.raises(ManifestError, match="outputs must be a list"):
        validate_manifest({"entries": [_entry("a", outputs=["../x.csv"])]}, nbdir)


def test_load_manifest_reports_yaml_errors(tmp_path):
    bad = tmp_path / "manifest.yml"
    bad.write_text("entries: [\n")
    with pytest.raises(ManifestError, match="not valid YAML"):
        book.load_manifest(bad)
    with pytest.raises(ManifestError, match="manifest not found"):
        book.load_manifest(tmp_path / "absent.yml")


def test_real_manifest_and_toc_are_valid():
    entries = book.load_manifest()
    book.check_toc(entries)
    assert entries, "the manifest has no entries"


# ------------------------------------------------------------------ toc, selection
def test_toc_must_match_the_manifest(nbdir, tmp_path):
    bookdir = tmp_path / "bk"
    bookdir.mkdir()
    (bookdir / "intro.md").write_text("# Intro\n")
    toc = bookdir / "_toc.yml"
    toc.write_text(yaml.safe_dump({"format": "jb-book", "root": "intro", "chapters": [
        {"file": "generated/a"}, {"file": "generated/ghost"}, {"file": "missing_page"}]}))
    entries = validate_manifest({"entries": [_entry("a"), _entry("b", "b.ipynb")]}, nbdir)
    with pytest.raises(ManifestError) as err:
        book.check_toc(entries, toc)
    msg = str(err.value)
    assert "manifest entry 'b' is not in _toc.yml" in msg
    assert "generated/ghost, which no manifest entry produces" in msg
    assert "missing_page, which does not exist" in msg


def test_only_selects_dependencies_too(nbdir):
    entries = validate_manifest({"entries": [_entry("a"), _entry("b", depends_on=["a"]),
                                             _entry("c")]}, nbdir)
    assert [e.name for e in book.select(entries, ["b"])] == ["a", "b"]
    assert [e.name for e in book.select(entries, None)] == ["a", "b", "c"]
    with pytest.raises(ManifestError, match="unknown entry"):
        book.select(entries, ["nope"])


def test_find_cycle():
    assert book.find_cycle({"a": ["b"], "b": []}) is None
    assert book.find_cycle({"a": ["b"], "b": ["a"]}) in (["a", "b", "a"], ["b", "a", "b"])


def test_cli_exit_status_2_on_invalid_manifest(tmp_path, monkeypatch, capsys):
    man = tmp_path / "manifest.yml"
    man.write_text(yaml.safe_dump({"entries": [_entry("a", "absent.ipynb")]}))
    monkeypatch.setattr(paths, "MANIFEST", man)
    assert book.main(["check"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("lunarcap.bookbuild.build: error: invalid manifest")
    assert "absent.ipynb" in err


# ------------------------------------------------------------------ page preparation, stamps
def test_prepare_for_book_sets_title_and_folds_code():
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Old\ntext"),
                nbformat.v4.new_code_cell("x = 1"), nbformat.v4.new_code_cell("x = 2"),
                nbformat.v4.new_code_cell("y = x"), nbformat.v4.new_code_cell("assert y"),
                nbformat.v4.new_code_cell("show()")]
    nb.cells[1].metadata["tags"] = ["parameters"]
    nb.cells[2].metadata["tags"] = ["injected-parameters"]
    nb.cells[4].metadata["tags"] = ["remove-input"]
    nb.cells[5].metadata["tags"] = ["show-input"]
    book.prepare_for_book(nb, "New title")
    assert nb.cells[0].source == "# New title\ntext"
    tags = [c.metadata.get("tags") for c in nb.cells[1:]]
    assert tags == [["parameters", "hide-cell"], ["injected-parameters", "remove-cell"],
                    ["hide-input"], ["remove-input"], ["show-input"]]
    nb2 = nbformat.v4.new_notebook()
    nb2.cells = [nbformat.v4.new_code_cell("1")]
    book.prepare_for_book(nb2, "T")
    assert nb2.cells[0].source == "# T"


def test_prepare_for_book_puts_results_before_the_setup():
    nb = nbformat.v4.new_notebook()
    src = ["# T\nintro", "a = 1", "a = 2", "page = build(a)\npage.header()", "page.show('t')",
           "page.glue()", "Prose after the first result."]
    nb.cells = [nbformat.v4.new_markdown_cell(src[0])]
    nb.cells += [nbformat.v4.new_code_cell(s) for s in src[1:6]]
    nb.cells.append(nbformat.v4.new_markdown_cell(src[6]))
    nb.cells[1].metadata["tags"] = ["parameters"]
    nb.cells[2].metadata["tags"] = ["injected-parameters"]
    nb.cells[5].metadata["tags"] = ["remove-cell"]
    book.prepare_for_book(nb, "Title")
    order = [c.source for c in nb.cells]
    assert order[0] == "# Title\nintro"
    assert order[1:4] == [src[4], src[5], src[6]]          # the results first
    assert order[4].startswith(book.SETUP_HEADING)          # then the set-up, headed
    assert order[5:] == [src[1], src[2], src[3]]
    assert nb.cells[-1].metadata["tags"] == ["hide-input"]  # the build call stays folded
    assert nb.cells[1].metadata["tags"] == ["remove-input"]  # a show cell: no toggle


def test_stamp_changes_with_parameters_and_detects_missing_outputs(nbdir, tmp_path, monkeypatch):
    monkeypatch.setattr(paths, "GENERATED", tmp_path / "gen")
    (tmp_path / "gen").mkdir()
    e = validate_manifest({"entries": [_entry("a", parameters={"x": 2},
                                              outputs=["tables/a.csv"])]}, nbdir)[0]
    s_full, s_quick = book.stamp_for(e, False, {}), book.stamp_for(e, True, {})
    assert s_full["digest"] != s_quick["digest"]
    assert not book.is_up_to_date(e, s_full)
    e.output.write_text("{}")
    e.stamp_path.write_text(json.dumps(s_full))
    assert not book.is_up_to_date(e, s_full)  # declared output missing
    (tmp_path / "gen" / "tables").mkdir()
    (tmp_path / "gen" / "tables" / "a.csv").write_text("a\n1\n")
    assert book.is_up_to_date(e, s_full)
    assert not book.is_up_to_date(e, s_quick)
    assert book.stamp_for(e, False, {"dep": "x"})["digest"] == s_full["digest"]  # no deps


# ------------------------------------------------------------------ paths and cache
def test_atomic_write_leaves_nothing_on_failure(tmp_path):
    target = tmp_path / "t.csv"
    target.write_text("old")
    with pytest.raises(RuntimeError):
        with paths.atomic_path(target) as tmp:
            tmp.write_text("half")
            raise RuntimeError("boom")
    assert target.read_text() == "old"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["t.csv"]
    paths.write_text_atomic(target, "new")
    assert target.read_text() == "new"


def test_output_names_cannot_escape():
    for bad in ("", "../x", "a/b", "/abs", ".hidden"):
        with pytest.raises(ValueError):
            paths.table_path(bad)
    assert paths.figure_path("f", "svg").parent == paths.FIGURES
    with pytest.raises(ValueError):
        paths.figure_path("f", "gif")


def test_write_csv_refuses_empty_tables(tmp_path, monkeypatch):
    import pandas as pd

    monkeypatch.setattr(paths, "TABLES", tmp_path)
    with pytest.raises(ValueError, match="empty table"):
        paths.write_csv(pd.DataFrame({"a": []}), "e")
    out = paths.write_csv(pd.DataFrame({"a": [1.5]}), "t")
    assert out.read_text() == "a\n1.5\n"


def test_cached_keys_include_code_version_and_bound_arguments(tmp_path, monkeypatch):
    import joblib

    monkeypatch.setattr(cache, "memory", joblib.Memory(str(tmp_path), verbose=0))
    calls = []

    @cache.cached(ignore=["verbose"])
    def f(a, b=2, verbose=False):
        calls.append((a, b))
        return a + b

    assert f(1) == f(1, 2) == f(1, b=2) == f(1, verbose=True) == 3
    assert calls == [(1, 2)]
    assert f.is_cached(1) and not f.is_cached(5)
    monkeypatch.setattr(cache, "code_version", lambda include_presentation=False: "other")
    assert f(1) == 3 and calls == [(1, 2), (1, 2)]  # a new code version recomputes
    with pytest.raises(ValueError, match="ignore names unknown"):
        cache.cached(ignore=["nope"])(lambda x: x)


def test_code_version_ignores_presentation_modules():
    v, vp = cache.code_version(), cache.code_version(include_presentation=True)
    assert len(v) == 16 and v != vp


# ------------------------------------------------------------------ executor (kernels)
def _book_tree(root: Path) -> Path:
    """An empty book below ``root`` (notebooks/, book/intro.md); returns notebooks/."""
    nbdir = root / "notebooks"
    nbdir.mkdir(parents=True)
    (root / "book").mkdir()
    (root / "book" / "intro.md").write_text("# Intro\n")
    return nbdir


@pytest.mark.notebooks
def test_failed_entry_stops_the_run_and_keeps_other_outputs(tmp_path):
    root = tmp_path / "tree"
    nbdir = _book_tree(root)
    _notebook(nbdir / "good.ipynb", body=textwrap.dedent("""
        import pandas as pd
        from lunarcap.repro import paths
        paths.write_csv(pd.DataFrame({"x": [x]}), output_name)
        """))
    _notebook(nbdir / "bad.ipynb", body="1 / 0")
    (nbdir / "manifest.yml").write_text(yaml.safe_dump({"entries": [
        _entry("good", "good.ipynb", parameters={"x": 7}, outputs=["tables/good.csv"]),
        _entry("bad", "bad.ipynb"),
        _entry("after", "good.ipynb", depends_on=["bad"]),
    ]}))
    (root / "book" / "_toc.yml").write_text(yaml.safe_dump({
        "format": "jb-book", "root": "intro",
        "chapters": [{"file": f"generated/{n}"} for n in ("good", "bad", "after")]}))
    env = dict(os.environ, LUNARCAP_ROOT=str(root), LUNARCAP_NO_CACHE="1")
    cmd = [sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--no-build", "--jobs", "2"]
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
    out = run.stdout + run.stderr
    assert run.returncode == 1, out
    assert "error: entry 'bad'" in out and "ZeroDivisionError" in out and "1 / 0" in out
    assert "code cell 2 of bad.ipynb raised ZeroDivisionError" in out, out
    gen = root / "book" / "generated"
    assert (gen / "good.ipynb").is_file() and (gen / "tables" / "good.csv").read_text() == "x\n7\n"
    assert (gen / "bad.failed.ipynb").is_file() and not (gen / "bad.ipynb").exists()
    assert not (gen / "after.ipynb").exists()
    assert not list(gen.glob(".*.tmp.ipynb"))
    # a rerun of the good entry alone is skipped: its stamp matches
    run2 = subprocess.run(cmd + ["--only", "good"], env=env, capture_output=True, text=True,
                          timeout=300)
    assert run2.returncode == 0, run2.stdout + run2.stderr
    assert "good ... up to date (skipped)" in run2.stdout


def _sleeping_tree(root: Path) -> dict:
    """A throw-away book whose two notebooks sleep (each also writes a CSV first)."""
    nbdir = _book_tree(root)
    _notebook(nbdir / "slow.ipynb", body=textwrap.dedent("""
        import time
        import pandas as pd
        from lunarcap.repro import paths
        paths.write_csv(pd.DataFrame({"x": [x]}), output_name)
        time.sleep(600)
        """))
    (nbdir / "manifest.yml").write_text(yaml.safe_dump({"entries": [
        _entry("one", "slow.ipynb", parameters={"x": 1}, outputs=["tables/one.csv"]),
        _entry("two", "slow.ipynb", parameters={"x": 2}, outputs=["tables/two.csv"]),
    ]}))
    (root / "book" / "_toc.yml").write_text(yaml.safe_dump({
        "format": "jb-book", "root": "intro",
        "chapters": [{"file": f"generated/{n}"} for n in ("one", "two")]}))
    return dict(os.environ, LUNARCAP_ROOT=str(root), LUNARCAP_NO_CACHE="1")


@pytest.mark.notebooks
@pytest.mark.parametrize("sig", ["SIGINT", "SIGTERM"])
def test_a_signal_to_the_main_process_alone_stops_everything(tmp_path, sig):
    """SIGINT/SIGTERM sent to the main process only (as `timeout` or a CI runner does).

    Within seconds: exit 128 + signal, one line saying so, no process left below it (the
    kernels run in sessions of their own and would not get a terminal's signal), no
    temporary file and no executed notebook of the interrupted entries.
    """
    import signal
    import time

    root = tmp_path / "tree"
    env = _sleeping_tree(root)
    gen = root / "book" / "generated"
    proc = subprocess.Popen([sys.executable, "-m", "lunarcap.bookbuild.build", "build",
                             "--no-build", "--jobs", "2"], env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        # both kernels are running once both notebooks have written their CSV
        while not ((gen / "tables" / "one.csv").exists() and (gen / "tables" / "two.csv").exists()):
            assert proc.poll() is None, proc.communicate()
            assert time.monotonic() < deadline, "the notebooks never started"
            time.sleep(0.2)
        below = book.descendants(proc.pid)
        assert len(below) >= 4  # two workers, two kernels (at least)
        t0 = time.monotonic()
        proc.send_signal(getattr(signal, sig))
        out, err = proc.communicate(timeout=30)
        took = time.monotonic() - t0
    finally:
        if proc.poll() is None:
            book._kill_all([proc.pid] + book.descendants(proc.pid))
    assert proc.returncode == 128 + getattr(signal, sig), out + err
    assert took < 15, took
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and f"interrupted by {sig}" in lines[0], err
    assert "stopped 2 running notebook(s) (one, two)" in lines[0]
    time.sleep(0.5)
    left = [p for p in below if book._alive(p)]
    assert not left, f"processes left behind: {left}"
    assert not [f.name for f in gen.rglob(".*") if f.is_file()]
    assert not (gen / "one.ipynb").exists() and not (gen / "two.ipynb").exists()
    assert not (gen / "one.stamp.json").exists()


def test_longest_first_starts_the_longest_chain_of_work_first(tmp_path, monkeypatch):
    """Ready entries start by the work they lead to: own time plus the longest chain after.

    Without a recorded run the manifest's ``expected_s`` counts; a stamp's recorded
    ``seconds`` takes precedence; ties keep the manifest's order.
    """
    monkeypatch.setattr(paths, "GENERATED", tmp_path)
    nb = tmp_path / "x.ipynb"

    def entry(name, deps=(), expected_s=0.0):
        return book.Entry(name, name, nb, {}, {}, tuple(deps), (), expected_s)

    entries = [entry("small"), entry("a", expected_s=10), entry("b", ["a"], 30),
               entry("big", expected_s=35), entry("c")]
    assert [e.name for e in book.longest_first(entries)] == ["a", "big", "b", "small", "c"]
    (tmp_path / "small.stamp.json").write_text(json.dumps({"seconds": 100.0}))
    assert [e.name for e in book.longest_first(entries)][:2] == ["small", "a"]
    bad = {"entries": [{"name": "x", "title": "X", "notebook": "x.ipynb", "expected_s": -1}]}
    with pytest.raises(ManifestError, match="expected_s must be a number of seconds"):
        validate_manifest(bad, tmp_path, check_notebooks=False)


@pytest.mark.notebooks
def test_studies_share_one_cluster_named_to_their_kernels_alone(tmp_path):
    """An entry whose parameters set ``workers`` (a Dask study) runs with the book's cluster.

    Its kernel gets the address in LUNARCAP_DASK_SCHEDULER, the same for two studies, and
    a scheduler is listening there while they run; an entry without ``workers`` gets none.
    """
    root = tmp_path / "tree"
    nbdir = _book_tree(root)
    body = textwrap.dedent("""
        import os
        import pandas as pd
        from lunarcap.repro import paths
        addr = os.environ.get("LUNARCAP_DASK_SCHEDULER", "")
        if addr:
            from dask.distributed import Client
            with Client(addr, timeout="30s") as c:
                n = len(c.scheduler_info()["workers"])
        else:
            n = 0
        paths.write_csv(pd.DataFrame({"addr": [addr or "none"], "n": [n]}), output_name)
        """)
    _notebook(nbdir / "study.ipynb", params="workers = 2\nquick = False\noutput_name = 'n'",
              body=body)
    _notebook(nbdir / "page.ipynb", body=body)
    names = ("s1", "s2", "plain")
    (nbdir / "manifest.yml").write_text(yaml.safe_dump({"entries": [
        _entry("s1", "study.ipynb", parameters={"workers": 2}, outputs=["tables/s1.csv"]),
        _entry("s2", "study.ipynb", parameters={"workers": 1}, outputs=["tables/s2.csv"]),
        _entry("plain", "page.ipynb", outputs=["tables/plain.csv"])]}))
    (root / "book" / "_toc.yml").write_text(yaml.safe_dump({
        "format": "jb-book", "root": "intro",
        "chapters": [{"file": f"generated/{n}"} for n in names]}))
    env = dict(os.environ, LUNARCAP_ROOT=str(root), LUNARCAP_NO_CACHE="1")
    env.pop("LUNARCAP_DASK_SCHEDULER", None)
    cmd = [sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--no-build", "--jobs", "2"]
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    tables = root / "book" / "generated" / "tables"
    got = {n: (tables / f"{n}.csv").read_text().splitlines()[1].split(",") for n in names}
    assert got["s1"][0].startswith("tcp://") and got["s1"] == got["s2"], got
    assert got["s1"][1] == "2" and got["plain"] == ["none", "0"], got


@pytest.mark.notebooks
def test_entries_share_a_kernel_but_not_its_namespace(tmp_path):
    """One worker runs its entries in one kernel (the modules stay imported), yet each
    page starts as in a fresh kernel: no variable, figure or study address of the page
    before it, and its code cells numbered from 1.
    """
    root = tmp_path / "tree"
    nbdir = _book_tree(root)
    body = textwrap.dedent("""
        import os
        import sys
        import pandas as pd
        import matplotlib.pyplot as plt
        from lunarcap.repro import paths
        row = {"pid": os.getpid(), "leaked": "leak" in globals(),
               "figures": len(plt.get_fignums()),
               "address": os.environ.get("LUNARCAP_DASK_SCHEDULER", "none"),
               "imported_before": "lunarcap.bookbuild.kernels_probe" in sys.modules}
        sys.modules.setdefault("lunarcap.bookbuild.kernels_probe", sys)
        paths.write_csv(pd.DataFrame([row]), output_name)
        leak = 1
        plt.figure()
        os.environ["LUNARCAP_DASK_SCHEDULER"] = "tcp://left.behind:1"
        """)
    _notebook(nbdir / "page.ipynb", body=body)
    names = ("first", "second", "third")
    (nbdir / "manifest.yml").write_text(yaml.safe_dump({"entries": [
        _entry(n, "page.ipynb", outputs=[f"tables/{n}.csv"],
               depends_on=[names[i - 1]] if i else [])
        for i, n in enumerate(names)]}))
    (root / "book" / "_toc.yml").write_text(yaml.safe_dump({
        "format": "jb-book", "root": "intro",
        "chapters": [{"file": f"generated/{n}"} for n in names]}))
    env = dict(os.environ, LUNARCAP_ROOT=str(root), LUNARCAP_NO_CACHE="1")
    env.pop("LUNARCAP_DASK_SCHEDULER", None)
    cmd = [sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--no-build", "--jobs", "1"]
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout + run.stderr
    gen = root / "book" / "generated"
    rows = {n: (gen / "tables" / f"{n}.csv").read_text().splitlines()[1].split(",")
            for n in names}
    assert len({r[0] for r in rows.values()}) == 1, rows  # one kernel
    assert [r[4] for r in rows.values()] == ["False", "True", "True"], rows
    for n in names:
        assert rows[n][1:4] == ["False", "0", "none"], (n, rows[n])
        nb = nbformat.read(str(gen / f"{n}.ipynb"), as_version=4)
        counts = [c.execution_count for c in nb.cells if c.cell_type == "code"
                  and c.execution_count is not None]
        assert sorted(counts) == list(range(1, len(counts) + 1)), (n, counts)
        assert not any("%reset" in c.source for c in nb.cells)
    assert not [f.name for f in gen.rglob(".*") if f.is_file()]


@pytest.mark.notebooks
def test_studies_run_on_an_existing_cluster_given_by_address(tmp_path, dask_cluster):
    """``build --scheduler ADDR`` (``make book SCHEDULER=ADDR``): the book's studies run on
    that cluster (a loopback scheduler and one worker started by the fixture), no local
    cluster is started, and an entry without ``workers`` gets no address.

    The study entry runs a real campaign (one dispersion sample of the 150 N plan in
    two-body dynamics): its run record names the given scheduler and its one worker, and
    the sample is flown there ("ok", a total delta-V above the nominal's impulsive 353 m/s).
    """
    root = tmp_path / "tree"
    nbdir = _book_tree(root)
    study = textwrap.dedent("""
        import os
        import pandas as pd
        from dask.distributed import Client
        from lunarcap.mission.plan import load_plan
        from lunarcap.repro import paths
        from lunarcap.studies.dispersions import samples as disp
        addr = os.environ.get("LUNARCAP_DASK_SCHEDULER", "")
        with Client(addr, timeout="30s") as c:
            n = len(c.scheduler_info()["workers"])
        plan = load_plan("song2011-150N").with_dynamics("two-body")
        res = disp.run_dispersions(plan, 1, 2011, disp.ErrorModel(thrust_sigma_pct=1.0),
                                   out=paths.GENERATED / "disp.csv", workers=workers,
                                   progress=False)
        row = res.table.iloc[0]
        paths.write_csv(pd.DataFrame({"addr": [addr], "n": [n],
                                      "run_scheduler": [res.run["scheduler"]],
                                      "run_workers": [res.run["workers"]],
                                      "status": [row.status],
                                      "dv": [row.total_delta_v_mps]}), output_name)
        """)
    plain = textwrap.dedent("""
        import os
        import pandas as pd
        from lunarcap.repro import paths
        addr = os.environ.get("LUNARCAP_DASK_SCHEDULER", "") or "none"
        paths.write_csv(pd.DataFrame({"addr": [addr]}), output_name)
        """)
    _notebook(nbdir / "study.ipynb", params="workers = 2\nquick = False\noutput_name = 'n'",
              body=study)
    _notebook(nbdir / "page.ipynb", body=plain)
    (nbdir / "manifest.yml").write_text(yaml.safe_dump({"entries": [
        _entry("s1", "study.ipynb", parameters={"workers": 2}, outputs=["tables/s1.csv"]),
        _entry("plain", "page.ipynb", outputs=["tables/plain.csv"])]}))
    (root / "book" / "_toc.yml").write_text(yaml.safe_dump({
        "format": "jb-book", "root": "intro",
        "chapters": [{"file": f"generated/{n}"} for n in ("s1", "plain")]}))
    env = dict(os.environ, LUNARCAP_ROOT=str(root), LUNARCAP_NO_CACHE="1")
    env.pop("LUNARCAP_DASK_SCHEDULER", None)
    cmd = [sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--no-build",
           "--jobs", "2"]
    run = subprocess.run(cmd + ["--scheduler", dask_cluster], env=env, capture_output=True,
                         text=True, timeout=900)
    assert run.returncode == 0, run.stdout + run.stderr
    tables = root / "book" / "generated" / "tables"
    s1 = (tables / "s1.csv").read_text().splitlines()[1].split(",")
    assert s1[0] == dask_cluster and s1[1] == "1", s1        # the fixture's one worker
    assert s1[2] == dask_cluster and s1[3] == "1", s1        # the campaign ran there
    assert s1[4] == "ok" and float(s1[5]) > 353.0, s1
    assert (tables / "plain.csv").read_text().splitlines()[1] == "none"


def test_a_scheduler_that_does_not_answer_is_refused_before_any_work(tmp_path):
    root = tmp_path / "tree"
    nbdir = _book_tree(root)
    _notebook(nbdir / "page.ipynb", body="raise SystemExit('must not run')")
    (nbdir / "manifest.yml").write_text(yaml.safe_dump({"entries": [
        _entry("plain", "page.ipynb")]}))
    (root / "book" / "_toc.yml").write_text(yaml.safe_dump({
        "format": "jb-book", "root": "intro", "chapters": [{"file": "generated/plain"}]}))
    env = dict(os.environ, LUNARCAP_ROOT=str(root), LUNARCAP_NO_CACHE="1")
    import socket

    with socket.socket() as s:   # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    cmd = [sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--no-build",
           "--scheduler", f"tcp://127.0.0.1:{port}"]
    run = subprocess.run(cmd, env=env, capture_output=True, text=True, timeout=120)
    lines = [ln for ln in run.stderr.splitlines() if ln.strip()]
    assert run.returncode == 2, run.stdout + run.stderr
    assert len(lines) == 1 and "--scheduler tcp://127.0.0.1:" in lines[0] and \
        "no Dask scheduler answers there" in lines[0], run.stderr
    assert not (root / "book" / "generated" / "plain.ipynb").exists()
