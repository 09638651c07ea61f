"""The one place for paths: repository, book, generated outputs, notebooks and cache.

Every table, figure and executed notebook the book shows is written below
:data:`GENERATED` (``book/generated/``, git-ignored) through the helpers here;
nothing else invents an output folder. Writes are atomic: the content goes to a
temporary file in the destination directory, which is then moved into place with
:func:`os.replace`, so an interrupted or failed run never leaves a half-written file.

Layout::

    <ROOT>/
        notebooks/            source notebooks (committed without outputs)
            manifest.yml      what the book executes (see :mod:`lunarcap.bookbuild.build`)
        book/                 jupyter-book sources (_config.yml, _toc.yml, *.md)
            generated/        executed notebooks <name>.ipynb and their stamps
                tables/       CSV files
                figures/      PNG and SVG files
            _build/html/      the built site
            _build/quick/     the quick book (``build --quick``): a copy of the sources
                generated/    with its own outputs
                _build/html/  and its own site
        .cache/joblib/        cached solutions (:mod:`lunarcap.repro.cache`)
        .cache/nlp/           compiled NLPs by code version, and the compiled node
                              functions of their derivatives (``nodes/``)
                              (:class:`lunarcap.repro.cache.NLPStore`)

The cache directory may be moved with the environment variable ``LUNARCAP_CACHE_DIR``,
the book being built with ``LUNARCAP_BOOK_DIR``, the whole tree with ``LUNARCAP_ROOT``.

Examples
--------
>>> from lunarcap.repro import paths
>>> paths.table_path("impulsive_baseline").name
'impulsive_baseline.csv'
>>> paths.figure_path("fig1_geometry", "svg").relative_to(paths.GENERATED).as_posix()
'figures/fig1_geometry.svg'
"""

from __future__ import annotations

import contextlib
import os
import re
import tempfile
from pathlib import Path


def _find_root() -> Path:
    """The repository root: ``LUNARCAP_ROOT`` if set, else the source tree of this package."""
    env = os.environ.get("LUNARCAP_ROOT")
    if env:
        return Path(env).resolve()
    return Path(__file__).resolve().parents[2]


#: Repository root (the directory holding ``pyproject.toml``); lunarcap is installed
#: editable (``pip install -e .``), so this is the source tree. Override with the
#: environment variable ``LUNARCAP_ROOT``.
ROOT = _find_root()

#: Source notebooks and the manifest.
NOTEBOOKS = ROOT / "notebooks"
MANIFEST = NOTEBOOKS / "manifest.yml"

#: jupyter-book sources (committed): pages, configuration, table of contents, _static.
BOOK_SOURCES = ROOT / "book"

#: Where the quick book (``build --quick``: coarse parameters, what ``make test`` builds)
#: is made: a copy of the sources with its own ``generated/`` and ``_build/``, so that a
#: quick build never replaces the full book's results or its stamps.
QUICK_BOOK = BOOK_SOURCES / "_build" / "quick"


def _layout(book: Path) -> tuple[Path, Path, Path, Path, Path, Path]:
    """``BOOK, GENERATED, TABLES, FIGURES, BUILD, HTML`` of the book in ``book``."""
    generated, build = book / "generated", book / "_build"
    return book, generated, generated / "tables", generated / "figures", build, build / "html"


#: The book being built (:data:`BOOK_SOURCES`, or the directory named by the environment
#: variable ``LUNARCAP_BOOK_DIR``, set by :func:`use_book` for the quick book and inherited
#: from there by the notebook kernels); below it :data:`GENERATED`, everything the
#: notebooks produce (git-ignored: executed notebooks, :data:`TABLES` of CSV files,
#: :data:`FIGURES`), and :data:`HTML`, the built site in :data:`BUILD`.
BOOK, GENERATED, TABLES, FIGURES, BUILD, HTML = _layout(BOOK_SOURCES)
TOC = BOOK_SOURCES / "_toc.yml"


def use_book(directory: str | os.PathLike) -> Path:
    """Make ``directory`` the book being built, in this process and its children.

    Moves :data:`BOOK` and everything below it (:data:`GENERATED`, :data:`TABLES`,
    :data:`FIGURES`, :data:`BUILD`, :data:`HTML`) and sets ``LUNARCAP_BOOK_DIR`` so that
    notebook kernels started afterwards write there too. Returns the resolved directory.
    """
    global BOOK, GENERATED, TABLES, FIGURES, BUILD, HTML
    BOOK, GENERATED, TABLES, FIGURES, BUILD, HTML = _layout(Path(directory).resolve())
    os.environ["LUNARCAP_BOOK_DIR"] = str(BOOK)
    return BOOK


@contextlib.contextmanager
def using_book(directory: str | os.PathLike):
    """:func:`use_book` for the length of a ``with`` block; the previous book after it."""
    previous, env = BOOK, os.environ.get("LUNARCAP_BOOK_DIR")
    try:
        yield use_book(directory)
    finally:
        use_book(previous)
        if env is None:
            os.environ.pop("LUNARCAP_BOOK_DIR", None)
        else:
            os.environ["LUNARCAP_BOOK_DIR"] = env


if os.environ.get("LUNARCAP_BOOK_DIR"):
    use_book(os.environ["LUNARCAP_BOOK_DIR"])


def stage_quick_book() -> Path:
    """Copy the book's sources into :data:`QUICK_BOOK` and return that directory.

    Every file and directory of :data:`BOOK_SOURCES` except ``_build`` and ``generated``
    is copied (modification times kept, so jupyter-book's incremental build still sees
    what changed); files removed from the sources are removed from the copy.
    """
    import shutil

    dest = QUICK_BOOK
    dest.mkdir(parents=True, exist_ok=True)
    skip = {"_build", "generated"}
    wanted = {p.name for p in BOOK_SOURCES.iterdir() if p.name not in skip}
    for old in dest.iterdir():
        if old.name not in skip and old.name not in wanted:
            if old.is_dir() and not old.is_symlink():
                shutil.rmtree(old)
            else:
                old.unlink()
    for name in sorted(wanted):
        src = BOOK_SOURCES / name
        if src.is_dir():
            shutil.copytree(src, dest / name, dirs_exist_ok=True)
        elif not (dest / name).is_file() or (dest / name).read_bytes() != src.read_bytes():
            shutil.copy2(src, dest / name)
    return dest

#: Cache of expensive results and compiled NLPs (git-ignored).
CACHE = Path(os.environ.get("LUNARCAP_CACHE_DIR", ROOT / ".cache"))
JOBLIB_CACHE = CACHE / "joblib"
#: The optimiser's compiled NLPs, once per machine (:func:`lunarcap.repro.cache.nlp_store`).
NLP_CACHE = CACHE / "nlp"

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]*$")

#: Figure formats written by :func:`lunarcap.report.figures.save_figure`.
FIGURE_FORMATS = ("png", "svg")


def check_name(name: str) -> str:
    """Validate an output name (letters, digits, ``_ . -``; no path separators).

    Raises
    ------
    ValueError
        If ``name`` could escape its directory or is empty.
    """
    if not isinstance(name, str) or not _NAME.match(name) or ".." in name:
        raise ValueError(f"invalid output name {name!r}: use letters, digits, '_', '-', '.'")
    return name


def executed_notebook_path(name: str) -> Path:
    """``book/generated/<name>.ipynb``: the executed notebook of a manifest entry."""
    return GENERATED / f"{check_name(name)}.ipynb"


def table_path(name: str) -> Path:
    """``book/generated/tables/<name>.csv``."""
    return TABLES / f"{check_name(name)}.csv"


def figure_path(name: str, fmt: str = "png") -> Path:
    """``book/generated/figures/<name>.<fmt>``."""
    if fmt not in FIGURE_FORMATS:
        raise ValueError(f"figure format must be one of {FIGURE_FORMATS}, got {fmt!r}")
    return FIGURES / f"{check_name(name)}.{fmt}"


def export_dir(name: str) -> Path:
    """``book/generated/export/<name>/``: the files a page exports for other tools."""
    return GENERATED / "export" / check_name(name)


def relative_to_page(path: Path, page: Path | None = None) -> str:
    """POSIX path of ``path`` relative to the directory of a book page.

    Parameters
    ----------
    path : Path
        A file below :data:`BOOK`.
    page : Path, optional
        The page (default: an executed notebook in :data:`GENERATED`).
    """
    page_dir = (page.parent if page is not None else GENERATED)
    return Path(os.path.relpath(Path(path).resolve(), page_dir.resolve())).as_posix()


def ensure_dirs() -> None:
    """Create the generated-output directories if missing."""
    for d in (GENERATED, TABLES, FIGURES):
        d.mkdir(parents=True, exist_ok=True)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike):
    """Yield a temporary path next to ``path``; move it onto ``path`` on success.

    If the body raises, the temporary file is removed and ``path`` is left as it was.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> with atomic_path(d / "x.txt") as tmp:
    ...     _ = tmp.write_text("hello")
    >>> (d / "x.txt").read_text()
    'hello'
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}.",
                               suffix=f".tmp{path.suffix}")
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        # mkstemp creates 0600; published files must be world-readable like any other
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically; return the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def write_csv(df, name: str, **to_csv_kwargs) -> Path:
    """Write a pandas DataFrame to ``book/generated/tables/<name>.csv`` atomically.

    Parameters
    ----------
    df : pandas.DataFrame
    name : str
        Output name (usually the manifest entry's ``output_name``, maybe with a suffix).
    **to_csv_kwargs
        Passed to :meth:`pandas.DataFrame.to_csv` (``index=False`` by default).

    Returns
    -------
    Path of the CSV file.
    """
    if len(df) == 0:
        raise ValueError(f"refusing to write an empty table {name!r}")
    to_csv_kwargs.setdefault("index", False)
    path = table_path(name)
    with atomic_path(path) as tmp:
        df.to_csv(tmp, **to_csv_kwargs)
    return path
