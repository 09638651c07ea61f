"""``lunarcap study``: the engine trade study on the command line (:mod:`.trade`).

Loss against thrust-to-weight with free ignitions, per Isp, one Dask task per engine. It
takes no plan (its arrival is the paper's) and has its own Dask options: its table is
resumed engine by engine, and a failed engine is recomputed only when asked
(``--retry-failed``). No ``--json``: the book reads its table.
"""

from __future__ import annotations

from lunarcap.physics.forces import PRESETS
from lunarcap.studies.registry import StudyCommand, StudyRun


def options(p) -> None:
    """The trade study's grid, its Dask options and its table."""
    p.add_argument("--thrust-min", default="50", metavar="N",
                   help="lowest thrust, N (default 50)")
    p.add_argument("--thrust-max", default="2000", metavar="N",
                   help="highest thrust, N (default 2000)")
    p.add_argument("--points", default="30", metavar="K",
                   help="log-spaced thrusts (default 30)")
    p.add_argument("--isp", default="200,250,300", metavar="S1,S2,...",
                   help="specific impulses, s (default 200,250,300)")
    p.add_argument("--workers", default="2", metavar="W",
                   help="local Dask worker processes, one thread each (default 2)")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of an existing Dask scheduler (default: a local cluster)")
    p.add_argument("--out", default=None, metavar="PATH",
                   help="CSV table, appended as engines finish and resumed on rerun "
                        "(default: .cache/study/engine_trade.csv)")
    p.add_argument("--dynamics", default="full", metavar="DYNAMICS",
                   help=f"perturbations: {', '.join(PRESETS)}, or the forces as a plan's "
                        "dynamics mapping, e.g. '{gravity: LP165P, degree: 8}' (a gravity "
                        "field: each burn solved in it, the loss against its impulsive limit "
                        "there, or its row says why there is none) (default full)")
    p.add_argument("--retry-failed", action="store_true",
                   help="recompute engines that failed in an earlier run")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


def prepare(args, plan=None) -> StudyRun:
    """The trade study's run: its grid checked (InputError) before any engine is solved."""
    from lunarcap.studies.engine_trade import trade

    spec = trade.StudySpec(args.thrust_min, args.thrust_max, args.points, args.isp,
                           args.dynamics)
    return StudyRun.of(trade.STUDY, lambda: trade.run_study(
        spec, out=args.out, workers=args.workers, scheduler=args.scheduler,
        retry_failed=args.retry_failed, progress=not args.no_progress))


COMMAND = StudyCommand("study", "engine trade study: loss vs thrust-to-weight on Dask",
                       options, prepare, plan=False)
