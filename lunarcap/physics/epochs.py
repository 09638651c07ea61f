"""Epochs on the TDB time scale: calendar strings, Julian dates, seconds past J2000.

Internally an epoch is a float of TDB seconds past J2000.0 (JD 2451545.0 TDB,
i.e. 2000-01-01 12:00:00 TDB). Calendar conversion uses the proleptic Gregorian
calendar with integer arithmetic, so conversions are exact to the millisecond.
"""

from __future__ import annotations

import re

from lunarcap.errors import InputError
from lunarcap.physics.constants import DAY_S, JD_J2000

_MONTHS = {m: i + 1 for i, m in enumerate(
    ["jan", "feb", "mar", "apr", "may", "jun", "jul", "aug", "sep", "oct", "nov", "dec"])}

_ISO = re.compile(
    r"^\s*(\d{4})-(\d{1,2})-(\d{1,2})[ T](\d{1,2}):(\d{2}):(\d{2}(?:\.\d+)?)\s*(TDB)?\s*$",
    re.IGNORECASE)
_DMY = re.compile(
    r"^\s*(\d{1,2})-([A-Za-z]{3})-(\d{4})\s+(\d{1,2}):(\d{2}):(\d{2}(?:\.\d+)?)\s*(\(?TDB\)?)?\s*$")


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


def seconds_from_calendar(text: str) -> float:
    """TDB seconds past J2000 of a calendar string.

    Parameters
    ----------
    text : str
        ``"2017-02-20 03:41:26 TDB"`` (ISO, optional fraction of a second and
        optional ``TDB`` suffix) or ``"20-Feb-2017 03:41:26 (TDB)"`` as printed in
        Song 2011.

    Returns
    -------
    float
        Seconds past J2000.0, TDB.

    Examples
    --------
    >>> seconds_from_calendar("2000-01-01 12:00:00 TDB")
    0.0
    """
    if not isinstance(text, str):
        raise InputError(f"epoch must be a string like '2017-02-20 03:41:26 TDB', got {text!r}")
    m = _ISO.match(text)
    if m:
        y, mo, d = int(m[1]), int(m[2]), int(m[3])
    else:
        m = _DMY.match(text)
        if not m:
            raise InputError(
                f"cannot read epoch {text!r}: expected 'YYYY-MM-DD HH:MM:SS[.fff] TDB'")
        d, y = int(m[1]), int(m[3])
        mo = _MONTHS.get(m[2].lower())
        if mo is None:
            raise InputError(f"cannot read month {m[2]!r} of epoch {text!r}")
    hh, mm, ss = int(m[4]), int(m[5]), float(m[6])
    if not (1 <= mo <= 12 and 1 <= d <= 31 and hh < 24 and mm < 60 and ss < 61):
        raise InputError(f"epoch {text!r} has a field out of range")
    days = _days_from_civil(y, mo, d)
    if _civil_from_days(days) != (y, mo, d):
        raise InputError(f"epoch {text!r} is not a calendar date")
    # exact: integers plus the seconds field, rounded to the microsecond
    return (days - _J2000_DAYS) * DAY_S + (hh * 3600 + mm * 60 - 43200) + round(ss, 6)


def calendar_from_seconds(t_s: float, decimals: int = 3) -> str:
    """Calendar string ``"YYYY-MM-DD HH:MM:SS.fff TDB"`` of TDB seconds past J2000.

    Parameters
    ----------
    t_s : float
        Seconds past J2000.0, TDB.
    decimals : int
        Digits of the seconds' fraction (0 to 6); rounded, not truncated.
    """
    scale = 10 ** decimals
    ticks = round((float(t_s) + 43200.0) * scale)  # ticks since 2000-01-01 00:00
    day_ticks = 86400 * scale
    days, rem = divmod(ticks, day_ticks)
    y, mo, d = _civil_from_days(_J2000_DAYS + days)
    secs, frac = divmod(rem, scale)
    hh, r = divmod(secs, 3600)
    mm, ss = divmod(r, 60)
    tail = f".{frac:0{decimals}d}" if decimals > 0 else ""
    return f"{y:04d}-{mo:02d}-{d:02d} {hh:02d}:{mm:02d}:{ss:02d}{tail} TDB"


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
