"""The studies, registered once: what the command line, the schemas and the glossary know of each.

A study is one folder of :mod:`lunarcap.studies` plus one line of :data:`STUDIES`. Its
folder holds the campaign (a module with its :class:`lunarcap.studies.study.Study`: the
table, the task, the statuses, the text), a ``command.py`` declaring its
:class:`StudyCommand` (the command's name, help and options, how parsed arguments become
a run, its ``--json`` records), and, if it reports quantities of its own, a
``glossary.yaml`` (:mod:`lunarcap.quantities`). The command line adds one subcommand per
registered study (:mod:`lunarcap.cli`), :mod:`lunarcap.schemas` one JSON Schema per study
that declares records, the benchmark lists them.

A ``command.py`` imports nothing heavy at module level (its campaign module only inside
``prepare``): the command line lists every study, and ``lunarcap plan`` should not pay
for importing pandas and Dask to do so. This is also why a study's command is declared
apart from its :class:`~lunarcap.studies.study.Study`, which lives with the campaign.

Examples
--------
>>> list(studies())
['study', 'burns', 'missed', 'dispersions']
>>> studies()["burns"].dask, sorted(studies()["burns"].records)
('count', ['burns', 'burns_count', 'burns_count_burn'])
"""

from __future__ import annotations

import argparse
import importlib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

#: The studies, in the order the command line lists them: ``"module:attribute"`` of each
#: study's :class:`StudyCommand`. One registration line per study.
STUDIES = [
    "lunarcap.studies.engine_trade.command:COMMAND",
    "lunarcap.studies.burn_count.command:COMMAND",
    "lunarcap.studies.missed.command:COMMAND",
    "lunarcap.studies.dispersions.command:COMMAND",
]

#: What a help text says of an option that overrides the plan's value.
PLAN_DEFAULT = "default: the plan's"


@dataclass(frozen=True)
class StudyRun:
    """A study run as the command line asked for it, and how its result is reported.

    Attributes
    ----------
    run : callable() -> result
        The run (a campaign: resumable, Ctrl-C leaves the finished cases in its table).
    units : str
        Its cases in words, plural ("samples"), for the line printed after Ctrl-C.
    document : callable(result) -> dict
        The ``--json`` document.
    text : callable(result) -> str
        The plain-text report.
    answered : callable(result) -> bool
        True if every case has an answer (the command exits 0; else 3).
    """

    run: Callable[[], Any]
    units: str
    document: Callable[[Any], dict]
    text: Callable[[Any], str]
    answered: Callable[[Any], bool]

    @classmethod
    def of(cls, study, run: Callable, head: dict | None = None, extra: Callable | None = None,
           **context) -> StudyRun:
        """The run of a :class:`lunarcap.studies.study.Study`, reported as the study declares.

        ``run()``: the study's campaign; the ``--json`` document is ``head``, the table and
        run, ``extra(result)`` and the decoded rows (:meth:`Study.to_json`); the text is
        ``study.text(result, **context)``; answered when every row's status is one of
        ``study.ok_statuses``.
        """
        return cls(run, study.units,
                   lambda res: study.to_json(res, head or {}, extra(res) if extra else None),
                   lambda res: study.text(res, **context),
                   lambda res: study.answered(res.table.to_dict("records")))


@dataclass(frozen=True)
class StudyCommand:
    """Everything outside its folder needs to know of a study (see the module).

    Attributes
    ----------
    name : str
        The command: ``lunarcap <name>``.
    help : str
        Its line in ``lunarcap --help``.
    options : callable(argparse.ArgumentParser)
        Adds the study's own options, between the plan's options (if ``plan``) and the
        Dask options (if ``dask``).
    prepare : callable(args, plan) -> StudyRun
        The run the parsed arguments ask for (``plan``: the plan named by the arguments,
        overrides applied, or None without ``plan``). Bad input raises
        :class:`lunarcap.errors.InputError` here, before any work.
    plan : bool
        The command takes a PLAN and the options overriding its fields (``--thrust``,
        ``--isp``, ``--dynamics``, ...) and ``--json``.
    dask : str or None
        The case in words ("count") if the command takes the shared Dask options
        (``--workers``, ``--scheduler``, ``--out``, ``--no-cache``, ``--no-progress``);
        None for a study that declares its own.
    signed : tuple of str
        Its options whose value may begin with '-' (a negative number, a list of them).
    records : dict
        Its ``--json`` records, ``{record: keys}`` as :data:`lunarcap.schemas.RECORDS`
        (a key is a glossary name, ``(name, kind)``, or ``{name: record}`` for a nested
        record); the one named ``name`` is the document. No records: no schema.
    arrays : frozenset of str
        Its records that are arrays of records where they appear.
    run_keys : tuple of str
        Keys its run record adds (``describe`` of :meth:`Study.run`) that the shared run
        record (:data:`lunarcap.schemas.RUN`) lacks.
    glossary : str or dict or None
        Its own quantities: a glossary file beside the module declaring the study
        (``"glossary.yaml"``, the format of :mod:`lunarcap.quantities`), or its entries.
    """

    name: str
    help: str
    options: Callable[[argparse.ArgumentParser], None]
    prepare: Callable[[argparse.Namespace, Any], StudyRun]
    plan: bool = True
    dask: str | None = None
    signed: tuple = ()
    records: dict = field(default_factory=dict)
    arrays: frozenset = frozenset()
    run_keys: tuple = ()
    glossary: str | dict | None = None


def _load(entry: str):
    """The :class:`StudyCommand` and the module of a :data:`STUDIES` entry."""
    module_name, _, attribute = entry.partition(":")
    module = importlib.import_module(module_name)
    return getattr(module, attribute or "COMMAND"), module


def studies() -> dict:
    """``{name: StudyCommand}`` of every registered study, in :data:`STUDIES`' order.

    Importing a study's ``command`` module is cheap (see the module). ValueError if two
    studies have one name.
    """
    out = {}
    for entry in STUDIES:
        command, _ = _load(entry)
        if command.name in out:
            raise ValueError(f"two studies are registered as {command.name!r}: {entry}")
        out[command.name] = command
    return out


def merge_quantities() -> None:
    """Merge every registered study's own quantities into the glossary (once each).

    The packaged studies' files are read with the glossary already (merged once by path,
    :data:`lunarcap.quantities.STUDY_FILES`); a study from elsewhere joins it here, which
    the schemas call before naming a key. ValueError if a name is defined twice.
    """
    from lunarcap import quantities as Q

    for entry in STUDIES:
        command, module = _load(entry)
        if isinstance(command.glossary, str):
            Q.merge_file(Path(module.__file__).resolve().parent / command.glossary)
        elif command.glossary:
            Q.merge(command.glossary, f"study {command.name} ({module.__name__})")
