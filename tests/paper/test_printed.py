"""Tests of lunarcap.paper.printed: Song 2011's printed numbers, complete and well formed.

Song, Park, Kim, Lee & Sim (2011), J. Astron. Space Sci. 28(3) 203-216. Tables 1-5 and
B1 are transcribed separately, so agreement between them is a real check of the
transcription; the full text (if present) is searched for every number.
"""

import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from lunarcap.errors import InputError
from lunarcap.mission.scenario import paper_engines, paper_scenario
from lunarcap.paper import printed as P
from lunarcap.physics import constants as C

PAPER_TXT = Path("/work/shared/paper/song2011_lunar_capture_finite_thrust.txt")
CASES = [(t, n) for t in (150, 300, 450) for n in (1, 2, 3)]
ROWS_PER_TABLE = {(150, 1): 6, (150, 2): 4, (150, 3): 4, (300, 1): 4, (300, 2): 4,
                  (300, 3): 4, (450, 1): 4, (450, 2): 3, (450, 3): 4}


@pytest.fixture(scope="module")
def flat_text():
    if not PAPER_TXT.exists():
        pytest.skip("paper full text not available")
    return re.sub(r"\s+", " ", PAPER_TXT.read_text())


@pytest.mark.parametrize("case", CASES)
def test_table_shape_and_columns(case):
    df = P.paper_table(*case)
    assert tuple(df.columns) == P.TABLE_COLUMNS
    assert len(df) == ROWS_PER_TABLE[case]
    assert df["best"].dtype == bool
    assert (df["start_min"] <= 0).all()
    assert (df["burn_duration_min"] > 0).all() and (df["delta_v_mps"] > 0).all()
    assert df.attrs["thrust_N"] == case[0] and df.attrs["loi"] == case[1]
    assert df.attrs["isp_s"] == P.PAPER_ENGINES[case[0]]


@pytest.mark.parametrize("case", CASES)
def test_exactly_one_best_row_equal_to_table_b1(case):
    df = P.paper_table(*case)
    best = df[df.best]
    assert len(best) == 1
    row = best.iloc[0]
    b1 = P.paper_best(*case)
    for col in ("start_min", "burn_duration_min", "delta_v_mps", "diff_percent"):
        assert float(row[col]) == b1[col], col


@pytest.mark.parametrize("case", CASES)
def test_best_row_has_the_smallest_delta_v(case):
    df = P.paper_table(*case)
    assert df.loc[df.delta_v_mps.idxmin(), "best"]


def test_impulsive_values_equal_across_tables():
    rows = P.paper_impulsive_rows()
    assert len(rows) == 9 + 3
    for n in (1, 2, 3):
        vals = rows.loc[rows.loi == n, "impulsive_delta_v_mps"].unique()
        assert list(vals) == [P.PAPER_IMPULSIVE_DV_MPS[n - 1]]
    assert P.PAPER_IMPULSIVE_DV_MPS == (353.272, 254.034, 245.363)


def test_table_b1_covers_every_case():
    b1 = P.paper_table_b1()
    assert len(b1) == 9
    assert set(zip(b1.thrust_N, b1.loi)) == set(CASES)
    assert (b1.impulsive_delta_v_mps.values
            == np.array([P.PAPER_IMPULSIVE_DV_MPS[n - 1] for n in b1.loi])).all()


def test_burn_duration_totals_are_table_b1_sums():
    # the text's totals (41.02, 19.69, 14.40 min) add up Table B1's durations
    for t, name in ((150, "burn_total_150N_min"), (300, "burn_total_300N_min"),
                    (450, "burn_total_450N_min")):
        total = sum(P.paper_best(t, n)["burn_duration_min"] for n in (1, 2, 3))
        assert P.quote(name).value == pytest.approx(total, abs=1e-9)


def test_start_offsets_agree_with_scenario_module():
    from lunarcap.paper.printed import PAPER_BEST_STARTS_MIN, PAPER_STARTS_MIN

    for (t, n) in CASES:
        assert sorted(P.paper_table(t, n).start_min.astype(float)) == sorted(
            PAPER_STARTS_MIN[(float(t), n)])
        assert float(P.paper_best(t, n)["start_min"]) == PAPER_BEST_STARTS_MIN[float(t)][n - 1]


def test_constants_module_agrees_with_quotes():
    q = P.quote
    assert q("mu_moon_km3s2").value == C.MU_MOON
    assert q("mu_earth_km3s2").value == C.MU_EARTH
    assert q("mu_sun_km3s2").value == C.MU_SUN_AS_PRINTED
    assert q("r_moon_km").value == C.R_MOON
    assert q("j2_moon").value == pytest.approx(C.J2_MOON, rel=1e-15)
    assert q("arrival_mass_kg").value == paper_scenario().mass_kg
    periods = (q("period_capture1_h").value * 3600, q("period_capture2_h").value * 3600,
               q("period_final_min").value * 60)
    assert periods == pytest.approx(paper_scenario().capture_periods_s, rel=1e-15)
    # the packaged plans' engines (what runs) are the ones the paper prints (Sec. 3.1)
    printed = tuple((q(f"engine{k}_thrust_N").value, q(f"engine{k}_isp_s").value)
                    for k in (1, 2, 3))
    assert printed == tuple(paper_engines().items())
    assert {float(t): i for t, i in P.PAPER_ENGINES.items()} == paper_engines()


def test_quote_parsing():
    q = P.quote("mu_sun_km3s2")
    assert q.value == 13271244207.6 and q.resolution == pytest.approx(0.1)
    assert P.quote("mass_after_loi1_150N_kg").resolution == pytest.approx(0.001)
    assert P.quote("mass_after_loi1_150N_kg").decimals == 3
    assert P.quote("j2_moon").value == pytest.approx(2.027e-4)
    assert P.quote("j2_moon").resolution == pytest.approx(1e-7)
    assert P.quote("fuel_saving_300N_vs_150N_kg").resolution == 1.0
    assert P.quote("loss_loi3_300N_mps").decimals == 3


def test_quotes_named_in_the_brief():
    expect = {
        "arrival_mass_kg": 524.895, "mass_after_loi1_150N_kg": 434.471,
        "mass_after_loi2_150N_kg": 381.005, "mass_final_150N_kg": 335.750,
        "mass_final_300N_kg": 369.289, "mass_final_450N_kg": 391.722,
        "kick_motor_dry_mass_kg": 315.422, "fuel_finite_150N_kg": 185.010,
        "fuel_impulsive_150N_kg": 189.145, "fuel_difference_150N_percent": 2.24,
        "fuel_impulsive_300N_kg": 154.146, "fuel_finite_300N_kg": 155.606,
        "fuel_impulsive_450N_kg": 132.028, "fuel_finite_450N_kg": 133.192,
        "loss_total_150N_mps": 20.20, "loss_total_150N_percent": 2.12,
        "loss_total_300N_mps": 5.11, "loss_loi3_300N_mps": 1.152,
        "loss_total_300N_percent": 0.55, "loss_total_450N_mps": 3.17,
        "loss_total_450N_percent": 0.33, "burn_total_150N_min": 41.02,
        "burn_total_300N_min": 19.69, "burn_total_450N_min": 14.40,
        "eq19_loi1_150N_min": 18.82, "eq19_loi2_150N_min": 11.50, "eq19_loi3_150N_min": 9.76,
        "eq19_half_loi1_300N_min": 4.21, "eq19_half_loi2_300N_min": 3.04,
        "eq19_half_loi3_300N_min": 2.65, "loss_loi1_150N_mps": 14.14,
        "loss_loi1_150N_percent": 3.93, "fig4_alpha_start_deg": 137.5,
        "fig4_alpha_end_deg": 215.3, "fig4_mass_start_kg": 524.9, "fig4_mass_end_kg": 335.8,
        "period_final_about_min": 118, "lro_thrust_N": 320, "lro_isp_s": 200,
        "selene_thrust_N": 500, "selene_isp_s": 300, "mu_earth_km3s2": 398600.441,
    }
    for name, v in expect.items():
        assert P.quote(name).value == v, name


def test_every_quote_is_documented_and_contains_its_number():
    df = P.quotes_table()
    assert df.name.is_unique and len(df) == len(P.QUOTES)
    for q in P.QUOTES.values():
        assert q.printed in q.text, q.name
        assert q.where.startswith(("Sec.", "Abstract", "Table", "Fig.")), q.name
        assert q.unit in {"kg", "m/s", "min", "h", "%", "km", "km³/s²", "N", "s", "deg", "t",
                          ""}, q.name


def test_every_number_occurs_in_the_paper(flat_text):
    for q in P.QUOTES.values():
        assert q.printed in flat_text, q.name
    for case in CASES:
        for r in P.paper_table(*case).itertuples():
            pat = f"{r.burn_duration_min:.2f} {r.delta_v_mps:.3f} {r.diff_percent:.2f}"
            assert pat + ("a" if r.best else " ") in flat_text + " ", (case, pat)
    for r in P.paper_table_b1().itertuples():
        assert (f"{r.start_min} {r.burn_duration_min:.2f} {r.delta_v_mps:.3f} "
                f"{r.diff_percent:.2f}") in flat_text
    for e in P.PAPER_EPOCHS_TDB.values():
        assert e.replace(" (TDB)", "") in flat_text


@pytest.mark.parametrize("bad", [(200, 1), (150, 4), (150, 0), ("x", 1), (150.5, 1)])
def test_bad_case_raises_input_error(bad):
    with pytest.raises(InputError):
        P.paper_table(*bad)
    with pytest.raises(InputError):
        P.paper_best(*bad)


def test_unknown_quote_raises_input_error():
    with pytest.raises(InputError):
        P.quote("no_such_number")


def test_tables_are_fresh_copies():
    df = P.paper_table(150, 1)
    df.loc[0, "delta_v_mps"] = -1.0
    assert P.paper_table(150, 1).loc[0, "delta_v_mps"] == 413.496
    assert isinstance(P.paper_table_b1(), pd.DataFrame)


def test_paper_start_tables_are_consistent():
    # every best start of Table B1 is one of the starts tried in Tables 1-5
    for thrust, best in P.PAPER_BEST_STARTS_MIN.items():
        for loi, start in enumerate(best, 1):
            assert start in P.PAPER_STARTS_MIN[(thrust, loi)]
