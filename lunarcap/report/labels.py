"""Column labels and units of the book's tables, defined once.

A column name carries its unit as a suffix (``delta_v_mps``, ``burn_duration_min``); the
label shown in the book is composed from the quantity's words and the unit
(:func:`label`: ``"ΔV (m/s)"``, ``"duration (min)"``). A ``paper_`` prefix adds
", paper"; an ``impulsive_`` prefix "impulsive ". Names that read better otherwise are
listed in :data:`LABELS`.

Examples
--------
>>> label("delta_v_mps"), label("paper_delta_v_mps"), label("loss_percent")
('ΔV (m/s)', 'ΔV, paper (m/s)', 'loss (%)')
>>> labels(["start_min", "thrust_N"])
{'start_min': 'start (min)', 'thrust_N': 'thrust (N)'}
"""

from __future__ import annotations

#: Unit suffixes of column names and the unit shown (longest suffix first when matching).
UNITS = {
    "_mps2": "m/s²", "_kmps2": "km/s²", "_kmps": "km/s", "_mps": "m/s", "_percent": "%",
    "_min": "min", "_deg": "deg", "_kg": "kg", "_km": "km", "_mm": "mm", "_m": "m", "_s": "s",
    "_h": "h", "_N": "N", "_LU": "LU",
}

#: Words of the quantities (the stem of a column name, without unit and prefix).
QUANTITIES = {
    "delta_v": "ΔV", "burn_duration": "duration", "start": "start", "loss": "loss",
    "thrust": "thrust", "isp": "Isp", "fuel": "propellant", "m_start": "mass before",
    "m_end": "mass after", "m0": "m₀", "final_mass": "final mass", "eq19_duration": "Eq. (19)",
    "v_end": "speed at the end", "rp_error": "r_p error", "ra_error": "r_a error",
    "inc_error": "i error", "gamma_error": "γ error", "objective": "J", "solve_wall": "wall",
    "nlp_solve": "IPOPT", "total_delta_v": "total ΔV", "total_loss": "total loss",
    "total_fuel": "propellant", "total_burn_duration": "burn time", "period": "period",
    "altitude": "altitude", "inclination": "inclination",
    "time_to_final_orbit": "time to final orbit",
    "objective_loss": "J loss", "robbins_loss": "Robbins' estimate",
}

#: Labels that are not composed from the name.
LABELS = {
    "burn": "burn", "loi": "LOI", "target": "target", "steering": "steering",
    "verified": "verified", "passed": "passed", "mesh": "mesh", "ipopt_status": "IPOPT status",
    "ipopt_iterations": "iterations", "thrust_to_weight": "T/(m₀g₀)", "engine": "engine",
    "best": "best", "part": "burn", "ignition_epoch": "ignition (TDB)",
}


def label(column: str) -> str:
    """The book's header of a column (words and unit)."""
    if column in LABELS:
        return LABELS[column]
    suffix = ""
    for s in sorted(UNITS, key=len, reverse=True):
        if column.endswith(s) and len(column) > len(s):
            suffix = s
            break
    stem = column[: len(column) - len(suffix)] if suffix else column
    extra = ""
    if stem.startswith("paper_"):
        stem, extra = stem[len("paper_"):], ", paper"
    before = ""
    if stem.startswith("impulsive_"):
        stem, before = stem[len("impulsive_"):], "impulsive "
    words = before + QUANTITIES.get(stem, stem.replace("_", " "))
    return f"{words}{extra}" + (f" ({UNITS[suffix]})" if suffix else "")


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
