"""The findings the landing page states, how to cite, and the check that no page says nan.

Fast: synthetic executed notebooks and HTML; the quick book's pages are checked in
tests/report/test_notebooks.py.
"""

import zipfile

import nbformat
import pytest

from lunarcap.bookbuild import bookcheck
from lunarcap.bookbuild.manifest import Entry
from lunarcap.report import landing as findings
from lunarcap.report.page import Page
from lunarcap.report.pages import findings as findings_page
from lunarcap.repro import paths


def _executed(path, page: Page):
    """An executed notebook holding ``page``'s glue, as myst-nb's glue writes it."""
    from IPython.display import Markdown

    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("page.glue()")
    prefix = "application/papermill.record/"
    for name, v in {**page.values, **page.notes}.items():
        mime = ({f"{prefix}text/markdown": v, f"{prefix}text/plain": repr(Markdown(v))}
                if name in page.notes else {f"{prefix}text/plain": repr(v)})
        cell.outputs.append(nbformat.v4.new_output(
            "display_data", data=mime,
            metadata={"scrapbook": {"mime_prefix": prefix, "name": name}}))
    nb.cells.append(cell)
    nbformat.write(nb, str(path))


def test_glued_values_and_findings_are_read_back_from_an_executed_notebook(tmp_path):
    p = Page("nb", {}, "summary", quick=True)
    p.value("total_delta_v_loss_mps_150N", 20.35)
    p.value("total_delta_v_loss_mps_300N", float("nan"))
    p.headline("The capture loses 20.35 m/s.")
    _executed(tmp_path / "summary.ipynb", p)
    g = findings.glued(tmp_path / "summary.ipynb")
    assert g["total_delta_v_loss_mps_150N"] == 20.35
    assert findings.shown(g["total_delta_v_loss_mps_300N"], ".2f") == \
        "— (not run in the quick book)"
    e = Entry("summary", "Table B1", tmp_path / "x.ipynb", {}, {}, (), ())
    items = findings.headlines([e], tmp_path, ["index", "generated/summary"])
    assert items == [findings.Headline("generated/summary", "Table B1",
                                       "The capture loses 20.35 m/s.")]
    assert "{doc}`Table B1 </generated/summary>`: The capture loses" in \
        findings.by_page_markdown(items, "/")


def test_the_first_screen_states_the_findings_with_their_numbers_and_how_to_cite():
    values = {"reproduction_report": {"b1_max_dv_diff_percent": 0.21, "n_inconsistent": 14,
                                      "n_findings": 61, "sun_ratio": 10.0},
              "verification": {"n_passed": 37, "n_cases": 37},
              "summary": {"total_delta_v_loss_mps_150N": 20.35,
                          "total_delta_v_loss_mps_300N": 5.12,
                          "total_delta_v_loss_mps_450N": 3.17}}
    items = [findings.Headline("generated/missed_thrust", "Missed thrust: a burn gone wrong",
                               "x")]
    cite = {"version": "0.1.0", "date": "2026-11-27"}
    md = findings_page.first_screen(values, items, ["generated/missed_thrust"], cite)
    assert md.index("{ref}`how to cite it <how-to-cite>`") < md.index("The paper, reproduced")
    assert "lunarcap 0.1.0 of 2026-11-27" in md
    assert "within 0.21 %" in md and "37 of 37" in md
    assert "20.35, 5.12 and 3.17 m/s (150 N / 200 s, 300 N / 250 s and 450 N / 300 s)" in md
    assert "14 of 61 checks" in md and "10 times too small" in md
    assert "1 pages beyond the paper: {doc}`Missed thrust </generated/missed_thrust>`" in md
    # a value no build produced says so instead of a number
    values["summary"].pop("total_delta_v_loss_mps_450N")
    md = findings_page.first_screen(values, items, [])
    assert "450 N / 300 s: not in this build" in md and "nan" not in md


def test_how_to_cite_comes_from_citation_cff_alone(tmp_path):
    c = findings.citation(paths.ROOT / "CITATION.cff")
    assert c["version"] and c["license"] == "BSD-3-Clause" and c["date"]
    bib = findings.bibtex(c)
    assert bib.startswith("@software{lunarcap,") and f"version = {{{c['version']}}}" in bib
    cff = tmp_path / "CITATION.cff"
    cff.write_text("cff-version: 1.2.0\ntitle: t\nversion: 9.9\nlicense: MIT\n"
                   "date-released: 2030-01-02\nrepository-code: https://example.org/x\n"
                   "authors:\n  - name: someone\n", encoding="utf-8")
    md = findings.citation_markdown(findings.citation(cff))
    assert "lunarcap 9.9, released 2030-01-02" in md and "<https://example.org/x>" in md
    assert "version = {9.9}" in md and "url     = {https://example.org/x}" in md


def test_the_archive_holds_every_data_file_and_depends_on_content_only(tmp_path):
    for rel in ("tables/a.csv", "data/s_study.csv", "export/x/plan.oem", "figures/f.png"):
        (tmp_path / rel).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / rel).write_text(rel, encoding="utf-8")
    out, n = findings.write_archive(tmp_path, "all.zip")
    names = zipfile.ZipFile(out).namelist()
    assert n == 3 and names == ["data/s_study.csv", "export/x/plan.oem", "tables/a.csv"]
    first = out.read_bytes()
    (tmp_path / "tables/a.csv").touch()                   # a newer file, the same content
    assert findings.write_archive(tmp_path, "all.zip")[0].read_bytes() == first


@pytest.mark.parametrize("html,found", [
    ("<p>the chains lose 20.35, nan and nan m/s</p>", 2),
    ("<p>divides the LOI 1 loss by NaN</p>", 1),
    ("<td>nan</td>", 1),
    ("<p>lose 20.35, — (not run in the quick book) m/s; Nanjing</p>", 0),
    ('<div class="cell_input"><pre>x = np.nan</pre></div><p>ok</p>', 0),
])
def test_a_page_that_says_nan_is_found(html, found):
    assert len(bookcheck.nan_mentions(bookcheck.page_words(html))) == found


def test_check_pages_names_each_page_that_says_nan(tmp_path):
    (tmp_path / "generated").mkdir()
    (tmp_path / "index.html").write_text("<p>lose 20.35, nan and nan m/s</p>")
    (tmp_path / "generated" / "a.html").write_text("<p>fine</p>")
    found = bookcheck.check_pages(tmp_path, ["index", "generated/a", "generated/not_built"])
    assert list(found) == ["index"] and len(found["index"]) == 2
