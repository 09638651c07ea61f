"""Executing the manifest's notebooks: papermill in worker processes, interruption, pages.

:func:`run_entries` runs the entries in dependency order, up to ``jobs`` at a time, each
in a worker process (:func:`execute_entry`: papermill on the worker's kernel, see
:mod:`lunarcap.bookbuild.kernels`, then :func:`prepare_for_book` arranges the executed
notebook as a page). SIGINT and SIGTERM stop the run within
seconds (:func:`interruptible`, :func:`stop_workers`): the workers, their kernels and the
temporary files of the interrupted executions are removed.
"""

from __future__ import annotations

import concurrent.futures as cf
import contextlib
import json
import multiprocessing
import os
import re
import resource
import signal
import threading
import time
from pathlib import Path

from lunarcap.bookbuild.manifest import KERNEL, Entry, is_up_to_date, read_stamp, stamp_for
from lunarcap.repro import paths

_ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")


_DISPLAY_TAGS = {"remove-cell", "remove-input", "remove-output", "hide-cell", "hide-input",
                 "hide-output", "show-input"}


def prepare_for_book(nb, title: str, quick_note: str | None = None) -> None:
    """Adapt an executed notebook for its page (in place).

    * ``# title`` (the manifest's) becomes the first heading, replacing the source's H1;
    * ``quick_note`` (:func:`quick_note`), if given, stands right under it: a page of the
      quick book says first that it is a reduced run;
    * the set-up (parameters, build call, provenance) moves to the end of the page, after
      the results (:func:`move_setup_to_end`);
    * papermill's ``injected-parameters`` cell is removed from the page (the provenance
      block lists the parameters of the run);
    * the ``parameters`` cell is folded (``hide-cell``);
    * every other code cell without a display tag gets ``hide-input``: readers see the
      tables and figures, the code is one click away; a cell that only shows the page's
      items (:func:`only_shows`) gets ``remove-input``, no toggle in the results. Tag a
      cell ``show-input`` to keep its code visible.
    """
    import nbformat

    for cell in nb.cells:
        if cell.cell_type == "markdown":
            lines = cell.source.splitlines()
            if lines and lines[0].startswith("# "):
                cell.source = "\n".join([f"# {title}"] + lines[1:])
                break
        nb.cells.insert(0, nbformat.v4.new_markdown_cell(f"# {title}"))
        break
    if quick_note:
        first = next(i for i, c in enumerate(nb.cells) if c.cell_type == "markdown")
        heading, _, rest = nb.cells[first].source.partition("\n")
        nb.cells[first].source = f"{heading}\n\n{quick_note}\n{rest}"
    move_setup_to_end(nb)
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        tags = list(cell.metadata.get("tags", []))
        if "injected-parameters" in tags:
            tags.append("remove-cell")
        elif "parameters" in tags and not _DISPLAY_TAGS & set(tags):
            tags.append("hide-cell")
        elif not _DISPLAY_TAGS & set(tags):
            tags.append("remove-input" if only_shows(cell.source) else "hide-input")
        cell.metadata["tags"] = tags


def quick_note(parameters: dict, quick_parameters: dict) -> str | None:
    """What a page of the quick book says under its title: its reduced parameters.

    ``build --quick`` (run by ``make test``) runs each page with its quick parameters,
    below the floors of the full book; the page says which and what the book runs
    instead, so no number of it is taken for the book's. None when the quick run
    changes nothing.

    >>> print(quick_note({"samples": 368}, {"samples": 2}))
    ```{admonition} Quick book: a reduced run, not the book's numbers
    :class: warning
    This page ran with samples = 2 (the book: 368), for the tests (`make test`).
    ```
    """
    changed = {k: v for k, v in quick_parameters.items() if parameters.get(k) != v}
    if not changed:
        return None
    said = "; ".join(f"{k} = {_value_text(v)} (the book: {_value_text(parameters.get(k))})"
                     for k, v in changed.items())
    return ("```{admonition} Quick book: a reduced run, not the book's numbers\n"
            ":class: warning\n"
            f"This page ran with {said}, for the tests (`make test`).\n```")


def _value_text(v) -> str:
    """A parameter as the quick note prints it: lists without quotes, None as "default"."""
    if v is None:
        return "its default"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value_text(x) for x in v) + "]"
    return f"{v:g}" if isinstance(v, float) else str(v)


#: A line that only shows an item of the page (``page.show("dv")``, ``page.glue()``...).
_SHOW_LINE = re.compile(r"^\s*(#.*|page\.(show|glue|check)\(.*\);?\s*(#.*)?)?$")


def only_shows(source: str) -> bool:
    r"""Whether a code cell only shows the page's items (no toggle: nothing to read).

    >>> only_shows('page.show("dv")\npage.show("duration");'), only_shows("x = 1")
    (True, False)
    """
    return all(_SHOW_LINE.match(line) for line in source.splitlines())


#: Heading of the section at the end of each page that holds its provenance and set-up code.
SETUP_HEADING = "## How this page was made"


def move_setup_to_end(nb) -> None:
    """Move a page's set-up to its end, so its results come first (in place).

    The set-up is the run of cells from the ``parameters`` cell to the first cell that
    shows the provenance (``.header(``, papermill's ``injected-parameters`` cell and the
    page's build call among them); it goes under :data:`SETUP_HEADING` at the end. The
    notebook was executed already, so the order of its cells is only the page's.
    """
    import nbformat

    cells = nb.cells
    start = next((i for i, c in enumerate(cells)
                  if "parameters" in c.get("metadata", {}).get("tags", [])), None)
    if start is None:
        return
    end = next((i for i in range(start, len(cells)) if cells[i].cell_type == "code"
                and ".header(" in cells[i].source), None)
    if end is None:
        return
    setup = cells[start:end + 1]
    intro = nbformat.v4.new_markdown_cell(
        f"{SETUP_HEADING}\n\nIts provenance, parameters and code.")
    nb.cells = cells[:start] + cells[end + 1:] + [intro] + setup


# ====================================================================== interruption
class Interrupted(Exception):
    """The run was interrupted by a signal (SIGINT or SIGTERM)."""

    def __init__(self, signum: int):
        super().__init__(signal.Signals(signum).name)
        self.signum = signum

    @property
    def exit_status(self) -> int:
        """128 + the signal number, as a shell reports a process killed by it."""
        return 128 + self.signum


def _raise_interrupted(signum, frame):
    raise Interrupted(signum)


@contextlib.contextmanager
def interruptible():
    """Turn SIGINT and SIGTERM into :class:`Interrupted` in the main thread (else a no-op)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    old = {s: signal.signal(s, _raise_interrupted) for s in (signal.SIGINT, signal.SIGTERM)}
    try:
        yield
    finally:
        for s, h in old.items():
            signal.signal(s, h)


def _process_table() -> dict[int, tuple[int, int]]:
    """``{pid: (parent pid, process group)}`` of every process, from ``/proc`` (Linux)."""
    table = {}
    for d in Path("/proc").glob("[0-9]*"):
        try:
            stat = (d / "stat").read_text()
        except OSError:
            continue
        # fields after the command name, which is in parentheses and may contain spaces
        fields = stat[stat.rindex(")") + 2:].split()
        if fields[0] != "Z":  # zombies are gone already
            table[int(d.name)] = (int(fields[1]), int(fields[2]))
    return table


def descendants(pid: int) -> list[int]:
    """Every living process below ``pid`` (children first); empty where ``/proc`` is absent."""
    table = _process_table()
    children: dict[int, list[int]] = {}
    for p, (ppid, _) in table.items():
        children.setdefault(ppid, []).append(p)
    out, todo = [], list(children.get(pid, []))
    while todo:
        p = todo.pop(0)
        out.append(p)
        todo += children.get(p, [])
    return out


def _kill_all(pids, sig=signal.SIGKILL) -> None:
    """Send ``sig`` to each process and to the process group it leads (a kernel's session)."""
    own_group = os.getpgrp()
    table = _process_table()
    for p in pids:
        with contextlib.suppress(OSError):
            if p in table and table[p][1] == p and p != own_group:
                os.killpg(p, sig)
            os.kill(p, sig)


#: Temporary files of the execution running in this worker process (removed if stopped).
_RUNNING_FILES: list[Path] = []


def _worker_init() -> None:
    """Worker set-up: SIGINT is the main process's business; SIGTERM stops the worker."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _worker_stop)


def _worker_stop(signum, frame) -> None:
    """Kill this worker's kernel (and whatever it started), remove its temporary files, exit."""
    _kill_all(descendants(os.getpid()))
    for f in _RUNNING_FILES:
        with contextlib.suppress(OSError):
            f.unlink()
    os._exit(128 + signum)


def _alive(pid: int) -> bool:
    table = _process_table()
    if table:
        return pid in table
    try:
        os.kill(pid, 0)
    except OSError:
        return False
    return True


def stop_workers(pool: cf.ProcessPoolExecutor, grace_s: float = 5.0) -> None:
    """Stop every worker of ``pool`` and everything below it; return when all are gone.

    Each worker gets SIGTERM (it kills its kernel and removes its temporary files); after
    ``grace_s`` whatever is left below this process is killed.
    """
    workers = list(getattr(pool, "_processes", None) or {})
    tree = set(descendants(os.getpid()))
    for w in workers:
        with contextlib.suppress(OSError):
            os.kill(w, signal.SIGTERM)
    deadline = time.monotonic() + grace_s
    while time.monotonic() < deadline and any(_alive(w) for w in workers):
        time.sleep(0.05)
    # multiprocessing's resource tracker (a child of this process) must live on: the pool's
    # shutdown unregisters its semaphores with it, and it exits with this process
    from multiprocessing import resource_tracker

    keep = {getattr(resource_tracker._resource_tracker, "_pid", None)}
    left = [p for p in tree | set(descendants(os.getpid())) if p not in keep and _alive(p)]
    _kill_all(left)
    for w in workers:  # reap
        with contextlib.suppress(OSError):
            os.waitpid(w, os.WNOHANG)
    pool.shutdown(wait=False, cancel_futures=True)


def remove_temporaries(since: float) -> list[Path]:
    """Remove temporary files below ``book/generated`` made since ``since`` (epoch s)."""
    removed = []
    if not paths.GENERATED.is_dir():
        return removed
    for f in paths.GENERATED.rglob(".*"):
        name = f.name
        if f.is_file() and (".tmp" in name or name.endswith(".stderr.log")):
            with contextlib.suppress(OSError):
                if f.stat().st_mtime >= since:
                    f.unlink()
                    removed.append(f)
    return removed


# ====================================================================== execution
def execute_entry(entry: Entry, parameters: dict, stamp: dict, timeout: float | None,
                  env: dict | None = None) -> dict:
    """Run one entry with papermill (in a worker process). Returns a result dict, never raises.

    The entry runs in this worker's kernel (:mod:`lunarcap.bookbuild.kernels`), after a
    prelude that empties its namespace and sets ``env``: environment variables for this
    run only (the shared study cluster's address, see :class:`StudyCluster`).
    """
    from lunarcap.bookbuild import kernels

    paths.ensure_dirs()
    tmp = paths.GENERATED / f".{entry.name}.tmp.ipynb"
    t0 = time.perf_counter()
    # The kernel inherits this process's stderr when it starts: send it (ipykernel's
    # start-up chatter, or a crash message) to this worker's log, whose lines written
    # during a failed run are quoted in its error report.
    errlog = paths.GENERATED / f".kernel-{os.getpid()}.stderr.log"
    _RUNNING_FILES[:] = [tmp]
    saved = os.dup(2)
    with open(errlog, "a") as fh:
        os.dup2(fh.fileno(), 2)
    offset = errlog.stat().st_size
    try:
        kernels.ready(KERNEL)
        return _execute(entry, parameters, stamp, timeout, tmp, t0, (errlog, offset),
                        env or {})
    finally:
        os.dup2(saved, 2)
        os.close(saved)
        _RUNNING_FILES.clear()


def _stderr_tail(errlog: tuple[Path, int], n: int = 10) -> str:
    """The last ``n`` lines the kernel wrote to ``errlog[0]`` after byte ``errlog[1]``."""
    path, offset = errlog
    try:
        with open(path, "rb") as fh:
            fh.seek(offset)
            text = fh.read().decode(errors="replace")
    except OSError:
        return ""
    lines = [ln for ln in text.splitlines()
             if ln.strip() and "running over TCP without encryption" not in ln]
    return ("\n--- kernel stderr (last lines) ---\n" + "\n".join(lines[-n:])) if lines else ""


def _cpu_s() -> float:
    """CPU seconds (user + system) of this worker's kernels and whatever they started.

    The finished children of this process (kernels stopped earlier) and the live kernel
    with its finished children (:func:`lunarcap.bookbuild.kernels.kernel_cpu_s`); the Dask
    workers of the shared study cluster are not below a kernel and not counted. Stamped as
    ``cpu_s`` beside the wall ``seconds`` (on a machine shared with other work the CPU
    time is the steadier figure).
    """
    from lunarcap.bookbuild import kernels

    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime + kernels.kernel_cpu_s()


def _execute(entry, parameters, stamp, timeout, tmp, t0, errlog, env) -> dict:
    import nbformat
    import papermill as pm
    from papermill.exceptions import PapermillExecutionError

    from lunarcap.bookbuild import kernels

    started = time.time() - 1.0  # declared outputs must be written by this run
    cpu0 = _cpu_s()
    try:
        source = kernels.with_prelude(nbformat.read(str(entry.notebook), as_version=4), env)
        pm.execute_notebook(source, str(tmp), parameters=parameters,
                            engine_name=kernels.engine_name(),
                            kernel_name=KERNEL, cwd=str(entry.notebook.parent),
                            progress_bar=False, log_output=False,
                            request_save_on_cell_execute=False, execution_timeout=timeout)
        nb = nbformat.read(str(tmp), as_version=4)
        kernels.drop_prelude(nb)
        prepare_for_book(nb, entry.title,
                         quick_note(entry.parameters, entry.quick_parameters)
                         if parameters.get("quick") else None)
        nbformat.write(nb, str(tmp))
        missing = [o for o in entry.outputs if not (paths.GENERATED / o).is_file()
                   or (paths.GENERATED / o).stat().st_size == 0
                   or (paths.GENERATED / o).stat().st_mtime < started]
        if missing:
            kernels.shutdown()
            os.replace(tmp, entry.failed_path)
            return {"ok": False, "seconds": time.perf_counter() - t0,
                    "error": f"the notebook ran but did not write its declared outputs {missing} "
                             "(paths below book/generated; fix the entry's 'outputs', in its "
                             "page's BOOK, or the notebook)"}
        os.replace(tmp, entry.output)
        stamp = dict(stamp, executed_utc=time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
                     seconds=round(time.perf_counter() - t0, 2),
                     cpu_s=round(_cpu_s() - cpu0, 2))
        paths.write_text_atomic(entry.stamp_path, json.dumps(stamp, indent=2, default=str))
        if entry.failed_path.exists():
            entry.failed_path.unlink()
        return {"ok": True, "seconds": time.perf_counter() - t0, "cpu_s": stamp["cpu_s"]}
    except PapermillExecutionError as exc:
        tb = _ANSI.sub("", "\n".join(exc.traceback or []))
        msg = (f"{_which_cell(entry, exc.source)} raised {exc.ename}: {exc.evalue}\n"
               f"--- cell source ---\n{exc.source}\n--- traceback (last lines) ---\n"
               + "\n".join(tb.splitlines()[-12:]))
    except Exception as exc:  # kernel died, timeout, bad notebook, ...
        msg = f"{type(exc).__name__}: {_ANSI.sub('', str(exc))}" + _stderr_tail(errlog)
    kernels.shutdown()  # a failed entry may leave the kernel in any state
    if tmp.exists():
        with contextlib.suppress(Exception):  # the failed notebook as a fresh kernel ran it
            nb = nbformat.read(str(tmp), as_version=4)
            kernels.drop_prelude(nb)
            nbformat.write(nb, str(tmp))
        os.replace(tmp, entry.failed_path)
    return {"ok": False, "seconds": time.perf_counter() - t0, "error": msg}


def _which_cell(entry: Entry, source: str) -> str:
    """``"code cell k of <notebook>"`` for the source of a failed cell (k from 1)."""
    import nbformat

    with contextlib.suppress(Exception):
        nb = nbformat.read(str(entry.notebook), as_version=4)
        code = [c.source for c in nb.cells if c.cell_type == "code"]
        if source in code:
            return f"code cell {code.index(source) + 1} of {entry.notebook.name}"
    return "a cell"


class StudyCluster:
    """The Dask cluster the book's studies share, started when the first study runs.

    Every study of the book (trade study, burn count, missed thrust, dispersions) would
    otherwise start a local cluster of its own, whose worker processes start, import
    lunarcap and load each NLP shape they need again (from the machine's NLP store:
    :func:`lunarcap.optim.nlp.stored`). This one is started once (``jobs`` workers, one
    thread each) and named to the notebooks' kernels by the environment variable
    :data:`lunarcap.studies.campaign.SCHEDULER_ENV` (set for that kernel alone,
    :func:`execute_entry`); its workers keep the NLPs they hold from one study to the
    next. A study is an entry whose manifest parameters set ``workers``.
    Not started when no study is executed (a rerun with nothing changed), nor when that
    variable names a scheduler already (an existing cluster's: the kernels are given
    that address instead, see ``--scheduler`` in :mod:`lunarcap.bookbuild.build`).
    """

    def __init__(self, workers: int):
        self.workers = workers
        self._stack = contextlib.ExitStack()
        self._client = None

    def start(self) -> dict:
        """Start the cluster (once); the environment naming it, for a study's kernel.

        If this process's environment names a scheduler already (``make book
        SCHEDULER=...``, ``build --scheduler``), that one, and no cluster is started.
        """
        from lunarcap.studies.campaign import SCHEDULER_ENV, dask_client

        if os.environ.get(SCHEDULER_ENV):
            return {SCHEDULER_ENV: os.environ[SCHEDULER_ENV]}
        if self._client is None:
            self._client = self._stack.enter_context(dask_client(self.workers, None, True))
        return {SCHEDULER_ENV: self._client.scheduler.address}

    def close(self, interrupted: bool = False) -> None:
        """Stop the cluster; after an interruption quietly (its workers were killed)."""
        if self._client is None:
            return
        if interrupted:
            from lunarcap.studies.campaign import _close_quietly

            _close_quietly(self._client, getattr(self._client, "cluster", None))
        with contextlib.suppress(Exception):
            self._stack.close()
        self._client = None


def _cost_s(entry: Entry) -> float:
    """What ``entry`` is expected to take: its last recorded run, else the manifest's hint."""
    stamp = read_stamp(entry) or {}
    seconds = stamp.get("seconds")
    return float(seconds) if isinstance(seconds, (int, float)) else entry.expected_s


def longest_first(entries: list[Entry]) -> list[Entry]:
    """``entries`` ordered by the work each one starts, longest first (ties: manifest order).

    The work of an entry is its own expected time (:func:`_cost_s`) plus the longest chain
    of entries that depend on it (its critical path), so a long chain starts early and the
    last minutes of a build are not spent with one core idle behind one long notebook.
    """
    cost = {e.name: _cost_s(e) for e in entries}
    after: dict[str, list[str]] = {e.name: [] for e in entries}
    for e in entries:
        for d in e.depends_on:
            if d in after:
                after[d].append(e.name)
    path: dict[str, float] = {}

    def chain(name: str) -> float:
        if name not in path:
            path[name] = cost[name] + max((chain(n) for n in after[name]), default=0.0)
        return path[name]

    return sorted(entries, key=lambda e: -chain(e.name))


def _outside_digests(entries: list[Entry]) -> dict[str, str]:
    """Current stamps of dependencies outside the selection (they are not run)."""
    names = {e.name for e in entries}
    digests: dict[str, str] = {}
    for e in entries:
        for d in e.depends_on:
            if d not in names:
                old = read_stamp(Entry(d, "", e.notebook, {}, {}, (), ()))
                digests[d] = (old or {}).get("digest")
    return digests


class _Run:
    """The state of one :func:`run_entries` call: what is left, running, done, failed."""

    def __init__(self, entries, quick, jobs, force, timeout, log):
        self.todo = {e.name: e for e in longest_first(entries)}
        self.digests = _outside_digests(entries)
        self.quick, self.jobs, self.force, self.timeout, self.log = \
            quick, max(1, jobs), force, timeout, log
        self.n_total, self.n_done = len(entries), 0
        self.running: dict[cf.Future, tuple[Entry, dict]] = {}
        self.failed: list[tuple[Entry, str]] = []
        self.cluster = StudyCluster(self.jobs)

    def launch(self, pool) -> None:
        """Start (or skip as up to date) every entry whose dependencies are done."""
        busy = {e.name for e, _ in self.running.values()}
        progressed = not self.failed
        while progressed:
            progressed = False
            for e in list(self.todo.values()):
                if len(self.running) >= self.jobs:
                    break
                if any(d in self.todo or d in busy for d in e.depends_on):
                    continue
                del self.todo[e.name]
                stamp = stamp_for(e, self.quick, self.digests)
                if not self.force and is_up_to_date(e, stamp):
                    self.n_done += 1
                    self.digests[e.name] = stamp["digest"]
                    self.log(f"[{self.n_done}/{self.n_total}] {e.name} ... up to date (skipped)")
                    progressed = True
                    continue
                self.log(f"      running {e.name} ...")
                env = self.cluster.start() if "workers" in e.parameters else {}
                fut = pool.submit(execute_entry, e, e.effective_parameters(self.quick), stamp,
                                  self.timeout, env)
                self.running[fut] = (e, stamp)
                busy.add(e.name)

    def collect(self, done) -> None:
        """Record the entries that finished."""
        for fut in done:
            e, stamp = self.running.pop(fut)
            try:
                res = fut.result()
            except Exception as exc:  # the worker process itself died
                res = {"ok": False, "seconds": 0.0, "error": f"worker crashed: {exc!r}"}
            self.n_done += 1
            if res["ok"]:
                self.digests[e.name] = stamp["digest"]
                self.log(f"[{self.n_done}/{self.n_total}] {e.name} ... ok {res['seconds']:.1f} s "
                         f"(CPU {res.get('cpu_s', float('nan')):.1f} s)")
            else:
                self.log(f"[{self.n_done}/{self.n_total}] {e.name} ... FAILED "
                         f"{res['seconds']:.1f} s")
                self.failed.append((e, res["error"]))

    def report_failures(self) -> None:
        """Name each failed entry, its error and where its executed notebook is."""
        if self.failed and self.todo:
            self.log(f"not run because of the failure: {sorted(self.todo)}")
        for e, err in self.failed:
            rel = e.failed_path.relative_to(paths.ROOT) if e.failed_path.exists() else None
            self.log(f"\nerror: entry {e.name!r} ({e.notebook.relative_to(paths.ROOT)}) "
                     f"failed: {err}")
            if rel:
                self.log(f"the executed notebook with the error is {rel}")
            self.log(f"other outputs in {_shown(paths.GENERATED)} were left as they were.")


def run_entries(entries: list[Entry], quick: bool = False, jobs: int = 2, force: bool = False,
                timeout: float | None = None, log=print) -> bool:
    """Execute ``entries`` in dependency order, up to ``jobs`` at a time, longest first.

    Among the entries ready to run, the one starting the most work goes first
    (:func:`longest_first`).

    Returns
    -------
    bool
        True if every entry ran (or was up to date); False after the first failure.
    """
    run = _Run(entries, quick, jobs, force, timeout, log)
    ctx = multiprocessing.get_context("spawn")
    pool = cf.ProcessPoolExecutor(max_workers=run.jobs, mp_context=ctx,
                                  initializer=_worker_init)
    started = time.time() - 1.0
    try:
        while True:
            run.launch(pool)
            if not run.running:
                break
            done, _ = cf.wait(list(run.running), return_when=cf.FIRST_COMPLETED)
            run.collect(done)
    except BaseException as exc:  # Interrupted, KeyboardInterrupt, or a bug here
        if isinstance(exc, Interrupted):
            exc.stopped = sorted(e.name for e, _ in run.running.values())
        stop_workers(pool)
        run.cluster.close(interrupted=True)
        remove_temporaries(started)
        raise
    pool.shutdown(wait=True)  # each worker stops its kernel as it exits
    run.cluster.close()
    remove_temporaries(started)  # the kernels' stderr logs (quoted where an entry failed)
    run.report_failures()
    return not run.failed


def _shown(path: Path) -> str:
    """``path`` relative to the repository when below it (as a reader types it)."""
    path = Path(path)
    return path.relative_to(paths.ROOT).as_posix() if path.is_relative_to(paths.ROOT) \
        else str(path)
