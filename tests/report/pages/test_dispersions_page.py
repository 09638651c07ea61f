"""The dispersions page: its sensitivity table and figure, and a small build.

* Every cell of the laws' table is a number or a reason, never nan; an exponent carries
  its standard error.
* The sensitivity figure on its log axes: every error bar stays inside the axes (a bar
  reaching zero would be drawn as a line through the whole axis), the legend covers no
  curve (it sits below the axes), the ticks read as plain numbers (0.5, 1, 2; 0.1, 1).
* ``sensitivity_plans`` runs the sensitivities of those plans only, with the same
  numbers as when every plan runs.
"""

import math

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figures.dispersions import plot_sensitivity
from lunarcap.report.pages.dispersions import SOURCE_LABELS, sensitivity_table


def _rows(means, ses=None, source="thrust_sigma_pct", engine="450 N"):
    ses = ses or [0.0] * len(means)
    return [{"engine": engine, "source": source, "sigma": f * 1.0, "factor": f,
             "example": 1.0, "unit": "%", "mean_above_nominal_mps": y,
             "mean_above_nominal_se_mps": se, "resolved": abs(y) >= 0.01,
             "max_above_nominal_mps": 2.0 * f}
            for f, y, se in zip((0.5, 1.0, 2.0), means, ses)]


def _law(status="fitted", exponent=1.0, se=0.04, reason="fitted over 3 sigmas"):
    return {"engine": "450 N", "source": "thrust_sigma_pct", "status": status,
            "exponent": exponent if status == "fitted" else math.nan,
            "exponent_se": se if status == "fitted" else math.nan, "draws": 10,
            "draws_needed": 7 if status == "fitted" else None, "reason": reason}


def test_a_law_without_a_power_says_why():
    t = sensitivity_table(_rows((-0.01, -0.02, 0.03)), [_law(
        "no power law", reason="the mean lies below the nominal beyond the gate's 0.01 m/s")])
    assert t.exponent_text[0].startswith("no power law: the mean lies below")
    for v in t.drop(columns=["exponent", "exponent_se", "draws_needed"]).iloc[0]:
        assert not (isinstance(v, float) and math.isnan(v))


def test_an_exponent_carries_its_standard_error_and_the_mean_at_the_example_sigma():
    t = sensitivity_table(_rows((0.25, 1.0, 4.0), [0.01, 0.04, 0.16]),
                          [_law(exponent=2.0, se=0.03)])
    assert t.exponent_text[0] == "2.00 ± 0.03"
    assert t.mean_text[0] == "1.000 ± 0.040" and t.sigma[0] == "1 %"


def test_an_unresolved_source_is_said_to_be_so():
    t = sensitivity_table(_rows((0.001, 0.002, 0.004)), [_law(
        "unresolved", reason="the mean above the nominal reaches the re-propagation gate's "
                             "0.01 m/s at 0 of 3 sigmas")])
    assert t.exponent_text[0].startswith("unresolved: ")
    assert t.mean_text[0].startswith("unresolved")


def _figure(means, ses):
    rows = _rows(means, ses) + _rows([0.02, 0.08, 0.3], [0.015, 0.05, 0.2],
                                     source="pointing_sigma_deg")
    return plot_sensitivity(rows, "450 N", SOURCE_LABELS)


def test_the_sensitivity_figure_keeps_its_error_bars_legend_and_ticks_readable():
    # a standard error larger than its mean (the old bar reached 0 on the log axis)
    fig = _figure([0.05, 0.2, 0.9], [0.08, 0.1, 0.3])
    ax = fig.axes[0]
    fig.canvas.draw()
    lo, hi = ax.get_ylim()
    for coll in ax.collections:   # the error bars' vertical segments
        for seg in coll.get_segments():
            ys = np.asarray(seg)[:, 1]
            assert ys.min() > lo and ys.max() < hi, (ys, lo, hi)
    legend = ax.get_legend().get_window_extent()
    assert legend.y1 <= ax.get_window_extent().y0   # below the axes: it covers no curve
    labels = [t.get_text() for t in ax.get_xticklabels() + ax.get_yticklabels()
              if t.get_text()]
    assert {"0.5", "1", "2"} <= set(labels)
    assert not any("10^" in s or "$" in s or "×" in s for s in labels), labels
    plt.close(fig)


def test_sensitivities_of_a_subset_of_plans_are_those_of_the_whole(tmp_path):
    """``sensitivity_plans`` runs the sensitivities of those plans only (one figure each),
    and a plan's sensitivity rows do not depend on which other plans run beside it (the
    same seed gives the same draws per plan); a name outside ``plans`` is refused."""
    import pytest

    from lunarcap.report.pages import dispersions
    from lunarcap.repro import paths

    plans = ["song2011-150N", "song2011-300N"]
    kw = dict(plans=plans, samples=2, seed=7, sigmas=dispersions.DEFAULT_SIGMAS,
              dynamics="two-body", workers=1, sensitivity_samples=2,
              sensitivity_factors=[1.0, 2.0])

    def page(output_name, sensitivity_plans=None):
        """The page as the notebook builds it, with the public API's runs."""
        import lunarcap

        caps = [lunarcap.load_plan(n, dynamics="two-body") for n in plans]
        opts = dict(seed=7, workers=1, **dispersions.DEFAULT_SIGMAS,
                    out=dispersions.table_file(output_name))
        chosen = plans if sensitivity_plans is None else sensitivity_plans
        budgets = [lunarcap.dispersions(c, samples=2, **opts) for c in caps]
        sens = [lunarcap.dispersions(c, samples=2, sensitivity=True, factors=[1.0, 2.0],
                                     antithetic=True, **opts)
                for n, c in zip(plans, caps) if n in chosen]
        return dispersions.build(budgets, sens, output_name, True,
                                 dict(kw, sensitivity_plans=sensitivity_plans))

    with paths.using_book(tmp_path / "book"):
        some = page("t_disp_some", ["song2011-300N"])
        every = page("t_disp_every")
        with pytest.raises(ValueError, match="sensitivity_plans"):
            dispersions.build([], [], "t_disp_bad", True,
                              dict(kw, sensitivity_plans=["song2011-450N"]))
    figs = sorted(k for k in some.items if k.startswith("sensitivity_") and k[-1] == "N")
    assert figs == ["sensitivity_300N"]
    assert sorted(k for k in every.items if k.startswith("sensitivity_") and k[-1] == "N") \
        == ["sensitivity_150N", "sensitivity_300N"]
    mine = [r for r in every.data["sensitivity"] if r["engine"].startswith("300 N")]
    assert len(mine) == len(some.data["sensitivity"]) > 0
    for a, b in zip(mine, some.data["sensitivity"]):
        assert a["source"] == b["source"] and a["sigma"] == b["sigma"]
        assert a["mean_above_nominal_mps"] == b["mean_above_nominal_mps"]
    # the page's checks hold at this size: the trim is in every total, within the gate
    assert all(ok for _, ok, _ in every.checks), every.checks
    assert set(every.items) >= {"budget", "trim", "cdf", "trim_orbit", "failures",
                                "sensitivity"}
