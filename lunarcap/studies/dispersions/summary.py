"""Dispersions: the planner's answer from a table of samples.

Percentiles of the delta-V flown and the propellant, the 99 % budget above the nominal
with a distribution-free confidence interval from order statistics (:func:`quantile_ci`;
a percentile is printed only when the samples bound its interval on both sides,
:func:`samples_needed`: 368 for the 95 % interval of the 99 % point), the mean above
the nominal with its standard error,
the failure probabilities, the convergence of the estimate with the number of samples,
and the command line's text (:func:`format_summary`). Pure data: no solving.
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

    Percentiles of the total delta-V and propellant over every sample (a sample not
    captured, or not corrected, counts as needing more than any captured one: its value
    is +inf, so failures push the percentiles up rather than vanishing), the 99 % budget
    above the nominal with its distribution-free confidence interval, the failure
    probabilities (with a 95 % Clopper-Pearson upper bound) and the failed samples with
    their reasons, and the final-orbit errors (RMS and max over the captured samples).
    """
    import pandas as pd
    from scipy.stats import beta

    df = pd.DataFrame(rows)
    n = len(df)
    ok = df[df.status == "ok"]
    nom = float(df.nominal_delta_v_mps.dropna().iloc[0]) if \
        df.nominal_delta_v_mps.notna().any() else math.nan
    nom_kg = float(df.nominal_propellant_kg.dropna().iloc[0]) if \
        df.nominal_propellant_kg.notna().any() else math.nan
    dv = np.sort(np.where(df.status == "ok", df.total_delta_v_mps.astype(float), np.inf))
    kg = np.sort(np.where(df.status == "ok", df.propellant_kg.astype(float), np.inf))
    out = {"samples": n, "captured_and_corrected": len(ok),
           "nominal_delta_v_mps": nom, "nominal_propellant_kg": nom_kg}
    for q in PERCENTILES:
        out[f"delta_v_p{q:g}_mps"] = _quantile(dv, q / 100)
        out[f"propellant_p{q:g}_kg"] = _quantile(kg, q / 100)
        lo, hi = quantile_ci(n, q / 100, level) if n else (0, 1)
        out[f"delta_v_p{q:g}_ci_mps"] = (dv[lo - 1] if lo >= 1 else -math.inf,
                                         dv[hi - 1] if hi <= n else math.inf)
        out[f"samples_needed_p{q:g}"] = samples_needed(q / 100, level)
    above = ok.total_delta_v_mps.astype(float).to_numpy() - nom
    out["mean_above_nominal_mps"] = float(above.mean()) if above.size else math.nan
    out["mean_above_nominal_se_mps"] = (float(above.std(ddof=1) / math.sqrt(above.size))
                                        if above.size > 1 else math.nan)
    lo, hi = quantile_ci(n, 0.99, level) if n else (0, 1)
    out["budget_p99_above_nominal_mps"] = out["delta_v_p99_mps"] - nom
    out["budget_p99_ci_mps"] = (dv[lo - 1] - nom if lo >= 1 else -math.inf,
                                dv[hi - 1] - nom if hi <= n else math.inf)
    out["budget_p99_ci_ranks"] = (lo, hi)
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
    return out


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
    """The text of a summary ``s``: the error model, the budget, failures, final orbit."""
    n = s["samples"]
    interval = f"{100 * s['ci_level']:g} % interval above"
    lines = [
        f"Dispersions of plan {plan.name} ({plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} "
        f"s, {plan.dynamics} dynamics): {n} sample(s), closed-loop re-planning "
        f"after each burn",
        f"  errors: {model.describe()}",
        f"  nominal: {s['nominal_delta_v_mps']:.3f} m/s, {s['nominal_propellant_kg']:.3f} kg "
        f"of propellant",
        f"  mean above nominal (captured samples): {s['mean_above_nominal_mps']:.3f} m/s "
        f"(standard error {s['mean_above_nominal_se_mps']:.3f} m/s)",
        f"  {'percentile':>10} | {'delta-V m/s':>11} {'above nominal':>13} "
        f"{interval:>24} | {'propellant kg':>13}"]
    for q in PERCENTILES:
        need = s[f"samples_needed_p{q:g}"]
        if n < need:   # the samples do not bound it: no number, the count it needs
            lines.append(f"  {q:>9g}% | not estimated: its interval needs {need} samples, "
                         f"this run has {n}")
            continue
        d = s[f"delta_v_p{q:g}_mps"]
        lo, hi = (v - s["nominal_delta_v_mps"] for v in s[f"delta_v_p{q:g}_ci_mps"])
        lines.append(f"  {q:>9g}% | {d:11.3f} {d - s['nominal_delta_v_mps']:13.3f} "
                     f"{f'[{lo:.3f}, {hi:.3f}]':>24} | {s[f'propellant_p{q:g}_kg']:13.3f}")
    if n >= s["samples_needed_p99"]:
        lo, hi = s["budget_p99_ci_mps"]
        lines.append(f"  99 % budget above nominal: {s['budget_p99_above_nominal_mps']:.3f} "
                     f"m/s, {100 * s['ci_level']:g} % interval [{lo:.3f}, {hi:.3f}] m/s "
                     f"(order statistics, distribution-free"
                     f"{'; inf: a failed sample' if math.isinf(hi) else ''})")
    else:
        lines.append(f"  99 % budget: not estimated ({n} samples; its distribution-free "
                     f"{100 * s['ci_level']:g} % interval needs {s['samples_needed_p99']})")
    lines.append(f"  not captured: {s['p_not_captured']:.4g} (95 % upper bound "
                 f"{s['p_not_captured_upper95']:.3g}); correction failed: "
                 f"{s['p_correction_failed']:.4g} (upper bound "
                 f"{s['p_correction_failed_upper95']:.3g})")
    for f in s["failures"]:
        lines.append(f"    sample {f['sample']}: {f['status']}: {f['reason']}")
    lines.append(f"  final orbit (RMS / max): perilune {s['final_rms_rp_error_km']:.3g} / "
                 f"{s['final_max_abs_rp_error_km']:.3g} km, apolune "
                 f"{s['final_rms_ra_error_km']:.3g} / {s['final_max_abs_ra_error_km']:.3g} km, "
                 f"inclination {s['final_rms_inc_error_deg']:.3g} / "
                 f"{s['final_max_abs_inc_error_deg']:.3g} deg")
    return "\n".join(lines)
