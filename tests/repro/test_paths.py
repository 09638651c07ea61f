"""The quick book is a copy of the sources with outputs of its own."""

import os
import subprocess
import sys

from lunarcap.repro import paths


def _sources(root):
    (root / "_static").mkdir(parents=True)
    (root / "_static" / "a.js").write_text("js")
    (root / "_toc.yml").write_text("toc")
    (root / "index.md").write_text("# index")
    (root / "generated").mkdir()
    (root / "generated" / "full.ipynb").write_text("{}")
    (root / "_build" / "html").mkdir(parents=True)
    (root / "_build" / "html" / "index.html").write_text("full")


def test_stage_quick_book_copies_sources_only_and_follows_removals(tmp_path, monkeypatch):
    src = tmp_path / "book"
    _sources(src)
    monkeypatch.setattr(paths, "BOOK_SOURCES", src)
    monkeypatch.setattr(paths, "QUICK_BOOK", src / "_build" / "quick")
    quick = paths.stage_quick_book()
    assert quick == src / "_build" / "quick"
    assert sorted(p.name for p in quick.iterdir()) == ["_static", "_toc.yml", "index.md"]
    assert (quick / "_static" / "a.js").read_text() == "js"
    # modification times are kept: jupyter-book's incremental build sees nothing changed
    assert (quick / "index.md").stat().st_mtime_ns == (src / "index.md").stat().st_mtime_ns
    # the quick book's own outputs survive re-staging; a page removed from the sources goes
    (quick / "generated").mkdir()
    (quick / "generated" / "q.ipynb").write_text("{}")
    (src / "index.md").unlink()
    (src / "new.md").write_text("new")
    paths.stage_quick_book()
    assert sorted(p.name for p in quick.iterdir()) == ["_static", "_toc.yml", "generated",
                                                       "new.md"]
    # the full book's outputs were never touched
    assert (src / "generated" / "full.ipynb").read_text() == "{}"
    assert (src / "_build" / "html" / "index.html").read_text() == "full"


def test_book_dir_reaches_child_processes(tmp_path):
    # notebook kernels are child processes: they must write into the book being built
    code = ("from lunarcap.repro import paths; "
            "print(paths.GENERATED); print(paths.HTML); print(paths.TOC)")
    env = dict(os.environ, LUNARCAP_BOOK_DIR=str(tmp_path / "q"))
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True,
                         text=True, check=True).stdout.split()
    assert out[0] == str((tmp_path / "q" / "generated").resolve())
    assert out[1] == str((tmp_path / "q" / "_build" / "html").resolve())
    assert out[2] == str(paths.BOOK_SOURCES / "_toc.yml")  # one table of contents


def test_using_book_moves_every_output_path_and_restores_them(tmp_path, monkeypatch):
    monkeypatch.delenv("LUNARCAP_BOOK_DIR", raising=False)
    before = (paths.BOOK, paths.GENERATED, paths.TABLES, paths.FIGURES, paths.BUILD, paths.HTML)
    with paths.using_book(tmp_path / "q") as book:
        assert book == (tmp_path / "q").resolve()
        assert paths.table_path("t") == book / "generated" / "tables" / "t.csv"
        assert paths.figure_path("f", "svg") == book / "generated" / "figures" / "f.svg"
        assert paths.HTML == book / "_build" / "html"
        assert os.environ["LUNARCAP_BOOK_DIR"] == str(book)
    assert (paths.BOOK, paths.GENERATED, paths.TABLES, paths.FIGURES, paths.BUILD,
            paths.HTML) == before
    assert "LUNARCAP_BOOK_DIR" not in os.environ
