"""Sensitivities with standard errors over independent draws (issue 36, item 1).

Synthetic tables (no flight): each sample's delta-V is a known function of its draw, so
the law and its standard error are known in closed form.

* A response nominal + c (sigma z)^2 on antithetic pairs: the pair's mean keeps the even
  part (c sigma^2 z^2), so the mean's standard error is c sigma^2 sd(z^2) / sqrt(pairs),
  not the 0 a single pair's spread gives; the exponent is 2 (exactly: every draw scales
  alike under common random numbers, so it has no sampling error).
* A linear response's pair mean is the nominal itself: unresolved, no exponent.
* A response that is no power law (two terms of different order): the delta-method
  standard error of the exponent agrees with the spread of the exponent over independent
  replications.
* No quantile interval on an antithetic table; the draws needed for a stated standard
  error scale as its square.
"""

import math

import numpy as np
import pandas as pd
import pytest

from lunarcap.studies.dispersions import sensitivity as S
from lunarcap.studies.dispersions.model import ErrorModel
from lunarcap.studies.dispersions.summary import summarise

NOMINAL = 870.0
SIGMAS = (0.5, 1.0, 2.0)


def _table(response, pairs: int, seed: int = 0, source="pointing_sigma_deg"):
    """An antithetic sensitivity table: sample 2j draws z_j, 2j + 1 draws -z_j."""
    z = np.random.default_rng(seed).standard_normal((pairs, 2))
    rows, models = [], []
    for sigma in SIGMAS:
        m = ErrorModel().only(source, sigma)
        models.append((source, sigma, m))
        for j in range(pairs):
            for k, sign in enumerate((1.0, -1.0)):
                dv = NOMINAL + response(sigma, sign * z[j])
                rows.append({**m.key(), "plan": "synthetic", "plan_id": "p", "thrust_N": 150.0,
                             "sample": 2 * j + k, "antithetic": True, "status": "ok",
                             "reason": "", "error": "", "total_delta_v_mps": dv,
                             "burns_delta_v_mps": dv, "propellant_kg": dv / 5,
                             "nominal_delta_v_mps": NOMINAL, "nominal_propellant_kg": 174.0,
                             "final_rp_error_km": 0.0, "final_ra_error_km": 0.0,
                             "final_inc_error_deg": 0.0})
    return pd.DataFrame(rows), models, z


def test_a_quadratic_response_reads_exponent_two_with_a_nonzero_standard_error():
    c = 0.7
    t, models, z = _table(lambda s, zz: c * (s * zz[0]) ** 2, pairs=12)
    rows = S.sensitivity_rows(t, models)
    z2 = z[:, 0] ** 2
    for r in rows:
        assert r["draws"] == 12 and r["antithetic"]
        assert r["mean_above_nominal_mps"] == pytest.approx(c * r["sigma"] ** 2 * z2.mean(),
                                                            rel=1e-9)
        # over the 12 pairs' means, not within one pair (which reads 0: z^2 is even)
        se = c * r["sigma"] ** 2 * z2.std(ddof=1) / math.sqrt(12)
        assert r["mean_above_nominal_se_mps"] == pytest.approx(se, rel=1e-9)
        assert r["mean_above_nominal_se_mps"] > 0.01
    (law,) = S.laws(t, models)
    assert law["status"] == "fitted" and law["exponent"] == pytest.approx(2.0, abs=1e-9)
    assert law["exponent_se"] == pytest.approx(0.0, abs=1e-9)
    assert law["per_sigma"] == pytest.approx(c * z2.mean(), rel=1e-9)


def test_a_linear_responses_pair_mean_is_the_nominal_and_unresolved():
    t, models, _ = _table(lambda s, zz: 3.0 * s * zz[0], pairs=6)
    rows = S.sensitivity_rows(t, models)
    assert all(abs(r["mean_above_nominal_mps"]) < 1e-9 and not r["resolved"] for r in rows)
    (law,) = S.laws(t, models)
    assert law["status"] == "unresolved" and math.isnan(law["exponent"])
    assert "0.01 m/s" in law["reason"]


def test_the_exponents_standard_error_is_the_spread_over_independent_replications():
    # y = a sigma z1^2 + b sigma^3 z2^2: no power law; the fitted exponent (between 1 and
    # 3) varies with the draws, and its delta-method error must predict how much
    def response(s, zz):
        return 0.4 * s * zz[0] ** 2 + 0.3 * s ** 3 * zz[1] ** 2

    x = np.log(SIGMAS)
    w = (x - x.mean()) / ((x - x.mean()) ** 2).sum()   # the least-squares slope's weights
    est, ses, naive = [], [], []
    for rep in range(300):
        z = np.random.default_rng(1000 + rep).standard_normal((20, 2))
        y = np.array([[response(s, z[j]) for s in SIGMAS] for j in range(20)])
        fit = S.power_law(SIGMAS, y)
        est.append(fit["exponent"])
        ses.append(fit["exponent_se"])
        # as if each sigma had its own draws (the common random numbers ignored)
        naive.append(math.sqrt(float(((w / y.mean(axis=0)) ** 2
                                      * y.var(axis=0, ddof=1) / 20).sum())))
    spread = float(np.std(est, ddof=1))
    assert 1.3 < np.mean(est) < 2.7 and spread > 0.02
    # the standard error of a standard error over 20 draws is ~1/sqrt(40): 20 % covers it
    assert np.mean(ses) == pytest.approx(spread, rel=0.2)
    assert np.mean(naive) > 1.3 * spread   # which would overstate it


def test_no_quantile_interval_on_an_antithetic_table():
    t, models, _ = _table(lambda s, zz: (s * zz[0]) ** 2, pairs=200)
    s = summarise(t[np.isclose(t.pointing_sigma_deg, 1.0)])
    assert s["antithetic"] and s["samples"] == 400
    assert all(math.isnan(v) for v in s["budget_p99_ci_mps"])
    rows = S.sensitivity_rows(t, models)
    assert all(math.isnan(r["budget_p99_above_nominal_mps"]) for r in rows)


def test_a_failed_sample_or_a_negative_mean_has_no_law_and_says_why():
    t, models, _ = _table(lambda s, zz: -2.0 * s * s * (1 + zz[0] ** 2), pairs=4)
    (law,) = S.laws(t, models)
    assert law["status"] == "no power law" and "below the nominal" in law["reason"]
    t, models, _ = _table(lambda s, zz: (s * zz[0]) ** 2, pairs=4)
    t.loc[t.index[-1], "status"] = "correction failed"
    (law,) = S.laws(t, models)
    assert law["status"] == "no power law" and "failed at sigma 2" in law["reason"]


def test_draws_needed_scale_as_the_square_of_the_standard_error():
    assert S.draws_needed(10, 0.1, target=0.05) == 40   # twice the target: 4 times the draws
    assert S.draws_needed(10, 0.05, target=0.05) == 10
    assert S.draws_needed(1, 0.1) is None and S.draws_needed(10, math.nan) is None
    # and met: the exponent's error over the draws it asks for is the target (synthetic
    # y = 0.4 sigma z1^2 + 0.3 sigma^3 z2^2, whose exponent has a spread of its own)
    def y(n, seed):
        z = np.random.default_rng(seed).standard_normal((n, 2))
        return np.array([[0.4 * s * a ** 2 + 0.3 * s ** 3 * b ** 2 for s in SIGMAS]
                         for a, b in z])

    pilot = S.power_law(SIGMAS, y(8, 3))["exponent_se"]
    n = S.draws_needed(8, pilot)
    ses = [S.power_law(SIGMAS, y(n, 100 + k))["exponent_se"] for k in range(40)]
    assert np.median(ses) == pytest.approx(S.TARGET_EXPONENT_SE, rel=0.5)
