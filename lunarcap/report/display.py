"""Showing tables and figures in the book: CSV/PNG/SVG out, a numbered MyST block in.

:func:`show_table` writes a DataFrame to ``book/generated/tables/<name>.csv`` and
displays it as a MyST ``table`` with its caption; :func:`show_figure` saves a figure
(PNG + SVG) and displays it as a MyST ``figure``. Both name the notebook and parameters
that made them (:func:`lunarcap.report.provenance.source_note`). Paths come from
:mod:`lunarcap.repro.paths` only.
"""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figures import save_figure
from lunarcap.report.provenance import source_note
from lunarcap.repro import paths


def markdown_table(df, floatfmt: str | dict = ".3f") -> str:
    """A Markdown pipe table of a DataFrame (numbers right-aligned).

    Parameters
    ----------
    df : pandas.DataFrame
    floatfmt : str or dict
        Format of float cells, one for all columns or per column name.
    """
    def fmt(col, v):
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


def _display_markdown(text: str) -> None:
    from IPython.display import Markdown, display

    display(Markdown(text))


def show_table(df, name: str, caption: str, notebook: str, parameters: dict | None = None,
               floatfmt: str | dict = ".3f", labels: dict | None = None, label: str | None = None,
               display: bool = True, columns: list | None = None) -> str:
    """Write ``df`` to ``tables/<name>.csv`` and show it as a numbered MyST table.

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
    text = (f":::{{table}} {caption}\n:name: {label}\n:align: center\n\n"
            f"{markdown_table(shown, floatfmt)}\n:::\n\n"
            f"{source_note(notebook, parameters)} Data: {{download}}`{csv.name} <{rel}>`.\n")
    if display:
        _display_markdown(text)
    return text


def show_figure(fig, name: str, caption: str, notebook: str, parameters: dict | None = None,
                alt: str | None = None, label: str | None = None, width: str = "100%",
                display: bool = True) -> str:
    """Save ``fig`` (PNG + SVG) and show the PNG as a numbered MyST figure with a caption.

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
    text = (f":::{{figure}} {png}\n:name: {label}\n:alt: {alt}\n:width: {width}\n\n"
            f"{caption} {source_note(notebook, parameters)} "
            f"Files: {{download}}`PNG <{png}>`, {{download}}`SVG <{svg}>`.\n:::\n")
    if display:
        _display_markdown(text)
    return text
