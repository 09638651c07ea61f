"""What every result of the public API offers: a table, a document, a figure, files.

A result (:class:`Result`) is read four ways, the same for a solved plan, one burn, a
study and a flight in GMAT: :meth:`~Result.to_frame` (a pandas table whose columns are
glossary names, units in the names), :meth:`~Result.to_dict` (the command line's ``--json``
document, strict JSON: valid against ``lunarcap/schemas/<command>.schema.json``),
:meth:`~Result.plot` (a matplotlib figure in the book's palette) and
:meth:`~Result.export` (files in a directory). :func:`jsonable` is the one conversion of a
document to strict JSON, which the command line prints too, so that its ``--json`` and the
API's :meth:`~Result.to_json` are the same text.
"""

from __future__ import annotations

import json
import math


def jsonable(obj):
    """``obj`` with numpy scalars as Python numbers and non-finite floats as None.

    Strict JSON has no NaN or infinity; a number that is not one (a loss without an
    impulsive limit, an apolune of an escape) is null.

    Examples
    --------
    >>> import numpy as np
    >>> jsonable({"dv_mps": np.float64(1.5), "ra_km": float("inf"), "n": [np.int64(2)]})
    {'dv_mps': 1.5, 'ra_km': None, 'n': [2]}
    """
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if hasattr(obj, "item"):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def dumps(doc: dict) -> str:
    """A document as the command line's ``--json`` prints it (2-space indent, strict JSON)."""
    return json.dumps(jsonable(doc), indent=2)


class Result:
    """The four readings every result offers (see the module); subclasses fill them in.

    ``stem`` names the files of :meth:`export` (letters, digits, ``.``, ``_``, ``-``).
    """

    stem = "result"

    def document(self) -> dict:
        """The ``--json`` document before its conversion to strict JSON."""
        raise NotImplementedError

    def to_dict(self) -> dict:
        """The command line's ``--json`` document as strict-JSON Python objects."""
        return jsonable(self.document())

    def to_json(self) -> str:
        """The ``--json`` text, as the command line prints it."""
        return dumps(self.document())

    def to_frame(self):
        """The result as a pandas DataFrame (glossary column names)."""
        raise NotImplementedError

    def plot(self):
        """The result's figure (matplotlib), in the book's palette.

        Drawn by the book's figure modules (:mod:`lunarcap.report.figures`), whose style
        module sets matplotlib's font sizes (10 pt text, 9 pt ticks) when first imported.
        """
        raise NotImplementedError

    def export(self, directory) -> dict:
        """Write ``<stem>.json`` (:meth:`to_json`) and ``<stem>.csv`` (:meth:`to_frame`).

        The directory is created if missing; InputError (naming it and the reason) if
        nothing can be written there. Returns ``{"json": Path, "csv": Path}``.
        """
        from lunarcap.capture.export import check_export_dir, safe_name

        out = check_export_dir(directory)
        stem = safe_name(self.stem)
        files = {"json": out / f"{stem}.json", "csv": out / f"{stem}.csv"}
        files["json"].write_text(self.to_json() + "\n", encoding="utf-8")
        self.to_frame().to_csv(files["csv"], index=False)
        return files

