"""Notebooks are tested by running them: a quick build of the whole book, then checks.

The build (``python -m lunarcap.report.build build --quick``) writes into the real, git-ignored
``book/generated`` and ``book/_build``. The source-notebook lint tests at the end are
fast and not marked.
"""

import json
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlparse

import nbformat
import pytest

from lunarcap.report import build as book
from lunarcap.repro import paths

ENTRIES = book.load_manifest()


@pytest.fixture(scope="module")
def quick_build():
    run = subprocess.run([sys.executable, "-m", "lunarcap.report.build", "build", "--quick"],
                         cwd=paths.ROOT, capture_output=True, text=True, timeout=1800)
    assert run.returncode == 0, run.stdout + run.stderr
    return run.stdout


class _Page(HTMLParser):
    def __init__(self):
        super().__init__()
        self.imgs, self.tables, self._rows, self._in_tbody = [], [], 0, False

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img":
            self.imgs.append(a.get("src", ""))
        elif tag == "table":
            self._rows = 0
        elif tag == "tbody":
            self._in_tbody = True
        elif tag == "tr" and self._in_tbody:
            self._rows += 1

    def handle_endtag(self, tag):
        if tag == "tbody":
            self._in_tbody = False
        elif tag == "table":
            self.tables.append(self._rows)


def _html_pages():
    return [paths.HTML / f"{f}.html" for f in book.toc_files()]


# ------------------------------------------------------------------ quick build
@pytest.mark.notebooks
def test_every_entry_produced_its_executed_notebook(quick_build):
    for e in ENTRIES:
        assert e.output.is_file(), e.name
        stamp = json.loads(e.stamp_path.read_text())
        assert stamp["parameters"]["quick"] is True and stamp["name"] == e.name
        nb = nbformat.read(str(e.output), as_version=4)
        errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
                  if o.get("output_type") == "error"]
        assert not errors, e.name
        assert nb.cells[0].source.startswith(f"# {e.title}")


@pytest.mark.notebooks
def test_declared_outputs_csvs_and_figures_exist(quick_build):
    for e in ENTRIES:
        for o in e.outputs:
            assert (paths.GENERATED / o).stat().st_size > 0, (e.name, o)
    csvs = sorted(paths.TABLES.glob("*.csv"))
    assert csvs
    for csv in csvs:
        lines = csv.read_text().strip().splitlines()
        assert len(lines) >= 2, f"{csv.name} has no data rows"
    pngs = sorted(paths.FIGURES.glob("*.png"))
    assert pngs
    for png in pngs:
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert png.with_suffix(".svg").is_file()


@pytest.mark.notebooks
def test_html_has_every_toc_page(quick_build):
    assert (paths.HTML / "index.html").is_file()
    missing = [p.relative_to(paths.HTML) for p in _html_pages() if not p.is_file()]
    assert not missing


@pytest.mark.notebooks
def test_every_image_resolves_and_no_table_is_empty(quick_build):
    n_img = 0
    for page in _html_pages():
        parser = _Page()
        parser.feed(page.read_text(encoding="utf-8"))
        for src in parser.imgs:
            url = urlparse(src)
            if url.scheme in ("http", "https"):
                pytest.fail(f"{page.name}: image {src} needs the network")
            if url.scheme == "data":
                continue
            target = (page.parent / unquote(url.path)).resolve()
            assert target.is_file(), f"{page.name}: <img src={src!r}> does not resolve"
            n_img += 1
        assert all(rows > 0 for rows in parser.tables), f"{page.name}: empty table"
    assert n_img >= 1


@pytest.mark.notebooks
def test_pages_are_self_contained(quick_build):
    """No launch/repository buttons or external stylesheets; only MathJax comes from a CDN."""
    for page in _html_pages():
        html = page.read_text(encoding="utf-8")
        for needle in ("mybinder.org", "colab.research.google.com", "github.com/executablebooks"):
            assert needle not in html, (page.name, needle)
        assert 'rel="stylesheet" href="http' not in html


@pytest.mark.notebooks
def test_rerun_with_nothing_changed_executes_nothing(quick_build):
    run = subprocess.run([sys.executable, "-m", "lunarcap.report.build", "build", "--quick",
                          "--no-build"], cwd=paths.ROOT, capture_output=True, text=True,
                         timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    assert run.stdout.count("up to date (skipped)") == len(ENTRIES)
    assert "running" not in run.stdout


# ------------------------------------------------------------------ source notebooks (fast)
SOURCES = sorted(paths.NOTEBOOKS.glob("*.ipynb"))


@pytest.mark.parametrize("path", SOURCES, ids=[p.name for p in SOURCES])
def test_source_notebook_has_no_outputs_and_one_parameters_cell(path):
    nb = nbformat.read(str(path), as_version=4)
    nbformat.validate(nb)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [], f"{path.name}: committed with outputs"
            assert cell.execution_count is None, f"{path.name}: committed with execution counts"
    tagged = [c for c in nb.cells if "parameters" in c.metadata.get("tags", [])]
    assert len(tagged) == 1, f"{path.name}: {len(tagged)} cells tagged 'parameters'"
    names, problems = book.notebook_parameters(path)
    assert not problems and {"quick", "output_name"} <= set(names)


@pytest.mark.parametrize("path", SOURCES, ids=[p.name for p in SOURCES])
def test_source_notebook_is_glue_around_its_page_module(path):
    # A notebook builds its page with a library module (lunarcap.report.pages.<page>) whose
    # NOTEBOOK names this notebook (for the provenance); it defines no functions, draws
    # nothing and assembles no tables itself, and its code is short.
    import importlib
    import re

    nb = nbformat.read(str(path), as_version=4)
    code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
    mods = re.findall(r"from lunarcap\.report\.pages import (\w+)", code)
    assert len(mods) == 1, f"{path.name}: builds its page with one lunarcap.report.pages module"
    module = importlib.import_module(f"lunarcap.report.pages.{mods[0]}")
    assert module.NOTEBOOK == f"notebooks/{path.name}"
    for pattern in (r"^\s*def ", r"^\s*class ", r"matplotlib", r"\bplt\.", r"pd\.DataFrame\(",
                    r"pd\.concat\("):
        assert not re.search(pattern, code, re.M), f"{path.name}: {pattern!r} in a notebook"
    lines = [ln for ln in code.splitlines() if ln.strip() and not ln.strip().startswith("#")]
    assert len(lines) <= 40, f"{path.name}: {len(lines)} lines of code"


def test_every_source_notebook_is_in_the_manifest():
    used = {Path(e.notebook).name for e in ENTRIES}
    assert {p.name for p in SOURCES} <= used
