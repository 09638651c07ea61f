"""The book's wide figures are drawn to be read at 1280 px: narrow enough to be shown at
about their natural size, no text below MIN_FONT_PT, and curves that differ by more than
colour. Synthetic data: what is checked is the layout, not the numbers."""

import matplotlib
import numpy as np
import pandas as pd
import pytest

from lunarcap.report import figures as F
from lunarcap.report.figures import (
    burn_count,
    free_ignition,
    other_engines,
    steering_laws,
    summary,
    trade_study,
)

matplotlib.use("Agg")

PARTS = {"loi1": "LOI 1", "loi2": "LOI 2", "loi3": "LOI 3", "sequence": "sequence"}
ISP = [200.0, 250.0, 300.0]
N_PER_RATIO = 524.895 * 9.80665


def _trade_rows(parts):
    tw = np.geomspace(0.01, 0.4, 5)
    return pd.DataFrame([dict(part=p, isp_s=i, thrust_to_weight=t, thrust_N=t * N_PER_RATIO,
                              objective_loss_percent=1 / t / 10, analytic_loss_percent=1 / t / 10,
                              paper_delta_v_loss_percent=1 / t / 10,
                              burn_duration_min=30 * (0.01 / t),
                              start_min=-15 * (0.01 / t), eq19_duration_min=28 * (0.01 / t))
                         for p in parts for i in ISP for t in tw])


def _figures():
    ok = _trade_rows(PARTS)
    paper = ok.groupby(["part", "isp_s"]).head(1)
    yield "trade loss", trade_study.plot_trade_study_loss(ok, ok, paper, ISP, PARTS, N_PER_RATIO)
    three = {k: v for k, v in PARTS.items() if k != "sequence"}
    yield "trade duration", trade_study.plot_trade_study_duration(_trade_rows(three), ISP, three,
                                                        N_PER_RATIO)
    chain = pd.DataFrame(dict(loi=[1, 2, 3], paper_delta_v_mps=[370.0, 250.0, 280.0],
                              paper_impulsive_delta_v_mps=[353.0, 245.0, 275.0],
                              loss_vs_paper_impulse_mps=[15.0, 4.0, 3.0], delta_v_loss_mps=[14.0,
                                                                                            4.5,
                                                                                            2.5]))
    yield "summary loss", summary.plot_summary_loss({f"{t} N": chain for t in (150, 300, 450)})
    rule = pd.DataFrame([dict(engine=f"{t} N", burn=b, rule_start_min=-10.0 / b,
                              free_start_min=-11.0 / b, grid_start_min=-10.0 / b,
                              eq19_duration_min=20.0 / b, start_minus_rule_min=-1.0 / b)
                         for t in (150, 300, 450) for b in (1, 2, 3)])
    yield "free ignition", free_ignition.plot_free_ignition_rule(rule)
    steer = pd.DataFrame([dict(engine=f"{t} N", loi=n, steering=law, delta_v_penalty_mps=1.0,
                               objective_penalty_mps=0.5, rp_miss_km=2.0)
                          for t in (150, 300, 450) for n in (1, 2, 3)
                          for law in ("inertial", "antivelocity")])
    yield "steering", steering_laws.plot_steering_penalty(steer, ["150 N", "300 N", "450 N"])
    totals = pd.DataFrame(dict(thrust_N=[150.0, 300.0, 450.0, 320.0, 500.0],
                               isp_s=[200.0, 250.0, 300.0, 200.0, 300.0],
                               origin=["paper's engine"] * 3 + ["LRO-class", "SELENE-class"],
                               total_fuel_kg=[190.0, 155.0, 133.0, 186.0, 130.0],
                               delta_v_loss_mps=[20.0, 5.0, 2.0, 4.6, 1.5]))
    yield "engine loss", other_engines.plot_engine_loss(totals, "delta_v_loss_mps",
                                                        "total ΔV loss (m/s)")
    counts = pd.DataFrame([dict(label=lab, n_burns=n, status="ok" if n > 1 else "infeasible",
                                total_delta_v_loss_mps=100.0 / n, time_to_final_orbit_h=5.0 * n)
                           for lab in ("song2011-150N", "song2011-300N", "lro-like-5burn")
                           for n in (1, 2, 3, 4, 5)])
    yield "burn count", burn_count.plot_burn_count(counts)


FIGURES = list(_figures())


@pytest.mark.parametrize("name,fig", FIGURES, ids=[n for n, _ in FIGURES])
def test_wide_figures_fit_the_column_and_no_text_is_small(name, fig):
    width_in = fig.get_size_inches()[0]
    assert width_in <= F.FIG_WIDTH_IN + 1e-9, f"{name}: {width_in} in wide"
    fig.canvas.draw()
    texts = [t for t in fig.findobj(matplotlib.text.Text)
             if t.get_visible() and t.get_text().strip()]
    small = sorted({(t.get_fontsize(), t.get_text()[:30]) for t in texts
                    if t.get_fontsize() < F.MIN_FONT_PT})
    assert texts and not small, f"{name}: text below {F.MIN_FONT_PT} pt: {small[:5]}"


def test_trade_study_curves_differ_by_marker_as_well_as_colour():
    fig = dict(FIGURES)["trade loss"]
    lines = [ln for ln in fig.axes[0].get_lines() if ln.get_label().startswith("optimal")]
    assert len(lines) == len(ISP)
    assert len({ln.get_marker() for ln in lines}) == len(ISP)
    robbins = [ln for ln in fig.axes[0].get_lines() if ln.get_label().startswith("Robbins")]
    assert all(ln.get_linestyle() != "-" for ln in robbins)


@pytest.mark.parametrize("name,fig", FIGURES, ids=[n for n, _ in FIGURES])
def test_every_legend_reads_as_large_as_the_axes(name, fig):
    # figstyle.save_figure refuses a figure with any of these problems (the book build
    # would fail on it): legend text below the axis labels, or any text below 9 pt
    assert F.legibility_problems(fig) == [], name
