"""The computing parts of the trade-study page, on a hand-made study table."""

import math

import pandas as pd
import pytest

from lunarcap.report.pages import trade_study as ts
from lunarcap.studies.engine_trade import trade as study


def _ok():
    # Robbins' expansion holds below an Eq. (19) duration of 0.5 / omega_s = 9.38 min
    return pd.DataFrame({
        "part": ["LOI1", "LOI1", "sequence", "sequence"],
        "thrust_N": [100.0, 1000.0, 100.0, 1000.0],
        "eq19_duration_min": [40.0, 4.0, float("nan"), float("nan")],
        "burn_duration_min": [44.0, 4.1, float("nan"), float("nan")],
        "start_min": [-30.0, -2.0, float("nan"), float("nan")],
        "objective_loss_mps": [20.0, 0.3, 25.0, 0.4],
        "analytic_loss_mps": [30.0, 0.4, float("nan"), float("nan")],
        "objective_loss_percent": [5.0, 0.08, 3.0, 0.05]})


def test_burn_ratios_robbins_only_where_it_holds():
    ratio, dur, start = ts.burn_ratios(_ok()[lambda d: d.part != "sequence"])
    assert ratio.tolist() == pytest.approx([0.75])            # only the 1000 N burn
    assert dur.tolist() == pytest.approx([1.1, 1.025])
    assert start.tolist() == pytest.approx([-0.75, -0.5])


def test_prose_values_from_the_table():
    spec = study.StudySpec(100.0, 1000.0, 2, (250.0,), "two-body")
    wide = pd.DataFrame({"status": ["ok", "failed"]})
    at_paper = pd.DataFrame({"thrust_N": [300.0, 150.0],
                             "optimal_loss_percent": [2.0, float("nan")],
                             "interpolation_error_pp": [0.08, float("nan")],
                             "paper_delta_v_loss_percent": [2.5, 1.0],
                             "analytic_loss_percent": [1.8, 1.0]})
    v = ts.prose_values(spec, wide, {"wall_s": 12.5, "computed": 3}, _ok(), at_paper)
    assert v["n_failed"] == 1 and v["n_engines"] == 2 and v["n_computed"] == 3
    assert v["seq_loss_high_max_mps"] == pytest.approx(0.4)   # the strongest engine's
    assert v["loss_min_mps"] == pytest.approx(0.3)
    assert v["n_robbins_valid"] == 1
    assert v["paper_diff_max"] == pytest.approx(0.5)
    assert v["robbins_diff_max"] == pytest.approx(0.2)
    assert v["interp_error_max_pp"] == pytest.approx(0.08) and v["n_paper_direct"] == 1
    assert v["dur_ratio_max"] == pytest.approx(1.1)
    assert v["start_ratio_min"] == pytest.approx(0.75)
    empty = ts.prose_values(spec, wide.iloc[:0], {"wall_s": 0.0, "computed": 0},
                            _ok().iloc[:0], at_paper.iloc[:0])
    assert math.isnan(empty["loss_min_mps"]) and empty["n_failed"] == 0


def _figures():
    """The page's two figures, drawn with its titles on the study's analytic curves."""
    import matplotlib

    matplotlib.use("Agg")
    from lunarcap.report.figures import trade_study as draw

    isp = [200.0, 250.0, 300.0]
    theory = study.analytic_curves([50.0, 150.0, 450.0, 2000.0], isp)
    ok = theory.assign(objective_loss_percent=theory.analytic_loss_percent,
                       burn_duration_min=1.1, eq19_duration_min=1.0, start_min=-0.6)
    npr = float(study.thrust_from_weight_ratio(1.0))
    loss = draw.plot_trade_study_loss(ok, theory, study.paper_points(), isp, ts.PART_TITLES,
                                      npr, ts.LOSS_AXIS_PERCENT)
    burns = {p: ts.BURN_TITLES[p] for p in study.PARTS[:3]}
    duration = draw.plot_trade_study_duration(ok[ok.part != "sequence"], isp, burns, npr)
    return loss, duration


def test_the_figures_text_lies_inside_them_and_names_the_papers_engines():
    """At 1280 px a duration panel's title ("LOI 1: hyperbola → 12.235 h: ignition") ran
    past the figure's right edge and the loss figure's star labels of 300 N and 450 N
    overlapped; the titles are short, the stars named in the legend."""
    for fig in _figures():
        fig.canvas.draw()
        r = fig.canvas.get_renderer()
        drawn = fig.get_tightbbox(r)                           # what is drawn, inches
        page = fig.bbox_inches
        assert drawn.x0 >= page.x0 - 0.01 and drawn.x1 <= page.x1 + 0.01, (drawn, page)
        for ax in fig.axes:   # a title wider than its panel overruns its neighbour or the
            title = ax.title  # edge, however the tick labels beside it happen to be sized
            if title.get_text():
                assert title.get_window_extent(r).width <= ax.get_window_extent(r).width, \
                    title.get_text()
    loss, _ = _figures()
    labels = [t.get_text() for lg in loss.legends for t in lg.get_texts()]
    for engine in ("150 N / 200 s", "300 N / 250 s", "450 N / 300 s"):
        assert f"paper, Table B1: {engine}" in labels
    assert not [t for ax in loss.axes for t in ax.texts]     # no label beside a star
