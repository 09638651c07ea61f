"""A study declared once: its cases' columns, its task, its statuses, its text and JSON forms.

Every study of lunarcap (the engine trade study :mod:`lunarcap.studies.engine_trade.trade`, the
number of burns :mod:`lunarcap.studies.burn_count.counts`, missed thrust
:mod:`lunarcap.studies.missed.cases`, dispersions
:mod:`lunarcap.studies.dispersions.samples`) is one :class:`Study`: the table (key and columns,
glossary names, :class:`lunarcap.studies.campaign.TableFormat`), the Dask task that computes
one case, the statuses a row may have and those that are answers, the words of its
progress bar, the code its rows depend on, the table's JSON-encoded columns and how a row
is decoded for ``--json``, and the text of its report. :meth:`Study.run` runs any of
them through :func:`lunarcap.studies.campaign.run_campaign` (tables, resume, Dask, progress,
Ctrl-C); the command line reports any of them alike
(:meth:`lunarcap.studies.registry.StudyRun.of`, :mod:`lunarcap.cli.studies`). What the
rest of lunarcap knows of a study (its command, options, ``--json`` records and
quantities) is declared beside it, in its folder's ``command.py``
(:mod:`lunarcap.studies.registry`).

The helpers the studies share live here too: :func:`plan_id`, :func:`plan_columns` (the
columns naming a plan in every plan study's table), :func:`check_workers`, and
:func:`waiting_for_table` (how long a run waits for its table, written by another run).
"""

from __future__ import annotations

import hashlib
import json
import os
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from lunarcap.errors import integer
from lunarcap.studies.campaign import CampaignResult, TableFormat, run_campaign


def plan_id(plan) -> str:
    """A short hash of what a plan's solves depend on (its key), for a study's table."""
    return hashlib.sha256(repr(plan.key()).encode()).hexdigest()[:12]


def plan_columns(plan) -> dict:
    """The columns that name a plan in a study's table: plan, plan_id, engine, dynamics."""
    return {"plan": plan.name, "plan_id": plan_id(plan), "thrust_N": plan.engine.thrust_N,
            "isp_s": plan.engine.isp_s, "dynamics": str(plan.dynamics)}


def check_workers(workers) -> int:
    """Number of local Dask workers (an integer >= 1), else InputError."""
    return integer("--workers", workers, 1)


#: How long (s) a study's run waits for another run writing its table: the innermost
#: :func:`waiting_for_table` block of this thread (0 outside any: refused at once).
_TABLE_WAIT_S: ContextVar[float] = ContextVar("lunarcap_table_wait_s", default=0.0)


@contextmanager
def waiting_for_table(wait_s: float) -> Iterator[None]:
    """Within the block, a study's run waits up to ``wait_s`` s for its table to be free.

    A table is written by one run at a time (the lock file beside it,
    :func:`lunarcap.studies.campaign.table_lock`); a run that finds it in use waits this
    long for the other to finish, then refuses (InputError). The wait belongs to the table
    shared, not to a study: :func:`lunarcap.run_study`'s ``lock_wait_s`` sets it for any
    study's run (a book page resuming the table the command line writes waits for it).

    >>> with waiting_for_table(60.0):
    ...     table_wait_s()
    60.0
    >>> table_wait_s()
    0.0
    """
    token = _TABLE_WAIT_S.set(float(wait_s))
    try:
        yield
    finally:
        _TABLE_WAIT_S.reset(token)


def table_wait_s() -> float:
    """How long a run started here and now waits for its table, s (:func:`waiting_for_table`)."""
    return _TABLE_WAIT_S.get()


def json_list(text) -> list:
    """A JSON-encoded list column of a table row (empty for an empty or missing cell)."""
    return json.loads(text) if isinstance(text, str) and text else []


@dataclass(frozen=True)
class Study:
    """One study's declaration (see the module).

    Attributes
    ----------
    name : str
        The table's file name (``<cache>/study/<name>.csv``) and the study's name in its
        run record.
    table : TableFormat
        The case key, the columns in order (glossary names), the text columns.
    task : callable
        The Dask task computing one case from its arguments; it returns the case's row (or
        rows) and records a failure as a status instead of raising.
    statuses : tuple of str
        Every status a row may have; ``ok_statuses``: those that answer the case (the
        command exits 0 when every row has one; a resumed run recomputes the others only
        when asked).
    unit, desc : str
        One case in words ("count"; plural with an s) and the progress bar's label.
    modules : tuple of str
        The study's own modules (relative to the package) whose code, with the numerical
        code, versions its rows (:func:`lunarcap.repro.cache.code_version`).
    decoders : tuple of (column, key, function)
        How a row is shown in ``--json``: ``key`` is ``function(row[column])`` (a column
        that becomes another key is dropped, one that keeps its name stays in place).
    rows_key : str
        The name of the list of rows in the ``--json`` output ("counts", "cases", ...).
    text : callable(result, **context) -> str
        The study's plain-text report (the run's lines are :meth:`run_lines`).
    guarded : bool
        The campaign runs each task inside :func:`lunarcap.studies.campaign.guarded` with the
        cache switch's position of :meth:`run` (an exception becomes an error row); False
        for a task that records its own failures (the trade study's four rows).
    error_rows, longest, affinity : callables, optional
        :func:`lunarcap.studies.campaign.run_campaign`'s: the rows of a case whose task raised,
        the cost estimate that orders submission, the grouping of cases on workers.
    """

    name: str
    table: TableFormat
    task: Callable
    statuses: tuple
    ok_statuses: tuple
    unit: str
    desc: str
    modules: tuple = ()
    decoders: tuple = ()
    rows_key: str = "rows"
    text: Callable | None = None
    guarded: bool = True
    error_rows: Callable | None = None
    longest: Callable | None = None
    affinity: Callable | None = field(default=None)

    @property
    def units(self) -> str:
        """Cases in words, plural ("counts")."""
        return self.unit + "s"

    def default_table_path(self) -> Path:
        """``<cache>/study/<name>.csv``."""
        from lunarcap.repro import paths

        return paths.CACHE / "study" / f"{self.name}.csv"

    def version(self) -> str:
        """The code version the study's rows are computed with."""
        from lunarcap.repro.cache import code_version

        return code_version(*self.modules)

    def run(self, cases: list, out: str | os.PathLike | None = None, *, task=None,
            workers: int = 2, scheduler: str | None = None, progress: bool = True,
            processes: bool = True, use_cache: bool | None = None,
            retry_failed: bool = False, lock_wait_s: float = 0.0,
            describe: dict | None = None) -> CampaignResult:
        """Run (or resume) the study's ``cases`` ((key, args) pairs) on Dask.

        ``out``: the table (default :meth:`default_table_path`); ``task`` replaces the
        study's own (tests); ``use_cache``: the cache switch's position in the tasks (False:
        every case computed again, whatever the table holds); ``lock_wait_s``: at least
        the wait of the :func:`waiting_for_table` block around the call; the rest as
        :func:`lunarcap.studies.campaign.run_campaign`.
        """
        return run_campaign(self, cases, out if out is not None else self.default_table_path(),
                            task=task, workers=workers, scheduler=scheduler,
                            progress=progress, processes=processes,
                            recompute=use_cache is False, use_cache=use_cache,
                            retry_failed=retry_failed,
                            lock_wait_s=max(float(lock_wait_s), table_wait_s()),
                            describe=describe)

    def decoded(self, row: dict) -> dict:
        """A table row as ``--json`` shows it (see ``decoders``)."""
        out = {k: v for k, v in row.items()
               if not any(k == col and key != col for col, key, _ in self.decoders)}
        for col, key, fn in self.decoders:
            out[key] = fn(row.get(col))
        return out

    def decode(self, row: dict, key: str):
        """One decoded value of a table row: ``decoded(row)[key]`` alone."""
        col, _, fn = next(d for d in self.decoders if d[1] == key)
        return fn(row.get(col))

    def to_json(self, result: CampaignResult, head: dict, extra: dict | None = None) -> dict:
        """The ``--json`` document: ``head``, the table and run, ``extra``, the rows."""
        rows = result.table.to_dict("records")
        return {**head, "table": str(result.path), "run": result.run, **(extra or {}),
                self.rows_key: [self.decoded(r) for r in rows]}

    def answered(self, rows) -> bool:
        """True if every row's status answers its case (the command's exit status 0)."""
        return all(r["status"] in self.ok_statuses for r in rows)

    def run_lines(self, result: CampaignResult, failed: int | None = None) -> list:
        """The report's last lines: what was computed or reused, the wall time, the table.

        ``failed``: a count of failed cases to name as well (the trade study's engines).
        """
        run = result.run
        bad = "" if failed is None else f", {failed} failed"
        return [f"{run['computed']} {self.unit}(s) computed, {run['reused']} taken from the "
                f"table{bad}; wall time {run['wall_s']:.1f} s ({run['scheduler']}, "
                f"{run['workers']} worker(s), cache: {run['cache']})",
                f"table: {result.path}"]
