"""Showing tables and figures in the book: CSV/PNG/SVG out, a captioned MyST block in.

:func:`show_table` writes a DataFrame to ``book/generated/tables/<name>.csv`` and
displays it as a MyST ``table`` with its caption; :func:`show_figure` saves a figure
(PNG + SVG) and displays it as a MyST ``figure``. Both name the notebook and parameters
that made them (:func:`lunarcap.report.provenance.source_note`). Paths come from
:mod:`lunarcap.repro.paths` only.

Numbering: the book's own tables and figures are numbered by Sphinx as "Book table N"
and "Book figure N" (``numfig_format`` in ``book/_config.yml``), so that no number of
ours reads like one of the paper's. A table or figure that regenerates one of the
paper's (``paper="Table 1"``, ``"Fig. 2"``...) carries the paper's number instead,
"Song et al. (2011) Table 1", at the head of its caption, and no book number: it gets no
label and the class ``lc-paper``, whose items :mod:`lunarcap.bookbuild.sphinx_ext` keeps
Sphinx from numbering.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figures import save_figure
from lunarcap.report.provenance import source_note
from lunarcap.repro import paths

#: How the book names the paper's own tables and figures ("Song et al. (2011) Table 1").
PAPER_CITATION = "Song et al. (2011)"
#: Class of the paper's tables and figures, which lunarcap.bookbuild.sphinx_ext leaves unnumbered.
PAPER_CLASS = "lc-paper"
#: The one wording of a verification's outcome on every page (never yes/no or True/False).
PASSED, FAILED = "passed", "failed"


def verdict(ok) -> str:
    """The book's word for a verification outcome.

    >>> verdict(True), verdict(False)
    ('passed', 'failed')
    """
    return PASSED if bool(ok) else FAILED


def markdown_table(df, floatfmt: str | dict = ".3f") -> str:
    """A Markdown pipe table of a DataFrame (numbers right-aligned).

    Parameters
    ----------
    df : pandas.DataFrame
    floatfmt : str or dict
        Format of float cells, one for all columns or per column name.
    """
    def fmt(col, v):
        if isinstance(v, (bool, np.bool_)):
            return verdict(v)
        if isinstance(v, (float, np.floating)):
            if not np.isfinite(v):
                return "—" if np.isnan(v) else ("∞" if v > 0 else "−∞")
            f = floatfmt.get(col, ".3f") if isinstance(floatfmt, dict) else floatfmt
            text = format(float(v), f)
            if text[:1] in "+-" and not any(ch in "123456789" for ch in text):
                text = text[1:]  # no "-0.00" for a value that rounds to zero
            return text
        return str(v).replace("|", "\\|")

    cols = list(df.columns)
    from pandas.api.types import is_numeric_dtype

    numeric = [is_numeric_dtype(df[c]) for c in cols]
    head = "| " + " | ".join(str(c).replace("|", "\\|") for c in cols) + " |"
    rule = "|" + "|".join("---:" if n else ":---" for n in numeric) + "|"
    body = ["| " + " | ".join(fmt(c, v) for c, v in zip(cols, row)) + " |"
            for row in df.itertuples(index=False)]
    return "\n".join([head, rule, *body])


def paper_caption(caption: str, paper: str | None) -> str:
    """The caption with the paper's number at its head (unchanged if ``paper`` is None).

    >>> paper_caption("Delta-V of LOI 1.", "Table 1")
    '**Song et al. (2011) Table 1.** Delta-V of LOI 1.'
    """
    return caption if paper is None else f"**{PAPER_CITATION} {paper}.** {caption}"


def _display_markdown(text: str) -> None:
    from IPython.display import Markdown, display

    display(Markdown(text))


def show_table(df, name: str, caption: str, notebook: str, parameters: dict | None = None,
               floatfmt: str | dict = ".3f", labels: dict | None = None, label: str | None = None,
               display: bool = True, columns: list | None = None,
               paper: str | None = None, source: bool = True) -> str:
    """Write ``df`` to ``tables/<name>.csv`` and show it as a captioned MyST table.

    Parameters
    ----------
    df : pandas.DataFrame
        Column names are those of the CSV: plain ``snake_case`` with the unit as suffix
        (``delta_v_mps``) is easiest for whoever reads the CSV back.
    name : str
        Output name (the CSV file name without extension).
    caption : str
        Caption (MyST Markdown; give units).
    notebook, parameters : the source notebook and the parameters of this run,
        named under the table (:func:`lunarcap.report.provenance.source_note`).
    floatfmt : str or dict
        Format of float cells in the displayed table, one for all or per column name
        (the CSV keeps full precision).
    labels : dict, optional
        Column name -> header shown in the book (with units), e.g.
        ``{"delta_v_mps": "ΔV (m/s)"}``.
    label : str, optional
        Cross-reference label (default ``tbl-<name>``), for ``{numref}`` from other pages.
    display : bool
        Display the Markdown (default) or only return it.
    columns : list, optional
        Columns shown in the book (default all); the CSV keeps every column.
    paper : str, optional
        The paper's number of the table this one regenerates (``"Table 1"``, ``"Table
        B1"``): the caption starts with "Song et al. (2011) Table 1" and the table has no
        label and no book number (see the module docstring).
    source : bool
        Name the notebook and parameters under the table (default). A book page names
        them once, in its provenance block (:meth:`lunarcap.report.page.Page.header`),
        and passes False: the same line under every table only repeats it.

    Returns
    -------
    str
        The Markdown shown.
    """
    csv = paths.write_csv(df, name)
    if columns is not None:
        df = df[list(columns)]
    label = label or f"tbl-{name}"
    rel = paths.relative_to_page(csv)
    shown = df.rename(columns=labels or {})
    if isinstance(floatfmt, dict) and labels:
        floatfmt = {labels.get(k, k): v for k, v in floatfmt.items()}
    name = f":class: {PAPER_CLASS}\n" if paper else f":name: {label}\n"
    text = (f":::{{table}} {paper_caption(caption, paper)}\n{name}:align: center\n\n"
            f"{markdown_table(shown, floatfmt)}\n:::\n\n"
            + (f"{source_note(notebook, parameters)} " if source else "")
            + f"Data: {{download}}`{csv.name} <{rel}>`.\n")
    if display:
        _display_markdown(text)
    return text


def show_figure(fig, name: str, caption: str, notebook: str, parameters: dict | None = None,
                alt: str | None = None, label: str | None = None, width: str = "100%",
                display: bool = True, paper: str | None = None, source: bool = True) -> str:
    """Save ``fig`` (PNG + SVG) and show the PNG as a MyST figure with a caption.

    Parameters
    ----------
    fig : matplotlib.figure.Figure (closed after saving)
    name : str
        Output name (``figures/<name>.png`` and ``.svg``).
    caption : str
        Caption (MyST Markdown; give units).
    notebook, parameters : named in the caption (:func:`lunarcap.report.provenance.source_note`).
    alt : str, optional
        Alternative text (default: the caption's first sentence).
    label : str, optional
        Cross-reference label (default ``fig-<name>``).
    width : str
        Display width.
    display : bool
        Display the Markdown (default) or only return it.
    paper : str, optional
        The paper's number of the figure this one regenerates (``"Fig. 2"``): the caption
        starts with "Song et al. (2011) Fig. 2" and the figure has no label and no book
        number (see the module docstring).
    source : bool
        Name the notebook and parameters in the caption (default); False on a book page,
        which names them once in its provenance block (as for :func:`show_table`).

    Returns
    -------
    str
        The Markdown shown.
    """
    files = save_figure(fig, name)
    plt.close(fig)
    label = label or f"fig-{name}"
    alt = alt or caption.split(". ")[0].replace("`", "").replace("$", "").replace("\\", "")
    png = paths.relative_to_page(files["png"])
    svg = paths.relative_to_page(files["svg"])
    name = f":figclass: {PAPER_CLASS}\n" if paper else f":name: {label}\n"
    text = (f":::{{figure}} {png}\n{name}:alt: {alt}\n:width: {width}\n\n"
            f"{paper_caption(caption, paper)} "
            + (f"{source_note(notebook, parameters)} " if source else "")
            + f"Files: {{download}}`PNG <{png}>`, {{download}}`SVG <{svg}>`.\n:::\n")
    if display:
        _display_markdown(text)
    return text
