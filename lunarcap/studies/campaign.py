"""Studies as campaigns of independent cases on Dask: a table, resumable, logged, with progress.

The machinery every study (:class:`lunarcap.studies.study.Study`: the engine trade study,
the number of burns, missed thrust, dispersions) runs on:

* **Execution**: one Dask task per case. By default a
  :class:`dask.distributed.LocalCluster` of ``workers`` processes, one thread each;
  ``scheduler="tcp://host:port"`` uses an existing cluster instead (its workers need
  lunarcap importable). Solves inside the tasks are also cached on disk by joblib
  (:mod:`lunarcap.repro.cache`).
* **Table**: one CSV file, appended as each case completes (rewritten to a temporary
  file and moved into place, so it is never half-written), each row carrying the code
  version it was computed with. A rerun skips every case already in the table for the
  current version (so an interrupted study resumes where it stopped); failed cases are
  kept, not retried unless asked.
* **Runs log**: each run appends its wall time, counts and the machine's load to
  ``<table stem>.runs.json`` next to the table, also when interrupted.
* **Lock**: a lock file next to the table keeps two runs from writing it at once.
* **Output path**: checked before any work: a path that cannot be written (its directory
  cannot be created, or is not writable) is an :class:`~lunarcap.errors.InputError`.
* **Progress**: a tqdm bar on stderr.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import json
import logging
import os
import socket
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pandas as pd

from lunarcap.errors import InputError, LunarcapError
from lunarcap.repro import paths


# ====================================================================== paths and locks
def check_output_path(path: str | os.PathLike, what: str = "--out") -> Path:
    """The table path, its directory created; InputError if it cannot be written.

    Checks, before any work: the path is not a directory, its directory exists or can be
    created, and a file can be created in it (the table's temporary file and lock).
    """
    path = Path(path).expanduser()
    if path.is_dir():
        raise InputError(f"{what} {path} is a directory: give a file name (.csv)")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with paths.atomic_path(path.with_name(f".{path.name}.probe")) as tmp:
            tmp.write_bytes(b"")
        path.with_name(f".{path.name}.probe").unlink(missing_ok=True)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise InputError(f"{what} {path}: cannot write in {path.parent} ({reason})") \
            from None
    if path.exists() and not os.access(path, os.W_OK):
        raise InputError(f"{what} {path}: the file is not writable")
    return path


@contextlib.contextmanager
def table_lock(path: Path, wait_s: float = 0.0, what: str = "table"):
    """Hold an exclusive lock on ``.<table>.lock`` next to ``path``.

    Waits up to ``wait_s`` seconds for another run to release it, then raises InputError.
    A lock file that cannot be created is an InputError too.
    """
    import fcntl

    path = Path(path)
    lock = path.with_name(f".{path.name}.lock")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        fh = open(lock, "w")
    except OSError as exc:
        raise InputError(f"the {what} {path} cannot be written: no lock file {lock} "
                         f"({exc.strerror or type(exc).__name__})") from None
    deadline = time.monotonic() + max(0.0, float(wait_s))
    try:
        while True:
            try:
                fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() >= deadline:
                    raise InputError(f"the {what} {path} is being written by another "
                                     f"run; wait for it to finish or give another --out") \
                        from None
                time.sleep(1.0)
        yield
    finally:
        fh.close()


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


# ====================================================================== runs log
def runs_path(table: str | os.PathLike) -> Path:
    """The run log next to a table: ``<stem>.runs.json``."""
    table = Path(table)
    return table.with_name(f"{table.stem}.runs.json")


def append_run(path: Path, record: dict) -> None:
    """Append one run record to the log of the table at ``path``."""
    rp = runs_path(path)
    runs = []
    if rp.exists():
        try:
            runs = json.loads(rp.read_text(encoding="utf-8"))
            if not isinstance(runs, list):
                raise ValueError("not a list")
        except ValueError:
            os.replace(rp, rp.with_suffix(".json.unreadable"))
            runs = []
    runs.append(record)
    paths.write_text_atomic(rp, json.dumps(runs, indent=1, default=str) + "\n")


def read_runs(table: str | os.PathLike) -> list[dict]:
    """The run records of a table (empty if none)."""
    rp = runs_path(table)
    try:
        runs = json.loads(rp.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return []
    return runs if isinstance(runs, list) else []


def loadavg() -> float | None:
    """1-minute load average of the machine (None where unavailable)."""
    try:
        return round(os.getloadavg()[0], 2)
    except (AttributeError, OSError):
        return None


def cache_description() -> str:
    """Where solves are cached (or that caching is off), for the runs log."""
    from lunarcap.repro import cache

    loc = cache.location()
    return "disabled (the cache switch is off)" if loc is None else f"joblib at {loc}"


def guarded(compute, use_cache: bool | None = None) -> tuple[dict | None, dict | None]:
    """Run ``compute()`` in a task: ``(result, None)``, or ``(None, error row)``.

    ``use_cache``: the cache switch's position shipped with the task (a worker is another
    process or thread: :func:`lunarcap.repro.cache.position` at submission; None: this
    thread's position); the call runs inside ``caching(use_cache)``. An exception becomes the row
    ``{"status": "error", "error": ...}``: a bug in one case must not lose the rest of a
    study.
    """
    from lunarcap.repro.cache import caching, position

    try:
        with caching(position(use_cache)):
            return compute(), None
    except Exception as exc:
        return None, {"status": "error", "error": f"{type(exc).__name__}: {exc}"}


# ====================================================================== Dask
#: Environment variable with the address of a Dask scheduler that every campaign given no
#: ``scheduler`` uses instead of starting a local cluster of its own. The book's build
#: sets it (:func:`lunarcap.bookbuild.execution.study_cluster`): the studies of all its pages
#: share two worker processes, which start once and build each NLP shape once for the
#: whole book, not once per study and worker.
SCHEDULER_ENV = "LUNARCAP_DASK_SCHEDULER"


def check_scheduler(scheduler) -> str | None:
    """The scheduler address (None: a local cluster); InputError if it is not text."""
    if scheduler is not None and (not isinstance(scheduler, str) or not scheduler.strip()):
        raise InputError(f"scheduler must be an address such as tcp://host:8786, "
                         f"got {scheduler!r}")
    return scheduler


@contextlib.contextmanager
def dask_client(workers: int, scheduler: str | None, processes: bool = True):
    """A Dask client: of an existing scheduler, or of a local cluster of ``workers``."""
    from dask.distributed import Client, LocalCluster

    if scheduler:
        try:
            client = Client(scheduler, timeout="20s")
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            raise InputError(f"cannot connect to the Dask scheduler {scheduler!r}: {exc}") \
                from None
        try:
            yield client
        finally:
            client.close()
        return
    cluster = client = None
    if processes:  # started here, not by the first worker's thread (see _block_sigint_here)
        from multiprocessing import resource_tracker

        resource_tracker.ensure_running()
    try:
        with _sigint_deferred():
            # no dashboard; the scheduler's HTTP (health) server on a free port, not 8787
            cluster = LocalCluster(n_workers=0, threads_per_worker=1, processes=processes,
                                   dashboard_address=None,
                                   scheduler_kwargs={"dashboard_address": ":0"},
                                   silence_logs=logging.ERROR)
            cluster.sync(_block_sigint_here)  # in the thread that will start the workers
        client = Client(cluster)
        cluster.scale(workers)
        try:
            client.wait_for_workers(workers, timeout=WORKER_START_TIMEOUT_S)
        except TimeoutError:
            raise LunarcapError(f"the local Dask cluster did not start {workers} worker(s) "
                                f"within {WORKER_START_TIMEOUT_S:g} s") from None
        yield client
    except KeyboardInterrupt:
        _close_quietly(client, cluster)
        raise
    finally:
        for c in (client, cluster):
            if c is not None:
                c.close()


#: How long a local cluster may take to start its workers, s.
WORKER_START_TIMEOUT_S = 300.0
#: Loggers that report a cluster's shutdown (silenced when it follows Ctrl-C).
_SHUTDOWN_LOGGERS = ("distributed", "tornado", "asyncio")


async def _block_sigint_here() -> None:
    """Block SIGINT in the calling thread: run in a local cluster's event-loop thread.

    That thread starts the worker processes (through threads of its own, which inherit
    its signal mask), and a process keeps the mask of the thread that started it, across
    exec. The workers so never see the SIGINT a terminal sends to the whole process group
    on Ctrl-C: only this process is interrupted, and closes the cluster
    (:func:`_close_quietly`). Interrupted themselves, workers die printing their
    tracebacks (about 30 lines each, the nannies add more). This process's main thread
    keeps SIGINT: a blocked signal goes to a thread that does not block it.

    multiprocessing's resource tracker, when a spawn starts it, unblocks SIGINT in the
    spawning thread afterwards (CPython bpo-33613 blocks it around its own spawn, the
    same way); :func:`dask_client` starts it beforehand from the main thread.
    """
    import signal

    signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})


@contextlib.contextmanager
def _sigint_deferred():
    """Ctrl-C within the block is raised (as KeyboardInterrupt) at its end, not inside.

    Around a local cluster's construction, so that a cluster object exists to be closed
    quietly when Ctrl-C comes while it starts. Outside the main thread, nothing changes.
    """
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    seen = []
    old = signal.signal(signal.SIGINT, lambda signum, frame: seen.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, old)
    if seen:
        raise KeyboardInterrupt


def _close_quietly(client, cluster) -> None:
    """Close a local cluster after Ctrl-C without a line on stderr from any process.

    While the workers are stopped (they never saw the SIGINT, see
    :func:`_block_sigint_here`), the scheduler and the nannies, in this process, log the
    cancelled tasks and lost connections (``distributed.nanny - ERROR`` with a
    traceback, about 13 lines). Those loggers are silenced for the rest of the process,
    which is ending; a failure to close is not reported either (the workers end with this
    process: a nanny's worker exits when its parent does). The close takes a few seconds
    (a busy worker is stopped after its nanny's timeout); SIGINT is ignored meanwhile.
    """
    import signal
    import threading

    for name in _SHUTDOWN_LOGGERS:
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
    main = threading.current_thread() is threading.main_thread()
    old = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
    try:  # a second Ctrl-C would interrupt the close with a traceback: ignored meanwhile
        for c in (client, cluster):
            with contextlib.suppress(Exception):
                if c is not None:
                    c.close(timeout=10)
    finally:
        if main:
            signal.signal(signal.SIGINT, old)


# ====================================================================== the table
@dataclass(frozen=True)
class TableFormat:
    """Columns of a campaign's CSV table: its case key, and all columns in order.

    ``row_key``: the columns that tell apart the rows of one case when its task returns
    several (the trade study's ``part``: LOI1, LOI2, LOI3, sequence); empty for one row
    per case. ``name``: what the table is called in messages.
    """

    key: tuple
    columns: tuple
    text_columns: tuple = ()
    row_key: tuple = ()
    name: str = "table of this study"

    def case_key(self, row) -> tuple:
        """The key of a row (or a case's key values) as comparable text."""
        out = []
        for k in self.key:
            v = row[k]
            out.append(f"{float(v):.6g}" if isinstance(v, (int, float)) and
                       not isinstance(v, bool) else str(v))
        return tuple(out)


def read_table(path: str | os.PathLike, fmt: TableFormat) -> pd.DataFrame:
    """The table at ``path`` (empty with ``fmt.columns`` if absent).

    Raises InputError if the path is a directory, unreadable, or not such a table.
    """
    path = Path(path)
    if path.is_dir():
        raise InputError(f"the {fmt.name} {path} is a directory: give a file name (.csv)")
    if not path.exists() or path.stat().st_size == 0:
        return pd.DataFrame(columns=list(fmt.columns))
    try:
        df = pd.read_csv(path, dtype={c: str for c in ("status", "code_version", "worker",
                                                          "error", *fmt.text_columns)})
    except (OSError, UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError,
            ValueError) as exc:
        raise InputError(f"cannot read the {fmt.name} {path}: {exc}") from None
    missing = [c for c in (*fmt.key, *fmt.row_key, "status", "code_version")
               if c not in df.columns]
    if missing:
        raise InputError(f"{path} is not a {fmt.name} (no column {', '.join(missing)}); "
                         f"give another --out")
    for c in ("error", "worker", *fmt.text_columns):
        if c in df:
            df[c] = df[c].fillna("")
    return df.reindex(columns=list(fmt.columns))


def set_aside_if_stale(path: Path, fmt: TableFormat) -> Path | None:
    """Rename a table of lunarcap's cache that lacks this study's key columns; its new name.

    A table below :data:`lunarcap.repro.paths.CACHE` (the book's studies, the default
    ``--out``) is lunarcap's own: one written by a version whose cases had other keys
    cannot be resumed, so it is renamed ``<name>.stale-<UTC time>.csv`` beside it (kept,
    not deleted) and the study starts a new table, saying so on stderr. A table anywhere
    else is the user's: :func:`read_table` refuses it. None when nothing was renamed.
    The line goes to the process's own stderr, not to a notebook cell's output.
    """
    path = Path(path)
    if not path.is_file() or not path.resolve().is_relative_to(paths.CACHE.resolve()):
        return None
    try:
        header = pd.read_csv(path, nrows=0).columns
    except (OSError, UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError,
            ValueError):
        return None
    missing = [c for c in (*fmt.key, *fmt.row_key, "status", "code_version")
               if c not in header]
    if not missing:
        return None
    stamp = _dt.datetime.now(_dt.timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    aside = path.with_name(f"{path.stem}.stale-{stamp}{path.suffix}")
    path.rename(aside)
    print(f"lunarcap: {path} was written by an older lunarcap (no column "
          f"{', '.join(missing)}); kept as {aside.name}, starting a new table",
          file=sys.__stderr__ or sys.stderr)  # a terminal, or a notebook kernel's log
    return aside


def append_rows(path: str | os.PathLike, rows: list[dict], columns) -> None:
    """Append rows to the table atomically (rewrite to a temporary file, then rename).

    A table whose header is not ``columns`` (written by an older version) is rewritten
    with ``columns`` first, so that every line has the header's fields.
    """
    path = Path(path)
    old = path.read_bytes() if path.exists() else b""
    if old and old.split(b"\n", 1)[0].decode("utf-8", "replace").strip().split(",") != \
            list(columns):
        # a table written with other columns (an older version): rewritten with these
        prev = pd.read_csv(path, dtype=str, keep_default_na=False)
        old = prev.reindex(columns=list(columns)).to_csv(index=False).encode()
    if old and not old.endswith(b"\n"):
        old += b"\n"
    text = pd.DataFrame(rows).reindex(columns=list(columns)).to_csv(index=False,
                                                                    header=not old)
    with paths.atomic_path(path) as tmp:
        tmp.write_bytes(old + text.encode())
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp's 0600 would hide the table


def replace_case_rows(path: str | os.PathLike, rows: list[dict], fmt: TableFormat,
                      version: str) -> None:
    """Write a recomputed case's rows in place of its earlier rows of ``version``.

    The rows of every other case (and this case's rows of other code versions) are kept
    as written; the new rows go at the end. Atomic, as :func:`append_rows`. Without this,
    ``--no-cache`` (compute every case again) after an interrupted run appended a second
    row for each case the first run had finished.
    """
    path = Path(path)
    old = pd.read_csv(path, dtype=str, keep_default_na=False) if path.exists() and \
        path.stat().st_size else pd.DataFrame(columns=list(fmt.columns), dtype=str)
    key = rows[0]
    same = pd.Series(True, index=old.index)
    for k in fmt.key:
        same &= old[k].map(lambda text, v=key[k]: _key_text(text, v)) == _key_text(key[k], key[k])
    same &= old["code_version"] == version
    text = pd.concat([old[~same].reindex(columns=list(fmt.columns)),
                      pd.DataFrame(rows).reindex(columns=list(fmt.columns))])
    with paths.atomic_path(path) as tmp:
        tmp.write_bytes(text.to_csv(index=False).encode())
        os.chmod(tmp, 0o666 & ~_umask())


def _key_text(value, like) -> str:
    """A key value as :meth:`TableFormat.case_key` writes it, read as the type of ``like``."""
    if isinstance(like, (int, float)) and not isinstance(like, bool):
        try:
            return f"{float(value):.6g}"
        except (TypeError, ValueError):
            return str(value)
    return str(value)


def latest(table: pd.DataFrame, fmt: TableFormat, version: str) -> dict:
    """The rows of the last attempt at every case computed with ``version``.

    Returns ``{case key: [row dict, ...]}`` (one row per case, or one per ``row_key`` in
    the order the task returned them). An attempt's rows are appended together, so a
    row key seen again for a case starts its next attempt.
    """
    out = {}
    if table.empty:
        return out
    for row in table[table.code_version.astype(str) == version].to_dict("records"):
        ck, rk = fmt.case_key(row), tuple(str(row[k]) for k in fmt.row_key)
        attempt = out.get(ck)
        if attempt is None or rk in attempt:
            attempt = out[ck] = {}
        attempt[rk] = row
    return {ck: list(rows.values()) for ck, rows in out.items()}


@dataclass
class CampaignResult:
    """What :func:`run_campaign` returns: the cases' rows (in case order), path, run record."""

    table: pd.DataFrame
    path: Path
    run: dict


def run_campaign(study, cases: list, out: str | os.PathLike, *, task=None, workers: int = 2,
                 scheduler: str | None = None, progress: bool = True,
                 retry_failed: bool = False, lock_wait_s: float = 0.0, processes: bool = True,
                 describe: dict | None = None, recompute: bool = False,
                 use_cache: bool | None = None) -> CampaignResult:
    """Run (or resume) a study's campaign: one Dask task per case not yet in the table.

    Parameters
    ----------
    study : lunarcap.studies.study.Study
        The study's declaration: its table format, task, code version, the statuses that
        answer a case, the progress bar's words, and optionally the rows of a task that
        raised (``error_rows``, default: the key with ``status`` "task error" and the
        message), an estimate of each case's cost (``longest``: cases are submitted in
        decreasing order of it, so few workers do not end on one long case; the table keeps
        the order of ``cases``) and a grouping of cases (``affinity``: cases solving NLPs of
        the same shapes go to one worker, which builds those NLPs once,
        :func:`assign_workers`).
    cases : list of (key, args)
        ``key`` a dict of the key columns (scalars), ``args`` the task's arguments.
    out : path of the CSV table (checked writable before any work)
    task : callable(*args) -> dict, or list of dict with the table's ``row_key``
        Replaces the study's task (tests). A task records a failure in its rows
        (``status``) rather than raise; one that raises (or whose worker dies) is
        recorded by ``error_rows``.
    workers, scheduler, processes : the cluster (see :func:`dask_client`); without
        ``scheduler``, the one named by the environment variable :data:`SCHEDULER_ENV`
        if set (``workers`` and ``processes`` are then those of that cluster)
    progress : show a tqdm bar on stderr
    retry_failed : recompute cases whose row's status does not answer them
    lock_wait_s : how long to wait for another run writing the same table
    describe : added to the run record
    recompute : compute every case again, whatever the table holds
    use_cache : the cache switch's position for the tasks of a study whose ``guarded`` is
        true: each runs inside :func:`guarded` (an exception becomes its error row)

    Raises
    ------
    InputError
        An unusable table path, a table in use, an unreachable scheduler: before any case.
    """
    fmt, version, ok_statuses = study.table, study.version(), study.ok_statuses
    longest = study.longest
    path = check_output_path(out)
    scheduler = check_scheduler(scheduler or os.environ.get(SCHEDULER_ENV) or None)
    info = {"t0": time.perf_counter(), "scheduler": scheduler, "version": version,
            "started": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC"),
            "load_start": loadavg(), "describe": describe or {}}
    counts = {"computed": 0, "failed": 0}
    state = {"cluster_s": 0.0, "workers": 0, "interrupted": False}
    keys = [fmt.case_key(k) for k, _ in cases]
    with table_lock(path, lock_wait_s, what=fmt.name):
        set_aside_if_stale(path, fmt)
        have = latest(read_table(path, fmt), fmt, version)
        todo = _todo(cases, keys, have, recompute, retry_failed, ok_statuses, longest)

        def record() -> dict:
            return _record(path, todo, len(cases), state, counts, info)

        try:
            if todo:
                tc = time.perf_counter()
                with dask_client(workers, scheduler, processes) as client:
                    _start_s(state, tc, client, workers)
                    where = assign_workers(client, todo, study.affinity, longest)
                    _compute(client, task or study.task, todo, fmt, version, path, counts,
                             progress, f"{study.desc} ({state['workers']} worker"
                             f"{'s' * (state['workers'] > 1)})", study.unit, ok_statuses,
                             study.error_rows or _task_error_row, set(have), where,
                             (use_cache,) if study.guarded else None)
        except KeyboardInterrupt:
            state["interrupted"] = True
            record()
            raise
        run = record()
        have = latest(read_table(path, fmt), fmt, version)
    rows = [row for ck in keys for row in have.get(ck, [])]
    return CampaignResult(pd.DataFrame(rows, columns=list(fmt.columns)), path, run)


def _record(path: Path, todo: list, n_cases: int, state: dict, counts: dict,
            info: dict) -> dict:
    """Append the record of a campaign run to its runs log; return it."""
    run = {"started_utc": info["started"],
           "wall_s": round(time.perf_counter() - info["t0"], 2),
           "cluster_start_s": round(state["cluster_s"], 2),
           "scheduler": (info["scheduler"] or "LocalCluster") if todo
           else "none (all in the table)",
           "workers": state["workers"] if todo else 0, "cases": n_cases,
           "computed": counts["computed"], "reused": n_cases - len(todo),
           "failed_computed": counts["failed"], "interrupted": state["interrupted"],
           "table": str(path), "cache": cache_description(), "code_version": info["version"],
           "host": socket.gethostname(), "cpu_count": os.cpu_count(),
           "load_avg_1min_start": info["load_start"], "load_avg_1min_end": loadavg(),
           **info["describe"]}
    append_run(path, run)
    return run


def _todo(cases, keys, have, recompute, retry_failed, ok_statuses, longest) -> list:
    """The cases to compute (see :func:`run_campaign`), longest first if ``longest``."""
    todo = [(k, a) for (k, a), ck in zip(cases, keys)
            if recompute or ck not in have
            or (retry_failed and any(r["status"] not in ok_statuses for r in have[ck]))]
    if longest is not None:
        todo.sort(key=lambda case: -longest(case[0]))
    return todo


def _start_s(state: dict, tc: float, client, workers: int) -> None:
    """Record how long the cluster took to start and how many workers it has."""
    state["cluster_s"] = time.perf_counter() - tc
    state["workers"] = len(client.scheduler_info().get("workers", {})) or workers


def assign_workers(client, todo: list, affinity=None, longest=None) -> list:
    """The worker each case of ``todo`` should run on (None: any), one per case.

    Cases are grouped by ``affinity(key)``; the groups, largest first (the sum of
    ``longest(key)``, else the number of cases), go each to the worker with the least
    work assigned so far. Without ``affinity``, or with one worker, every case may run
    anywhere.
    """
    addrs = sorted(client.scheduler_info().get("workers", {}))
    if affinity is None or len(addrs) < 2:
        return [None] * len(todo)
    cost: dict = {}
    for key, _ in todo:
        g = affinity(key)
        cost[g] = cost.get(g, 0.0) + (float(longest(key)) if longest else 1.0)
    load = dict.fromkeys(addrs, 0.0)
    home = {}
    for g in sorted(cost, key=lambda g: -cost[g]):
        home[g] = min(addrs, key=lambda a: load[a])
        load[home[g]] += cost[g]
    return [home[affinity(key)] for key, _ in todo]


def _compute(client, task, todo, fmt, version, path, counts, progress, desc, unit,
             ok_statuses, error_rows, present=frozenset(), where=None, guard=None) -> None:
    """Submit one task per case; append each case's rows as its task completes.

    ``present``: case keys with rows of ``version`` in the table already (a case
    recomputed on request, or retried): their rows are replaced, not duplicated.
    ``where``: per case, the worker it should run on (None: any; see
    :func:`assign_workers`). ``guard``: ``(use_cache,)`` to run each task inside
    :func:`guarded`, None to run it as it is.
    """
    from dask.distributed import as_completed
    from tqdm import tqdm

    futures = {}
    for rank, (key, args) in enumerate(todo):
        addr = where[rank] if where else None
        fut = client.submit(_run_task, task, key, args, guard, pure=False,
                            priority=len(todo) - rank, workers=[addr] if addr else None,
                            allow_other_workers=bool(addr))
        futures[fut] = key
    bar = tqdm(as_completed(list(futures)), total=len(futures), unit=unit, desc=desc,
               file=sys.stderr, disable=not progress, dynamic_ncols=True)
    for fut in bar:
        key = futures.pop(fut)
        try:
            rows = fut.result()
        except Exception as exc:  # the task raised, its worker died, or it was cancelled
            rows = error_rows(key, _one_line(f"{type(exc).__name__}: {exc}"))
        fut.release()
        rows = rows if isinstance(rows, list) else [rows]
        for row in rows:
            row["code_version"] = version  # the version this run scheduled under
        ck = fmt.case_key(key)
        if ck in present:
            replace_case_rows(path, rows, fmt, version)
        else:
            append_rows(path, rows, fmt.columns)
        counts["computed"] += 1
        if any(row.get("status") not in ok_statuses for row in rows):
            counts["failed"] += 1
        bar.set_postfix(failed=counts["failed"], refresh=False)


def _task_error_row(key: dict, message: str) -> dict:
    """The row of a case whose task raised: its key, status "task error", the message."""
    return dict(key, status="task error", error=message)


_SET_UP: list = []   # whether this process has set the optimiser's NLP store


def _worker_setup() -> None:
    """Once per worker: the optimiser's NLP store, whichever study module comes first.

    NLPs built on this machine are then loaded, not built (:func:`lunarcap.optim.nlp.stored`).
    """
    if not _SET_UP:
        from lunarcap.optim.solve import use_nlp_store
        from lunarcap.repro.cache import nlp_store

        use_nlp_store(nlp_store())
        _SET_UP.append(True)


def _run_task(task, key: dict, args: tuple, guard: tuple | None = None) -> dict | list[dict]:
    """In a worker: the task's row (or rows) with key, timing and worker recorded.

    ``guard``: ``(use_cache,)``: the task runs inside :func:`guarded` (the cache switch at
    that position; an exception is the error row).
    """
    _worker_setup()
    t0 = time.perf_counter()
    if guard is None:
        out = task(*args)
    else:
        out, error = guarded(lambda: task(*args), *guard)
        out = error or out
    rows = [dict(r) for r in out] if isinstance(out, list) else [dict(out)]
    done = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S")
    for row in rows:
        row.update(key)
        row.setdefault("task_wall_s", time.perf_counter() - t0)
        row["worker"] = f"{socket.gethostname()}:{os.getpid()}"
        row["completed_utc"] = done
        if "error" in row:
            row["error"] = _one_line(row["error"])
    return rows if isinstance(out, list) else rows[0]


def _one_line(text: str, limit: int = 500) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."
