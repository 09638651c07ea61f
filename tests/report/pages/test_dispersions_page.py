"""The dispersions page's sensitivity table: every cell a number or a reason, never nan."""

import math

from lunarcap.report.pages.dispersions import sensitivity_table


def _rows(means):
    return [{"engine": "450 N", "source": "thrust_sigma_pct", "sigma": s, "unit": "%",
             "mean_above_nominal_mps": y, "max_above_nominal_mps": 2.0 * s}
            for s, y in zip((0.5, 1.0, 2.0), means)]


def test_a_law_without_a_power_says_why():
    # a mean that goes negative (the 450 N thrust error of the full build) has no power law
    t = sensitivity_table(_rows((-0.01, -0.02, 0.03)))
    assert t.mean_exponent[0].startswith("none (a value <= 0")
    assert t.max_exponent[0] == "1.00"      # the costliest sample: linear in sigma
    for v in t.iloc[0]:
        assert not (isinstance(v, float) and math.isnan(v))


def test_a_quadratic_law_reads_two():
    t = sensitivity_table(_rows((0.25, 1.0, 4.0)))
    assert t.mean_exponent[0] == "2.00"


def test_sensitivities_of_a_subset_of_plans_are_those_of_the_whole(tmp_path):
    """``sensitivity_plans`` runs the sensitivities of those plans only (one figure each),
    and a plan's sensitivity rows do not depend on which other plans run beside it (the
    same seed gives the same draws per plan); a name outside ``plans`` is refused."""
    import pytest

    from lunarcap.report.pages import dispersions
    from lunarcap.repro import paths

    plans = ["song2011-150N", "song2011-300N"]
    kw = dict(samples=2, seed=7, dynamics="two-body", workers=1, quick=True,
              sensitivity_samples=2)
    with paths.using_book(tmp_path / "book"):
        some = dispersions.build(plans, output_name="t_disp_some", **kw,
                                 sensitivity_plans=["song2011-300N"])
        every = dispersions.build(plans, output_name="t_disp_every", **kw)
        with pytest.raises(ValueError, match="sensitivity_plans"):
            dispersions.build(plans, output_name="t_disp_bad", **kw,
                              sensitivity_plans=["song2011-450N"])
    figs = sorted(k for k in some.items if k.startswith("sensitivity_") and k[-1] == "N")
    assert figs == ["sensitivity_300N"]
    assert sorted(k for k in every.items if k.startswith("sensitivity_") and k[-1] == "N") \
        == ["sensitivity_150N", "sensitivity_300N"]
    mine = [r for r in every.data["sensitivity"] if r["engine"].startswith("300 N")]
    assert len(mine) == len(some.data["sensitivity"]) > 0
    for a, b in zip(mine, some.data["sensitivity"]):
        assert a["source"] == b["source"] and a["sigma"] == b["sigma"]
        assert a["mean_above_nominal_mps"] == b["mean_above_nominal_mps"]
