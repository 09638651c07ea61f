"""Every number printed in Song et al. (2011), as data with its location.

Source: Song, Y.-J., Park, S.-Y., Kim, H.-D., Lee, J.-H. & Sim, E.-S. (2011),
"Analysis of Delta-V Losses During Lunar Capture Sequence Using Finite Thrust",
J. Astron. Space Sci. 28(3), 203-216, doi:10.5140/JASS.2011.28.3.203
(hereafter "Song 2011").

Nothing here is computed: the values are transcribed as printed, errors included
(:mod:`lunarcap.paper.audit` checks them against each other and against physics). Each
table names its table number; each number from the prose names its section, the
paragraph within that section counted in reading order (paragraph breaks are inferred
from the flattened two-column text, so the opening words of the paragraph or sentence
are given too), and the words it is printed with (``Quote.text``).

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

import pandas as pd

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_engines

__all__ = [
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

#: Impulsive delta-Vs of LOI 1, 2, 3, m/s, as printed in every table (Tables 1-5, B1),
#: taken by Song 2011 from Song et al. (2009c).
PAPER_IMPULSIVE_DV_MPS = (353.272, 254.034, 245.363)

#: The three engines studied, thrust N -> specific impulse s (abstract; Sec. 3.1, para 2;
#: Sec. 3.2, para 1; Table B1), keyed by integer thrust as the tables print it. The
#: engines run are the packaged plans' (:func:`lunarcap.mission.scenario.paper_engines`).
PAPER_ENGINES = {int(t): isp for t, isp in paper_engines().items()}

#: The paper's ignition offsets, min before perilune (Tables 1-5), by (thrust N, LOI).
PAPER_STARTS_MIN = {
    (150.0, 1): (0.0, -6.0, -8.0, -10.0, -12.0, -14.0),
    (150.0, 2): (0.0, -3.0, -6.0, -9.0),
    (150.0, 3): (0.0, -3.0, -5.0, -7.0),
    (300.0, 1): (0.0, -2.0, -4.0, -6.0),
    (300.0, 2): (0.0, -1.0, -3.0, -5.0),
    (300.0, 3): (0.0, -1.0, -2.0, -3.0),
    (450.0, 1): (0.0, -2.0, -3.0, -4.0),
    (450.0, 2): (0.0, -2.0, -4.0),
    (450.0, 3): (0.0, -1.0, -2.0, -3.0),
}

#: The paper's best offsets (Table B1), min, by thrust N -> (LOI1, LOI2, LOI3).
PAPER_BEST_STARTS_MIN = {150.0: (-10.0, -6.0, -5.0), 300.0: (-4.0, -3.0, -2.0),
                         450.0: (-3.0, -2.0, -2.0)}

#: Columns of :func:`paper_table`.
TABLE_COLUMNS = ("start_min", "burn_duration_min", "delta_v_mps", "diff_percent", "best")

# ---------------------------------------------------------------------------------------
# Tables 1-5. Rows: (start offset min, burn duration min, delta-V m/s, difference %, best)
# where "best" is the row the paper marks with footnote a ("Best solution.").
# ---------------------------------------------------------------------------------------

_TABLES = {
    (150, 1): {
        "source": "Table 1",
        "title": "Delta-V comparisons for the 1st LOI maneuver (arrival hyperbolic trajectory "
                 "to 1st 12 hour elliptical capture orbit), 150 N, Isp 200 s",
        "impulsive": 353.272,
        "rows": [
            (0, 21.71, 413.496, 17.05, False),
            (-6, 20.10, 379.643, 7.46, False),
            (-8, 19.61, 369.630, 4.63, False),
            (-10, 19.51, 367.415, 3.93, True),
            (-12, 19.56, 368.529, 4.31, False),
            (-14, 19.77, 372.791, 5.23, False),
        ],
    },
    (150, 2): {
        "source": "Table 2",
        "title": "Delta-V comparisons for the 2nd LOI maneuver (the 1st 12 hour elliptical "
                 "capture orbit to the 2nd 3.5 hour elliptical capture orbit), 150 N, Isp 200 s",
        "impulsive": 254.034,
        "rows": [
            (0, 12.16, 269.682, 6.16, False),
            (-3, 11.74, 259.410, 2.11, False),
            (-6, 11.65, 257.527, 1.37, True),
            (-9, 11.90, 263.462, 3.71, False),
        ],
    },
    (150, 3): {
        "source": "Table 3",
        "title": "Delta-V comparisons for the 3rd LOI maneuver (the 2nd 3.5 hour elliptical "
                 "capture orbit to the final circular mission operational orbit), 150 N, "
                 "Isp 200 s",
        "impulsive": 245.363,
        "rows": [
            (0, 14.53, 377.356, 53.79, False),
            (-3, 10.81, 252.268, 2.81, False),
            (-5, 9.86, 248.000, 1.07, True),
            (-7, 9.98, 251.180, 2.37, False),
        ],
    },
    (300, 1): {
        "source": "Table 4 (1st LOI)",
        "title": "Delta-V comparison results between the impulsive and the finite thrust, "
                 "300 N, Isp 250 s",
        "impulsive": 353.272,
        "rows": [
            (0, 8.52, 367.497, 4.03, False),
            (-2, 8.35, 359.584, 1.79, False),
            (-4, 8.28, 356.590, 0.94, True),
            (-6, 8.32, 358.486, 1.48, False),
        ],
    },
    (300, 2): {
        "source": "Table 4 (2nd LOI)",
        "title": "Delta-V comparison results between the impulsive and the finite thrust, "
                 "300 N, Isp 250 s",
        "impulsive": 254.034,
        "rows": [
            (0, 6.15, 257.292, 1.28, False),
            (-1, 6.11, 255.441, 0.55, False),
            (-3, 6.09, 254.675, 0.25, True),
            (-5, 6.16, 257.998, 1.56, False),
        ],
    },
    (300, 3): {
        "source": "Table 4 (3rd LOI)",
        "title": "Delta-V comparison results between the impulsive and the finite thrust, "
                 "300 N, Isp 250 s",
        "impulsive": 245.363,
        "rows": [
            (0, 5.67, 263.823, 7.52, False),
            (-1, 5.39, 249.962, 1.87, False),
            (-2, 5.32, 246.515, 0.47, True),
            (-3, 5.35, 247.739, 0.97, False),
        ],
    },
    (450, 1): {
        "source": "Table 5 (1st LOI)",
        "title": "Delta-V comparison results between the impulsive and the finite thrust, "
                 "450 N, Isp 300 s",
        "impulsive": 353.272,
        "rows": [
            (0, 6.63, 362.935, 2.74, False),
            (-2, 6.52, 356.528, 0.92, False),
            (-3, 6.49, 355.549, 0.64, True),
            (-4, 6.50, 355.846, 0.73, False),
        ],
    },
    (450, 2): {
        "source": "Table 5 (2nd LOI)",
        "title": "Delta-V comparison results between the impulsive and the finite thrust, "
                 "450 N, Isp 300 s",
        "impulsive": 254.034,
        "rows": [
            (0, 4.20, 255.074, 0.41, False),
            (-2, 4.19, 254.387, 0.14, True),
            (-4, 4.23, 257.516, 1.37, False),
        ],
    },
    (450, 3): {
        "source": "Table 5 (3rd LOI)",
        "title": "Delta-V comparison results between the impulsive and the finite thrust, "
                 "450 N, Isp 300 s",
        "impulsive": 245.363,
        "rows": [
            (0, 3.83, 253.225, 3.07, False),
            (-1, 3.73, 246.317, 0.41, False),
            (-2, 3.72, 245.906, 0.22, True),
            (-3, 3.74, 246.943, 0.64, False),
        ],
    },
}

# Table B1 (Appendix B): "Summary of delta-V comparison results between the impulsive and
# the finite thrust. For each simulation cases, only the best solutions are presented."
# Transcribed independently of Tables 1-5 so that the two can be compared.
# engine -> LOI -> (start min, burn duration min, delta-V m/s, difference %)
_TABLE_B1_IMPULSIVE = {1: 353.272, 2: 254.034, 3: 245.363}
_TABLE_B1 = {
    150: {1: (-10, 19.51, 367.415, 3.93), 2: (-6, 11.65, 257.527, 1.37),
          3: (-5, 9.86, 248.000, 1.07)},
    300: {1: (-4, 8.28, 356.590, 0.94), 2: (-3, 6.09, 254.675, 0.25),
          3: (-2, 5.32, 246.515, 0.47)},
    450: {1: (-3, 6.49, 355.549, 0.64), 2: (-2, 4.19, 254.387, 0.14),
          3: (-2, 3.72, 245.906, 0.22)},
}


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


# ---------------------------------------------------------------------------------------
# Numbers printed in the prose
# ---------------------------------------------------------------------------------------


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


def _quotes(*entries) -> dict[str, Quote]:
    out = {}
    for e in entries:
        q = Quote(*e)
        if q.name in out:
            raise RuntimeError(f"duplicate quote {q.name}")  # pragma: no cover
        out[q.name] = q
    return out


_S31_1 = "Sec. 3.1, para 1 ('To numerically optimize the established problem...')"
_S31_2 = "Sec. 3.1, para 2 ('To design a hypothetical lunar capture sequence...')"
_S32_1 = "Sec. 3.2 ('To derive the initial spacecraft states at the time of 1st LOI...')"
_S321_1 = "Sec. 3.2.1, para 1 ('For first analysis, the on-board engine's capability...')"
_S321_2 = "Sec. 3.2.1, para 2 ('As shown in Table 1, differences in the 1st LOI...')"
_S321_3 = "Sec. 3.2.1, para 3 ('From the results shown in Table 2...')"
_S321_4 = "Sec. 3.2.1, para 4 ('To analyze the final de-orbit maneuver (3rd LOI)...')"
_S321_5 = "Sec. 3.2.1, para 5 ('According to the simulation results shown above...')"
_S322_2 = "Sec. 3.2.2, para 2 ('In Table 4, simulation results are shown...')"
_S322_3 = "Sec. 3.2.2, para 3 ('Table 5 summarizes the simulation results...')"
_S33_1 = "Sec. 3.3, para 1 ('An example of a lunar capture trajectory...')"
_S33_2 = "Sec. 3.3, para 2 ('In Fig. 4, thrust steering angle and mass variation...')"
_S4 = "Sec. 4, para 1 ('In this work, semi-optimal lunar capture orbits...')"
_ABS = "Abstract"
_S22 = "Sec. 2.2"

#: Every number of the prose, by name. ``QUOTES[name].value`` is the number in its unit.
QUOTES: dict[str, Quote] = _quotes(
    # --- Abstract
    ("abstract_period_capture1_h", "12", "h", _ABS,
     "two different intermediate capture orbits having orbital periods of about 12 hours"),
    ("abstract_period_capture2_h", "3.5", "h", _ABS, "... and 3.5 hours"),
    ("abstract_final_altitude_km", "100", "km", _ABS,
     "final mission operation around the Moon is assumed to be 100 km altitude", False),
    ("abstract_final_inclination_deg", "90", "deg", _ABS, "with 90 degree of inclination",
     False),
    ("abstract_max_loss_percent", "2", "%", _ABS,
     "a difference of up to about 2% delta-V can occur during the lunar capture sequences"),
    # --- Sec. 1
    ("intro_tli_loss_percent_low", "2", "%", "Sec. 1 ('In the preliminary trajectory design "
     "studies...')", "about 2-5% of TLI delta-V magnitude differences may occur"),
    ("intro_tli_loss_percent_high", "5", "%", "Sec. 1 ('In the preliminary trajectory design "
     "studies...')", "about 2-5% of TLI delta-V magnitude differences may occur"),
    # --- Sec. 2.2
    ("thrust_direction_bound_lower", "-1.01", "", f"{_S22}, Eq. (12) ('Although the magnitude "
     "of unit pointing thrust vector...')",
     "these bounds are given as -1.01 and 1.01 for lower and upper bound", False),
    ("thrust_direction_bound_upper", "1.01", "", f"{_S22}, Eq. (12) ('Although the magnitude "
     "of unit pointing thrust vector...')",
     "these bounds are given as -1.01 and 1.01 for lower and upper bound", False),
    # --- Sec. 3.1, para 1: constants
    ("mu_moon_km3s2", "4,902.800", "km³/s²", _S31_1,
     "gravitational constant of the Moon is assumed to be about 4,902.800 km3/s2"),
    ("mu_earth_km3s2", "398,600.441", "km³/s²", _S31_1, "for the Earth 398,600.441 km3/s2",
     False),
    ("mu_sun_km3s2", "13,271,244,207.6", "km³/s²", _S31_1,
     "for the Sun 13,271,244,207.6 km3/s2", False),
    ("r_moon_km", "1,738.2", "km", _S31_1, "radius of the Moon is assumed to be about 1,738.2 km"),
    ("j2_moon", "0.2027e-3", "", _S31_1,
     "J2 coefficient for the Moon is assumed to be about 0.2027e-3"),
    # --- Sec. 3.1, para 2: capture orbits and engines
    ("period_capture1_about_h", "12", "h", _S31_2,
     "two different intermediate elliptical capture orbits having orbital periods of about "
     "12 hours and 3.5 hours"),
    ("period_capture2_about_h", "3.5", "h", _S31_2, "... 12 hours and 3.5 hours"),
    ("final_altitude_km", "100", "km", _S31_2,
     "final mission operation orbit ... assumed to be 100 km altitude and 90 degree of "
     "inclination", False),
    ("final_inclination_deg", "90", "deg", _S31_2, "... 90 degree of inclination", False),
    ("period_final_about_min", "118", "min", _S31_2, "with orbital period of about 118 minutes"),
    ("period_capture1_h", "12.235", "h", _S31_2,
     "each capture orbit's orbital period is given as about 12.235 hours, 3.525 hours and "
     "117.848 minutes, respectively"),
    ("period_capture2_h", "3.525", "h", _S31_2, "... 3.525 hours ..."),
    ("period_final_min", "117.848", "min", _S31_2, "... and 117.848 minutes"),
    ("engine1_thrust_N", "150", "N", _S31_2, "150 N with Isp of 200 sec", False),
    ("engine1_isp_s", "200", "s", _S31_2, "150 N with Isp of 200 sec", False),
    ("engine2_thrust_N", "300", "N", _S31_2, "300 N with Isp of 250 seconds", False),
    ("engine2_isp_s", "250", "s", _S31_2, "300 N with Isp of 250 seconds", False),
    ("engine3_thrust_N", "450", "N", _S31_2, "450 N with Isp of 300 seconds", False),
    ("engine3_isp_s", "300", "s", _S31_2, "450 N with Isp of 300 seconds", False),
    ("lro_thrust_N", "320", "N", _S31_2, "about 320 N with Isp of 200 seconds for NASA's LRO"),
    ("lro_isp_s", "200", "s", _S31_2, "about 320 N with Isp of 200 seconds for NASA's LRO"),
    ("selene_thrust_N", "500", "N", _S31_2,
     "about 500 N with Isp of 300 seconds for JAXA's SELENE"),
    ("selene_isp_s", "300", "s", _S31_2, "about 500 N with Isp of 300 seconds for JAXA's SELENE"),
    # --- Sec. 3.2, para 1
    ("kick_motor_thrust_t", "9.8", "t", _S32_1,
     "trajectory solutions derived with kick motor's nominal performance, a maximum thrust of "
     "about 9.8 tons"),
    # --- Sec. 3.2.1, para 1
    ("arrival_mass_kg", "524.895", "kg", _S321_1,
     "overall mass at the perilune arrival was about 524.895 kg (only spacecraft's dry mass + "
     "fuel) excluding the kick motor's dry mass"),
    ("kick_motor_dry_mass_kg", "315.422", "kg", _S321_1,
     "excluding the kick motor's dry mass, which was about 315.422 kg"),
    ("kslv2_capacity_t", "2.6", "t", _S321_1,
     "Korea Space Launch Vehicle-II (KSLV-II) ... with an on-orbit capacity of 2.6 tons", False),
    ("kslv2_parking_altitude_km", "300", "km", _S321_1, "at 300 km altitude", False),
    ("kslv2_parking_inclination_deg", "80", "deg", _S321_1,
     "with 80 deg inclined circular Earth parking orbit", False),
    # --- Sec. 3.2.1, para 2 (LOI 1, 150 N)
    ("best_start_loi1_150N_min", "10", "min", _S321_2,
     "1st LOI burn must be started ... at around about 10 minutes before perilune's arrival"),
    ("loss_loi1_150N_mps", "14.14", "m/s", _S321_2,
     "delta-V loss is found to be about 14.14 m/s (about 3.93%)"),
    ("loss_loi1_150N_percent", "3.93", "%", _S321_2, "about 14.14 m/s (about 3.93%)"),
    ("burn_loi1_150N_about_min", "19.5", "min", _S321_2,
     "about 19.5 minutes of continuous de-orbit burn is required"),
    ("mass_after_loi1_150N_kg", "434.471", "kg", _S321_2,
     "After burn out of 1st LOI maneuver, spacecraft mass is found to be about 434.471 kg"),
    ("fuel_loi1_150N_about_kg", "90", "kg", _S321_2,
     "which means about 90 kg of fuel is required to perform 1st LOI maneuver"),
    ("eq19_loi1_150N_min", "18.82", "min", _S321_2,
     "the estimated finite burn duration (shown with Eq. (19)) using impulsive delta-V is "
     "found to be about 18.82 minutes"),
    ("eq19_half_loi1_150N_min", "9.5", "min", _S321_2,
     "almost half the value of this estimated finite burn duration (about 9.5 minutes) nearly "
     "matches the best burn start time derived in Table 1"),
    ("period_capture1_about2_h", "12", "h", _S321_2,
     "After about 12 hours, a spacecraft again encountered perilune"),
    # --- Sec. 3.2.1, para 3 (LOI 2, 150 N)
    ("best_start_loi2_150N_min", "-6", "min", _S321_3,
     "the 2nd LOI burn must be started at about -6 minutes before 2nd approach of perilune"),
    ("burn_loi2_150N_min", "11.65", "min", _S321_3,
     "De-orbit finite burn's duration in this scenario is found to be about 11.65 minutes"),
    ("loss_loi2_150N_mps", "3.49", "m/s", _S321_3,
     "Delta-V loss about to be 3.49 m/s (about 1.37%)"),
    ("loss_loi2_150N_percent", "1.37", "%", _S321_3, "3.49 m/s (about 1.37%)"),
    ("eq19_loi2_150N_min", "11.50", "min", _S321_3,
     "The estimated finite burn duration using impulsive delta-V is found to be about 11.50 "
     "minutes"),
    ("mass_after_loi2_150N_kg", "381.005", "kg", _S321_3,
     "After successful burn of the 2nd LOI, spacecraft mass is about 381.005 kg"),
    ("fuel_loi2_150N_about_kg", "53", "kg", _S321_3,
     "which means about 53 kg of fuel is required for the 2nd LOI maneuver"),
    ("period_capture2_about2_h", "3.5", "h", _S321_3,
     "After about 3.5 hours, spacecraft again approached perilune"),
    # --- Sec. 3.2.1, para 4 (LOI 3, 150 N)
    ("best_start_loi3_150N_min", "-5", "min", _S321_4,
     "ignition of 3rd LOI must be started at about -5 minutes before 3rd approach of perilune"),
    ("burn_loi3_150N_min", "9.86", "min", _S321_4,
     "Finite burn duration in this scenario is about 9.86 minutes"),
    ("loss_loi3_150N_mps", "2.64", "m/s", _S321_4, "delta-V loss of about 2.64 m/s (about 1.07%)"),
    ("loss_loi3_150N_percent", "1.07", "%", _S321_4, "2.64 m/s (about 1.07%)"),
    ("eq19_loi3_150N_min", "9.76", "min", _S321_4,
     "estimated burn duration (estimated: about 9.76 minutes, half of estimated: about 4.88 "
     "minutes)"),
    ("eq19_half_loi3_150N_min", "4.88", "min", _S321_4, "half of estimated: about 4.88 minutes"),
    ("mass_final_150N_kg", "335.750", "kg", _S321_4,
     "spacecraft mass delivered to the final mission operational orbit is found to be about "
     "335.750 kg"),
    ("fuel_loi3_150N_about_kg", "45", "kg", _S321_4,
     "which means about 45 kg of fuel is required for the 3rd LOI"),
    # --- Sec. 3.2.1, para 5 (150 N summary)
    ("loss_pct_loi1_150N_summary", "3.93", "%", _S321_5,
     "delta-V losses of about 3.93, 1.37 and 1.07% will occur"),
    ("loss_pct_loi2_150N_summary", "1.37", "%", _S321_5, "about 3.93, 1.37 and 1.07%"),
    ("loss_pct_loi3_150N_summary", "1.07", "%", _S321_5, "about 3.93, 1.37 and 1.07%"),
    ("loss_total_150N_mps", "20.20", "m/s", _S321_5,
     "Overall magnitude of delta-V loss ... is about 20.20 m/s, which is about 2.12%"),
    ("loss_total_150N_percent", "2.12", "%", _S321_5, "about 20.20 m/s, which is about 2.12%"),
    ("fuel_finite_150N_kg", "185.010", "kg", _S321_5,
     "a total of about 185.010 kg of fuel is required for finite thrust (including every LOI "
     "maneuver)"),
    ("fuel_impulsive_150N_kg", "189.145", "kg", _S321_5,
     "and about 189.145 kg of fuel for impulsive thrust"),
    ("fuel_difference_150N_kg", "4", "kg", _S321_5,
     "Therefore, about 4 kg of fuel, about 2.24% more, is needed when the finite burn engine "
     "model is assumed"),
    ("fuel_difference_150N_percent", "2.24", "%", _S321_5, "about 4 kg of fuel, about 2.24% more"),
    ("burn_total_150N_min", "41.02", "min", _S321_5,
     "it is found that about 41.02 minutes (about 19.51 minutes for 1st LOI, about 11.65 "
     "minutes for 2nd LOI and about 9.86 minutes for 3rd LOI) of de-orbit burn is required"),
    ("burn_loi1_150N_min", "19.51", "min", _S321_5, "about 19.51 minutes for 1st LOI"),
    ("burn_loi2_150N_summary_min", "11.65", "min", _S321_5, "about 11.65 minutes for 2nd LOI"),
    ("burn_loi3_150N_summary_min", "9.86", "min", _S321_5, "about 9.86 minutes for 3rd LOI"),
    # --- Sec. 3.2.2, para 2 (300 N)
    ("loss_total_300N_mps", "5.11", "m/s", _S322_2,
     "about 5.11 m/s (3.32 m/s for 1st LOI, 0.64 m/s for 2nd LOI and 1.152 m/s for 3rd LOI) of "
     "delta-V loss will occur"),
    ("loss_loi1_300N_mps", "3.32", "m/s", _S322_2, "3.32 m/s for 1st LOI", False),
    ("loss_loi2_300N_mps", "0.64", "m/s", _S322_2, "0.64 m/s for 2nd LOI", False),
    ("loss_loi3_300N_mps", "1.152", "m/s", _S322_2, "1.152 m/s for 3rd LOI", False),
    ("loss_total_300N_percent", "0.55", "%", _S322_2,
     "In terms of a percentage rate, 5.11 m/s is about 0.55."),
    ("loss_total_150N_mps_recalled", "20.20", "m/s", _S322_2,
     "the use of 150 N with Isp of 200 seconds on-board engine, which showed about 20.20 m/s "
     "(about 2.12%) loss"),
    ("loss_total_150N_percent_recalled", "2.12", "%", _S322_2, "about 20.20 m/s (about 2.12%)"),
    ("eq19_half_loi1_300N_min", "4.21", "min", _S322_2,
     "For the 1st LOI maneuver, half of estimated burn duration is about 4.21 minutes"),
    ("eq19_half_loi2_300N_min", "3.04", "min", _S322_2,
     "while it is about 3.04 minutes for the 2nd LOI maneuver"),
    ("eq19_half_loi3_300N_min", "2.65", "min", _S322_2,
     "and about 2.65 minutes for the 3rd LOI maneuver"),
    ("burn_total_300N_min", "19.69", "min", _S322_2,
     "about 19.69 minutes (about 8.28 minutes for 1st LOI, about 6.09 minutes for 2nd LOI and "
     "about 5.32 minutes for 3rd LOI) of overall burn duration is required"),
    ("burn_loi1_300N_min", "8.28", "min", _S322_2, "about 8.28 minutes for 1st LOI"),
    ("burn_loi2_300N_min", "6.09", "min", _S322_2, "about 6.09 minutes for 2nd LOI"),
    ("burn_loi3_300N_min", "5.32", "min", _S322_2, "about 5.32 minutes for 3rd LOI"),
    ("mass_final_300N_kg", "369.289", "kg", _S322_2,
     "Final spacecraft's mass is found to be about 369.289 kg"),
    ("fuel_finite_300N_about_kg", "155", "kg", _S322_2,
     "this means that about 155 kg of fuel, about 34 kg less than the case in which on-board "
     "engine of 150 N and Isp of 200 seconds (about 189 kg) are used"),
    ("fuel_saving_300N_vs_150N_kg", "34", "kg", _S322_2,
     "about 34 kg less than the case ... 150 N"),
    ("fuel_150N_recalled_kg", "189", "kg", _S322_2,
     "on-board engine of 150 N and Isp of 200 seconds (about 189 kg)"),
    ("fuel_difference_300N_percent", "0.9", "%", _S322_2,
     "From a fuel consumption perspective, only about 0.9% of difference (about 154.146 kg of "
     "fuel for impulsive thrust and about 155.606 kg of fuel for finite thrust)"),
    ("fuel_impulsive_300N_kg", "154.146", "kg", _S322_2,
     "about 154.146 kg of fuel for impulsive thrust"),
    ("fuel_finite_300N_kg", "155.606", "kg", _S322_2, "about 155.606 kg of fuel for finite thrust"),
    # --- Sec. 3.2.2, para 3 (450 N)
    ("loss_total_450N_mps", "3.17", "m/s", _S322_3,
     "about 3.17 m/s (2.28 m/s for 1st LOI, 0.35 m/s for 2nd LOI and 0.54 m/s for 3rd LOI) of "
     "delta-V loss will occur"),
    ("loss_loi1_450N_mps", "2.28", "m/s", _S322_3, "2.28 m/s for 1st LOI", False),
    ("loss_loi2_450N_mps", "0.35", "m/s", _S322_3, "0.35 m/s for 2nd LOI", False),
    ("loss_loi3_450N_mps", "0.54", "m/s", _S322_3, "0.54 m/s for 3rd LOI", False),
    ("loss_total_450N_percent", "0.33", "%", _S322_3,
     "which is only about 0.33% when expressed as a percentage"),
    ("burn_total_450N_min", "14.40", "min", _S322_3,
     "About 14.40 minutes (about 6.49 minutes for 1st LOI, about 4.19 minutes for 2nd LOI and "
     "about 3.72 minutes for 3rd LOI) of overall burn duration is required"),
    ("burn_loi1_450N_min", "6.49", "min", _S322_3, "about 6.49 minutes for 1st LOI"),
    ("burn_loi2_450N_min", "4.19", "min", _S322_3, "about 4.19 minutes for 2nd LOI"),
    ("burn_loi3_450N_min", "3.72", "min", _S322_3, "about 3.72 minutes for 3rd LOI"),
    ("mass_final_450N_kg", "391.722", "kg", _S322_3,
     "Final spacecraft's mass is found to be about 391.722 kg"),
    ("fuel_finite_450N_about_kg", "133", "kg", _S322_3,
     "which means about 133 kg of on-board fuel is required"),
    ("fuel_difference_450N_kg", "1.2", "kg", _S322_3,
     "only about 1.2 kg of fuel (0.8%) difference (about 132.028 kg of fuel for impulsive "
     "thrust and about 133.192 kg of fuel for finite thrust)"),
    ("fuel_difference_450N_percent", "0.8", "%", _S322_3, "about 1.2 kg of fuel (0.8%)", False),
    ("fuel_impulsive_450N_kg", "132.028", "kg", _S322_3,
     "about 132.028 kg of fuel for impulsive thrust"),
    ("fuel_finite_450N_kg", "133.192", "kg", _S322_3, "about 133.192 kg of fuel for finite thrust"),
    # --- Sec. 3.3
    ("lunar_unit_km", "1,738.2", "km", _S33_1,
     "every axis is scaled to have 1 lunar unit (LU), which is about 1,738.2 km"),
    ("fig4_burn_loi1_150N_min", "19.51", "min", _S33_2,
     "During the 19.51 minutes of 1st LOI burn", False),
    ("fig4_alpha_start_deg", "137.5", "deg", _S33_2,
     "in-plane thrust angle, alpha(t), gradually increased from about 137.5 degree to about "
     "215.3 degree (top of Fig. 4)"),
    ("fig4_alpha_end_deg", "215.3", "deg", _S33_2, "... to about 215.3 degree (top of Fig. 4)"),
    ("fig4_beta_deg", "0", "deg", _S33_2,
     "out-of-plane thrust angle, beta(t), remained at almost 0 degree (middle of Fig. 4)"),
    ("fig4_mass_start_kg", "524.9", "kg", _S33_2,
     "the spacecraft mass is continuously decreased from about 524.9 kg to about 335.8 kg "
     "(bottom of Fig. 4)"),
    ("fig4_mass_end_kg", "335.8", "kg", _S33_2, "... to about 335.8 kg (bottom of Fig. 4)"),
    # --- Sec. 4
    ("conclusion_max_loss_percent", "2", "%", _S4,
     "it is found that up to about 2% of delta-V loss"),
    ("conclusion_loss_450N_percent", "0.33", "%", _S4, "0.33% loss with 450 N, Isp 300 seconds",
     False),
    ("conclusion_loss_300N_percent", "0.55", "%", _S4, "0.55% loss with 300 N, Isp 250 seconds",
     False),
    ("conclusion_loss_150N_percent", "2.12", "%", _S4, "2.12% loss with 150 N, Isp 200 seconds",
     False),
)

#: The perilune epochs printed in Sec. 3.2.1, TDB, in the paper's own format
#: (1st: para 1; 2nd: para 2; 3rd: para 3).
PAPER_EPOCHS_TDB = {
    1: "20-Feb-2017 03:41:26 (TDB)",
    2: "20-Feb-2017 15:55:33 (TDB)",
    3: "20-Feb-2017 19:27:05 (TDB)",
}

#: Where each epoch of :data:`PAPER_EPOCHS_TDB` is printed.
PAPER_EPOCHS_WHERE = {1: _S321_1, 2: _S321_2, 3: _S321_3}


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
