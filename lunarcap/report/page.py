"""A book page as data: its tables, figures, the numbers its prose quotes, notes, checks.

A page module (:mod:`lunarcap.report.pages`) builds a :class:`Page`; the page's notebook
computes its result with lunarcap's public API, passes it to the page module, which
formats it, and shows the page, so what the book shows is computed (and tested) in the
library, and a notebook is a parameters cell, a few public calls, a few ``show`` calls,
prose and glue::

    capture = lunarcap.paper_plan(150.0, 200.0)
    burns = [lunarcap.solve_burn(capture, 1, start=s) for s in (-8.0, -10.0)]
    page = sweep.build(burns, "loi_sweep")
    page.header()          # provenance admonition
    page.show("dv")        # a table: CSV written, numbered MyST table displayed
    page.show("dv_plot")   # a figure: PNG + SVG written, MyST figure displayed
    page.glue()            # the numbers and notes the prose quotes (myst-nb glue)
    page.check()           # the headline assertions (the build fails if they fail)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lunarcap.report import display as _display
from lunarcap.report.labels import labels as _labels

#: Head of the glued text of a missing value: :mod:`lunarcap.bookbuild.sphinx_ext` prints the
#: reason that follows it wherever the prose pastes the value, whatever the number format
#: (``{glue:text}`x:.2f``` of a missing ``x`` reads "— (not run in the quick book)").
MISSING_PREFIX = "lunarcap-missing:"
#: Why a value is missing when the page does not say: a quick build leaves cases out.
QUICK_REASON = "not run in the quick book"
FULL_REASON = "not computed in this run"


def missing(reason: str) -> str:
    """The glued text of a value that is missing for ``reason`` (see :data:`MISSING_PREFIX`).

    >>> missing("not run in the quick book")
    'lunarcap-missing:not run in the quick book'
    """
    return f"{MISSING_PREFIX}{reason}"


def missing_text(text) -> str | None:
    """The words a missing value is printed as, or None if ``text`` is not one.

    >>> missing_text(missing("no recovery")), missing_text("12.5")
    ('— (no recovery)', None)
    """
    if isinstance(text, str) and text.startswith(MISSING_PREFIX):
        return f"— ({text[len(MISSING_PREFIX):]})"
    return None


def is_missing(v) -> bool:
    """True for NaN (or None) and for a value already marked missing."""
    if v is None:
        return True
    if isinstance(v, str):
        return v.startswith(MISSING_PREFIX)
    try:
        return math.isnan(float(v))
    except (TypeError, ValueError):
        return False


def solver_description(**extra) -> dict:
    """The solver settings a page's provenance block names (one definition for all pages).

    The transcription and meshes (:data:`lunarcap.optim.collocation.DEFAULT_MESHES`) and
    the verification gate with its tolerances (:mod:`lunarcap.optim.verify`); ``extra``
    entries are added or replace these.
    """
    from lunarcap.optim import verify as V
    from lunarcap.optim.collocation import DEFAULT_MESHES

    meshes = " → ".join(f"{m.n_burn}×{m.n_coast} LGR-{m.degree}" for m in DEFAULT_MESHES)
    gate = (f"re-propagation with CVODES (Adams, rtol 1e-13) from the initial state; end "
            f"position {V.TOL_POSITION_M:g} m, end speed {V.TOL_SPEED_MPS * 1e3:g} mm/s, "
            f"objective {V.TOL_DV_MPS:g} m/s, r_p and r_a {V.TOL_RP_M:g} m, i and γ "
            f"{V.TOL_ANGLE_DEG:g} deg, perilune branch")
    out = {"transcription": "Legendre-Gauss-Radau collocation", "NLP": "IPOPT (MUMPS)",
           "meshes": meshes, "gate": gate}
    out.update(extra)
    return out


def _words(xs: list[str]) -> str:
    return xs[0] if len(xs) == 1 else ", ".join(xs[:-1]) + " and " + xs[-1]


def listing(values: dict, names_labels, spec: str = "", unit: str = "") -> str:
    """Several values as prose lists them, the missing ones grouped by their reason.

    ``values``: glued values (a missing one is :func:`missing`); ``names_labels``:
    [(name, label)], e.g. [("loss_150N", "150 N"), ...]. Labels sharing their last word
    are joined ("150 and 300 N").

    >>> v = {"a": 1.0, "b": 2.0, "c": missing("not run in the quick book")}
    >>> listing(v, [("a", "150 N"), ("b", "300 N")], ".1f", " m/s")
    '1.0 and 2.0 m/s (150 and 300 N)'
    >>> listing(v, [("a", "150 N"), ("c", "450 N")], ".1f", " m/s")
    '1.0 m/s (150 N; 450 N: not run in the quick book)'
    """
    have = [(n, lab) for n, lab in names_labels if not is_missing(values.get(n))]
    gone: dict[str, list[str]] = {}
    for n, lab in names_labels:
        v = values.get(n)
        if is_missing(v):
            why = v[len(MISSING_PREFIX):] if isinstance(v, str) else FULL_REASON
            gone.setdefault(why, []).append(lab)
    rest = "; ".join(f"{_words(labs)}: {why}" for why, labs in gone.items())
    if not have:
        return f"— ({rest})"
    labels = [lab for _, lab in have]
    last = labels[-1].split()[-1]
    shared = len(labels) > 1 and all(len(x.split()) == 2 and x.split()[-1] == last
                                     for x in labels)
    labs = _words([x.split()[0] for x in labels]) + f" {last}" if shared else _words(labels)
    nums = _words([format(values[n], spec) for n, _ in have])
    return f"{nums}{unit} ({labs}" + (f"; {rest}" if rest else "") + ")"


def counted(k, n, what: str, verb: tuple[str, str] = ("has", "have")) -> str:
    """"k of n <what> <verb>", the verb agreeing with k (the subject), for computed prose.

    ``verb``: its singular and plural forms. Prose that pastes two glued counts before a
    verb cannot agree with them; it pastes this sentence instead.

    >>> counted(1, 8, "plan-and-count cases", ("has", "have"))
    '1 of 8 plan-and-count cases has'
    >>> counted(3, 8, "cases", ("is recovered", "are recovered"))
    '3 of 8 cases are recovered'
    >>> counted(0, 8, "cases")
    'none of the 8 cases has'
    """
    k, n = int(k), int(n)
    if k == 0:
        return f"none of the {n} {what} {verb[0]}"
    return f"{k} of {n} {what} {verb[0] if k == 1 else verb[1]}"


@dataclass
class Table:
    """A table of a page: the CSV content and how it is shown."""

    df: object                # pandas.DataFrame, columns snake_case with unit suffixes
    caption: str
    columns: dict | None = None   # display header overrides (default labels.label)
    floatfmt: dict | str = ".3f"
    show_columns: list | None = None  # columns shown (default all; the CSV keeps all)
    name: str | None = None           # output name suffix (default: the key)
    paper: str | None = None          # the paper's table it regenerates ("Table 1")


@dataclass
class Figure:
    """A figure of a page (a matplotlib Figure, closed once shown)."""

    fig: object
    caption: str
    alt: str | None = None
    width: str = "100%"
    name: str | None = None           # output name suffix (default: the key)
    paper: str | None = None          # the paper's figure it regenerates ("Fig. 2")


@dataclass
class Page:
    """What one book page shows (see the module docstring)."""

    notebook: str
    parameters: dict
    output_name: str
    quick: bool = False
    solver: dict | None = None
    ephemeris: object = None
    items: dict = field(default_factory=dict)
    values: dict = field(default_factory=dict)
    notes: dict = field(default_factory=dict)
    checks: list = field(default_factory=list)
    data: dict = field(default_factory=dict)   # raw results, for readers of the notebook

    # ------------------------------------------------------------------ building
    def table(self, key: str, df, caption: str, columns: dict | None = None,
              floatfmt: dict | str = ".3f", show_columns: list | None = None,
              name: str | None = None, paper: str | None = None) -> None:
        """Add a table (written to ``tables/<output_name>_<name or key>.csv`` when shown).

        ``paper`` names the paper's table it regenerates ("Table 1"): the caption then
        carries the paper's number, not a book number (:mod:`lunarcap.report.display`).
        """
        self.items[key] = Table(df, caption, columns, floatfmt, show_columns, name, paper)

    def figure(self, key: str, fig, caption: str, alt: str | None = None,
               width: str = "100%", name: str | None = None,
               paper: str | None = None) -> None:
        """Add a figure (``figures/<output_name>_<name or key>.png/.svg`` when shown).

        The figure is closed at once (it can still be saved), so the notebook's inline
        backend does not display it a second time where the page is built. ``paper``
        names the paper's figure it regenerates ("Fig. 2"), as for :meth:`table`.
        """
        import matplotlib.pyplot as plt

        plt.close(fig)
        self.items[key] = Figure(fig, caption, alt, width, name, paper)

    def value(self, name: str, v, why: str | None = None) -> None:
        """A number (or short text) the page's prose quotes through glue.

        NumPy scalars are stored as plain Python numbers: myst-nb's ``{glue:text}`` formats
        those, while a NumPy 2 scalar would print as ``np.float64(...)``. A missing value
        (NaN or None) is stored as :func:`missing` with ``why`` (default: not run in the
        quick book, or not computed in this run), so the prose says why instead of
        printing "nan".
        """
        if is_missing(v):
            if not (isinstance(v, str) and v.startswith(MISSING_PREFIX)):
                v = missing(why or self.missing_reason)
            self.values[name] = v
            return
        self.values[name] = v.item() if hasattr(v, "item") and not isinstance(v, str) else v

    @property
    def missing_reason(self) -> str:
        """Why a value this page did not compute is missing, when the page does not say."""
        return QUICK_REASON if self.quick else FULL_REASON

    def text(self, name: str, spec: str = "", unit: str = "") -> str:
        """A glued value as the prose prints it: formatted, or its missing reason.

        >>> p = Page("nb", {}, "x", quick=True)
        >>> p.value("dv_mps", 12.345); p.value("other_mps", float("nan"))
        >>> p.text("dv_mps", ".1f", " m/s"), p.text("other_mps", ".1f", " m/s")
        ('12.3 m/s', '— (not run in the quick book)')
        """
        v = self.values[name]
        gone = missing_text(v)
        return gone if gone is not None else f"{format(v, spec)}{unit}"

    def data_link(self, src, name: str | None = None) -> str:
        """Copy a data file this page used into ``book/generated/data/``; its download link.

        For the data a reader cannot otherwise take away (a study's whole table, kept in
        the cache directory): the copy is ``data/<output_name>_<name>`` (default: the
        file's name) and the MyST ``{download}`` link to it is returned, for a caption or
        the prose. The book's archive of all its data includes it
        (:func:`lunarcap.report.landing.write_archive`).
        """
        import shutil
        from pathlib import Path

        from lunarcap.repro import paths

        src = Path(src)
        dest = paths.GENERATED / "data" / f"{self.output_name}_{name or src.name}"
        dest.parent.mkdir(parents=True, exist_ok=True)
        with paths.atomic_path(dest) as tmp:
            shutil.copyfile(src, tmp)
        return f"{{download}}`{dest.name} <{paths.relative_to_page(dest)}>`"

    def listing(self, names_labels, spec: str = "", unit: str = "") -> str:
        """Several glued values as prose lists them (:func:`listing` of this page's values).

        >>> p = Page("nb", {}, "x", quick=True)
        >>> for k, v in (("a", 1.0), ("b", float("nan")), ("c", float("nan"))): p.value(k, v)
        >>> p.listing([("a", "150 N"), ("b", "300 N"), ("c", "450 N")], ".1f", " m/s")
        '1.0 m/s (150 N; 300 N and 450 N: not run in the quick book)'
        """
        return listing(self.values, names_labels, spec, unit)

    def capture(self, key: str, dynamics: str | None) -> str:
        """Name the capture this page flies, glued as ``capture_named`` for its prose.

        ``key``: one of :data:`lunarcap.quantities.CAPTURES` ("fixed", "free", "joint",
        "free_periods"); the same engine needs a different delta-V in each, and in each
        dynamics, so every page that quotes one says which.

        >>> Page("nb", {}, "x").capture("free", "full")
        'free ignitions, full dynamics'
        """
        from lunarcap.quantities import capture_name

        text = f"{capture_name(key)}, {dynamics or 'the plan’s own'} dynamics"
        self.value("capture_named", text)
        return text

    def headline(self, markdown: str) -> None:
        """The page's finding in one or two sentences with its numbers (MyST Markdown).

        Glued as ``headline``; the findings page and the landing page quote it with a link
        to this page (:mod:`lunarcap.report.landing`).
        """
        self.notes["headline"] = markdown

    def note(self, name: str, markdown: str) -> None:
        """A MyST block the prose includes through ``{glue:md}``."""
        self.notes[name] = markdown

    def expect(self, what: str, ok: bool, detail: str = "") -> None:
        """A headline check: :meth:`check` fails the page if it is False."""
        self.checks.append((what, bool(ok), detail))

    # ------------------------------------------------------------------ showing
    def name_of(self, key: str) -> str:
        """Output name of an item: ``<output_name>_<name or key>``."""
        return f"{self.output_name}_{self.items[key].name or key}"

    def header(self, display: bool = True) -> str:
        """The provenance admonition of the page."""
        from lunarcap.report import provenance

        prov = provenance.collect(ephemeris=self.ephemeris, solver=self.solver)
        text = provenance.render_markdown(prov, self.notebook, self.parameters, self.quick)
        if display:
            _display._display_markdown(text)
        return text

    def show(self, key: str, display: bool = True) -> str:
        """Write one table or figure and display it (returns the MyST text).

        The notebook and parameters that made it are not repeated under it: the page names
        them once, in its provenance block (:meth:`header`, at the page's end).
        """
        item = self.items[key]
        if isinstance(item, Table):
            df = item.df
            shown = item.show_columns or list(df.columns)
            heads = _labels(shown, **(item.columns or {}))
            return _display.show_table(df, self.name_of(key), item.caption, self.notebook,
                                       self.parameters, floatfmt=item.floatfmt, labels=heads,
                                       columns=shown, display=display, paper=item.paper,
                                       source=False)
        return _display.show_figure(item.fig, self.name_of(key), item.caption, self.notebook,
                                    self.parameters, alt=item.alt, width=item.width,
                                    display=display, paper=item.paper, source=False)

    def glue(self) -> None:
        """Glue every value and note (for ``{glue:text}`` and ``{glue:md}`` in the prose)."""
        from IPython.display import Markdown
        from myst_nb import glue

        for name, v in self.values.items():
            glue(name, v, display=False)
        for name, md in self.notes.items():
            glue(name, Markdown(md), display=False)

    def check(self) -> None:
        """Raise AssertionError naming every failed headline check."""
        failed = [f"{what}{': ' + detail if detail else ''}"
                  for what, ok, detail in self.checks if not ok]
        if failed:
            raise AssertionError("; ".join(failed))
