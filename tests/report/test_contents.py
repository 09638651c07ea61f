"""A book page is its module, its notebook and one registration line (lunarcap.report.contents).

The build reads what it executes and the table of contents from the registered pages
(lunarcap.report.pages.PAGES): a toy page added in a temporary package, with a tiny
notebook, reaches both without any other file; a page or notebook without its other half
is an error naming it.
"""

import sys
import textwrap

import nbformat
import pytest
import yaml

from lunarcap.bookbuild import manifest
from lunarcap.report import contents, pages
from lunarcap.repro import paths


def _notebook(path):
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_markdown_cell("# Toy"),
                nbformat.v4.new_code_cell("x = 1\nquick = False\noutput_name = 'toy'"),
                nbformat.v4.new_code_cell("print(x)")]
    nb.cells[1].metadata["tags"] = ["parameters"]
    nbformat.write(nb, str(path))
    return path


def _toy_page(tmp_path, notebook, part="Beyond the paper", order=65, module="toy_page"):
    """A page module in the temporary package ``toybook`` (on sys.path via the fixture)."""
    package = tmp_path / "toybook"
    package.mkdir(exist_ok=True)
    (package / "__init__.py").write_text("")
    (package / f"{module}.py").write_text(textwrap.dedent(f"""
        from lunarcap.report.contents import BookPage, Execution, table_files

        NOTEBOOK = {str(notebook)!r}
        BOOK = BookPage(NOTEBOOK, {part!r}, {order}, (
            Execution("toy", "A toy page", parameters=dict(x=2), quick_parameters=dict(x=3),
                      depends_on=("table1",), outputs=table_files("toy", "x")),
        ))
        """))
    return f"toybook.{module}"


@pytest.fixture
def register(tmp_path, monkeypatch):
    """Register a page module: the one line a new page adds to PAGES."""
    assert manifest.from_pages(), "lunarcap's book has no notebooks/manifest.yml"
    monkeypatch.syspath_prepend(str(tmp_path))

    def add(name):
        monkeypatch.setattr(pages, "PAGES", pages.PAGES + (name,))
    yield add
    for name in [n for n in sys.modules if n.split(".")[0] == "toybook"]:
        del sys.modules[name]


def test_a_registered_toy_page_reaches_the_manifest_and_the_table_of_contents(tmp_path,
                                                                             register):
    register(_toy_page(tmp_path, _notebook(tmp_path / "toy.ipynb")))
    entries = {e.name: e for e in manifest.load_manifest()}
    toy = entries["toy"]
    assert toy.notebook == (tmp_path / "toy.ipynb").resolve()
    assert toy.title == "A toy page" and toy.depends_on == ("table1",)
    assert toy.effective_parameters(quick=True) == {"x": 3, "quick": True,
                                                    "output_name": "toy"}
    assert toy.outputs == ("tables/toy_x.csv",)
    files = manifest.toc_files()
    # order 65 of "Beyond the paper": after the real missions (60), before the plans (70)
    i = files.index("generated/toy")
    assert files[i - 1:i + 3] == ["generated/real_missions", "generated/toy",
                                  "generated/plan_lro_like", "generated/plan_two_burn"]
    manifest.check_toc(list(entries.values()))
    # the files given to jupyter-book and kept beside the build
    toc = yaml.safe_load(manifest.write_contents(tmp_path / "build").read_text())
    beyond = next(p for p in toc["parts"] if p["caption"] == "Beyond the paper")
    assert {"file": "generated/toy"} in beyond["chapters"]
    written = yaml.safe_load((tmp_path / "build" / "manifest.yml").read_text())
    assert [e for e in written["entries"] if e["name"] == "toy"][0]["parameters"] == {"x": 2}


def test_the_registered_pages_make_the_book_in_its_order():
    pages_ = contents.registered()
    assert contents.problems(pages_) == []
    names = [x.name for x in contents.executions(pages_)]
    assert len(names) == len(set(names)) and names[:3] == ["fig1_geometry",
                                                           "impulsive_baseline", "lunar_pole"]
    parts = dict(contents.toc_parts(pages_))
    assert list(parts) == list(contents.PARTS)
    assert parts["The problem"] == ["model", "generated/lunar_pole"]
    assert parts["Reproduce"] == ["generated/glossary", "rerun", "api", "references"]
    assert parts["The paper's tables"][-1] == "generated/summary"


def test_a_page_whose_notebook_is_missing_is_an_error_naming_it(tmp_path, register):
    register(_toy_page(tmp_path, tmp_path / "absent.ipynb", module="lost_page"))
    with pytest.raises(manifest.ManifestError) as err:
        manifest.load_manifest()
    assert "page toybook.lost_page: its notebook" in str(err.value)
    assert "absent.ipynb does not exist" in str(err.value)


def test_a_notebook_without_a_page_is_an_error_naming_it(tmp_path):
    notebooks = tmp_path / "notebooks"
    notebooks.mkdir()
    _notebook(notebooks / "orphan.ipynb")
    errors = contents.problems(contents.registered(), notebooks)
    assert errors == ["notebook orphan.ipynb has no page: declare BOOK in its page module "
                      "and register the module in lunarcap.report.pages.PAGES"]


def test_a_registration_without_a_page_and_places_that_clash_are_errors(tmp_path, register):
    with pytest.raises(contents.ContentsError, match="page toybook.nothing: no such module"):
        contents.registered(["toybook.nothing"])
    register("glossary")  # twice
    nb = _notebook(tmp_path / "toy.ipynb")
    clash = _toy_page(tmp_path, nb, part="Results", order=10, module="clash")
    elsewhere = _toy_page(tmp_path, nb, part="Appendix", module="elsewhere")
    errors = contents.problems(contents.registered(pages.PAGES + (clash, elsewhere)))
    assert ("page lunarcap.report.pages.glossary: notebook notebooks/glossary.ipynb is "
            "lunarcap.report.pages.glossary's already") in errors
    assert ("page toybook.clash and page lunarcap.report.pages.findings both stand at order "
            "10 of part 'Results'") in errors
    assert any(e.startswith("page toybook.elsewhere: unknown part 'Appendix'")
               for e in errors)
    assert any("toy.ipynb is toybook.clash's already" in e for e in errors)


def test_the_book_keeps_no_manifest_or_toc_in_its_sources():
    # generated beside the build only: no copy to keep in step by hand, and a stale
    # notebooks/manifest.yml would be executed instead of the registered pages
    assert not paths.MANIFEST.exists() and not paths.TOC.exists()


def test_a_floor_must_be_a_floor_on_a_parameter_of_its_execution(tmp_path):
    nb = _notebook(tmp_path / "toy.ipynb")
    x = contents.Execution("toy", "Toy", parameters=dict(samples=368),
                           floors=dict(samples=contents.at_least(368, "the 99 % point"),
                                       seed=contents.at_least(1, "a seed"), workers=2))
    page = ("toybook.floored", contents.BookPage(str(nb), "Beyond the paper", 66, (x,)))
    errors = contents.problems([page], tmp_path / "none")
    assert errors == [
        "page toybook.floored: execution 'toy': floor of 'seed': no such parameter in its "
        "parameters",
        "page toybook.floored: execution 'toy': floor of 'workers' must be a Floor "
        "(at_least, includes...)"]
