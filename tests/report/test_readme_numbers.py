"""The README quotes only numbers a build produces, and the same ones as the book.

A number the README takes from the book carries a marker right after it naming the page
and the glued value it is, and the format it is printed with::

    Delta-V 912.8<!-- book: plan_lro_like::total_delta_v_mps:.1f --> m/s

(the marker is an HTML comment: invisible on a rendered README). Three checks:

* every marker names a page of the manifest and a value that page's code glues;
* every result-like number of the README (a number with a unit of the book's results:
  m/s, km, h, kg, %) is marked, or says which run of its own produced it
  (``2,056.9<!-- run: lunarcap plan, two-body --> km``, the run named in the text too), or
  is a number the package itself states (an input, a constant, a tolerance: it appears in
  the package's source or its plans), so a figure copied from a past run cannot stay in
  the README;
* with the full book built (``make book``), every marked number is the book's value as
  printed with the marker's format; without it, that check is skipped (``make test``
  builds the quick book only, whose cases are not the README's).
"""

import re
from pathlib import Path

import pytest

from lunarcap.bookbuild.manifest import load_manifest
from lunarcap.report import landing as F
from lunarcap.repro import paths

README = paths.ROOT / "README.md"
#: A marked number: the number, then the marker.
MARKED = re.compile(r"(?P<num>[-+]?\d[\d,]*(?:\.\d+)?)<!-- book: (?P<entry>\w+)::(?P<name>\w+)"
                    r":(?P<fmt>[^ ]*) -->")
#: A number the README says a run of its own produced (the run named in the text and in
#: the marker): ``2,056.9<!-- run: lunarcap plan, two-body --> km``.
RUN = re.compile(r"(?P<num>[-+]?\d[\d,]*(?:\.\d+)?)<!-- run: [^>]+ -->")
#: A result-like number: digits (thousands commas allowed), then one of the result units.
RESULT = re.compile(r"(?<![\w.\-])(?P<num>\d[\d,]*(?:\.\d+)?)(?:<!--[^>]*-->)?\s?"
                    r"(?P<unit>m/s|km|h|kg|%)(?![\w/])")


def _plain(num: str) -> str:
    return num.replace(",", "")


def _package_numbers() -> set[str]:
    """Every number written in the package's source and plans (inputs, constants, limits)."""
    text = "\n".join(p.read_text(encoding="utf-8") for p in
                     [*(paths.ROOT / "lunarcap").rglob("*.py"),
                      *(paths.ROOT / "lunarcap").rglob("*.yaml")])
    return {_plain(m) for m in re.findall(r"\d[\d,]*(?:\.\d+)?", text)}


def _page_source(entry) -> str:
    """The notebook and the page module of a manifest entry (where its glued names live)."""
    nb = entry.notebook
    module = paths.ROOT / "lunarcap" / "report" / "pages" / f"{nb.stem}.py"
    if nb.stem == "loi_sweep":
        module = module.with_name("sweep.py")
    return nb.read_text(encoding="utf-8") + (module.read_text(encoding="utf-8")
                                             if module.is_file() else "")


def unmarked_results(text: str, known: set[str]) -> list[str]:
    """Result-like numbers of ``text`` neither marked nor stated by the package."""
    marked = {m.start("num") for r in (MARKED, RUN) for m in r.finditer(text)}
    out = []
    for m in RESULT.finditer(text):
        if m.start("num") in marked or _plain(m.group("num")) in known:
            continue
        out.append(text[max(m.start() - 40, 0): m.end() + 10].replace("\n", " "))
    return out


def test_every_marker_names_a_page_and_a_value_it_glues():
    text = README.read_text(encoding="utf-8")
    entries = {e.name: e for e in load_manifest(check_notebooks=False)}
    marks = list(MARKED.finditer(text))
    assert marks, "the README quotes no number of the book"
    for m in marks:
        assert m.group("entry") in entries, m.group(0)
        # a name composed per engine ("total_delta_v_mps_150N") is glued from its stem
        stem = re.sub(r"_\d+N$", "", m.group("name"))
        src = _page_source(entries[m.group("entry")])
        assert f'"{m.group("name")}"' in src or f'"{stem}"' in src, m.group(0)


def test_the_readme_quotes_no_result_a_build_does_not_produce():
    bad = unmarked_results(README.read_text(encoding="utf-8"), _package_numbers())
    assert not bad, ("numbers the README quotes that no build produces (mark each with "
                     "<!-- book: page::name:format --> or say which run made it): "
                     + " | ".join(bad[:8]))


def test_the_check_catches_a_figure_copied_from_a_past_run():
    # the README's missed-thrust distances before issue 27: no build printed them
    old = ("every 720 min case: the spacecraft is 23,000-48,000 km from the Moon by then; "
           "43,688 km from the Moon ... lasts at least 85.6 h, more than the 24 h allowed")
    found = unmarked_results(old, _package_numbers())
    assert any("23,000" in f for f in found) and any("43,688" in f for f in found)
    assert unmarked_results("a loss of 76.2<!-- book: plan_lro_like::total_delta_v_loss_mps"
                            ":.1f --> m/s", set()) == []


def test_the_readme_numbers_are_the_full_books():
    text = README.read_text(encoding="utf-8")
    generated = paths.BOOK_SOURCES / "generated"
    values, problems = {}, []
    for m in MARKED.finditer(text):
        nb = generated / f"{m.group('entry')}.ipynb"
        if not nb.is_file():
            pytest.skip(f"the full book is not built ({nb.name} missing): run `make book`")
        if m.group("entry") not in values:
            values[m.group("entry")] = F.glued(nb)
        v = values[m.group("entry")].get(m.group("name"))
        shown = F.shown(v, m.group("fmt")) if v is not None else "(not glued)"
        if shown != m.group("num"):
            problems.append(f"{m.group('num')} in the README, {shown} in the book "
                            f"({m.group('entry')}::{m.group('name')})")
    assert not problems, "; ".join(problems)


def test_marked_numbers_are_compared_as_printed(tmp_path):
    # the comparison is of the text: a number that rounds differently is a difference
    assert F.shown(912.76, ".1f") == "912.8" and F.shown(22372.4, ",.0f") == "22,372"
    m = MARKED.search("needs 890.2<!-- book: plan_two_burn::total_delta_v_mps:.1f --> m/s")
    assert (m.group("num"), m.group("entry"), m.group("name"), m.group("fmt")) == \
        ("890.2", "plan_two_burn", "total_delta_v_mps", ".1f")
    assert Path(README).is_file()
