"""The study commands: each registered study run from its parsed arguments and reported.

Every study (:data:`lunarcap.studies.registry.STUDIES`) becomes a command through
:func:`command`: the plan its arguments name (overrides applied), the run its
``prepare`` makes of them, then :func:`report`: the run, through the public API's
:func:`lunarcap.api.studies.run_prepared` as :func:`lunarcap.run_study` runs it (Ctrl-C
is one line, status 130, the finished cases kept in its table), the result's ``--json``
document or its text, and status 0 when every case has an answer, 3 otherwise.
"""

from __future__ import annotations

import sys

from lunarcap.api.studies import run_prepared
from lunarcap.cli.args import plan_from_args
from lunarcap.studies.registry import StudyRun


def _resumable(run, unit: str):
    """``(run(), None)``, or ``(None, 130)`` after Ctrl-C.

    On Ctrl-C one line says that the finished ``unit`` are in the study's table, which
    keeps every finished case, so running the same command again resumes.
    """
    try:
        return run(), None
    except KeyboardInterrupt:
        print(f"lunarcap: interrupted; finished {unit} are in the table, run the same command "
              "again to resume", file=sys.stderr)
        return None, 130


def report(args, study_run: StudyRun, name: str | None = None, plan=None) -> int:
    """Run ``study_run`` and report it (``--json`` or text); the exit status.

    ``name``, ``plan``: the study's command and plan, kept with the result.
    """
    res, status = _resumable(lambda: run_prepared(study_run, name, plan), study_run.units)
    if status:
        return status
    print(res.to_json() if getattr(args, "json", False) else res.text())
    return 0 if res.answered else 3


def run_study(args, study, run, head: dict | None = None, extra=None, **context) -> int:
    """Run any study (a :class:`lunarcap.studies.study.Study`) and report it; the exit status.

    ``run()``: the study's run; then its ``--json`` document (``head``, the table and run,
    ``extra(result)``, the decoded rows) or its text (``study.text(result, **context)``):
    :meth:`lunarcap.studies.registry.StudyRun.of` and :func:`report`.
    """
    return report(args, StudyRun.of(study, run, head, extra, **context))


def command(study):
    """The function running the registered ``study`` (a ``StudyCommand``) from its arguments."""
    def run(args) -> int:
        plan = plan_from_args(args) if study.plan else None
        return report(args, study.prepare(args, plan), study.name, plan)

    run.__doc__ = f"``lunarcap {study.name}``: {study.help}."
    return run
