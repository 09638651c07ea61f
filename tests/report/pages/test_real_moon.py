"""The "real Moon" page: its small functions, and the page built on a small case.

* frames_distance: DE405's principal axes against the IAU (2009) frame over 2017 are
  85-115 arcsec apart (the physics tests measure 92-109"), and the distance at 100 km is
  the chord of that angle at 1838.2 km.
* redesign_table: the totals are the sums, a burn without a limit leaves the total's limit
  undefined (never 0), its reason is kept.
* histories / evolution_table: days from the cut-off, extremes from the Evolution's own
  arrays; end_distance_km is the distance of the end positions.
* build: the J2 design flown in its own model misses by < 1 m, in LP165P 2x2 by
  kilometres; a page without a re-design says why for every number it lacks.
"""

from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from lunarcap.physics import constants as C
from lunarcap.physics.elements import rv_from_mee
from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.physics.evolution import Evolution
from lunarcap.physics.propagate import Trajectory
from lunarcap.report.page import is_missing
from lunarcap.report.pages import real_moon
from lunarcap.repro import paths


def test_frames_distance_is_the_chord_of_about_100_arcsec():
    t0 = seconds_from_calendar("2017-01-01 00:00:00 TDB")
    d = real_moon.frames_distance(t0, t0 + 365 * 86400.0, n=40)
    assert 85.0 < d["min_arcsec"] < d["max_arcsec"] < 115.0
    for a, km in ((d["min_arcsec"], d["min_km"]), (d["max_arcsec"], d["max_km"])):
        assert km == pytest.approx(np.radians(a / 3600) * (C.R_MOON + 100.0), rel=1e-6)


def _result(rows):
    return SimpleNamespace(table=lambda: pd.DataFrame(rows))


def test_redesign_table_sums_and_keeps_the_reason():
    design = _result([{"delta_v_mps": 366.0, "delta_v_loss_mps": 13.5},
                      {"delta_v_mps": 248.0, "delta_v_loss_mps": 2.8}])
    why = "no impulsive limit in LP165P 20x20: the circle ... lies 218 m below"
    field = _result([{"delta_v_mps": 365.9, "impulsive_limit_mps": 353.0,
                      "delta_v_loss_mps": 12.9},
                     {"delta_v_mps": 247.8, "impulsive_limit_mps": None,
                      "delta_v_loss_mps": None, "impulsive_limit_reason": why}])
    df = real_moon.redesign_table(design, field)
    assert list(df.burn) == ["1", "2", "total"]
    tot = df.iloc[-1]
    assert tot.design_delta_v_mps == pytest.approx(614.0)
    assert tot.redesign_delta_v_mps == pytest.approx(613.7)
    assert tot.delta_v_change_mps == pytest.approx(-0.3)
    assert np.isnan(tot.redesign_impulsive_limit_mps) and np.isnan(tot.redesign_delta_v_loss_mps)
    assert list(df.no_limit_reason) == ["", why, ""]


def _evolution(t0, rp, ra, inc, r_end):
    n = len(rp)
    x = np.array([r_end, 0, 0, 0.1, 0.2, 0.3, 500.0])
    return Evolution(t0, 1.0, "test", t0 + 7000.0 * np.arange(n), np.array(rp), np.array(ra),
                     np.array(inc), x, Trajectory(np.array([t0]), x[:, None]))


def test_histories_and_evolution_table():
    evs = {"J2": _evolution(100.0, [100.0, 99.0], [101.0, 102.0], [90.0, 90.5], 1838.2),
           "field": _evolution(100.0, [98.0, 95.0], [103.0, 104.0], [90.0, 91.0], 1839.2)}
    h = real_moon.histories(evs)
    np.testing.assert_allclose(h["J2"]["days"], [0.0, 7000.0 / 86400.0], atol=1e-12)
    t = real_moon.evolution_table(evs).set_index("model")
    assert t.loc["field", "after_min_perilune_altitude_km"] == 95.0
    assert t.loc["field", "after_max_apolune_altitude_km"] == 104.0
    assert t.loc["field", "after_inclination_change_deg"] == pytest.approx(1.0)
    a, b = (np.array(rv_from_mee(*ev.final_state[:6], C.MU_MOON)[0]) for ev in evs.values())
    assert real_moon.end_distance_km(evs["J2"], evs["field"]) == pytest.approx(
        np.linalg.norm(a - b))
    assert real_moon.end_distance_km(evs["J2"], evs["field"]) == pytest.approx(1.0)


def _computed(degrees, evolve_degrees, compare, days):
    """What the notebook computes with the public API, for a small case (no re-design)."""
    import lunarcap

    design = lunarcap.solve("song2011-150N", impulsive=False)
    holds = ["rtn", "inertial"]
    model = lambda d: None if d is None else real_moon.field(d)   # noqa: E731
    arrival = {(d, h): design.fly_open_loop(model(d), h, 60.0)
               for d in [None, *degrees] for h in holds}
    ignition = {h: design.fly_open_loop(model(compare), h) for h in holds}
    afters = {d: design.fly_final_orbit(days, model(d), rtol=real_moon.EVOLUTION_RTOL)
              for d in [None, *evolve_degrees]}
    return design, afters, arrival, ignition


@pytest.mark.slow
def test_page_on_a_small_case(tmp_path):
    design, afters, arrival, ignition = _computed(["2x0", 2], [2], 2, 0.25)
    with paths.using_book(tmp_path):
        page = real_moon.build(design, None, afters, arrival, ignition, compare_degree=2,
                               quick=True, output_name="real_moon_test")
    assert page.parameters["degrees"] == ["2x0", 2] and page.parameters["after_days"] == 0.25
    assert page.parameters["design_degree"] is None and page.parameters["evolve_degrees"] == [2]
    miss = page.items["miss"].df
    own = miss[miss.model == "J2 (the design's)"].set_index("hold").open_loop_miss_km
    assert own["RTN"] < 1e-3 and own["inertial"] < 0.01
    assert (miss[miss.model == "LP165P 2x2"].open_loop_miss_km > 1.0).all()
    # C20 alone about the body's pole is a field of its own: the design's J2 moved to the
    # pole of the field's frame misses too, by another distance than the whole degree 2
    inertial = miss[miss.hold == "inertial"].set_index("model").open_loop_miss_km
    assert inertial["LP165P 2x0"] > 10 * own["inertial"]
    assert abs(inertial["LP165P 2x0"] - inertial["LP165P 2x2"]) > 0.1
    assert page.values["share_2x2_percent"] == pytest.approx(100.0)
    assert page.values["share_2x0_percent"] == pytest.approx(
        100.0 * inertial["LP165P 2x0"] / inertial["LP165P 2x2"])
    assert "LP165P 2x0" in page.notes["degree2_text"]
    # the open loop from the first ignition misses less than from the arrival
    opens = page.items["opens"].df.set_index(["start", "hold"]).open_loop_miss_km
    assert opens[("first ignition", "RTN")] < opens[("arrival", "RTN")]
    # without a re-design every number it would give says why
    for k in ("redesign_total_mps", "redesign_change_mps", "redesign_model"):
        assert is_missing(page.values[k]) and "quick" in page.values[k]
    assert "not designed again" in page.notes["no_limit_text"]
    assert "no field deeper than LP165P 2x2" in page.notes["deeper"]
    shown = page.items["redesign"].df
    assert (shown.limit_shown == "not run in the quick book").all()
    assert "not run in the quick book" in page.notes["headline"]
    page.check()
    # what build is handed is checked before anything is set out
    with pytest.raises(ValueError, match="compared field"):
        real_moon.build(design, None, afters, arrival, ignition, compare_degree=8)
    with pytest.raises(ValueError, match="afters"):
        real_moon.build(design, None, {2: afters[2]}, arrival, ignition, compare_degree=2)
    with pytest.raises(ValueError, match="redesign"):   # the design itself, not in a field
        real_moon.build(design, design, afters, arrival, ignition, compare_degree=2)


def test_fields_are_named_by_degree_or_degree_and_order():
    assert real_moon.degree_order(20) == (20, 20)
    assert real_moon.degree_order("2x0") == (2, 0)
    assert real_moon.field("2x0")["order"] == 0 and real_moon.field(8)["order"] == 8
    assert real_moon.model_name(real_moon.field("2x0")) == "LP165P 2x0"
    for bad in ("2x3", "x2", "twenty", 1, True, 2.5):
        with pytest.raises(ValueError, match="degree"):
            real_moon.degree_order(bad)
    assert real_moon._degrees(["2x0", 2, 50]) == "2x0, 2x2 and 50x50"


def _shares(m2x0, m2x2, compare="LP165P 20x20"):
    from lunarcap.report.page import Page

    page = Page("nb", {}, "x")
    miss = pd.Series({"LP165P 2x0": m2x0, "LP165P 2x2": m2x2, compare: 40.0})
    return page, real_moon.degree2_text(page, miss, compare)


def test_the_degree_2_sentence_says_what_the_shares_show():
    """The page once asserted "the degree-2 terms, the C22 ellipticity above all" without a
    row to show it; the sentence is now computed from C20 alone (2x0) and the whole
    degree 2 (2x2), whichever way they fall."""
    page, text = _shares(4.0, 30.0)          # 10 % from C20, 75 % with C22
    assert page.values["share_2x0_percent"] == pytest.approx(10.0)
    assert page.values["share_2x2_percent"] == pytest.approx(75.0)
    assert "comes with C22" in text and "10.0 %" in text and "75 %" in text
    _, text = _shares(24.0, 30.0)            # 60 % from C20 alone
    assert "is C20's alone" in text
    from lunarcap.report.page import Page

    page = Page("nb", {}, "x", quick=True)   # 2x0 not flown: said so, not a number
    text = real_moon.degree2_text(page, pd.Series({"LP165P 2x2": 3.0, "LP165P 20x20": 6.0}),
                                  "LP165P 20x20")
    assert is_missing(page.values["share_2x0_percent"]) and "50 %" in text


def test_no_limit_text_says_why_with_the_gap():
    from lunarcap.report.page import Page

    why = "no impulsive limit in LP165P 20x20: the circle asked ... lies 218 m below"
    burns = [SimpleNamespace(impulsive={"reason": None, "delta_v_mps": 353.0}),
             SimpleNamespace(impulsive={"reason": why, "circle_gap_m": 217.98})]
    page = Page("nb", {}, "x")
    text = real_moon.no_limit_text(page, SimpleNamespace(burns=burns))
    assert text.startswith("Burn 2 has no impulsive limit") and text.endswith(f"> {why}")
    assert "218 m below that perilune" in text and page.values["circle_gap_m"] == 217.98
    all_in_reach = SimpleNamespace(burns=burns[:1])
    assert "Every burn" in real_moon.no_limit_text(Page("nb", {}, "x"), all_in_reach)


def _losses(field_losses):
    return pd.DataFrame({"burn": ["1", "2", "3", "total"],
                         "design_delta_v_loss_mps": [13.549, 4.016, 2.784, 20.349],
                         "redesign_delta_v_loss_mps": list(field_losses) + [np.nan]})


def test_loss_text_pairs_only_burns_with_a_loss_and_says_why_without():
    from lunarcap.report.page import Page

    page = Page("nb", {}, "x")
    text = real_moon.loss_text(page, _losses([13.59, 4.188, np.nan]), True, "")
    assert "burn 1: 13.590 m/s (13.549 in J2); burn 2: 4.188 m/s (4.016 in J2)." in text
    assert "burn 3" not in text
    none = real_moon.loss_text(page, _losses([np.nan] * 3), False, real_moon.NO_LIMITS_REASON)
    assert real_moon.NO_LIMITS_REASON in none and "13.549, 4.016, 2.784 m/s" in none
    quick = _losses([np.nan] * 3).assign(design_delta_v_loss_mps=np.nan)   # no limits in J2 either
    assert "nan" not in real_moon.loss_text(page, quick, False, "not run in the quick book")


def test_scope_text_names_what_the_run_left_out_and_how_to_add_it():
    from lunarcap.report.page import Page

    book = real_moon.scope_text(Page("nb", {}, "x"), [2, 8, 20], [2, 8, 20], 20, False, 7.0)
    assert "degrees: [2x0, 2, 8, 20, 50]" in book
    assert "LP165P 2x2, 8x8 and 20x20, follows its final orbit 7 days in J2 and" in book
    assert "without that design's impulsive limits" in book
    assert "evolve_degrees: [2, 8, 20, 50]" in book and "-p redesign_limits true" in book
    full = real_moon.scope_text(Page("nb", {}, "x"), [2, 8, 20, 50], [2, 50], 20, True, 7.0)
    assert "left out" not in full and "without" not in full
    quick = real_moon.scope_text(Page("nb", {}, "x", quick=True), [2], [], None, False, 1.0)
    assert "quick book" in quick and "does not design it again" in quick
    assert "redesign_limits" not in quick   # no re-design: no limits to add


def test_redesign_without_limits_says_why(monkeypatch):
    """A re-design solved without its limits (the notebook's impulsive=False): the limit
    columns are left out and say why."""
    from lunarcap.report.page import Page

    rows = [{"delta_v_mps": 366.0, "delta_v_loss_mps": 13.5, "impulsive_limit_mps": 352.5},
            {"delta_v_mps": 248.0, "delta_v_loss_mps": 2.8, "impulsive_limit_mps": 245.2}]
    design = SimpleNamespace(plan=None, burns=_result(rows))
    field = SimpleNamespace(
        table=lambda: pd.DataFrame([{"delta_v_mps": 365.9, "delta_v_loss_mps": None,
                                     "impulsive_limit_mps": None},
                                    {"delta_v_mps": 247.8, "delta_v_loss_mps": None,
                                     "impulsive_limit_mps": None}]),
        totals=lambda: {"all_verified": True},
        plan=SimpleNamespace(dynamics=real_moon.field(20)))
    redesign = SimpleNamespace(plan=field.plan, burns=field)
    # the captures' burns stand for their chains (PlanResult: table, totals)
    monkeypatch.setattr(real_moon, "PlanResult", lambda plan, burns: burns)
    page = Page("nb", {}, "x")
    real_moon._redesign(page, design, redesign, 20, limits=False)
    df = page.items["redesign"].df
    assert (df.limit_shown == real_moon.NO_LIMITS_REASON).all()
    assert (df.loss_shown == real_moon.NO_LIMITS_REASON).all()
    shown = page.items["redesign"]   # the empty columns are left out, the caption says why
    assert "limit_shown" not in shown.show_columns and "loss_shown" not in shown.show_columns
    assert real_moon.NO_LIMITS_REASON in shown.caption
    assert page.values["redesign_total_mps"] == pytest.approx(613.7)
    assert real_moon.NO_LIMITS_REASON in page.values["redesign_loss_1_mps"]
    assert real_moon.NO_LIMITS_REASON in page.notes["loss_text"]


def test_revolution_days_are_even_where_the_perilune_crosses_a_turn():
    """Perilunes 0.3 of a period later each turn wrap round to 0.1 minutes after the
    previous one: the curve would step there; the revolutions are drawn evenly at their
    mean period instead (the book's 8x8 curve stepped at day 4.2)."""
    period_s, t0 = 7070.0, 1000.0
    phase = (0.2 + 0.3 * np.arange(12)) % 1.0
    ev = SimpleNamespace(t0_s=t0, perilune_epoch_s=t0 + period_s * (np.arange(12) + phase))
    raw = np.diff(ev.perilune_epoch_s)
    assert raw.min() < 0.35 * period_s     # the step the raw epochs have
    d = real_moon.revolution_days(ev)
    np.testing.assert_allclose(np.diff(d), np.diff(d)[0], rtol=1e-12)
    assert np.diff(d)[0] * C.DAY_S == pytest.approx(period_s, rel=0.05)


def test_evolution_figure_is_legible_with_units():
    import matplotlib.pyplot as plt

    from lunarcap.report import figures
    from lunarcap.report.figures.real_moon import plot_evolution

    evs = {"J2": _evolution(100.0, [100.0, 99.0, 99.5], [101.0, 102.0, 101.5],
                            [90.0, 90.5, 90.6], 1838.2),
           "LP165P 20x20": _evolution(100.0, [98.0, 95.0, 93.0], [103.0, 104.0, 106.0],
                                      [90.0, 91.0, 91.2], 1839.2)}
    fig = plot_evolution(real_moon.histories(evs))
    assert figures.legibility_problems(fig) == []
    labels = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
    assert labels == ["J2", "LP165P 20x20", "perilune", "apolune"]
    assert all("(" in a.get_ylabel() for a in fig.axes) and "(" in fig.axes[-1].get_xlabel()
    plt.close(fig)
