"""Dispersions: the planner's answer from a table of samples.

Percentiles of the delta-V flown (the burns and the trim) and the propellant, the 99 %
budget above the nominal with a distribution-free confidence interval from order
statistics (:func:`quantile_ci`; a percentile is printed only when the samples bound its
interval on both sides, :func:`samples_needed`: 368 for the 95 % interval of the 99 %
point) and the same of the burns alone, the mean above the nominal with its standard
error (of the pairs' means on an antithetic table, :func:`standard_error`), the trim's
distribution (:func:`trim_summary`), the failure probabilities, the convergence of the
estimate with the number of samples, and the command line's text
(:func:`format_summary`). Pure data: no solving.
"""

from __future__ import annotations

import math

import numpy as np

from lunarcap.mission.plan import CapturePlan
from lunarcap.studies.dispersions.model import ErrorModel

#: Percentiles of the budget reported.
PERCENTILES = (50.0, 90.0, 95.0, 99.0)


# ====================================================================== the answer
def quantile_ci(n: int, q: float, level: float = 0.95) -> tuple:
    """Ranks (1-based, inclusive) (lo, hi) of order statistics bracketing the q-quantile.

    Distribution-free: P(X_(lo) <= x_q <= X_(hi)) >= ``level`` for any continuous
    distribution (binomial(n, q) counts of samples below x_q), the interval as nearly
    symmetric in probability as possible. A rank of 0 or n + 1 means that side is
    unbounded at this n (too few samples).
    """
    from scipy.stats import binom

    a = (1 - level) / 2
    lo = int(binom.ppf(a, n, q))          # P(B <= lo - 1) <= a
    hi = int(binom.ppf(1 - a, n, q)) + 1  # P(B >= hi) <= a
    while lo > 0 and binom.cdf(hi - 1, n, q) - binom.cdf(lo - 1, n, q) < level:
        lo -= 1
    while hi <= n and binom.cdf(hi - 1, n, q) - binom.cdf(lo - 1, n, q) < level:
        hi += 1
    return max(lo, 0), min(hi, n + 1)


def samples_needed(q: float, level: float = 0.95) -> int:
    """Fewest samples whose order statistics bound the q-quantile on both sides at ``level``.

    The two-sided interval of :func:`quantile_ci` has a finite upper rank once
    P(all n samples below x_q) = q^n <= (1 - level)/2, and a lower one once
    (1 - q)^n < (1 - level)/2: for the 99 % point at 95 %, n = 368 (the one-sided 95 %
    bound, 0.99^n <= 0.05, needs 299). Found from the closed form, then confirmed on
    :func:`quantile_ci` itself.
    """
    a = (1 - level) / 2
    n = max(1, math.ceil(math.log(a) / math.log(max(q, 1 - q))) - 1)
    while not _bounded(n, q, level):
        n += 1
    return n


def _bounded(n: int, q: float, level: float) -> bool:
    """True if :func:`quantile_ci` (n, q, level) has both ranks within 1..n."""
    lo, hi = quantile_ci(n, q, level)
    return lo >= 1 and hi <= n


def summarise(rows, level: float = 0.95) -> dict:
    """The planner's answer from a table's rows (a DataFrame or list of dicts).

    Percentiles of the total delta-V (the burns and the trim) and propellant over every
    sample (a sample not captured, or not corrected, counts as needing more than any
    captured one: its value is +inf, so failures push the percentiles up rather than
    vanishing), the 99 % budget above the nominal with its distribution-free confidence
    interval, and the same of the burns alone (the budget without the trim); the trim's
    distribution over the captured samples (:func:`trim_summary`); the failure
    probabilities (with a 95 % Clopper-Pearson upper bound) and the failed samples with
    their reasons; the final-orbit errors before the trim (RMS and max over the captured
    samples) and the largest after it.

    On an antithetic table (samples 2j and 2j + 1 the negated draws of each other) the
    samples are not independent: the mean's standard error is that of the pairs' means
    (each pair one draw), and no quantile interval is given (order statistics need
    independent samples): the ``*_ci_*`` entries are NaN and ``antithetic`` is True.
    """
    import pandas as pd
    from scipy.stats import beta

    df = pd.DataFrame(rows)
    n = len(df)
    ok = df[df.status == "ok"]
    nom = _first(df, "nominal_delta_v_mps")
    anti = bool("antithetic" in df and n and df.antithetic.astype(bool).all())
    burns = df.burns_delta_v_mps if "burns_delta_v_mps" in df else df.total_delta_v_mps
    dv, kg, dv_burns = (np.sort(np.where(df.status == "ok", c.astype(float), np.inf))
                        for c in (df.total_delta_v_mps, df.propellant_kg, burns))
    out = {"samples": n, "captured_and_corrected": len(ok), "antithetic": anti,
           "nominal_delta_v_mps": nom,
           "nominal_propellant_kg": _first(df, "nominal_propellant_kg")}
    for q in PERCENTILES:
        out[f"delta_v_p{q:g}_mps"] = _quantile(dv, q / 100)
        out[f"propellant_p{q:g}_kg"] = _quantile(kg, q / 100)
        out[f"delta_v_p{q:g}_ci_mps"] = _interval(dv, q / 100, level, anti)
        out[f"samples_needed_p{q:g}"] = samples_needed(q / 100, level)
    above = ok.total_delta_v_mps.astype(float).to_numpy() - nom
    out["mean_above_nominal_mps"] = float(above.mean()) if above.size else math.nan
    out["mean_above_nominal_se_mps"] = standard_error(ok, "total_delta_v_mps", anti)
    lo, hi = quantile_ci(n, 0.99, level) if n else (0, 1)
    out["budget_p99_above_nominal_mps"] = out["delta_v_p99_mps"] - nom
    out["budget_p99_ci_mps"] = tuple(v - nom for v in _interval(dv, 0.99, level, anti))
    out["budget_p99_ci_ranks"] = (lo, hi)
    out["budget_p99_burns_above_nominal_mps"] = _quantile(dv_burns, 0.99) - nom
    out["budget_p99_burns_ci_mps"] = tuple(v - nom for v in
                                           _interval(dv_burns, 0.99, level, anti))
    out["ci_level"] = level
    for status, name in (("not captured", "p_not_captured"),
                         ("correction failed", "p_correction_failed")):
        k = int((df.status == status).sum())
        out[name] = k / n if n else math.nan
        out[name + "_upper95"] = float(beta.ppf(0.95, k + 1, n - k)) if n else math.nan
    bad = df[df.status != "ok"]
    out["failures"] = [{"sample": int(r["sample"]), "status": r["status"],
                        "reason": r["reason"] or r.get("error", "")}
                       for r in bad.to_dict("records")]
    for c in ("final_rp_error_km", "final_ra_error_km", "final_inc_error_deg"):
        v = ok[c].astype(float).dropna().to_numpy()
        out[c.replace("final_", "final_rms_")] = float(np.sqrt(np.mean(v ** 2))) if v.size \
            else math.nan
        out[c.replace("final_", "final_max_abs_")] = float(np.abs(v).max()) if v.size \
            else math.nan
    out.update(trim_summary(ok, level, anti))
    return out


def _first(df, column: str) -> float:
    """The first non-missing value of ``column`` (NaN if none)."""
    return float(df[column].dropna().iloc[0]) if df[column].notna().any() else math.nan


def _interval(sorted_values: np.ndarray, q: float, level: float, antithetic: bool) -> tuple:
    """The distribution-free interval of the q-quantile of sorted values.

    -inf/inf where a side is unbounded; NaN on antithetic samples, which order statistics
    do not cover.
    """
    n = sorted_values.size
    if antithetic or not n:
        return (math.nan, math.nan)
    lo, hi = quantile_ci(n, q, level)
    return (float(sorted_values[lo - 1]) if lo >= 1 else -math.inf,
            float(sorted_values[hi - 1]) if hi <= n else math.inf)


def standard_error(ok, column: str, antithetic: bool) -> float:
    """Standard error of the mean of ``column`` over the samples ``ok`` (a DataFrame).

    Independent samples: s / sqrt(n). Antithetic pairs: each pair (samples 2j, 2j + 1,
    both in ``ok``) is one draw whose value is the pair's mean; the standard error is the
    pairs' means' standard deviation over sqrt(pairs) (NaN below two pairs). A single
    pair's spread measures only the response's odd part, which the pair's mean cancels.
    """
    if antithetic:
        v = pair_means(ok, column)
    else:
        v = ok[column].astype(float).to_numpy()
    return float(v.std(ddof=1) / math.sqrt(v.size)) if v.size > 1 else math.nan


def pair_means(ok, column: str) -> np.ndarray:
    """The antithetic pairs' means of ``column`` (pairs with both samples in ``ok``)."""
    s = ok["sample"].astype(int).to_numpy()
    v = dict(zip(s, ok[column].astype(float).to_numpy()))
    return np.array([(v[j] + v[j + 1]) / 2 for j in sorted(v) if j % 2 == 0 and j + 1 in v])


def trim_summary(ok, level: float = 0.95, antithetic: bool = False) -> dict:
    """The trim over the captured and corrected samples ``ok`` (a DataFrame).

    ``trim_p50/p90/p99_mps`` (order statistics, :func:`_quantile`) with the 99 % point's
    distribution-free interval (``trim_p99_ci_mps``: NaN on an antithetic table), the
    mean with its standard error, the largest, the share of samples that needed one,
    the 99 % point of its propellant, and the largest errors of the trimmed orbits
    (against the plan's final orbit at the trim's check epoch). NaN where the table has
    no trim column (a table of the study before the trim).
    """
    if "trim_delta_v_mps" not in ok or not len(ok):
        return {k: (math.nan, math.nan) if k.endswith("_ci_mps") else math.nan
                for k in TRIM_KEYS}
    v = np.sort(ok.trim_delta_v_mps.astype(float).to_numpy())
    out = {f"trim_p{q:g}_mps": _quantile(v, q / 100) for q in (50, 90, 99)}
    out["trim_p99_ci_mps"] = _interval(v, 0.99, level, antithetic)
    out["trim_mean_mps"] = float(v.mean())
    out["trim_mean_se_mps"] = standard_error(ok, "trim_delta_v_mps", antithetic)
    out["trim_max_mps"] = float(v[-1])
    out["trimmed_share"] = float(np.mean(v > 0))
    out["trim_propellant_p99_kg"] = _quantile(np.sort(ok.trim_propellant_kg.astype(float)
                                                      .to_numpy()), 0.99)
    for c in ("rp_error_m", "ra_error_m", "inc_error_deg"):
        e = np.abs(ok[f"trimmed_{c}"].astype(float).dropna().to_numpy())
        out[f"trimmed_max_abs_{c}"] = float(e.max()) if e.size else math.nan
    return out


#: The keys of :func:`trim_summary`.
TRIM_KEYS = ("trim_p50_mps", "trim_p90_mps", "trim_p99_mps", "trim_p99_ci_mps",
             "trim_mean_mps", "trim_mean_se_mps", "trim_max_mps", "trimmed_share",
             "trim_propellant_p99_kg", "trimmed_max_abs_rp_error_m",
             "trimmed_max_abs_ra_error_m", "trimmed_max_abs_inc_error_deg")


def _quantile(sorted_values: np.ndarray, q: float) -> float:
    """The q-quantile as the order statistic of rank ceil(q n) (inf if that sample failed)."""
    n = sorted_values.size
    if n == 0:
        return math.nan
    return float(sorted_values[max(1, math.ceil(q * n)) - 1])


def convergence(rows, q: float = 0.99) -> "object":
    """The q-quantile of the delta-V above nominal after the first N samples, N = 1..n.

    A pandas DataFrame (samples, estimate_mps, ci_lo_mps, ci_hi_mps): how the estimate
    and its distribution-free 95 % interval settle with N, in sample order.
    """
    import pandas as pd

    df = pd.DataFrame(rows).sort_values("sample")
    nom = float(df.nominal_delta_v_mps.dropna().iloc[0])
    vals = np.where(df.status == "ok", df.total_delta_v_mps.astype(float), np.inf) - nom
    recs = []
    for n in range(1, len(vals) + 1):
        s = np.sort(vals[:n])
        lo, hi = quantile_ci(n, q)
        recs.append({"samples": n, "estimate_mps": _quantile(s, q),
                     "ci_lo_mps": s[lo - 1] if lo >= 1 else -math.inf,
                     "ci_hi_mps": s[hi - 1] if hi <= n else math.inf})
    return pd.DataFrame(recs)


def settled_after(conv, tol_mps: float = 1.0) -> int | None:
    """Fewest samples N after which the estimate stays within ``tol_mps`` of its last value."""
    est = conv.estimate_mps.to_numpy()
    if not est.size or not np.isfinite(est[-1]):
        return None
    off = ~(np.abs(est - est[-1]) <= tol_mps)
    idx = np.nonzero(off)[0]
    return int(conv.samples.iloc[idx[-1] + 1]) if idx.size else int(conv.samples.iloc[0])


def format_summary(plan: CapturePlan, model: ErrorModel, s: dict) -> str:
    """The text of a summary ``s``: the error model, the budget, the trim, failures, orbit."""
    n = s["samples"]
    interval = f"{100 * s['ci_level']:g} % interval above"
    lines = [
        f"Dispersions of plan {plan.name} ({plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} "
        f"s, {plan.dynamics} dynamics): {n} sample(s), closed-loop re-planning "
        f"after each burn, a trim to the final orbit after the last",
        f"  errors: {model.describe()}",
        f"  nominal: {s['nominal_delta_v_mps']:.3f} m/s, {s['nominal_propellant_kg']:.3f} kg "
        f"of propellant",
        f"  mean above nominal (captured samples, burns and trim): "
        f"{s['mean_above_nominal_mps']:.3f} m/s (standard error "
        f"{s['mean_above_nominal_se_mps']:.3f} m/s)",
        f"  {'percentile':>10} | {'delta-V m/s':>11} {'above nominal':>13} "
        f"{interval:>24} | {'propellant kg':>13}"]
    for q in PERCENTILES:
        need = s[f"samples_needed_p{q:g}"]
        if s.get("antithetic"):
            lines.append(f"  {q:>9g}% | not estimated: antithetic pairs (an interval from "
                         f"order statistics needs independent samples)")
            continue
        if n < need:   # the samples do not bound it: no number, the count it needs
            lines.append(f"  {q:>9g}% | not estimated: its interval needs {need} samples, "
                         f"this run has {n}")
            continue
        d = s[f"delta_v_p{q:g}_mps"]
        lo, hi = (v - s["nominal_delta_v_mps"] for v in s[f"delta_v_p{q:g}_ci_mps"])
        lines.append(f"  {q:>9g}% | {d:11.3f} {d - s['nominal_delta_v_mps']:13.3f} "
                     f"{f'[{lo:.3f}, {hi:.3f}]':>24} | {s[f'propellant_p{q:g}_kg']:13.3f}")
    lines += _budget_lines(s)
    lines.append(f"  not captured: {s['p_not_captured']:.4g} (95 % upper bound "
                 f"{s['p_not_captured_upper95']:.3g}); correction failed: "
                 f"{s['p_correction_failed']:.4g} (upper bound "
                 f"{s['p_correction_failed_upper95']:.3g})")
    for f in s["failures"]:
        lines.append(f"    sample {f['sample']}: {f['status']}: {f['reason']}")
    lines.append(f"  final orbit before the trim (RMS / max): perilune "
                 f"{s['final_rms_rp_error_km']:.3g} / {s['final_max_abs_rp_error_km']:.3g} km, "
                 f"apolune {s['final_rms_ra_error_km']:.3g} / "
                 f"{s['final_max_abs_ra_error_km']:.3g} km, inclination "
                 f"{s['final_rms_inc_error_deg']:.3g} / {s['final_max_abs_inc_error_deg']:.3g} "
                 f"deg")
    return "\n".join(lines + _trim_lines(s))


def _budget_lines(s: dict) -> list:
    """The 99 % budget with the trim and without it (the burns alone), or why not."""
    n, level = s["samples"], f"{100 * s['ci_level']:g} %"
    if s.get("antithetic"):
        return ["  99 % budget: not estimated (antithetic pairs: the mean and its standard "
                "error above are the pairs')"]
    if n < s["samples_needed_p99"]:
        return [f"  99 % budget: not estimated ({n} samples; its distribution-free {level} "
                f"interval needs {s['samples_needed_p99']})"]
    out = []
    for what, key in (("99 % budget above nominal, burns and trim",
                       "budget_p99_above_nominal_mps"),
                      ("  without the trim (the burns alone)",
                       "budget_p99_burns_above_nominal_mps")):
        lo, hi = s[key.replace("above_nominal_mps", "ci_mps")]
        out.append(f"  {what}: {s[key]:.3f} m/s, {level} interval [{lo:.3f}, {hi:.3f}] m/s"
                   + (" (order statistics, distribution-free)" if "trim" in what else "")
                   + ("; inf: a failed sample" if math.isinf(hi) else ""))
    return out


def _trim_lines(s: dict) -> list:
    """The trim's distribution and the trimmed orbits' largest errors (if the table has it)."""
    if not math.isfinite(s.get("trim_max_mps", math.nan)):
        return []
    n, need = s["captured_and_corrected"], s["samples_needed_p99"]
    if s.get("antithetic"):
        p99 = f"{s['trim_p99_mps']:.3f} (antithetic: no interval)"
    elif n >= need:
        lo, hi = s["trim_p99_ci_mps"]
        p99 = f"{s['trim_p99_mps']:.3f} [{lo:.3f}, {hi:.3f}]"
    else:
        p99 = f"not estimated (its interval needs {need} captured samples, has {n})"
    return [f"  trim to the final orbit (two impulses; {100 * s['trimmed_share']:.0f} % of "
            f"the captured samples needed one): median {s['trim_p50_mps']:.3f}, 90 % "
            f"{s['trim_p90_mps']:.3f}, 99 % {p99}, largest {s['trim_max_mps']:.3f} m/s; mean "
            f"{s['trim_mean_mps']:.3f} m/s (standard error {s['trim_mean_se_mps']:.3f})",
            f"  after the trim, every orbit within the gate of the plan's final orbit "
            f"(largest errors: perilune {s['trimmed_max_abs_rp_error_m']:.3g} m, apolune "
            f"{s['trimmed_max_abs_ra_error_m']:.3g} m, inclination "
            f"{s['trimmed_max_abs_inc_error_deg']:.2g} deg)"]
