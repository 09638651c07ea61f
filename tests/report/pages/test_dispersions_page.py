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
