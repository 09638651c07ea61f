"""Tests of lunarcap.physics.epochs: TDB calendar strings, Julian dates, seconds past J2000.

The independent reference is Python's :mod:`datetime`, which implements the same
proleptic Gregorian calendar with its own (C) arithmetic.
"""

from datetime import date, datetime, timedelta

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import epochs

J2000 = datetime(2000, 1, 1, 12, 0, 0)


def test_j2000_is_zero_seconds():
    # J2000.0 is 2000-01-01 12:00:00 TDB = JD 2451545.0 by definition: exact.
    assert epochs.seconds_from_calendar("2000-01-01 12:00:00 TDB") == 0.0
    assert epochs.calendar_from_seconds(0.0) == "2000-01-01 12:00:00.000 TDB"
    assert epochs.jd_from_seconds(0.0) == 2451545.0
    assert epochs.seconds_from_jd(2451545.0) == 0.0


def test_paper_epoch_form_parses():
    # Song 2011 prints epochs as '20-Feb-2017 03:41:26 (TDB)'; both spellings must give the
    # same number, and it must equal datetime's count of seconds (integers: exact).
    t_paper = epochs.seconds_from_calendar("20-Feb-2017 03:41:26 (TDB)")
    t_iso = epochs.seconds_from_calendar(paper_scenario().epoch_tdb)
    expected = (datetime(2017, 2, 20, 3, 41, 26) - J2000).total_seconds()
    assert t_paper == t_iso == expected
    # the variants the parser advertises: 'T' separator, lower-case month; a string without
    # a scale only with the scale given apart (a CCSDS file's TIME_SYSTEM)
    assert epochs.seconds_from_calendar("2017-02-20T03:41:26 TDB") == expected
    assert epochs.seconds_from_calendar("20-feb-2017 03:41:26 TDB") == expected
    assert epochs.seconds_from_calendar("2017-02-20T03:41:26", scale="TDB") == expected


def test_paper_epoch_julian_date():
    # JD of 2017-02-20 00:00 is 2457804.5 (JD 2451545.0 at 2000-01-01 12:00 plus 6259.5 days,
    # counted by datetime); the fraction is 3 h 41 min 26 s of a day. One float JD resolves
    # ~4e-5 s, i.e. 5e-10 day: tolerance 1e-9 day.
    days = (datetime(2017, 2, 20) - J2000).days + 0.5  # J2000 is noon
    jd_expected = 2451545.0 + days + (3 * 3600 + 41 * 60 + 26) / 86400.0
    t = epochs.seconds_from_calendar(paper_scenario().epoch_tdb)
    assert epochs.jd_from_seconds(t) == pytest.approx(jd_expected, abs=1e-9)
    whole, frac = epochs.jd_split_from_seconds(t)
    assert whole == 2451545.0 + 6259.0  # whole days past J2000 noon: exact
    assert frac == pytest.approx((15.0 * 3600 + 41 * 60 + 26) / 86400.0, abs=1e-15)
    # the two-part JD converts back exactly to the millisecond
    assert epochs.seconds_from_jd(whole, frac) == pytest.approx(t, abs=1e-6)


def test_calendar_round_trip_random_epochs_1900_2100():
    # Random epochs in whole milliseconds between 1900 and 2100: calendar -> seconds ->
    # calendar must be exact at the millisecond, and both must agree with datetime.
    rng = np.random.default_rng(20170220)
    lo = (datetime(1900, 1, 1) - J2000).total_seconds()
    hi = (datetime(2100, 12, 31, 23, 59, 59) - J2000).total_seconds()
    ms = rng.integers(int(lo * 1000), int(hi * 1000), size=400)
    for n in ms:
        t = int(n) / 1000.0
        text = epochs.calendar_from_seconds(t)
        dt = J2000 + timedelta(milliseconds=int(n))
        assert text == dt.strftime("%Y-%m-%d %H:%M:%S.") + f"{dt.microsecond // 1000:03d} TDB"
        back = epochs.seconds_from_calendar(text)
        # |t| <= 3.2e9 s, so a double resolves ~5e-7 s: the round trip is exact to 1e-6 s
        assert abs(back - t) < 1e-6
        assert round(back * 1000) == n


def test_calendar_from_seconds_rounds_fraction():
    # 0.9996 s past midnight rounds up to the next second at 3 decimals (carry into minutes,
    # hours and the date): 1999-12-31 23:59:59.9996 -> 2000-01-01 00:00:00.000.
    t = (datetime(1999, 12, 31, 23, 59, 59) - J2000).total_seconds() + 0.9996
    assert epochs.calendar_from_seconds(t) == "2000-01-01 00:00:00.000 TDB"
    assert epochs.calendar_from_seconds(t, 0) == "2000-01-01 00:00:00 TDB"


def test_leap_day_and_century_rules():
    # 2000 is a leap year (divisible by 400), 1900 and 2100 are not: datetime agrees.
    assert epochs.seconds_from_calendar("2000-02-29 12:00:00 TDB") == 59 * 86400.0
    for bad in ("1900-02-29 00:00:00 TDB", "2100-02-29 00:00:00 TDB",
                "2017-02-30 00:00:00 TDB"):
        with pytest.raises(InputError):
            epochs.seconds_from_calendar(bad)


@pytest.mark.parametrize("text", [
    "not an epoch",
    "2017-13-01 00:00:00 TDB",        # month 13
    "2017-02-20 24:00:00 TDB",        # hour 24
    "2017-02-20 03:61:26 TDB",        # minute 61
    "20-Foo-2017 03:41:26 (TDB)",     # unknown month
    "2017-02-20",                     # no time of day
    "",
])
def test_malformed_epoch_raises_input_error(text):
    with pytest.raises(InputError):
        epochs.seconds_from_calendar(text)


def test_non_string_epoch_raises_input_error():
    with pytest.raises(InputError):
        epochs.seconds_from_calendar(540834086.0)


# ---------------------------------------------------------------------- UTC (issue 18)
def test_epoch_without_scale_is_refused_with_the_reason():
    # '2040-06-01T00:00:00' was silently read as TDB; the scales differ by 69 s.
    with pytest.raises(InputError, match="names no time scale"):
        epochs.seconds_from_calendar("2040-06-01T00:00:00")
    with pytest.raises(InputError, match="names UTC but TDB"):
        epochs.seconds_from_calendar("2040-06-01T00:00:00 UTC", scale="TDB")


def test_utc_and_tdb_of_the_paper_arrival():
    # TDB - UTC = 37 s (leap seconds since 1972, TAI - UTC from 2017-01-01) + 32.184 s
    # (TT - TAI) + TDB - TT (-1.24 ms on 2017-02-20, eraDtdb at the geocentre).
    t = epochs.seconds_from_calendar(paper_scenario().epoch_tdb)
    utc = epochs.calendar_from_seconds(t, 6, scale="UTC")
    assert utc == "2017-02-20 03:40:16.814760 UTC"
    assert epochs.seconds_from_calendar(utc) == t           # same instant: bit for bit
    assert epochs.seconds_from_calendar("2017-02-20T03:40:16.814760Z") == t
    assert epochs.calendar_from_seconds(t, 3, iso=True) == "2017-02-20T03:41:26.000"


def test_utc_leap_second_and_table():
    # 2016-12-31 23:59:60 UTC exists (TAI - UTC went 36 -> 37 s): it is one second after
    # 23:59:59 and one before 2017-01-01 00:00:00, and is written back as 23:59:60.
    a, b, c = (epochs.seconds_from_calendar(x) for x in (
        "2016-12-31 23:59:59 UTC", "2016-12-31 23:59:60 UTC", "2017-01-01 00:00:00 UTC"))
    assert b - a == pytest.approx(1.0, abs=1e-6) and c - b == pytest.approx(1.0, abs=1e-6)
    assert epochs.calendar_from_seconds(b, 1, scale="UTC") == "2016-12-31 23:59:60.0 UTC"
    table = epochs.leap_second_table()
    assert table["source"].startswith("astropy-iers-data")
    assert table["tai_minus_utc_s"] == 37.0 and table["expires"] >= "2027-01-01"
    # before 1972-01-01 + the table: 2000-01-01 12:00 TDB = 11:58:55.816 UTC (32 s leap)
    assert epochs.calendar_from_seconds(0.0, scale="UTC") == "2000-01-01 11:58:55.816 UTC"


def test_every_leap_second_of_the_table_exists_and_no_other_second_60():
    # issue 24: 23:59:60 on a day without a leap second was read as the next day's 00:00
    # (ERFA's warning swallowed). Every day the table ends with a leap second (TAI - UTC
    # up by 1 s the next day, 1972 on) has a 23:59:60 one second after 23:59:59; the day
    # before it, a day in the middle of the year and a day past the table have none.
    import erfa

    epochs.leap_second_table()
    table = erfa.leap_seconds.get()
    steps = [(int(r["year"]), int(r["month"])) for prev, r in zip(table[:-1], table[1:])
             if r["year"] >= 1972 and r["tai_utc"] - prev["tai_utc"] == 1.0]
    assert len(steps) == 27       # 1972-06-30 to 2016-12-31 (IERS Bulletin C)
    for y, mo in steps:
        last = date(y, mo, 1) - timedelta(days=1)
        a, b = (epochs.seconds_from_calendar(f"{last} 23:59:{s} UTC") for s in ("59", "60.5"))
        assert b - a == pytest.approx(1.5, abs=3e-6)   # each rounded to 1 us
        for bad in (f"{last - timedelta(days=1)} 23:59:60 UTC",
                    f"{last} 23:58:60 UTC", f"{last} 23:59:61 UTC", f"{last} 23:59:60 TDB"):
            with pytest.raises(InputError, match="does not exist"):
                epochs.seconds_from_calendar(bad)
    for bad in ("2026-11-03 23:59:60.000 UTC", "2016-06-30 23:59:60 UTC",
                "2090-12-31 23:59:60 UTC", "2026-11-03 24:00:00 UTC"):
        with pytest.raises(InputError, match="does not exist"):
            epochs.seconds_from_calendar(bad)


@pytest.mark.parametrize("day, tai_minus_utc_s", [
    ("1972-03-01", 10.0), ("1975-03-01", 14.0), ("1985-03-01", 22.0), ("2017-03-01", 37.0)])
def test_tai_minus_utc_from_1972_is_the_iers_table(day, tai_minus_utc_s):
    # IERS Bulletin C / Leap_Second.dat: whole seconds from 1972. TDB - UTC = TAI - UTC +
    # 32.184 s (TT - TAI) + TDB - TT (|.| < 2 ms). Loading the file without ERFA's
    # pre-1972 rows made eraDat drift: 40.1 s instead of 22 s in 1985.
    d = (epochs.seconds_from_calendar(f"{day} 00:00:00 TDB")
         - epochs.seconds_from_calendar(f"{day} 00:00:00 UTC"))
    assert -d == pytest.approx(tai_minus_utc_s + 32.184, abs=2e-3)


def test_utc_round_trip_random_epochs():
    rng = np.random.default_rng(18)
    for t in rng.uniform(-3e8, 1.3e9, 50).round(6):
        # to the nanosecond in UTC: the same TDB microsecond, bit for bit
        assert epochs.seconds_from_calendar(epochs.calendar_from_seconds(t, 9, "UTC")) == t
        # to the microsecond: the same instant within the UTC string's rounding
        back = epochs.seconds_from_calendar(epochs.calendar_from_seconds(t, 6, "UTC"))
        assert abs(back - t) <= 1.01e-6
