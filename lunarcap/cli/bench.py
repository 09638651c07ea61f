"""``lunarcap bench``: the paper's 37 cases solved and verified uncached, timed.

``--warm``: warm solves of the dymos peer benchmark's cases instead; ``--studies``: where
the time goes (:func:`lunarcap.studies.bench.studies`).
"""

from __future__ import annotations


def cmd_bench(args) -> int:
    """Solve and verify all 37 paper cases uncached; print timings and residuals."""
    from lunarcap.studies.bench import run, warm_solves

    if args.studies:
        from lunarcap.studies.bench import studies

        studies(cold=not args.no_cold)
        return 0
    if args.warm:
        rows = warm_solves(args.dynamics or "two-body", args.repeats)
        return 0 if all(r["verified"] for r in rows) else 3
    rows = run(args.dynamics or "full", reuse=not args.resolve_earlier)
    return 0 if all(r["verification_passed"] for r in rows) else 3
