"""The book's API reference (book/api.md) documents every public name, each with an example.

The page is Sphinx autodoc over ``lunarcap.__all__``: its directives name each public
object, whose docstring Sphinx renders. A name added to ``__all__`` and not to the page,
or a page entry left behind when a name goes, fails here rather than in a reader's hands.
"""

import re

import pytest

import lunarcap
from lunarcap.report import contents
from lunarcap.repro import paths

API_PAGE = paths.BOOK_SOURCES / "api.md"
#: ``.. autofunction:: load_plan`` and its kin: one documented entry each.
_ENTRY = re.compile(r"^\s*\.\. auto(?:function|class|exception|data)::\s+(\w+)", re.M)
#: Names that are not objects with a docstring of their own: described in the page's text.
IN_PROSE = {"__version__"}


def documented(text: str) -> dict:
    """``{"entries": [...], "summary": [...]}``: the autodoc entries and autosummary rows."""
    summary = []
    for block in re.finditer(r"\.\. autosummary::\n((?:[ \t]+.*\n|\n)+)", text):
        summary += [ln.strip() for ln in block[1].splitlines()
                    if ln.strip() and not ln.strip().startswith(":")]
    return {"entries": _ENTRY.findall(text), "summary": summary}


@pytest.fixture(scope="module")
def page():
    return API_PAGE.read_text(encoding="utf-8")


def test_every_public_name_has_an_entry_and_a_summary_row(page):
    names = set(lunarcap.__all__) - IN_PROSE
    doc = documented(page)
    assert names - set(doc["entries"]) == set(), "public names without an entry"
    assert names - set(doc["summary"]) == set(), "public names missing from the summary"
    assert set(doc["entries"]) | set(doc["summary"]) <= set(lunarcap.__all__), \
        "entries for names that are not public"
    assert len(doc["entries"]) == len(set(doc["entries"])), "a name documented twice"
    for name in IN_PROSE:
        assert f"lunarcap.{name}" in page, name


def test_the_check_sees_a_name_left_out():
    text = API_PAGE.read_text(encoding="utf-8").replace(".. autofunction:: missed\n", "")
    assert "missed" not in documented(text)["entries"]


@pytest.mark.parametrize("name", sorted(set(lunarcap.__all__) - IN_PROSE))
def test_every_public_name_has_an_example(name):
    doc = getattr(lunarcap, name).__doc__ or ""
    assert ">>> " in doc, f"lunarcap.{name}: its docstring has no example"


def test_the_reference_is_in_the_table_of_contents():
    files = contents.toc_files(contents.registered())
    assert "api" in files and "generated/tutorial" in files
    assert files.index("generated/tutorial") < files.index("generated/impulsive_baseline")
