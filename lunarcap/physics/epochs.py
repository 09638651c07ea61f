"""Epochs: calendar strings in TDB or UTC, Julian dates, TDB seconds past J2000.

Internally an epoch is a float of TDB seconds past J2000.0 (JD 2451545.0 TDB,
i.e. 2000-01-01 12:00:00 TDB); SPICE calls the same number ephemeris time (ET).
Calendar strings name their time scale: ``"2017-02-20 03:41:26 TDB"`` or
``"2017-02-20 03:40:16.816 UTC"`` (``T`` or a space between date and time; ``Z`` is UTC;
Song 2011's ``"20-Feb-2017 03:41:26 (TDB)"``). A string without a scale is refused
rather than guessed: the two scales differ by more than a minute (69.18 s in 2017).

TDB strings convert with integer calendar arithmetic (proleptic Gregorian), exact to the
microsecond. UTC strings go through the IAU SOFA algorithms as ERFA implements them
(``pyerfa``): UTC -> TAI with the leap-second table, TAI -> TT (+32.184 s), TT -> TDB with
``eraDtdb`` (Fairhead & Bretagnon's series at the geocentre, |TDB - TT| < 2 ms). The
leap-second table is IERS's ``Leap_Second.dat`` as shipped by the ``astropy-iers-data``
package (updated with IERS Bulletin C; no network at run time), loaded into ERFA on
first use (:func:`leap_second_table`); after the table's expiry date UTC - TAI is taken
as its last value (no leap second announced). The TDB seconds of a UTC string are
rounded to the microsecond, like a TDB string's, so the same instant written in either
scale gives the same number, bit for bit, when the UTC string carries nanoseconds
(``calendar_from_seconds(t, 9, scale="UTC")``); with microseconds, to 1 microsecond.
"""

from __future__ import annotations

import re
import warnings
from functools import lru_cache

from lunarcap.errors import InputError
from lunarcap.physics.constants import DAY_S, JD_J2000

#: Time scales a calendar string may name.
SCALES = ("TDB", "UTC")

_MONTHS = {m: i + 1 for i, m in enumerate(
    ["jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec"])}

_ISO = re.compile(
    r"^\s*(\d{4})-(\d{1,2})-(\d{1,2})[ T](\d{1,2}):(\d{2}):(\d{2}(?:\.\d+)?)"
    r"\s*(?:\(?(TDB|UTC)\)?|(Z))?\s*$", re.IGNORECASE)
_DMY = re.compile(
    r"^\s*(\d{1,2})-([A-Za-z]{3})-(\d{4})\s+(\d{1,2}):(\d{2}):(\d{2}(?:\.\d+)?)"
    r"\s*(?:\(?(TDB|UTC)\)?)?\s*$", re.IGNORECASE)


def _days_from_civil(y: int, m: int, d: int) -> int:
    """Days of the proleptic Gregorian date (y, m, d) since 1970-01-01."""
    y -= m <= 2
    era = (y if y >= 0 else y - 399) // 400
    yoe = y - era * 400
    doy = (153 * (m + (-3 if m > 2 else 9)) + 2) // 5 + d - 1
    doe = yoe * 365 + yoe // 4 - yoe // 100 + doy
    return era * 146097 + doe - 719468


def _civil_from_days(z: int) -> tuple[int, int, int]:
    """Inverse of :func:`_days_from_civil`."""
    z += 719468
    era = (z if z >= 0 else z - 146096) // 146097
    doe = z - era * 146097
    yoe = (doe - doe // 1460 + doe // 36524 - doe // 146096) // 365
    y = yoe + era * 400
    doy = doe - (365 * yoe + yoe // 4 - yoe // 100)
    mp = (5 * doy + 2) // 153
    d = doy - (153 * mp + 2) // 5 + 1
    m = mp + (3 if mp < 10 else -9)
    return y + (m <= 2), m, d


_J2000_DAYS = _days_from_civil(2000, 1, 1)  # J2000.0 is 12:00 of this day


def seconds_from_calendar(text: str, scale: str | None = None) -> float:
    """TDB seconds past J2000 of a calendar string in TDB or UTC.

    Parameters
    ----------
    text : str
        ``"2017-02-20 03:41:26 TDB"``, ``"2017-02-20T03:40:16.816 UTC"`` (ISO, optional
        fraction of a second, ``Z`` for UTC) or ``"20-Feb-2017 03:41:26 (TDB)"`` as
        printed in Song 2011.
    scale : {"TDB", "UTC"}, optional
        The scale of a string that names none (a CCSDS file's ``TIME_SYSTEM``); without
        it such a string is refused. A string naming another scale is refused too.

    Returns
    -------
    float
        Seconds past J2000.0, TDB (rounded to the microsecond).

    Examples
    --------
    >>> seconds_from_calendar("2000-01-01 12:00:00 TDB")
    0.0
    >>> seconds_from_calendar("2017-02-20 03:40:16.814760 UTC")
    540834086.0
    """
    if not isinstance(text, str):
        raise InputError(f"epoch must be a string like '2017-02-20 03:41:26 TDB', got {text!r}")
    m = _ISO.match(text)
    if m:
        y, mo, d = int(m[1]), int(m[2]), int(m[3])
        named = "UTC" if m[8] else m[7]
    else:
        m = _DMY.match(text)
        if not m:
            raise InputError(
                f"cannot read epoch {text!r}: expected 'YYYY-MM-DD HH:MM:SS[.fff] TDB' (or UTC)")
        d, y = int(m[1]), int(m[3])
        mo = _MONTHS.get(m[2].lower())
        if mo is None:
            raise InputError(f"cannot read month {m[2]!r} of epoch {text!r}")
        named = m[7]
    named = named.upper() if named else None
    if scale is not None:
        scale = scale.upper()
        if scale not in SCALES:
            raise InputError(f"time scale {scale!r} is not supported (use TDB or UTC)")
        if named and named != scale:
            raise InputError(f"epoch {text!r} names {named} but {scale} was expected")
    named = named or scale
    if named is None:
        raise InputError(f"epoch {text!r} names no time scale: write it with TDB or UTC "
                         f"after the time, e.g. '2040-06-01 00:00:00 UTC' (the two differ "
                         f"by more than a minute)")
    hh, mm, ss = int(m[4]), int(m[5]), float(m[6])
    _check_fields(text, y, mo, d, hh, mm, ss, named)
    days = _days_from_civil(y, mo, d)
    if named == "UTC":
        return _tdb_seconds_from_utc(y, mo, d, hh, mm, ss, text)
    # exact: integers plus the seconds field, rounded to the microsecond
    return (days - _J2000_DAYS) * DAY_S + (hh * 3600 + mm * 60 - 43200) + round(ss, 6)


def _check_fields(text: str, y: int, mo: int, d: int, hh: int, mm: int, ss: float,
                  scale: str) -> None:
    """InputError naming the field of a calendar epoch that does not exist.

    A day has hours 00-23 (``24:00:00`` is the next day's ``00:00:00``: refused, not
    carried over). In UTC the second 60 exists only in the last minute of a day that
    ends with a leap second (IERS's table, :func:`leap_second_table`; none is assumed
    after its expiry); in TDB never.
    """
    for name, value, lo, hi in (("month", mo, 1, 12), ("day", d, 1, 31), ("hour", hh, 0, 23),
                                ("minute", mm, 0, 59)):
        if not lo <= value <= hi:
            raise InputError(f"epoch {text!r} does not exist: its {name} {value} is not in "
                             f"{lo:02d}-{hi:02d}")
    if _civil_from_days(_days_from_civil(y, mo, d)) != (y, mo, d):
        raise InputError(f"epoch {text!r} is not a calendar date")
    if ss < 60.0:
        return
    day = f"{y:04d}-{mo:02d}-{d:02d}"
    leap = _leap_second_s(y, mo, d) if scale == "UTC" else 0.0
    if leap <= 0.0 or (hh, mm) != (23, 59) or ss >= 60.0 + leap:
        why = (f"{day} ends at 23:59:59.999... UTC (no leap second that day in IERS's "
               f"table, valid to {leap_second_table()['expires']})"
               if scale == "UTC" and leap <= 0.0 else
               "a minute has seconds 00-59 (60 only at the end of a UTC day with a leap "
               "second)" if scale != "UTC" or (hh, mm) != (23, 59) else
               f"the leap second of {day} is 23:59:60.000-23:59:60.999... UTC")
        raise InputError(f"epoch {text!r} does not exist: {why}")


def _leap_second_s(y: int, mo: int, d: int) -> float:
    """The leap second added at the end of the UTC day (y, mo, d), s (0: none).

    TAI - UTC at the start of the next day minus at the start of this one (ERFA's
    ``eraDat`` with IERS's table); 0 outside the table (before 1960).
    """
    erfa = _erfa()
    nxt = _civil_from_days(_days_from_civil(y, mo, d) + 1)
    try:
        return float(_quiet(erfa.dat, *nxt, 0.0)) - float(_quiet(erfa.dat, y, mo, d, 0.0))
    except erfa.ErfaError:
        return 0.0


def calendar_from_seconds(t_s: float, decimals: int = 3, scale: str = "TDB",
                          iso: bool = False) -> str:
    """Calendar string ``"YYYY-MM-DD HH:MM:SS.fff TDB"`` (or UTC) of TDB seconds past J2000.

    Parameters
    ----------
    t_s : float
        Seconds past J2000.0, TDB.
    decimals : int
        Digits of the seconds' fraction (0 to 6; 9 in UTC); rounded, not truncated.
    scale : {"TDB", "UTC"}
        The scale written (UTC through ERFA and the leap-second table; a leap second is
        written as 23:59:60).
    iso : bool
        ``"YYYY-MM-DDTHH:MM:SS.fff"`` without the scale (CCSDS files, whose
        ``TIME_SYSTEM`` names it).

    Examples
    --------
    >>> calendar_from_seconds(0.0, scale="UTC")
    '2000-01-01 11:58:55.816 UTC'
    """
    scale = scale.upper()
    if scale == "UTC":
        y, mo, d, hh, mm, ss, frac = _utc_fields(float(t_s), decimals)
    elif scale == "TDB":
        mult = 10 ** decimals
        ticks = round((float(t_s) + 43200.0) * mult)  # ticks since 2000-01-01 00:00
        days, rem = divmod(ticks, 86400 * mult)
        y, mo, d = _civil_from_days(_J2000_DAYS + days)
        secs, frac = divmod(rem, mult)
        hh, r = divmod(secs, 3600)
        mm, ss = divmod(r, 60)
    else:
        raise InputError(f"time scale {scale!r} is not supported (use TDB or UTC)")
    tail = f".{frac:0{decimals}d}" if decimals > 0 else ""
    if iso:
        return f"{y:04d}-{mo:02d}-{d:02d}T{hh:02d}:{mm:02d}:{ss:02d}{tail}"
    return f"{y:04d}-{mo:02d}-{d:02d} {hh:02d}:{mm:02d}:{ss:02d}{tail} {scale}"


# ---------------------------------------------------------------------- UTC (ERFA)
@lru_cache(maxsize=1)
def leap_second_table() -> dict:
    """Load IERS's leap-second table into ERFA (once) and describe it.

    The table is ``Leap_Second.dat`` of the ``astropy-iers-data`` package (IERS Bulletin
    C, refreshed with each release of the package); ERFA's own compiled-in table is the
    fallback if the package cannot be read.

    Returns
    -------
    dict
        ``source`` (file or "ERFA built-in"), ``expires`` (``YYYY-MM-DD``), ``last``
        (the last leap second's date) and ``tai_minus_utc_s`` (its value).
    """
    import erfa

    source, expires = "ERFA built-in", str(erfa.leap_seconds.expires)[:10]
    try:
        from importlib.resources import files

        path = files("astropy_iers_data") / "data" / "Leap_Second.dat"
        text = path.read_text(encoding="ascii")
        rows, months = [], {"january": 1, "june": 6, "july": 7, "december": 12}
        for line in text.splitlines():
            low = line.lower()
            if "file expires on" in low:
                dd, month, yyyy = low.split("expires on")[1].split()[:3]
                expires = f"{int(yyyy):04d}-{months.get(month, 1):02d}-{int(dd):02d}"
            elif line.strip() and not line.lstrip().startswith("#"):
                _mjd, _day, month_n, year, tai_utc = line.split()[:5]
                rows.append((int(year), int(month_n), float(tai_utc)))
        import numpy as np

        # the file starts in 1972; ERFA's rows before it (UTC with a drift, which eraDat
        # applies to the table's first 14 rows) are kept, else eraDat drifts 1972-1985
        # (TAI - UTC of 40.1 s in 1985 instead of 22 s)
        erfa.leap_seconds.set()
        builtin = erfa.leap_seconds.get()
        table = np.concatenate([builtin[builtin["year"] < 1972],
                                np.array(rows, dtype=builtin.dtype)])
        import datetime as _dt

        erfa.leap_seconds.set(table)
        erfa.leap_seconds.expires = _dt.datetime.fromisoformat(expires)
        source = "astropy-iers-data Leap_Second.dat"
    except Exception:  # the package missing or unreadable: ERFA's compiled-in table
        erfa.leap_seconds.set()
    last = erfa.leap_seconds.get()[-1]
    return {"source": source, "expires": expires,
            "last": f"{int(last['year']):04d}-{int(last['month']):02d}-01",
            "tai_minus_utc_s": float(last["tai_utc"])}


def _erfa():
    import erfa

    leap_second_table()
    return erfa


def _quiet(fn, *args):
    """An ERFA call with its 'dubious year' warning silenced.

    Epochs past the table's expiry: UTC - TAI stays at its last value (module docstring).
    """
    import erfa

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", erfa.ErfaWarning)
        return fn(*args)


def _tdb_seconds_from_utc(y, mo, d, hh, mm, ss, text) -> float:
    erfa = _erfa()
    try:
        u1, u2 = _quiet(erfa.dtf2d, "UTC", y, mo, d, hh, mm, ss)
    except erfa.ErfaError as exc:
        raise InputError(f"epoch {text!r} is not a UTC time: {exc}") from None
    a1, a2 = _quiet(erfa.utctai, u1, u2)
    t1, t2 = erfa.taitt(a1, a2)
    dtr = erfa.dtdb(t1, t2, 0.0, 0.0, 0.0, 0.0)   # TDB - TT at the geocentre, s
    b1, b2 = erfa.tttdb(t1, t2, dtr)
    return round(((float(b1) - JD_J2000) + float(b2)) * DAY_S, 6)


def _utc_fields(t_s: float, decimals: int) -> tuple:
    erfa = _erfa()
    b1, b2 = jd_split_from_seconds(t_s)
    dtr = erfa.dtdb(b1, b2, 0.0, 0.0, 0.0, 0.0)  # TDB - TT (its change over dtr: < 1e-12 s)
    t1, t2 = erfa.tdbtt(b1, b2, dtr)
    a1, a2 = erfa.tttai(t1, t2)
    u1, u2 = _quiet(erfa.taiutc, a1, a2)
    y, mo, d, hmsf = _quiet(erfa.d2dtf, "UTC", decimals, u1, u2)
    h = hmsf.tolist() if hasattr(hmsf, "tolist") else hmsf
    return int(y), int(mo), int(d), int(h[0]), int(h[1]), int(h[2]), int(h[3])


def jd_from_seconds(t_s: float) -> float:
    """TDB Julian date of TDB seconds past J2000 (one float; ~40 microseconds resolution)."""
    return JD_J2000 + float(t_s) / DAY_S


def jd_split_from_seconds(t_s: float) -> tuple[float, float]:
    """TDB Julian date as (whole part, fraction of a day) for full precision."""
    whole_days, rem = divmod(float(t_s), DAY_S)
    return JD_J2000 + whole_days, rem / DAY_S


def seconds_from_jd(jd: float, jd2: float = 0.0) -> float:
    """TDB seconds past J2000 of a (possibly two-part) TDB Julian date."""
    return ((float(jd) - JD_J2000) + float(jd2)) * DAY_S
