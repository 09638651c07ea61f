"""Column labels and units of the book's tables and axes, read from the glossary.

A reported quantity's header is its glossary label and unit
(:class:`lunarcap.quantities.Quantity`: ``delta_v_loss_mps`` -> ``"ΔV loss (m/s)"``), so
a column reads the same in every table, axis and JSON key. A column that is a page's own
(not a reported quantity) is composed from its name: the words of the stem and the unit
its suffix states (:func:`lunarcap.quantities.unit_of`).

Examples
--------
>>> label("delta_v_mps"), label("paper_delta_v_mps"), label("delta_v_loss_percent")
('ΔV (m/s)', 'ΔV, paper (m/s)', 'ΔV loss (%)')
>>> labels(["start_min", "thrust_N"])
{'start_min': 'start (min)', 'thrust_N': 'thrust (N)'}
"""

from __future__ import annotations

from lunarcap import quantities as Q

#: Unit suffixes of column names and the unit shown (the glossary's).
UNITS = Q.UNIT_SUFFIXES


def label(column: str) -> str:
    """The book's header of a column: the glossary's label and unit, else words and unit."""
    try:
        return Q.lookup(column).header
    except KeyError:
        pass
    unit = Q.unit_of(column)
    suffix = next((s for s in sorted(UNITS, key=len, reverse=True)
                   if unit and column.endswith(s)), "")
    stem = column[: len(column) - len(suffix)] if suffix else column
    words = stem.replace("_", " ")
    return f"{words} ({unit})" if unit else words


def labels(columns, **overrides) -> dict:
    """``{column: label}`` for ``columns``, with per-table overrides."""
    return {c: overrides.get(c, label(c)) for c in columns}


def engine_label(thrust_N: float, isp_s: float) -> str:
    """An engine as the tables name it, e.g. ``engine_label(150, 200)`` is '150 N / 200 s'."""
    return f"{thrust_N:g} N / {isp_s:g} s"


#: Orbits with a period shorter than this are described in minutes (the paper's 117.848 min
#: final orbit), longer ones in hours (12.235 h, 3.525 h), h.
MINUTES_BELOW_H = 3.0


def period_text(period_h: float, decimals: int = 3) -> str:
    """An orbit's period as the paper writes it: hours, or minutes below 3 h.

    Examples
    --------
    >>> period_text(12.235), period_text(117.86793 / 60), period_text(float("inf"))
    ('12.235 h', '117.9 min', 'hyperbola')
    """
    if period_h == float("inf"):
        return "hyperbola"
    if period_h < MINUTES_BELOW_H:
        return f"{60.0 * period_h:.1f} min"
    return f"{period_h:.{decimals}f} h"
