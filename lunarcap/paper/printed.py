"""Every number printed in Song et al. (2011), as data with its location.

Source: Song, Y.-J., Park, S.-Y., Kim, H.-D., Lee, J.-H. & Sim, E.-S. (2011),
"Analysis of Delta-V Losses During Lunar Capture Sequence Using Finite Thrust",
J. Astron. Space Sci. 28(3), 203-216, doi:10.5140/JASS.2011.28.3.203
(hereafter "Song 2011").

The numbers live in the data file ``lunarcap/data/song2011_printed.yaml`` (:data:`DATA_FILE`),
transcribed as printed, errors included (:mod:`lunarcap.paper.audit` checks them against
each other and against physics); this module reads it once, at import, into the objects
below. Each table names its table number; each number from the prose names its section,
the paragraph within that section counted in reading order (paragraph breaks are inferred
from the flattened two-column text, so the opening words of the paragraph are given too),
and the words it is printed with (``Quote.text``).

Tables 1-5 are :func:`paper_table`; Table B1 is :func:`paper_table_b1` and
:func:`paper_best`; the numbers in the prose are :data:`QUOTES` (see :func:`quote`
and :func:`quotes_table`); the three perilune epochs are :data:`PAPER_EPOCHS_TDB`.

Units: minutes (min) for ignition offsets and burn durations, m/s for delta-V, per cent
for differences, kg for masses, km and km³/s² for the constants of Sec. 3.1.
Ignition offsets are minutes *before* perilune and carry the paper's '-' sign
(Tables 1-3 print the zero offset as "-0"; it is stored as 0).

Examples
--------
>>> paper_best(150, 1)["delta_v_mps"]
367.415
>>> float(paper_table(450, 2)["delta_v_mps"].min())
254.387
>>> quote("mass_after_loi1_150N_kg").value
434.471
"""

from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path

import pandas as pd

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_engines

__all__ = [
    "DATA_FILE",
    "PAPER_IMPULSIVE_DV_MPS",
    "PAPER_ENGINES",
    "PAPER_EPOCHS_TDB",
    "QUOTES",
    "Quote",
    "TABLE_COLUMNS",
    "paper_best",
    "paper_impulsive_rows",
    "paper_table",
    "paper_table_b1",
    "quote",
    "quotes_table",
]

#: The data file of the printed numbers (package data of :mod:`lunarcap.data`).
DATA_FILE = Path(__file__).resolve().parent.parent / "data" / "song2011_printed.yaml"

#: Columns of :func:`paper_table`.
TABLE_COLUMNS = ("start_min", "burn_duration_min", "delta_v_mps", "diff_percent", "best")


@dataclass(frozen=True)
class Quote:
    """One number printed in Song 2011's prose.

    Attributes
    ----------
    name : str
        Key in :data:`QUOTES`.
    printed : str
        The number exactly as printed (digits, commas and exponent), e.g. ``"434.471"``.
    unit : str
        Unit of ``value`` ("kg", "m/s", "min", "h", "%", "km", "km³/s²", "N", "s",
        "deg", "t" (metric tons) or "" for pure numbers).
    where : str
        Section and paragraph (counted in reading order within the section), or table,
        figure or equation.
    text : str
        The words the number is printed with (a verbatim excerpt, "..." marks omissions).
    approximate : bool
        True when the paper writes "about" before the number.
    """

    name: str
    printed: str
    unit: str
    where: str
    text: str
    approximate: bool = True

    @property
    def value(self) -> float:
        """The printed number as a float, in ``unit``."""
        return float(self.printed.replace(",", ""))

    @property
    def resolution(self) -> float:
        """One unit in the last printed digit, in ``unit`` (e.g. 0.001 for "434.471")."""
        exp = Decimal(self.printed.replace(",", "")).as_tuple().exponent
        return float(Decimal(1).scaleb(exp))

    @property
    def decimals(self) -> int:
        """Number of printed digits after the decimal point (0 for integers)."""
        exp = Decimal(self.printed.replace(",", "")).as_tuple().exponent
        return max(0, -exp)


def _read(path: Path = DATA_FILE) -> dict:
    """The data file as plain YAML mappings, lists, strings and numbers.

    libyaml's safe loader where installed (the file is read at import by every page and
    study that compares with the paper); the numbers are converted by PyYAML's own
    constructors either way, so the values do not depend on the parser.
    """
    import yaml

    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    return yaml.load(path.read_text(encoding="utf-8"), Loader=loader)


def _quotes(groups: list) -> dict[str, Quote]:
    """:data:`QUOTES` from the file's ``quotes`` (numbers grouped by where they are printed)."""
    out = {}
    for group in groups:
        for e in group["numbers"]:
            q = Quote(e["name"], e["printed"], e["unit"], group["where"], e["text"],
                      e.get("approximate", True))
            if q.name in out:
                raise RuntimeError(f"duplicate quote {q.name}")  # pragma: no cover
            out[q.name] = q
    return out


def _by_thrust_and_loi(rows: list) -> dict:
    """Table B1's rows ``[thrust N, LOI, *values]`` as thrust -> LOI -> tuple of values."""
    out: dict = {}
    for t, n, *values in rows:
        out.setdefault(t, {})[n] = tuple(values)
    return out


_DATA = _read()

#: Tables 1-5 by (thrust N, LOI): ``source``, ``title``, ``impulsive`` (the impulsive row
#: printed in that table, m/s) and ``rows`` (tuples in the order of :data:`TABLE_COLUMNS`).
_TABLES = {(tab["thrust_N"], tab["loi"]): {"source": tab["source"], "title": tab["title"],
                                          "impulsive": tab["impulsive_delta_v_mps"],
                                          "rows": [tuple(r) for r in tab["rows"]]}
           for tab in _DATA["tables"]}

#: Table B1's impulsive rows, m/s, by LOI.
_TABLE_B1_IMPULSIVE = dict(_DATA["table_b1"]["impulsive_delta_v_mps"])

#: Table B1, thrust N -> LOI -> (start min, burn duration min, delta-V m/s, difference %).
_TABLE_B1 = _by_thrust_and_loi(_DATA["table_b1"]["rows"])

#: Impulsive delta-Vs of LOI 1, 2, 3, m/s, as printed in every table (Tables 1-5, B1),
#: taken by Song 2011 from Song et al. (2009c).
PAPER_IMPULSIVE_DV_MPS = tuple(_TABLE_B1_IMPULSIVE[n] for n in (1, 2, 3))

#: The three engines studied, thrust N -> specific impulse s (abstract; Sec. 3.1, para 2;
#: Sec. 3.2, para 1; Table B1), keyed by integer thrust as the tables print it. The
#: engines run are the packaged plans' (:func:`lunarcap.mission.scenario.paper_engines`).
PAPER_ENGINES = {int(t): isp for t, isp in paper_engines().items()}

#: The paper's ignition offsets, min before perilune (Tables 1-5), by (thrust N, LOI).
PAPER_STARTS_MIN = {(float(t), n): tuple(float(r[0]) for r in tab["rows"])
                    for (t, n), tab in _TABLES.items()}

#: The paper's best offsets (Table B1), min, by thrust N -> (LOI1, LOI2, LOI3).
PAPER_BEST_STARTS_MIN = {float(t): tuple(float(by_loi[n][0]) for n in (1, 2, 3))
                         for t, by_loi in _TABLE_B1.items()}

#: Every number of the prose, by name. ``QUOTES[name].value`` is the number in its unit.
QUOTES: dict[str, Quote] = _quotes(_DATA["quotes"])

#: The perilune epochs printed in Sec. 3.2.1, TDB, in the paper's own format
#: (1st: para 1; 2nd: para 2; 3rd: para 3).
PAPER_EPOCHS_TDB = {e["n"]: e["epoch"] for e in _DATA["perilune_epochs_tdb"]}

#: Where each epoch of :data:`PAPER_EPOCHS_TDB` is printed.
PAPER_EPOCHS_WHERE = {e["n"]: e["where"] for e in _DATA["perilune_epochs_tdb"]}


# ---------------------------------------------------------------------------------------
# Tables 1-5 and B1
# ---------------------------------------------------------------------------------------


def _check_case(thrust_N, loi) -> tuple[int, int]:
    """Validate an (engine thrust N, LOI number) pair and return it as ints."""
    try:
        t, n = int(thrust_N), int(loi)
    except (TypeError, ValueError):
        raise InputError(f"thrust must be one of 150, 300, 450 N and LOI one of 1, 2, 3; "
                         f"got thrust={thrust_N!r}, loi={loi!r}") from None
    if t != thrust_N or n != loi or (t, n) not in _TABLES:
        raise InputError(f"Song 2011 has no table for thrust={thrust_N!r} N, loi={loi!r}: "
                         "thrust must be one of 150, 300, 450 N and LOI one of 1, 2, 3")
    return t, n


def paper_table(thrust_N: float, loi: int) -> pd.DataFrame:
    """The finite-burn rows of one of Song 2011's Tables 1-5, as printed.

    Parameters
    ----------
    thrust_N : {150, 300, 450}
        Engine thrust, N (150 N: Tables 1-3; 300 N: Table 4; 450 N: Table 5).
    loi : {1, 2, 3}
        Lunar orbit insertion number.

    Returns
    -------
    pandas.DataFrame
        One row per ignition point, columns ``start_min`` (ignition, min before
        perilune, negative), ``burn_duration_min`` (min), ``delta_v_mps`` (m/s),
        ``diff_percent`` (difference from the impulsive delta-V, %, as printed) and
        ``best`` (the row the paper marks "Best solution"). ``attrs`` holds ``source``
        (e.g. "Table 1"), ``title``, ``thrust_N``, ``isp_s``, ``loi`` and
        ``impulsive_delta_v_mps`` (the impulsive row printed in that table, m/s).

    Examples
    --------
    >>> t = paper_table(150, 1)
    >>> t.attrs["source"], int(t.loc[t.best, "start_min"].iloc[0])
    ('Table 1', -10)
    """
    t, n = _check_case(thrust_N, loi)
    tab = _TABLES[(t, n)]
    df = pd.DataFrame(tab["rows"], columns=list(TABLE_COLUMNS))
    df["start_min"] = df["start_min"].astype(int)
    df["best"] = df["best"].astype(bool)
    df.attrs.update(source=tab["source"], title=tab["title"], thrust_N=t,
                    isp_s=PAPER_ENGINES[t], loi=n,
                    impulsive_delta_v_mps=tab["impulsive"])
    return df


def paper_impulsive_rows() -> pd.DataFrame:
    """The impulsive row as printed in each of Tables 1-5 and Table B1.

    Returns
    -------
    pandas.DataFrame
        Columns ``source``, ``thrust_N`` (0 for Table B1), ``loi`` and
        ``impulsive_delta_v_mps`` (m/s).
    """
    rows = [(tab["source"], t, n, tab["impulsive"]) for (t, n), tab in _TABLES.items()]
    rows += [("Table B1", 0, n, dv) for n, dv in _TABLE_B1_IMPULSIVE.items()]
    return pd.DataFrame(rows, columns=["source", "thrust_N", "loi", "impulsive_delta_v_mps"])


def paper_table_b1() -> pd.DataFrame:
    """Table B1 (Appendix B): the best finite-burn case of every engine and LOI.

    Returns
    -------
    pandas.DataFrame
        Columns ``thrust_N``, ``isp_s``, ``loi``, ``start_min`` (min), ``burn_duration_min``
        (min), ``delta_v_mps`` (m/s), ``diff_percent`` (%), ``impulsive_delta_v_mps`` (the
        impulsive rows of Table B1, m/s).
    """
    rows = []
    for t, by_loi in _TABLE_B1.items():
        for n, (s, d, dv, pct) in by_loi.items():
            rows.append((t, PAPER_ENGINES[t], n, s, d, dv, pct, _TABLE_B1_IMPULSIVE[n]))
    df = pd.DataFrame(rows, columns=["thrust_N", "isp_s", "loi", "start_min",
                                     "burn_duration_min", "delta_v_mps", "diff_percent",
                                     "impulsive_delta_v_mps"])
    df.attrs["source"] = "Table B1"
    return df


def paper_best(thrust_N: float, loi: int) -> dict:
    """The best case of one engine and LOI as printed in Table B1.

    Parameters
    ----------
    thrust_N : {150, 300, 450}
        Engine thrust, N.
    loi : {1, 2, 3}
        Lunar orbit insertion number.

    Returns
    -------
    dict
        ``start_min`` (min before perilune), ``burn_duration_min`` (min),
        ``delta_v_mps`` (m/s), ``diff_percent`` (%), ``impulsive_delta_v_mps`` (m/s),
        ``isp_s`` (s), ``source`` ("Table B1").

    Examples
    --------
    >>> paper_best(300, 3)["burn_duration_min"]
    5.32
    """
    t, n = _check_case(thrust_N, loi)
    s, d, dv, pct = _TABLE_B1[t][n]
    return {"start_min": s, "burn_duration_min": d, "delta_v_mps": dv, "diff_percent": pct,
            "impulsive_delta_v_mps": _TABLE_B1_IMPULSIVE[n], "isp_s": PAPER_ENGINES[t],
            "source": "Table B1"}


def quote(name: str) -> Quote:
    """One number of the paper's prose by name (see :data:`QUOTES`).

    Parameters
    ----------
    name : str
        Key of :data:`QUOTES`, e.g. ``"mass_after_loi1_150N_kg"``.

    Returns
    -------
    Quote
    """
    try:
        return QUOTES[name]
    except KeyError:
        raise InputError(f"no printed number called {name!r}; "
                         "see lunarcap.paper.printed.QUOTES") from None


def quotes_table() -> pd.DataFrame:
    """All numbers of the prose as a table.

    Returns
    -------
    pandas.DataFrame
        Columns ``name``, ``value`` (in ``unit``), ``printed``, ``unit``, ``approximate``,
        ``where`` and ``text``.
    """
    return pd.DataFrame(
        [(q.name, q.value, q.printed, q.unit, q.approximate, q.where, q.text)
         for q in QUOTES.values()],
        columns=["name", "value", "printed", "unit", "approximate", "where", "text"])
