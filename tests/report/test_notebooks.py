"""Notebooks are tested by running them: a quick build of the whole book, then checks.

The build (``python -m lunarcap.bookbuild.build build --quick``) writes into the real, git-ignored
``book/generated`` and ``book/_build``. The source-notebook lint tests at the end are
fast and not marked.
"""

import json
import re
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlparse

import nbformat
import pandas as pd
import pytest

from lunarcap.bookbuild import build as book
from lunarcap.repro import paths

ENTRIES = book.load_manifest()


def _full_book_files():
    """(path, size, mtime) of every file the full book's build made (may be none yet)."""
    full = [paths.BOOK_SOURCES / "generated", paths.BOOK_SOURCES / "_build" / "html"]
    return {(f.as_posix(), f.stat().st_size, f.stat().st_mtime_ns)
            for d in full if d.is_dir() for f in d.rglob("*") if f.is_file()}


@pytest.fixture(scope="module")
def quick_build():
    """The quick book, built in ``book/_build/quick``; the tests below read it there."""
    before = _full_book_files()
    run = subprocess.run([sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--quick"],
                         cwd=paths.ROOT, capture_output=True, text=True, timeout=1800)
    assert run.returncode == 0, run.stdout + run.stderr
    touched = before ^ _full_book_files()
    with paths.using_book(paths.QUICK_BOOK):
        yield {"stdout": run.stdout, "touched_full_book": touched}


@pytest.mark.notebooks
def test_quick_build_leaves_the_full_book_alone(quick_build):
    # `make test` after `make book` must not replace the full book's pages, tables or
    # stamps with the quick ones (nor make the next `make book` start over)
    assert not quick_build["touched_full_book"], sorted(quick_build["touched_full_book"])[:5]
    assert (paths.HTML / "index.html").is_file()
    assert paths.HTML.is_relative_to(paths.BOOK_SOURCES / "_build" / "quick")


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


_VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source",
         "track", "wbr"}


class _Reader(HTMLParser):
    """What a reader of a built page gets: scripts and stylesheets it loads, the text it
    shows (cell outputs apart from prose; code cells and literal code blocks left out),
    the kinds of cell outputs, and the captions with their numbers."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack = []                   # open elements: (tag, classes)
        self.assets = []                  # (kind, url) of scripts and stylesheets
        self.text = {"output": [], "prose": []}
        self.output_kinds = []            # classes of the output blocks in cell outputs
        self.captions = []                # [number, text] per table or figure caption

    def _inside(self, cls=None, tags=()):
        return any((cls is not None and cls in c) or t in tags for t, c in self.stack)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        cls = set((a.get("class") or "").split())
        rel = set((a.get("rel") or "").split())
        if tag == "script" and a.get("src"):
            self.assets.append(("script", a["src"]))
        elif tag == "link" and ("stylesheet" in rel or
                                ("preload" in rel and a.get("as") in ("script", "style"))):
            self.assets.append(("stylesheet" if "stylesheet" in rel else "preload",
                                a.get("href", "")))
        if "output" in cls and self._inside("cell_output"):
            self.output_kinds.append(cls - {"output", "notranslate"})
        if tag in ("caption", "figcaption"):
            self.captions.append(["", ""])
        if tag not in _VOID:
            self.stack.append((tag, cls))

    def handle_startendtag(self, tag, attrs):
        self.handle_starttag(tag, attrs)
        if tag not in _VOID:
            self.stack.pop()

    def handle_endtag(self, tag):
        for i in range(len(self.stack) - 1, -1, -1):
            if self.stack[i][0] == tag:
                del self.stack[i:]
                break

    def handle_data(self, data):
        if self._inside(tags=("script", "style")) or self._inside("cell_input"):
            return
        if self._inside(tags=("caption", "figcaption")) and self.captions:
            self.captions[-1][0 if self._inside("caption-number") else 1] += data
        if self._inside("cell_output"):
            self.text["output"].append(data)
        elif not self._inside(tags=("pre", "code")) and not self._inside("highlight"):
            self.text["prose"].append(data)


def _read(page: Path) -> _Reader:
    reader = _Reader()
    reader.feed(page.read_text(encoding="utf-8"))
    return reader


#: Markup that should have been rendered, Python reprs, tracebacks and progress bars: none
#: belongs in what a reader sees.
LEAKS = {
    "a raw MyST directive": re.compile(r":::\{|```\{|^\s*:(name|alt|width|align):", re.M),
    "a raw MyST role or glue": re.compile(r"\{glue|\{(download|doc|ref|numref|eq|math)\}`"),
    "a Python repr": re.compile(r"<Figure size|<matplotlib|\bDataFrame\b|object at 0x|"
                                r"\bnp\.float64\(|<lunarcap\."),
    "a traceback": re.compile(r"Traceback \(most recent call last\)|\w+Error: "),
    "a progress bar": re.compile(r"\d+%\||\d+(\.\d+)?(it|s|engine)/s\]|\|[█▏▎▍▌▋▊▉]+"),
}
#: A run of characters without a space longer than this would be a line thousands of px
#: wide (a repr of a whole Markdown block is one); the longest honest one is a path or a
#: hash in a provenance block (about 70).
LONGEST_WORD = 200


def leaks(reader: _Reader) -> list[str]:
    """Every leak in a page: markup, reprs, tracebacks, progress bars, stray outputs."""
    found = []
    for where, chunks in reader.text.items():
        text = "\n".join(chunks)
        for what, pattern in LEAKS.items():
            for m in pattern.finditer(text):
                context = text[max(0, m.start() - 40):m.end() + 40].replace("\n", " ")
                found.append(f"{what} in the {where}: ...{context}...")
        for word in text.split():
            if len(word) > LONGEST_WORD:
                found.append(f"a {len(word)}-character word in the {where}: {word[:80]}...")
    for kinds in reader.output_kinds:
        stray = kinds & {"stream", "stderr", "text_plain", "traceback"}
        if stray:
            found.append(f"a stray output ({', '.join(sorted(stray))}) in a cell output")
    return found


def remote_assets(reader: _Reader) -> list[str]:
    """Scripts and stylesheets a page would fetch from another host."""
    return [f"{kind} {url}" for kind, url in reader.assets if re.match(r"(https?:)?//", url)]


#: The paper's own tables and figures (Song et al. 2011).
PAPER_ITEMS = {f"Table {k}" for k in ("1", "2", "3", "4", "5", "B1")} | {
    f"Fig. {k}" for k in range(1, 6)}
_PAPER_LABEL = re.compile(r"^Song et al\. \(2011\) (Table [A-Z]?\d+|Fig\. \d+)\b")


def paper_items_of_title(title: str) -> set:
    """The paper's tables or figures a page title names: "Table 4: ..." -> {"Table 4"},
    "Figs. 2–5: ..." -> Figs. 2 to 5, "Table B1 and ..." -> {"Table B1"}."""
    m = re.match(r"(Tables?|Figs?\.)\s*([A-Z]?)(\d+)(?:[–-](\d+))?", title)
    if not m:
        return set()
    kind = "Table" if m[1].startswith("Table") else "Fig."
    last = int(m[4] or m[3])
    return {f"{kind} {m[2]}{k}" for k in range(int(m[3]), last + 1)}


def numbering_problems(reader: _Reader, title: str) -> list[str]:
    """Captions whose number could be taken for one of the paper's, or that carry a paper
    number on a page that does not regenerate that table or figure."""
    named = paper_items_of_title(title)
    problems, shown = [], set()
    for number, text in reader.captions:
        number, text = number.strip(), " ".join(text.split())
        if number and not re.fullmatch(r"Book (table|figure) \d+", number):
            bare = re.fullmatch(r"(Table|Fig\.) ?([A-Z]?\d+)", number)
            clash = bare and f"{bare[1]} {bare[2]}" in PAPER_ITEMS
            problems.append(f"caption number {number!r}" + (" collides with the paper's"
                                                            if clash else " is not a book number"))
        label = _PAPER_LABEL.match(text)
        if label:
            shown.add(label[1])
            if number:
                problems.append(f"{label[1]} of the paper also numbered {number!r}")
            if label[1] not in named:
                problems.append(f"a caption claims the paper's {label[1]} on a page titled "
                                f"{title!r}")
    problems += [f"the page titled {title!r} shows no caption labelled Song et al. (2011) "
                 f"{item}" for item in sorted(named - shown)]
    return problems


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
def test_page_table_columns_with_a_unit_are_glossary_names(quick_build):
    """Every column of every table a page writes (``tables/*.csv`` of the quick book) that
    carries a unit suffix (:data:`lunarcap.report.labels.UNITS`: ``_mps``, ``_min``, ...)
    is a glossary name (:mod:`lunarcap.quantities`), so a page's number reads like the
    CLI's and the studies'. Words-only columns (``unit``, ``quantity``, ``source``,
    ``case``, ``note``, ``engine``, ...) may stay outside the glossary: they name rows or
    carry text, not a measured quantity. :data:`PAGE_COLUMNS_PENDING` lists the unit
    columns not yet named (each must still occur, so the list only shrinks)."""
    from lunarcap import quantities as Q
    from lunarcap.report.labels import UNITS

    seen, unknown = set(), {}
    for csv in sorted(paths.TABLES.glob("*.csv")):
        columns = [str(c) for c in pd.read_csv(csv, nrows=0).columns]
        seen.update(columns)
        for c in Q.unknown(columns):
            if any(c.endswith(s) and len(c) > len(s) for s in UNITS):
                unknown.setdefault(c, csv.name)
    assert len(list(paths.TABLES.glob("*.csv"))) >= 40 and "delta_v_mps" in seen
    new = {c: f for c, f in unknown.items() if c not in PAGE_COLUMNS_PENDING}
    assert not new, "unit columns not in the glossary: " + ", ".join(
        f"{c} ({f})" for c, f in sorted(new.items()))
    assert PAGE_COLUMNS_PENDING <= set(unknown), sorted(PAGE_COLUMNS_PENDING - set(unknown))


#: Unit columns of the pages' tables not yet in the glossary (to be emptied).
PAGE_COLUMNS_PENDING: set = set()


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
    """No launch/repository buttons; no script or stylesheet from another host, MathJax
    included: it is shipped in _static/mathjax (sphinx-mathjax-offline), so the book's
    equations render with no network (`make screenshots` checks that in Chromium)."""
    n_math_pages = 0
    for page in [paths.HTML / "index.html", *_html_pages()]:
        html = page.read_text(encoding="utf-8")
        for needle in ("mybinder.org", "colab.research.google.com", "github.com/executablebooks"):
            assert needle not in html, (page.name, needle)
        reader = _read(page)
        assert not remote_assets(reader), (page.name, remote_assets(reader))
        for kind, url in reader.assets:
            target = (page.parent / unquote(urlparse(url).path)).resolve()
            assert target.is_file(), f"{page.name}: {kind} {url} does not resolve"
        mathjax = [url for _, url in reader.assets if "mathjax" in url.lower()]
        if 'class="math' in html:
            assert mathjax, f"{page.name} has math but loads no MathJax"
            n_math_pages += 1
    assert n_math_pages >= 2  # the model page and the Fig. 1 page at least


@pytest.mark.notebooks
def test_no_leaked_markup_reprs_tracebacks_or_stray_outputs(quick_build):
    problems = [f"{page.relative_to(paths.HTML)}: {p}" for page in _html_pages()
                for p in leaks(_read(page))]
    assert not problems, "\n".join(problems)


@pytest.mark.notebooks
def test_caption_numbers_never_read_like_the_papers(quick_build):
    # the book's own tables and figures are "Book table N" / "Book figure N"; those that
    # regenerate the paper's carry "Song et al. (2011) Table 1" (no book number), only on
    # the page whose title names them, and every such page shows them
    titles = {f"generated/{e.name}": e.title for e in ENTRIES}
    problems, n_numbered, n_paper = [], 0, 0
    for page in _html_pages():
        key = page.relative_to(paths.HTML).with_suffix("").as_posix()
        reader = _read(page)
        problems += [f"{key}: {p}" for p in numbering_problems(reader, titles.get(key, ""))]
        n_numbered += sum(bool(n.strip()) for n, _ in reader.captions)
        n_paper += sum(bool(_PAPER_LABEL.match(" ".join(t.split()))) for _, t in reader.captions)
    assert not problems, "\n".join(problems)
    assert n_numbered >= 20 and n_paper >= 15  # the checks above did see captions


@pytest.mark.notebooks
def test_no_built_page_says_nan(quick_build):
    # a value a quick run leaves out is printed as its reason ("— (not run in the quick
    # book)"), never "nan" (the landing page read "lose 20.35, nan and nan m/s"); the
    # build itself refuses such a page, for the full book too (bookbuild/bookcheck.py)
    from lunarcap.bookbuild.bookcheck import check_pages

    assert check_pages(paths.HTML, book.toc_files()) == {}
    assert "not run in the quick book" in (paths.HTML / "index.html").read_text(
        encoding="utf-8")   # the quick book says why it leaves the 300 N and 450 N out


#: A finding: a number with the unit of a delta-V, a loss or a share.
_FINDING = re.compile(r"\d+(?:\.\d+)?\s?(?:m/s|%)")


@pytest.mark.notebooks
def test_the_landing_pages_first_screen_states_a_finding_and_how_to_cite(quick_build):
    # read as a reader does: headless Chromium, 1280 x 800 CSS px, offline. Before issue 27
    # the first screen held the title, a paragraph citing the paper and "The problem".
    import shutil

    from lunarcap.bookbuild import screenshots

    if shutil.which("chromium") is None:
        pytest.fail("this test reads the landing page in headless Chromium, which is not "
                    "installed: on Debian, `apt-get install -y chromium` (README, 'Two "
                    "commands')")
    shot = paths.BUILD / "screenshots" / "first_screen_1280x800.png"
    seen = screenshots.first_screen(paths.HTML, "index", 1280, 800, shot)
    findings = [t for t in seen["text"] if _FINDING.search(t)]
    assert findings, f"no finding with a number in the first 800 px: {seen['text'][:6]}"
    assert seen["findings"] and seen["findings"][0]["top"] < 800
    cite = [a for a in seen["links"] if a["href"].endswith("#how-to-cite")]
    assert cite, f"no link to how to cite in the first 800 px: {seen['links'][:8]}"
    assert shot.is_file() and shot.stat().st_size > 10_000


@pytest.mark.notebooks
def test_the_findings_page_lists_every_page_with_its_finding(quick_build):
    from lunarcap.report import landing as findings

    pages = [e for e in ENTRIES if e.name != "findings"]   # the page that lists them
    items = findings.headlines(pages, paths.GENERATED, book.toc_files())
    assert {h.page for h in items} == {f"generated/{e.name}" for e in pages}
    assert all(h.markdown for h in items), [h.page for h in items if not h.markdown]
    landing = (paths.GENERATED / "findings_landing.md").read_text(encoding="utf-8")
    for h in items:   # the landing page's list names every page of the book's last part
        if h.page in ("generated/missed_thrust", "generated/dispersions", "generated/exchange"):
            assert f"</{h.page}>" in landing, h.page


@pytest.mark.notebooks
def test_rerun_with_nothing_changed_executes_nothing(quick_build):
    run = subprocess.run([sys.executable, "-m", "lunarcap.bookbuild.build", "build", "--quick",
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
    # (joining the public API's results of several plans, pd.concat, is a worked example's
    # step, as a reader with several plans would write it; building a table is not)
    for pattern in (r"^\s*def ", r"^\s*class ", r"matplotlib", r"\bplt\.", r"pd\.DataFrame\("):
        assert not re.search(pattern, code, re.M), f"{path.name}: {pattern!r} in a notebook"
    # the parameters cell declares, it computes nothing: its lines are not counted
    body = "\n".join(c.source for c in nb.cells if c.cell_type == "code"
                     and "parameters" not in c.metadata.get("tags", []))
    lines = [ln for ln in body.splitlines() if ln.strip() and not ln.strip().startswith("#")]
    assert len(lines) <= 40, f"{path.name}: {len(lines)} lines of code"


def test_every_source_notebook_is_in_the_manifest():
    used = {Path(e.notebook).name for e in ENTRIES}
    assert {p.name for p in SOURCES} <= used
