"""The other-engines page (lunarcap.report.pages.other_engines), two-body, one engine."""

import numpy as np
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper.printed import PAPER_IMPULSIVE_DV_MPS
from lunarcap.physics.constants import G0_MPS2
from lunarcap.report.pages import other_engines

pytestmark = pytest.mark.slow

LRO = dict(engines=[[320.0, 200.0]], engine_names=["LRO-class"], paper_engines=[],
           starts=["free"] * 3, dynamics="two-body")


def _page(model_loss: bool, output_name: str):
    """The page as the notebook builds it: each engine's paper plan solved by the public API."""
    import lunarcap

    results = {label: lunarcap.solve(lunarcap.paper_plan(t, i, starts=LRO["starts"],
                                                         dynamics=LRO["dynamics"]),
                                     impulsive=model_loss)
               for t, i, _, label in other_engines.engine_rows(
                   LRO["engines"], LRO["engine_names"], LRO["paper_engines"])}
    return other_engines.build(results, output_name, True, dict(LRO, model_loss=model_loss))


@pytest.fixture(scope="module")
def page():
    return _page(True, "t_other")


def test_burns_obey_the_rocket_equation_and_carry_the_mass(page):
    b = page.items["burns"].df
    m_before = np.r_[paper_scenario().mass_kg, b.m_end_kg.to_numpy()[:-1]]
    np.testing.assert_allclose(m_before - b.fuel_kg, b.m_end_kg)
    np.testing.assert_allclose(b.delta_v_mps, G0_MPS2 * 200.0 * np.log(m_before / b.m_end_kg),
                               rtol=1e-6)
    assert (b.verified == "passed").all()


def test_each_loss_is_measured_against_its_named_reference(page):
    b = page.items["burns"].df
    np.testing.assert_allclose(b.loss_vs_paper_impulse_mps,
                               b.delta_v_mps - np.array(PAPER_IMPULSIVE_DV_MPS))
    np.testing.assert_allclose(b.delta_v_loss_mps, b.delta_v_mps - b.impulsive_limit_mps)
    # (the rows are the solved plan's: test_the_solved_plans_rows_are_the_sweeps_sequence_table
    # holds them to the sweeps' chain of paper cases)
    # "vs ours" is the objective loss: positive; for LOI 3 (a circle) it is the delta-V one
    assert (b.objective_loss_mps > 0).all()
    assert b.objective_loss_mps.iloc[2] == pytest.approx(b.delta_v_loss_mps.iloc[2], abs=1e-6)
    t = page.items["totals"].df.iloc[0]
    # the two losses differ by exactly the difference of the two impulsive totals
    assert t.total_delta_v_loss_mps - t.total_loss_vs_paper_impulse_mps == pytest.approx(
        sum(PAPER_IMPULSIVE_DV_MPS) - t.total_impulsive_limit_mps)
    for key in ("losses", "totals"):
        heads = page.items[key].columns
        name = "loss_vs_paper_impulse_mps" if key == "losses" \
            else "total_loss_vs_paper_impulse_mps"
        assert heads[name].startswith("loss vs paper")
        assert heads["objective_loss_mps" if key == "losses" else "total_objective_loss_mps"] \
            .startswith("loss vs ours")


def _figure_loss(page):
    ax = page.items["loss_figure"].fig.axes[0]
    pts = [ln.get_ydata()[0] for ln in ax.lines if len(ln.get_ydata())]
    assert len(pts) == 1
    return pts[0], ax.get_ylabel()


def test_prose_and_figure_quote_the_same_loss(page):
    t = page.items["totals"].df.iloc[0]
    y, ylabel = _figure_loss(page)
    assert y == page.values["plotted_loss_mps_320N"] == t.total_objective_loss_mps
    assert "our impulsive limits" in ylabel
    assert f"{t.total_objective_loss_mps:.2f} m/s over the capture against our impulsive" \
        in page.notes["placement"]
    # the note gives the loss against the paper's reference too, named as such
    assert (f"{t.total_loss_vs_paper_impulse_mps:.2f} m/s "
            f"({t.total_loss_vs_paper_impulse_percent:.2f} %) against the paper's") \
        in page.notes["loss_note"]
    # plain floats: myst-nb's {glue:text} cannot format numpy scalars (np.float64(...))
    assert all(type(v) in (float, str) for v in page.values.values())  # str: a reason or a name
    page.check()


def test_without_model_loss_the_paper_reference_is_plotted_and_named():
    p = _page(False, "t_other_paper")
    t = p.items["totals"].df.iloc[0]
    y, ylabel = _figure_loss(p)
    assert y == p.values["plotted_loss_mps_320N"] == t.total_loss_vs_paper_impulse_mps
    assert "paper's impulsive" in ylabel
    assert "not computed in this build" in p.notes["loss_note"]
    assert "delta_v_loss_mps" not in p.items["burns"].df
    p.check()


def test_the_solved_plans_rows_are_the_sweeps_sequence_table(page):
    """The page's rows, from lunarcap.solve on the paper's plan, are sequence_table's.

    The page once computed both and checked their losses agreed (1e-9 m/s); it now reads
    only the solved plan (:func:`other_engines.sequence_of`), so this holds it to the
    sweeps' own chain of paper cases, column by column.
    """
    from lunarcap.studies.sweeps import sequence_table

    seq = page.data["sequences"]["LRO-class, 320 N / 200 s"]
    ref = sequence_table(320.0, 200.0, ("free",) * 3, "two-body", with_impulsive_model=True)
    assert list(seq.columns) == list(ref.columns)
    for col in ref.columns:
        np.testing.assert_allclose(seq[col].astype(float), ref[col].astype(float),
                                   rtol=0, atol=1e-9, err_msg=col)
