"""lunarcap: finite-burn lunar capture, reproducing and extending Song et al. (2011).

Song, Park, Kim, Lee & Sim (2011), "Analysis of Delta-V Losses During Lunar Capture
Sequence Using Finite Thrust", J. Astron. Space Sci. 28(3) 203-216.

The public API (:mod:`lunarcap.api`) is importable from here: load a plan and change it,
solve and verify it, run a study on it, export it and fly it in GMAT::

    import lunarcap
    plan = lunarcap.load_plan("two-burn-8h", thrust_N=440, mass_kg=900)
    res = lunarcap.solve(plan)
    res.to_frame(); res.plot(); res.export("out/")

Its names are imported when first used, so that ``import lunarcap`` (and the command
line, and every Dask worker) pays for none of them.
"""

__all__ = ["__version__", "BurnSolution", "CapturePlan", "CaptureResult", "GmatFlight",
           "InputError", "JointSolution", "LunarcapError", "PlanError", "SolveError",
           "StudyResult", "available", "burns", "dispersions", "engine_trade", "load_plan",
           "missed", "paper_plan", "run_study", "solve", "solve_burn", "solve_joint"]


def __getattr__(name):
    """A public name, from :mod:`lunarcap.api` (or the installed metadata) when first asked."""
    if name == "__version__":
        from importlib.metadata import PackageNotFoundError, version

        try:
            return version("lunarcap")
        except PackageNotFoundError:  # a source tree without installation
            return "0+unknown"
    if name in __all__:
        import importlib

        value = getattr(importlib.import_module("lunarcap.api"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'lunarcap' has no attribute {name!r}")


def __dir__():
    """The module's names and the public API's."""
    return sorted(set(globals()) | set(__all__))
