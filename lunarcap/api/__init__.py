"""lunarcap's public Python API: plans, solves, studies, exports, as the command line has them.

Everything here is importable from :mod:`lunarcap` itself (``lunarcap.__all__``):

* plans: :func:`load_plan` (a file, a packaged name, a mapping, with changes),
  :func:`paper_plan`, :func:`available`; a plan is a :class:`CapturePlan`, changed by its
  ``with_*`` methods;
* solves: :func:`solve` (every burn, verified: a :class:`CaptureResult`, which exports the
  capture (OEM, SPK, GMAT script, ...) and flies it in GMAT: :class:`GmatFlight`) and
  :func:`solve_burn` (one burn: a :class:`BurnSolution`) and :func:`solve_joint` (every
  burn in one NLP minimising the total delta-V: a :class:`JointSolution`);
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

#: Where each public name is defined (imported when first asked for: the command line and
#: the Dask workers import this package without paying for the plans' and studies' modules).
_WHERE = {
    "lunarcap.api.capture": ("BurnSolution", "CaptureResult", "GmatFlight", "solve",
                             "solve_burn"),
    "lunarcap.api.joint": ("JointSolution", "solve_joint"),
    "lunarcap.api.plans": ("available", "load_plan", "paper_plan"),
    "lunarcap.api.studies": ("StudyResult", "burns", "dispersions", "engine_trade", "missed",
                             "run_study"),
    "lunarcap.errors": ("InputError", "LunarcapError", "SolveError"),
    "lunarcap.mission.plan": ("CapturePlan", "PlanError"),
}
_MODULE = {name: module for module, names in _WHERE.items() for name in names}

__all__ = sorted(_MODULE)


def __getattr__(name):
    """A public name, imported from its module when first asked for."""
    if name not in _MODULE:
        raise AttributeError(f"module 'lunarcap.api' has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(_MODULE[name]), name)
    globals()[name] = value
    return value


def __dir__():
    """The package's names and the public API's."""
    return sorted(set(globals()) | set(__all__))
