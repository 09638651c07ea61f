"""The book's contents: what each page executes and where it stands in the table of contents.

A page module of :mod:`lunarcap.report.pages` declares itself in one constant, ``BOOK``
(a :class:`BookPage`): its notebook, the executions of that notebook (:class:`Execution`:
each is one page of the book, with its parameters, quick parameters, dependencies,
outputs and expected time) and its part and order in the table of contents.
:data:`lunarcap.report.pages.PAGES` registers each page module in one line. From these
this module derives what the book's build executes (:func:`manifest`, the entries
:mod:`lunarcap.bookbuild.manifest` validates and runs) and the jupyter-book table of
contents (:func:`toc`), with the Markdown pages of ``book/`` placed by :data:`MARKDOWN`.
Nothing is kept in two places, so a new page is its module, its notebook and one line.
"""

from __future__ import annotations

import copy
import importlib
from dataclasses import dataclass, field
from pathlib import Path

from lunarcap.repro import paths

#: The parts of the table of contents, in the order the book shows them.
PARTS = ("The problem", "Results", "The paper's tables", "The paper's figures",
         "Verification", "Beyond the paper", "Reproduction report", "Reproduce")
#: The root page of the book (``book/index.md``).
ROOT_FILE = "index"
#: The Markdown pages of ``book/`` in the table of contents: (file, part, order).
MARKDOWN = (("model", "The problem", 10), ("rerun", "Reproduce", 20),
            ("api", "Reproduce", 25), ("references", "Reproduce", 30))
#: ``depends_on`` naming every other execution of the book (a page that reads them all).
EVERY_PAGE = "*"


class ContentsError(ValueError):
    """The registered pages are inconsistent; the message lists every problem, by name."""


@dataclass(frozen=True)
class Execution:
    """One execution of a page's notebook by papermill: one page of the book.

    Attributes
    ----------
    name : str
        Output name: ``book/generated/<name>.ipynb``, and ``output_name`` in the notebook.
    title : str
        The heading of the generated page (replaces the notebook's first ``# ...``).
    parameters : dict
        Injected by papermill; each must be assigned in the notebook's ``parameters`` cell.
    quick_parameters : dict
        Overrides for ``build --quick`` (a coarse run for the tests).
    depends_on : tuple of str
        Executions that must have run first (their solves are cached for this one), or
        ``(EVERY_PAGE,)``.
    outputs : tuple of str
        Files below ``book/generated`` the notebook writes (checked after the run).
    expected_s : float, optional
        About how long a fresh run takes on 2 cores, s: the long ones start first.
    floors : dict of str to Floor
        The least each named parameter may be in the full book (:class:`Floor`): the
        size the page's claims need. The build refuses to run a page below them
        (:func:`lunarcap.bookbuild.manifest.check_floors`); the quick book is exempt and
        says so on the page.
    """

    name: str
    title: str
    parameters: dict = field(default_factory=dict)
    quick_parameters: dict = field(default_factory=dict)
    depends_on: tuple = ()
    outputs: tuple = ()
    expected_s: float | None = None
    floors: dict = field(default_factory=dict)

    @property
    def output(self) -> Path:
        """The executed notebook of the book being built."""
        return paths.executed_notebook_path(self.name)

    @property
    def toc_file(self) -> str:
        """Its file in the table of contents (no extension)."""
        return f"generated/{self.name}"


#: The kinds of :class:`Floor`: what a parameter of the full book must be.
FLOOR_KINDS = ("at_least", "at_most", "includes", "one_of")


@dataclass(frozen=True)
class Floor:
    """The least a page's parameter may be in the full book, and why.

    A study page's claims hold at a size: a 99 % point needs 368 samples to be bounded
    with 95 % confidence, a convergence in degree needs the degree-50 field. The page
    declares that size once, beside its parameters (``Execution.floors``), and the build
    checks it before the page runs, so an edit that shrinks a grid fails instead of
    printing weaker numbers.

    Attributes
    ----------
    kind : {"at_least", "at_most", "includes", "one_of"}
        ``at_least``/``at_most``: the parameter, a number, is >= / <= ``value``;
        ``includes``: the parameter, a list, holds every element of ``value`` (numbers
        compared as floats); ``one_of``: the parameter is one of ``value``.
    value : number or list
    why : str
        What the floor is for, in the page's terms (quoted when a run is refused).
    """

    kind: str
    value: object
    why: str

    def __post_init__(self):
        if self.kind not in FLOOR_KINDS:
            raise ContentsError(f"unknown floor kind {self.kind!r}; the kinds: "
                                f"{list(FLOOR_KINDS)}")
        if self.kind in ("includes", "one_of") and not isinstance(self.value, (list, tuple)):
            raise ContentsError(f"a floor {self.kind!r} needs a list, got {self.value!r}")
        if self.kind in ("at_least", "at_most") and not _is_number(self.value):
            raise ContentsError(f"a floor {self.kind!r} needs a number, got {self.value!r}")

    def shortfall(self, value) -> str | None:
        """How ``value`` falls short of the floor (a phrase), or None if it meets it."""
        if self.kind in ("at_least", "at_most"):
            if not _is_number(value):
                return f"is {value!r}, not a number"
            low = self.kind == "at_least"
            if (value < self.value) if low else (value > self.value):
                return (f"is {value:g}, {'below' if low else 'above'} its floor "
                        f"{'>=' if low else '<='} {self.value:g}")
            return None
        if self.kind == "one_of":
            ok = any(_same(value, v) for v in self.value)
            return None if ok else f"is {value!r}, not one of {list(self.value)!r}"
        have = value if isinstance(value, (list, tuple)) else []
        missing = [v for v in self.value if not any(_same(v, h) for h in have)]
        return (f"lacks {missing!r} (has {value!r})" if missing else None)

    def as_dict(self) -> dict:
        """``{kind: value, "why": why}``, as the build's manifest lists it."""
        return {self.kind: list(self.value) if isinstance(self.value, tuple) else self.value,
                "why": self.why}

    @classmethod
    def from_dict(cls, raw) -> "Floor":
        """The inverse of :meth:`as_dict`; ContentsError naming what is wrong."""
        if not isinstance(raw, dict):
            raise ContentsError(f"a floor must be a mapping, got {raw!r}")
        kinds = [k for k in raw if k != "why"]
        if len(kinds) != 1 or not isinstance(raw.get("why"), str) or not raw["why"].strip():
            raise ContentsError(f"a floor is one of {list(FLOOR_KINDS)} with its value and "
                                f"a non-empty 'why', got {raw!r}")
        return cls(kinds[0], raw[kinds[0]], raw["why"])


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _same(a, b) -> bool:
    """Equal, numbers compared as floats (a list of 0.5 meets a floor of 0.50)."""
    if _is_number(a) and _is_number(b):
        return float(a) == float(b)
    return type(a) is type(b) and a == b


def at_least(value, why: str) -> Floor:
    """The parameter (a number) may not be below ``value`` in the full book."""
    return Floor("at_least", value, why)


def at_most(value, why: str) -> Floor:
    """The parameter (a number) may not be above ``value`` in the full book."""
    return Floor("at_most", value, why)


def includes(values, why: str) -> Floor:
    """The parameter (a list) must hold every one of ``values`` in the full book."""
    return Floor("includes", tuple(values), why)


def one_of(values, why: str) -> Floor:
    """The parameter must be one of ``values`` in the full book."""
    return Floor("one_of", tuple(values), why)


def below_floors(parameters: dict, floors: dict) -> list[str]:
    """Each floor ``parameters`` miss, as ``"<parameter> <shortfall> (<why>)"``.

    A floored parameter the page does not give is missing, not met.

    >>> below_floors({"samples": 4}, {"samples": at_least(368, "the 99 % point")})
    ['samples is 4, below its floor >= 368 (the 99 % point)']
    """
    out = []
    for name, floor in floors.items():
        if name not in parameters:
            out.append(f"{name} is not given, so its floor is not met ({floor.why})")
            continue
        short = floor.shortfall(parameters[name])
        if short:
            out.append(f"{name} {short} ({floor.why})")
    return out


@dataclass(frozen=True)
class BookPage:
    """What a page module shows in the book: its notebook, executions and place.

    Attributes
    ----------
    notebook : str
        The page's notebook, relative to the repository root (``notebooks/<x>.ipynb``).
    part : str
        The caption of its part of the table of contents (one of :data:`PARTS`).
    order : int
        Its place in the part: pages and :data:`MARKDOWN` files sorted by it.
    executions : tuple of Execution
        One per page of the book it makes, shown in this order.
    """

    notebook: str
    part: str
    order: int
    executions: tuple

    @property
    def notebook_path(self) -> Path:
        """The notebook's absolute path."""
        return paths.ROOT / self.notebook


def table_files(name: str, *stems: str) -> tuple[str, ...]:
    """Outputs ``tables/<name>_<stem>.csv``, as :meth:`lunarcap.report.page.Page.table` writes.

    >>> table_files("summary", "b1")
    ('tables/summary_b1.csv',)
    """
    return tuple(f"tables/{name}_{s}.csv" for s in stems)


def figure_files(name: str, *stems: str) -> tuple[str, ...]:
    """Outputs ``figures/<name>_<stem>.png`` and ``.svg``, as ``Page.figure`` writes them.

    >>> figure_files("summary", "loss")
    ('figures/summary_loss.png', 'figures/summary_loss.svg')
    """
    return tuple(f"figures/{name}_{s}.{ext}" for s in stems for ext in ("png", "svg"))


# ====================================================================== the registry
def registered(names=None) -> list[tuple[str, BookPage]]:
    """``(module name, BookPage)`` of every registered page, in registration order.

    Parameters
    ----------
    names : sequence of str, optional
        Page modules: a name without a dot is a module of :mod:`lunarcap.report.pages`.
        Default :data:`lunarcap.report.pages.PAGES`, read when called.

    Raises
    ------
    ContentsError
        A registered module that does not exist or declares no ``BOOK``.
    """
    from lunarcap.report import pages

    out, errors = [], []
    for name in pages.PAGES if names is None else names:
        module_name = name if "." in name else f"{pages.__name__}.{name}"
        try:
            module = importlib.import_module(module_name)
        except ModuleNotFoundError as exc:  # the page's, not one the page imports
            if not f"{module_name}.".startswith(f"{exc.name}."):
                raise
            errors.append(f"page {module_name}: no such module")
            continue
        book = getattr(module, "BOOK", None)
        if not isinstance(book, BookPage):
            errors.append(f"page {module_name}: declares no BOOK (a BookPage)")
            continue
        out.append((module_name, book))
    if errors:
        raise ContentsError("the registered pages are invalid:\n  - " + "\n  - ".join(errors))
    return out


def problems(pages: list[tuple[str, BookPage]], notebooks_dir: Path | None = None
             ) -> list[str]:
    """What is wrong with the registered pages, each problem naming its page or notebook.

    A page whose notebook is missing, a notebook of ``notebooks_dir`` (default
    ``notebooks/``) that no page claims, two pages with one notebook, a page without
    executions, an unknown part, and two places with the same order in one part.
    """
    errors, owner = [], {}
    for module, book in pages:
        nb = book.notebook_path.resolve()
        if not nb.is_file():
            errors.append(f"page {module}: its notebook {book.notebook} does not exist")
        if nb in owner:
            errors.append(f"page {module}: notebook {book.notebook} is {owner[nb]}'s already")
        owner.setdefault(nb, module)
        if not book.executions or not all(isinstance(x, Execution) for x in book.executions):
            errors.append(f"page {module}: executions must be a non-empty tuple of Execution")
        if book.part not in PARTS:
            errors.append(f"page {module}: unknown part {book.part!r}; the parts: {list(PARTS)}")
        for x in book.executions if isinstance(book.executions, tuple) else ():
            if isinstance(x, Execution):
                errors += [f"page {module}: execution {x.name!r}: {e}"
                           for e in _floor_declaration_problems(x)]
    for nb in sorted(Path(notebooks_dir or paths.NOTEBOOKS).glob("*.ipynb")):
        if nb.resolve() not in owner:
            errors.append(f"notebook {nb.name} has no page: declare BOOK in its page module "
                          f"and register the module in lunarcap.report.pages.PAGES")
    places: dict[tuple, str] = {}
    for what, part, order in _places(pages):
        if (part, order) in places:
            errors.append(f"{what} and {places[part, order]} both stand at order {order} "
                          f"of part {part!r}")
        places.setdefault((part, order), what)
    return errors


def _floor_declaration_problems(x: Execution) -> list[str]:
    """Floors that are not :class:`Floor` or name no parameter of the execution."""
    errors = []
    for name, floor in x.floors.items():
        if not isinstance(floor, Floor):
            errors.append(f"floor of {name!r} must be a Floor (at_least, includes...)")
        elif name not in x.parameters:
            errors.append(f"floor of {name!r}: no such parameter in its parameters")
    return errors


def _places(pages) -> list[tuple[str, str, int]]:
    """``(what, part, order)`` of every page and Markdown file of the table of contents."""
    return ([(f"page {m}", b.part, b.order) for m, b in pages]
            + [(f"book/{f}.md", part, order) for f, part, order in MARKDOWN])


# ====================================================================== what the build reads
def executions(pages: list[tuple[str, BookPage]]) -> list[Execution]:
    """Every execution, in registration order (the order the build lists them in)."""
    return [x for _, b in pages for x in b.executions]


def manifest(pages: list[tuple[str, BookPage]], notebooks_dir: Path | None = None) -> dict:
    """The build's manifest, ``{"entries": [...]}``, one entry per execution.

    Each entry holds the keys of an :class:`Execution` and ``notebook`` (relative to
    ``notebooks_dir`` when below it, else absolute); ``expected_s`` only when declared.
    Parameters are copies, so validating or running them leaves the declarations as
    they are.
    """
    root = Path(notebooks_dir or paths.NOTEBOOKS).resolve()
    entries = []
    for _, book in pages:
        nb = book.notebook_path.resolve()
        notebook = nb.relative_to(root).as_posix() if nb.is_relative_to(root) else str(nb)
        for x in book.executions:
            e = {"name": x.name, "title": x.title, "notebook": notebook,
                 "parameters": copy.deepcopy(dict(x.parameters)),
                 "quick_parameters": copy.deepcopy(dict(x.quick_parameters)),
                 "depends_on": list(x.depends_on), "outputs": list(x.outputs)}
            if x.expected_s is not None:
                e["expected_s"] = x.expected_s
            if x.floors:
                e["floors"] = {k: f.as_dict() for k, f in x.floors.items()}
            entries.append(e)
    return {"entries": entries}


def toc_parts(pages: list[tuple[str, BookPage]]) -> list[tuple[str, list[str]]]:
    """``[(caption, [files])]``: each part of :data:`PARTS` holding a page, in order.

    Within a part, pages and Markdown files by their order; a page's executions in the
    order it declares them.
    """
    placed = [(b.order, [x.toc_file for x in b.executions], b.part) for _, b in pages]
    placed += [(order, [f], part) for f, part, order in MARKDOWN]
    out = []
    for caption in PARTS:
        files = [f for order, fs, part in sorted(placed, key=lambda p: p[0])
                 if part == caption for f in fs]
        if files:
            out.append((caption, files))
    return out


def toc(pages: list[tuple[str, BookPage]]) -> dict:
    """The jupyter-book table of contents (the content of a ``_toc.yml``)."""
    return {"format": "jb-book", "root": ROOT_FILE,
            "parts": [{"caption": caption, "chapters": [{"file": f} for f in files]}
                      for caption, files in toc_parts(pages)]}


def toc_files(pages: list[tuple[str, BookPage]]) -> list[str]:
    """Every file of the table of contents, root first (no extension)."""
    return [ROOT_FILE] + [f for _, files in toc_parts(pages) for f in files]
