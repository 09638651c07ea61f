"""Dispersions: how the budget scales with each error source's sigma.

Instead of one budget under borrowed sigmas, each error source alone: for every sigma of
an :class:`~lunarcap.studies.dispersions.model.ErrorModel` that is not zero, the study is run
with that sigma at ``factors`` times its value and every other error at 0, all on the
same draws (common random numbers: sample k of a seed draws the same normals whatever the
sigmas, so the differences between sigmas are not sampling noise). A reader reads off
the budget for their own engine's sigma.

:func:`sensitivity_models` lists the models, :func:`run_sensitivity` runs them as one
campaign, :func:`sensitivity_rows` summarises each (mean above the nominal with its
standard error, the largest sample, the 99 % budget only when the samples bound it) and
:func:`slopes` gives the exponent of each source's law (d ln y / d ln sigma: 1 linear,
2 quadratic) and its value per unit sigma.
"""

from __future__ import annotations

import math

import numpy as np

from lunarcap.studies.dispersions.model import SIGMAS, ErrorModel
from lunarcap.studies.dispersions.summary import summarise

#: Multiples of each given sigma run by default.
FACTORS = (0.5, 1.0, 2.0)


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

    Returns ``(models, CampaignResult)``; ``kw``: :func:`run_dispersions`'s options.
    """
    from lunarcap.errors import InputError
    from lunarcap.studies.dispersions.samples import run_dispersions

    models = sensitivity_models(model, factors)
    if not models:
        raise InputError("--sensitivity needs at least one non-zero sigma to vary")
    return models, run_dispersions(plans, samples, seed, [m for _, _, m in models], **kw)


def sensitivity_rows(table, models) -> list:
    """One row per (plan, source, sigma) of a sensitivity campaign's table.

    Columns: plan, thrust_N, source, unit, sigma, samples, mean_above_nominal_mps (over
    the captured samples) and its standard error, max_above_nominal_mps (the largest
    sample; infinite if one failed), budget_p99_above_nominal_mps with its interval (NaN
    when the samples do not bound it: :func:`samples_needed`), samples_needed_p99, failed.
    """
    rows = []
    for plan_id in dict.fromkeys(table.plan_id):
        t_plan = table[table.plan_id == plan_id]
        for source, sigma, m in models:
            sel = np.ones(len(t_plan), bool)
            for k, v in m.key().items():
                col = t_plan[k]
                sel &= (col.fillna("").astype(str) == v) if isinstance(v, str) else \
                    np.isclose(col.astype(float), v, rtol=1e-12, atol=0.0)
            t = t_plan[sel]
            if not len(t):
                continue
            s = summarise(t)
            n, need = s["samples"], s["samples_needed_p99"]
            bounded = n >= need
            lo, hi = s["budget_p99_ci_mps"]
            rows.append({"plan": t.plan.iloc[0], "thrust_N": float(t.thrust_N.iloc[0]),
                         "source": source, "unit": SIGMAS[source], "sigma": sigma,
                         "samples": n,
                         "mean_above_nominal_mps": s["mean_above_nominal_mps"],
                         "mean_above_nominal_se_mps": s["mean_above_nominal_se_mps"],
                         "max_above_nominal_mps": _largest(t) - s["nominal_delta_v_mps"],
                         "budget_p99_above_nominal_mps":
                             s["budget_p99_above_nominal_mps"] if bounded else math.nan,
                         "budget_p99_ci_lo_mps": lo if bounded else math.nan,
                         "budget_p99_ci_hi_mps": hi if bounded else math.nan,
                         "samples_needed_p99": need,
                         "failed": int((t.status != "ok").sum())})
    return rows


def _largest(t) -> float:
    """The largest total delta-V of a table's samples (inf if one failed), m/s."""
    v = np.where(t.status == "ok", t.total_delta_v_mps.astype(float), np.inf)
    return float(v.max())


def slopes(rows, column: str = "mean_above_nominal_mps") -> list:
    """Per (plan, source): the law of ``column`` in sigma between its two largest sigmas.

    ``exponent``: d ln y / d ln sigma (1: linear, 2: quadratic); ``per_sigma``: y at the
    largest sigma over sigma^exponent rounded to the nearer of 1 and 2 (m/s per unit^1
    or unit^2), so y(sigma) ~ per_sigma * sigma^law for a reader's own sigma.
    """
    out = []
    keys = dict.fromkeys((r["plan"], r["source"]) for r in rows)
    for plan, source in keys:
        pts = sorted((r["sigma"], r[column]) for r in rows
                     if r["plan"] == plan and r["source"] == source)
        if len(pts) < 2:
            continue
        (s1, y1), (s2, y2) = pts[-2], pts[-1]
        exponent = math.log(y2 / y1) / math.log(s2 / s1) if y1 > 0 and y2 > 0 and \
            math.isfinite(y1 + y2) else math.nan
        law = 2 if exponent > 1.5 else 1
        out.append({"plan": plan, "source": source, "unit": SIGMAS[source],
                    "exponent": exponent, "law": law, "per_sigma": y2 / s2 ** law,
                    "column": column})
    return out


def format_sensitivity(plan, rows, result) -> str:
    """The CLI's text of a sensitivity: one line per source and sigma, then the laws."""
    lines = [f"Sensitivity of plan {plan.name} ({plan.engine.thrust_N:g} N / "
             f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics): each source alone, the "
             f"others 0, the same draws",
             f"  {'source':<22} {'sigma':>10} {'samples':>7} | {'mean above nominal m/s':>24} "
             f"{'largest':>9} | 99 % budget above nominal m/s"]
    for r in rows:
        p99 = (f"{r['budget_p99_above_nominal_mps']:.3f} [{r['budget_p99_ci_lo_mps']:.3f}, "
               f"{r['budget_p99_ci_hi_mps']:.3f}]"
               if math.isfinite(r["budget_p99_above_nominal_mps"]) else
               f"not estimated (needs {r['samples_needed_p99']} samples)")
        mean = f"{r['mean_above_nominal_mps']:.4f} +- {r['mean_above_nominal_se_mps']:.4f}"
        lines.append(f"  {r['source']:<22} {r['sigma']:>6.4g} {r['unit']:<3} {r['samples']:>7} "
                     f"| {mean:>24} {r['max_above_nominal_mps']:9.3f} | {p99}"
                     + (f" ({r['failed']} failed)" if r["failed"] else ""))
    lines.append("  laws (d ln y / d ln sigma between the two largest sigmas):")
    for column, what in (("mean_above_nominal_mps", "mean"),
                         ("max_above_nominal_mps", "largest")):
        for s in slopes(rows, column):
            if not math.isfinite(s["exponent"]):
                lines.append(f"    {s['source']:<22} {what}: no power law here (a value "
                             f"<= 0 or a failure)")
                continue
            lines.append(f"    {s['source']:<22} {what}: exponent {s['exponent']:.2f}, "
                         f"~ {s['per_sigma']:.4g} m/s x (sigma/{s['unit']})^{s['law']}")
    from lunarcap.studies.dispersions.samples import STUDY

    return "\n".join([*lines, *STUDY.run_lines(result)])
