"""lunarcap's public Python API: plans, solves, studies, exports, as the command line has them.

Everything here is importable from :mod:`lunarcap` itself (``lunarcap.__all__``):

* plans: :func:`load_plan` (a file, a packaged name, a mapping, with changes),
  :func:`paper_plan`, :func:`available`; a plan is a :class:`CapturePlan`, changed by its
  ``with_*`` methods;
* solves: :func:`solve` (every burn, verified: a :class:`CaptureResult`, which exports the
  capture (OEM, SPK, GMAT script, ...) and flies it in GMAT: :class:`GmatFlight`) and
  :func:`solve_burn` (one burn: a :class:`BurnSolution`);
* studies: :func:`run_study` (any registered study), :func:`missed`, :func:`burns`,
  :func:`dispersions`, :func:`engine_trade`, each a :class:`StudyResult`, locally or on a
  Dask cluster;
* errors: :class:`InputError` (bad input: the command line's exit status 2),
  :class:`PlanError` (an InputError naming a plan's field), :class:`SolveError` (a solve
  that did not converge or failed verification: status 3), :class:`LunarcapError`.

Every result has :meth:`~.results.Result.to_frame`, :meth:`~.results.Result.to_dict`
(the ``--json`` document), :meth:`~.results.Result.plot` and
:meth:`~.results.Result.export`. The command line is a shell over these calls.

Examples
--------
>>> import lunarcap
>>> plan = lunarcap.load_plan("two-burn-8h", thrust_N=440, mass_kg=900)
>>> plan.engine.thrust_N, plan.burns[0].describe()
(440.0, 'ellipse, 8 h')
"""

from lunarcap.api.capture import BurnSolution, CaptureResult, GmatFlight, solve, solve_burn
from lunarcap.api.plans import available, load_plan, paper_plan
from lunarcap.api.studies import (
    StudyResult,
    burns,
    dispersions,
    engine_trade,
    missed,
    run_study,
)
from lunarcap.errors import InputError, LunarcapError, SolveError
from lunarcap.mission.plan import CapturePlan, PlanError

__all__ = ["BurnSolution", "CapturePlan", "CaptureResult", "GmatFlight", "InputError",
           "LunarcapError", "PlanError", "SolveError", "StudyResult", "available", "burns",
           "dispersions", "engine_trade", "load_plan", "missed", "paper_plan", "run_study",
           "solve", "solve_burn"]
