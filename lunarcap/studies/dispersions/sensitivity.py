"""Dispersions: how the budget scales with each error source's sigma.

Instead of one budget under borrowed sigmas, each error source alone: for every sigma of
an :class:`~lunarcap.studies.dispersions.model.ErrorModel` that is not zero, the study is run
with that sigma at ``factors`` times its value (0.5, 1 and 2 by default) and every other
error at 0, all on the same draws (common random numbers: sample k of a seed draws the
same normals whatever the sigmas, so the differences between sigmas are not sampling
noise). A reader reads off the budget for their own engine's sigma.

**Draws.** The unit of sampling is a *draw*: one sample, or with ``antithetic`` one pair
(samples 2j and 2j + 1 fly the negated numbers of each other), whose value is the pair's
mean. Pairs are independent of each other; the two samples of a pair are not, and the
spread within one pair measures only the response's odd part, which the pair's mean
cancels. Every standard error here is computed over independent draws; no quantile
interval is given on an antithetic table (order statistics need independent samples).

**Laws.** :func:`laws` fits, per source, ln ybar(sigma) = ln c + b ln sigma by least
squares over the sigmas run (ybar the mean above the nominal over the draws), and gives
the exponent b (1: linear, 2: quadratic) with its standard error by the delta method on
the draws: b = sum_k w_k ln ybar_k with w_k the regression weights, so
var(b) = sum_kl w_k w_l cov(y_k, y_l) / (n ybar_k ybar_l), the covariance over the n
draws that every sigma shares (the common random numbers correlate the sigmas; treating
them as independent would overstate the error). For a pure power law the exponent then
has no sampling error at all (every draw scales alike), while its value at each sigma
keeps the draws' spread. A sigma whose mean above the nominal is below the re-propagation
gate's resolution (:data:`lunarcap.optim.gate.TOL_DV_MPS`, 0.01 m/s) is *unresolved*; a
source with fewer than two resolved sigmas gets no exponent.

**How many draws.** The standard error falls as 1/sqrt(n): :func:`draws_needed` gives the
draws per sigma for a stated standard error of the exponent (:data:`TARGET_EXPONENT_SE`)
from those run, n (se / target)^2.
"""

from __future__ import annotations

import math

import numpy as np

from lunarcap.optim.gate import TOL_DV_MPS
from lunarcap.studies.dispersions.model import SIGMAS, ErrorModel
from lunarcap.studies.dispersions.summary import pair_means, summarise

#: Multiples of each given sigma run by default.
FACTORS = (0.5, 1.0, 2.0)
#: The standard error of an exponent the draws are sized for (:func:`draws_needed`): a
#: mean scaled to a sigma twice (or half) the one run is then off by at most
#: 0.1 ln 2 = 7 % through the exponent, less than the mean's own standard error at the
#: few pairs a sensitivity affords, and a linear law is told from a quadratic one by 10.
TARGET_EXPONENT_SE = 0.1


def sensitivity_models(model: ErrorModel, factors=FACTORS) -> list:
    """[(source, sigma, ErrorModel with that sigma alone)] for each non-zero sigma.

    Covariances are not varied (give them as sigmas to see their law).
    """
    out = []
    for name in SIGMAS:
        value = getattr(model, name)
        if value:
            out += [(name, f * value, model.only(name, f * value)) for f in factors]
    return out


def run_sensitivity(plans, samples: int, seed: int, model: ErrorModel, factors=FACTORS,
                    **kw):
    """Run :func:`sensitivity_models` on ``plans`` as one campaign (see run_dispersions).

    Returns ``(models, CampaignResult)``; ``kw``: :func:`run_dispersions`'s options
    (``antithetic=True`` flies pairs: ``samples`` must then be even).
    """
    from lunarcap.errors import InputError
    from lunarcap.studies.dispersions.samples import run_dispersions

    models = sensitivity_models(model, factors)
    if not models:
        raise InputError("--sensitivity needs at least one non-zero sigma to vary")
    if kw.get("antithetic") and int(samples) % 2:
        raise InputError(f"antithetic samples come in pairs: --samples must be even, got "
                         f"{samples}")
    return models, run_dispersions(plans, samples, seed, [m for _, _, m in models], **kw)


def _selected(t_plan, m: ErrorModel):
    """The rows of one plan's table flown under the error model ``m``."""
    sel = np.ones(len(t_plan), bool)
    for k, v in m.key().items():
        col = t_plan[k]
        sel &= (col.fillna("").astype(str) == v) if isinstance(v, str) else \
            np.isclose(col.astype(float), v, rtol=1e-12, atol=0.0)
    return t_plan[sel]


def sensitivity_rows(table, models) -> list:
    """One row per (plan, source, sigma) of a sensitivity campaign's table.

    Columns: plan, plan_id, thrust_N, source, unit, sigma, samples, draws (independent:
    pairs on an antithetic table), antithetic, mean_above_nominal_mps (over the captured
    samples) and its standard error over the draws, resolved (the mean at least the
    gate's 0.01 m/s), trim_mean_mps, max_above_nominal_mps (the largest sample; infinite
    if one failed), budget_p99_above_nominal_mps with its interval (NaN on an antithetic
    table or when the samples do not bound it), samples_needed_p99, failed.
    """
    rows = []
    for pid in dict.fromkeys(table.plan_id):
        t_plan = table[table.plan_id == pid]
        for source, sigma, m in models:
            t = _selected(t_plan, m)
            if not len(t):
                continue
            s = summarise(t)
            anti = s["antithetic"]
            bounded = not anti and s["samples"] >= s["samples_needed_p99"]
            lo, hi = s["budget_p99_ci_mps"]
            nom = s["nominal_delta_v_mps"]
            rows.append({"plan": t.plan.iloc[0], "plan_id": pid,
                         "thrust_N": float(t.thrust_N.iloc[0]), "source": source,
                         "unit": SIGMAS[source], "sigma": sigma, "samples": s["samples"],
                         "draws": s["samples"] // 2 if anti else s["samples"],
                         "antithetic": anti,
                         "mean_above_nominal_mps": s["mean_above_nominal_mps"],
                         "mean_above_nominal_se_mps": s["mean_above_nominal_se_mps"],
                         "resolved": bool(abs(s["mean_above_nominal_mps"]) >= TOL_DV_MPS),
                         "trim_mean_mps": s["trim_mean_mps"],
                         "max_above_nominal_mps": _largest(t) - nom,
                         "budget_p99_above_nominal_mps":
                             s["budget_p99_above_nominal_mps"] if bounded else math.nan,
                         "budget_p99_ci_lo_mps": lo if bounded else math.nan,
                         "budget_p99_ci_hi_mps": hi if bounded else math.nan,
                         "samples_needed_p99": s["samples_needed_p99"],
                         "failed": int((t.status != "ok").sum())})
    return rows


def _largest(t) -> float:
    """The largest total delta-V of a table's samples (inf if one failed), m/s."""
    v = np.where(t.status == "ok", t.total_delta_v_mps.astype(float), np.inf)
    return float(v.max())


def draw_values(t, antithetic: bool) -> dict:
    """{draw index: total delta-V above the nominal} of one source and sigma's samples.

    A draw is a sample, or a pair's mean (indexed by its first sample) on an antithetic
    table; a draw with a failed sample is left out.
    """
    ok = t[t.status == "ok"].copy()
    nom = float(t.nominal_delta_v_mps.dropna().iloc[0])
    ok["above"] = ok.total_delta_v_mps.astype(float) - nom
    s = ok["sample"].astype(int).to_numpy()
    if antithetic:
        first = sorted(j for j in s if j % 2 == 0 and j + 1 in set(s))
        return dict(zip(first, pair_means(ok, "above")))
    return dict(zip(s, ok.above.to_numpy()))


def power_law(sigmas, values) -> dict:
    """The least-squares law ln ybar = ln c + b ln sigma and its delta-method standard error.

    ``sigmas`` (K,), ``values`` (n draws, K sigmas): the same draws at every sigma. Returns
    ``exponent``, ``exponent_se`` (NaN below two draws), ``means`` (ybar per sigma),
    ``means_se``. Every mean must be positive.
    """
    y = np.asarray(values, float)
    x = np.log(np.asarray(sigmas, float))
    n = y.shape[0]
    means = y.mean(axis=0)
    w = (x - x.mean()) / ((x - x.mean()) @ (x - x.mean()))
    b = float(w @ np.log(means))
    if n < 2:
        return {"exponent": b, "exponent_se": math.nan, "means": means,
                "means_se": np.full(len(means), math.nan)}
    cov = np.cov(y, rowvar=False, ddof=1) / n
    g = w / means
    return {"exponent": b, "exponent_se": float(math.sqrt(max(g @ cov @ g, 0.0))),
            "means": means, "means_se": np.sqrt(np.diag(cov))}


def laws(table, models) -> list:
    """Per (plan, source): its law of the mean above the nominal in sigma, or why none.

    ``status``: "fitted" (``exponent`` and ``exponent_se`` over the resolved sigmas,
    ``per_sigma`` the law's value at sigma = 1 unit: y ~ per_sigma (sigma/unit)^exponent),
    "unresolved" (fewer than two sigmas whose mean reaches the gate's 0.01 m/s), or
    "no power law" (a failed sample, or a mean below zero beyond the resolution);
    ``reason`` says which in words. ``draws``: independent draws per sigma;
    ``draws_needed``: per sigma for :data:`TARGET_EXPONENT_SE` (:func:`draws_needed`).
    """
    out = []
    for pid in dict.fromkeys(table.plan_id):
        t_plan = table[table.plan_id == pid]
        for source in dict.fromkeys(s for s, _, _ in models):
            levels = [(sigma, _selected(t_plan, m)) for s, sigma, m in models if s == source]
            levels = [(sigma, t) for sigma, t in levels if len(t)]
            if levels:
                out.append(_law(t_plan, source, levels))
    return out


def _law(t_plan, source: str, levels: list) -> dict:
    """One source's law from its (sigma, samples) levels (see :func:`laws`)."""
    anti = bool(t_plan.antithetic.astype(bool).all()) if "antithetic" in t_plan else False
    per = [(sigma, draw_values(t, anti)) for sigma, t in levels]
    common = sorted(set.intersection(*(set(d) for _, d in per)))
    base = {"plan": t_plan.plan.iloc[0], "plan_id": t_plan.plan_id.iloc[0], "source": source,
            "unit": SIGMAS[source], "draws": len(common), "exponent": math.nan,
            "exponent_se": math.nan, "per_sigma": math.nan, "draws_needed": None}
    failed = [sigma for sigma, t in levels if (t.status != "ok").any()]
    if failed:
        return dict(base, status="no power law",
                    reason=f"a sample failed at sigma {failed[0]:g} {SIGMAS[source]}")
    y = np.array([[d[j] for _, d in per] for j in common])
    means = y.mean(axis=0) if len(common) else np.full(len(per), math.nan)
    if (means <= -TOL_DV_MPS).any():
        return dict(base, status="no power law",
                    reason="the mean lies below the nominal beyond the gate's 0.01 m/s")
    keep = [k for k, m in enumerate(means) if m >= TOL_DV_MPS]
    if len(keep) < 2:
        return dict(base, status="unresolved",
                    reason=f"the mean above the nominal reaches the re-propagation gate's "
                           f"{TOL_DV_MPS:g} m/s at {len(keep)} of {len(per)} sigmas")
    sig = np.array([per[k][0] for k in keep])
    fit = power_law(sig, y[:, keep])
    b, se = fit["exponent"], fit["exponent_se"]
    c = float(np.exp(np.mean(np.log(fit["means"])) - b * np.mean(np.log(sig))))
    return dict(base, status="fitted", exponent=b, exponent_se=se, per_sigma=c,
                draws_needed=draws_needed(len(common), se),
                reason=f"fitted over {len(keep)} sigmas")


def draws_needed(draws: int, se: float, target: float = TARGET_EXPONENT_SE) -> int | None:
    """Draws per sigma for an exponent's standard error of ``target``: n (se / target)^2.

    The standard error of a mean over independent draws falls as 1/sqrt(n); None when
    ``se`` is not known (fewer than two draws). At least 2.
    """
    if not math.isfinite(se) or draws < 2:
        return None
    return max(2, math.ceil(draws * (se / target) ** 2))


def format_sensitivity(plan, rows, result, fitted=None) -> str:
    """The CLI's text of a sensitivity: one line per source and sigma, then the laws."""
    draw = "pairs" if rows and rows[0]["antithetic"] else "samples"
    lines = [f"Sensitivity of plan {plan.name} ({plan.engine.thrust_N:g} N / "
             f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics): each source alone, the "
             f"others 0, the same draws",
             f"  {'source':<22} {'sigma':>10} {draw:>7} | {'mean above nominal m/s':>24} "
             f"{'largest':>9} | 99 % budget above nominal m/s"]
    for r in rows:
        if r["antithetic"]:
            p99 = "none on antithetic pairs (order statistics need independent samples)"
        elif math.isfinite(r["budget_p99_above_nominal_mps"]):
            p99 = (f"{r['budget_p99_above_nominal_mps']:.3f} [{r['budget_p99_ci_lo_mps']:.3f}, "
                   f"{r['budget_p99_ci_hi_mps']:.3f}]")
        else:
            p99 = f"not estimated (needs {r['samples_needed_p99']} samples)"
        mean = f"{r['mean_above_nominal_mps']:.4f} +- {r['mean_above_nominal_se_mps']:.4f}"
        lines.append(f"  {r['source']:<22} {r['sigma']:>6.4g} {r['unit']:<3} {r['draws']:>7} "
                     f"| {mean:>24} {r['max_above_nominal_mps']:9.3f} | {p99}"
                     + (f" ({r['failed']} failed)" if r["failed"] else ""))
    lines.append("  laws of the mean (ln y = ln c + b ln sigma over the resolved sigmas; "
                 "standard error over the draws):")
    for s in fitted or []:
        if s["status"] != "fitted":
            lines.append(f"    {s['source']:<22} {s['status']}: {s['reason']}")
            continue
        need = s["draws_needed"]
        lines.append(f"    {s['source']:<22} exponent {s['exponent']:.2f} +- "
                     f"{s['exponent_se']:.2f}, ~ {s['per_sigma']:.4g} m/s x "
                     f"(sigma/{s['unit']})^{s['exponent']:.2f}"
                     + (f" ({need} {draw} per sigma for +- {TARGET_EXPONENT_SE:g})"
                        if need else ""))
    from lunarcap.studies.dispersions.samples import STUDY

    return "\n".join([*lines, *STUDY.run_lines(result)])
