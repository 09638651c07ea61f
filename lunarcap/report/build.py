"""Execute the notebooks of the manifest with papermill, then build the HTML book.

Usage::

    python -m lunarcap.report.build build [--quick] [--jobs N] [--only NAME ...] [--force]
                                          [--no-build]
    python -m lunarcap.report.build check          # validate the manifest and the table of contents

The manifest ``notebooks/manifest.yml`` has one entry per execution::

    entries:
      - name: impulsive_baseline          # output name: book/generated/<name>.ipynb
        title: "Impulsive baseline"       # heading of the generated page
        notebook: impulsive_baseline.ipynb  # source, relative to notebooks/
        parameters: {thrust_N: 150.0}     # injected by papermill
        quick_parameters: {}              # overrides for --quick (CI): coarse mesh, one case
        depends_on: []                    # names of entries that must run first
        outputs: [tables/impulsive_baseline.csv]  # files below book/generated it writes

Every entry also receives ``quick`` (bool) and ``output_name`` (its name). Entries run
in dependency order, independent ones in parallel on up to ``--jobs`` processes.
Each executed notebook is written to a temporary file and moved into place only on
success; a failure stops the run (entries already running finish), names the entry
and cell, keeps the failed notebook as ``book/generated/<name>.failed.ipynb`` and
leaves every other output intact.

An entry is skipped when its stamp ``book/generated/<name>.stamp.json`` matches: same
source notebook, parameters, quick flag, lunarcap source
(:func:`lunarcap.repro.cache.code_version`),
environment lock, title and dependency stamps, and its outputs exist. Expensive
solutions are cached separately by :mod:`lunarcap.repro.cache`.

The book is then built with ``jupyter-book build book -W -n --keep-going`` with
execution off (``--all`` whenever the generated notebooks changed since the last
build, because pages quoting glued numbers of other pages must be rewritten).

Interrupting a run (Ctrl-C, or SIGINT/SIGTERM sent to the main process alone, as CI
runners and ``timeout`` do) stops it within seconds: the workers ignore SIGINT and leave
the decision to the main process, which asks each worker to stop (SIGTERM), kills every
process below it that is left (the Jupyter kernels run in sessions of their own, so a
terminal's Ctrl-C does not reach them), removes the temporary files of the interrupted
executions and prints one line. Executed notebooks and their outputs are only ever moved
into place complete, so ``book/generated`` keeps what earlier runs made.

``--quick`` builds a separate book: the sources are copied to ``book/_build/quick/``,
whose own ``generated/`` and ``_build/html/`` receive the quick outputs and site
(:func:`lunarcap.repro.paths.stage_quick_book`), so the quick build that ``make test``
runs never replaces the full book or makes its next build start over.

Exit status: 0 success, 1 an entry or the book build failed, 2 invalid manifest or usage,
130 interrupted by SIGINT, 143 interrupted by SIGTERM.
"""

from __future__ import annotations

import argparse
import ast
import concurrent.futures as cf
import contextlib
import dataclasses
import hashlib
import json
import multiprocessing
import os
import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import yaml

from lunarcap.repro import paths

ENTRY_KEYS = {"name", "title", "notebook", "parameters", "quick_parameters", "depends_on",
              "outputs"}
REQUIRED_KEYS = {"name", "title", "notebook"}
#: Parameters every notebook declares and the book injects.
INJECTED = ("quick", "output_name")
KERNEL = "python3"
STAMP_VERSION = 1


class ManifestError(ValueError):
    """The manifest (or the table of contents) is invalid; the message lists every problem."""


@dataclasses.dataclass(frozen=True)
class Entry:
    """One execution of a notebook (see the module docstring for the fields)."""

    name: str
    title: str
    notebook: Path
    parameters: dict
    quick_parameters: dict
    depends_on: tuple
    outputs: tuple

    def effective_parameters(self, quick: bool) -> dict:
        """Parameters papermill injects: parameters, quick overrides, ``quick``, ``output_name``."""
        p = dict(self.parameters)
        if quick:
            p.update(self.quick_parameters)
        p["quick"] = bool(quick)
        p["output_name"] = self.name
        return p

    @property
    def output(self) -> Path:
        """The executed notebook."""
        return paths.executed_notebook_path(self.name)

    @property
    def stamp_path(self) -> Path:
        """The stamp recording what the executed notebook was made from."""
        return paths.GENERATED / f"{self.name}.stamp.json"

    @property
    def failed_path(self) -> Path:
        """Where the executed notebook of a failed run is kept."""
        return paths.GENERATED / f"{self.name}.failed.ipynb"


# ====================================================================== manifest validation
def notebook_parameters(nb_path: Path) -> tuple[list[str], list[str]]:
    """Names assigned in the notebook's ``parameters`` cell, and problems found.

    Returns
    -------
    (names, problems) : list of str, list of str
    """
    import nbformat

    try:
        nb = nbformat.read(str(nb_path), as_version=4)
    except Exception as exc:  # nbformat raises assorted errors on bad JSON
        return [], [f"cannot read notebook {nb_path}: {exc}"]
    cells = [c for c in nb.cells if "parameters" in c.get("metadata", {}).get("tags", [])]
    if len(cells) != 1:
        return [], [f"notebook {nb_path.name} must have exactly one cell tagged 'parameters' "
                    f"(found {len(cells)})"]
    try:
        tree = ast.parse(cells[0].source)
    except SyntaxError as exc:
        return [], [f"notebook {nb_path.name}: parameters cell is not valid Python: {exc}"]
    names = []
    for node in tree.body:
        targets = node.targets if isinstance(node, ast.Assign) else (
            [node.target] if isinstance(node, ast.AnnAssign) else [])
        names += [t.id for t in targets if isinstance(t, ast.Name)]
    problems = [f"notebook {nb_path.name}: parameters cell must define {n!r}"
                for n in INJECTED if n not in names]
    return names, problems


def find_cycle(graph: dict[str, list[str]]) -> list[str] | None:
    """A dependency cycle ``[a, b, ..., a]`` in ``graph`` (name -> dependencies), or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for d in graph.get(n, ()):
            if state.get(d) == 1:
                return stack[stack.index(d):] + [d]
            if d in graph and state.get(d) is None:
                found = visit(d)
                if found:
                    return found
        stack.pop()
        state[n] = 2
        return None

    for n in graph:
        if state.get(n) is None:
            found = visit(n)
            if found:
                return found
    return None


def validate_manifest(data, notebooks_dir: Path | None = None,
                      check_notebooks: bool = True) -> list[Entry]:
    """Validate a parsed manifest and return its entries in file order.

    Parameters
    ----------
    data : dict
        The parsed YAML: ``{"entries": [ {...}, ... ]}``.
    notebooks_dir : Path, optional
        Directory the ``notebook`` fields are relative to (default ``notebooks/``).
    check_notebooks : bool
        Also open each notebook and check its parameters cell declares every parameter
        the manifest gives (and ``quick``, ``output_name``).

    Raises
    ------
    ManifestError
        Listing every problem found (unknown or missing keys, duplicate names, missing
        notebooks, unknown parameters, unknown dependencies, dependency cycles).
    """
    notebooks_dir = Path(notebooks_dir or paths.NOTEBOOKS)
    errors: list[str] = []
    if not isinstance(data, dict) or set(data) != {"entries"} or not isinstance(
            data.get("entries"), list):
        raise ManifestError("manifest must be a mapping with one key 'entries' holding a list")
    entries: list[Entry] = []
    seen: set[str] = set()
    nb_params: dict[Path, tuple] = {}
    for i, raw in enumerate(data["entries"]):
        where = f"entry {i + 1}"
        if not isinstance(raw, dict):
            errors.append(f"{where}: must be a mapping, got {type(raw).__name__}")
            continue
        name = raw.get("name")
        if isinstance(name, str):
            where = f"entry {i + 1} ({name!r})"
        unknown = sorted(set(raw) - ENTRY_KEYS)
        if unknown:
            errors.append(f"{where}: unknown key(s) {unknown}; allowed: {sorted(ENTRY_KEYS)}")
        missing = sorted(REQUIRED_KEYS - set(raw))
        if missing:
            errors.append(f"{where}: missing key(s) {missing}")
            continue
        try:
            paths.check_name(name)
        except ValueError as exc:
            errors.append(f"{where}: {exc}")
            continue
        if name in seen:
            errors.append(f"{where}: duplicate name {name!r}")
        seen.add(name)
        if not isinstance(raw["title"], str) or not raw["title"].strip():
            errors.append(f"{where}: title must be a non-empty string")
        nb = (Path(notebooks_dir) / str(raw["notebook"])).resolve()
        if not str(raw["notebook"]).endswith(".ipynb") or not nb.is_file():
            errors.append(f"{where}: notebook {raw['notebook']!r} not found in {notebooks_dir}")
            nb = None
        params = raw.get("parameters") or {}
        quick = raw.get("quick_parameters") or {}
        for key, val in (("parameters", params), ("quick_parameters", quick)):
            if not isinstance(val, dict):
                errors.append(f"{where}: {key} must be a mapping")
            else:
                bad = [k for k in val if k in INJECTED]
                if bad:
                    errors.append(f"{where}: {key} may not set {bad} (injected by the book)")
        deps = raw.get("depends_on") or []
        if not isinstance(deps, list) or not all(isinstance(d, str) for d in deps):
            errors.append(f"{where}: depends_on must be a list of entry names")
            deps = []
        outputs = raw.get("outputs") or []
        if not isinstance(outputs, list) or not all(
                isinstance(o, str) and not o.startswith("/") and ".." not in Path(o).parts
                for o in outputs):
            errors.append(f"{where}: outputs must be a list of paths relative to book/generated")
            outputs = []
        if nb is not None and check_notebooks and isinstance(params, dict) and isinstance(
                quick, dict):
            if nb not in nb_params:
                nb_params[nb] = notebook_parameters(nb)
            names, problems = nb_params[nb]
            errors += [f"{where}: {p}" for p in problems]
            if names:
                undeclared = sorted((set(params) | set(quick)) - set(names))
                if undeclared:
                    errors.append(f"{where}: parameter(s) {undeclared} are not defined in the "
                                  f"parameters cell of {nb.name}")
        if nb is not None:
            entries.append(Entry(name, str(raw["title"]).strip(), nb, dict(params)
                                 if isinstance(params, dict) else {},
                                 dict(quick) if isinstance(quick, dict) else {},
                                 tuple(deps), tuple(outputs)))
    names = {e.name for e in entries} | seen
    for e in entries:
        for d in e.depends_on:
            if d not in names:
                errors.append(f"entry {e.name!r}: depends_on unknown entry {d!r}")
            if d == e.name:
                errors.append(f"entry {e.name!r}: depends on itself")
    cycle = find_cycle({e.name: [d for d in e.depends_on if d != e.name] for e in entries})
    if cycle:
        errors.append("dependency cycle: " + " -> ".join(cycle))
    if errors:
        raise ManifestError("invalid manifest:\n  - " + "\n  - ".join(errors))
    return entries


def load_manifest(path: Path | None = None, check_notebooks: bool = True) -> list[Entry]:
    """Read and validate the manifest (default ``notebooks/manifest.yml``).

    See :func:`validate_manifest`.
    """
    path = Path(path or paths.MANIFEST)
    if not path.is_file():
        raise ManifestError(f"manifest not found: {path}")
    try:
        data = yaml.safe_load(path.read_text(encoding="utf-8"))
    except yaml.YAMLError as exc:
        raise ManifestError(f"manifest {path} is not valid YAML: {exc}") from exc
    return validate_manifest(data, path.parent, check_notebooks)


def toc_files(toc_path: Path | None = None) -> list[str]:
    """Every ``file:`` of the jupyter-book table of contents, root first (no extension)."""
    toc = yaml.safe_load(Path(toc_path or paths.TOC).read_text(encoding="utf-8"))
    out = [toc["root"]]

    def walk(node):
        if isinstance(node, dict):
            if "file" in node:
                out.append(node["file"])
            for v in node.values():
                walk(v)
        elif isinstance(node, list):
            for v in node:
                walk(v)

    walk({k: v for k, v in toc.items() if k != "root"})
    return [re.sub(r"\.(md|ipynb)$", "", f) for f in out]


def check_toc(entries: list[Entry], toc_path: Path | None = None) -> None:
    """Every entry must appear in the toc as ``generated/<name>`` and vice versa.

    Raises
    ------
    ManifestError
    """
    toc_path = Path(toc_path or paths.TOC)
    files = toc_files(toc_path)
    gen = {f.split("/", 1)[1] for f in files if f.startswith("generated/")}
    names = {e.name for e in entries}
    errors = [f"manifest entry {n!r} is not in {toc_path.name} (add '- file: generated/{n}')"
              for n in sorted(names - gen)]
    errors += [f"{toc_path.name} lists generated/{n}, which no manifest entry produces"
               for n in sorted(gen - names)]
    book_dir = Path(toc_path).parent
    for f in files:
        if not f.startswith("generated/") and not any(
                (book_dir / f"{f}{ext}").is_file() for ext in (".md", ".ipynb")):
            errors.append(f"{toc_path.name} lists {f}, which does not exist in {book_dir}")
    if errors:
        raise ManifestError("table of contents does not match the manifest:\n  - "
                            + "\n  - ".join(errors))


def select(entries: list[Entry], only: list[str] | None) -> list[Entry]:
    """The entries named in ``only`` and everything they depend on (all if ``only`` is empty)."""
    if not only:
        return list(entries)
    by_name = {e.name: e for e in entries}
    unknown = [n for n in only if n not in by_name]
    if unknown:
        raise ManifestError(f"--only: unknown entr{'y' if len(unknown) == 1 else 'ies'} "
                            f"{unknown}; known: {sorted(by_name)}")
    keep: set[str] = set()
    todo = list(only)
    while todo:
        n = todo.pop()
        if n not in keep:
            keep.add(n)
            todo += list(by_name[n].depends_on)
    return [e for e in entries if e.name in keep]


# ====================================================================== stamps
def _sha256_file(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def stamp_for(entry: Entry, quick: bool, dep_digests: dict[str, str]) -> dict:
    """What an executed notebook is made from (its ``digest`` summarises the rest)."""
    from lunarcap.repro.cache import code_version

    lock = paths.ROOT / "environment-lock.txt"
    rec = {
        "stamp_version": STAMP_VERSION,
        "name": entry.name,
        "title": entry.title,
        "notebook": entry.notebook.relative_to(paths.ROOT).as_posix()
        if entry.notebook.is_relative_to(paths.ROOT) else str(entry.notebook),
        "notebook_sha256": _sha256_file(entry.notebook),
        "parameters": entry.effective_parameters(quick),
        "code_version": code_version(include_presentation=True),
        "environment_lock_sha256": _sha256_file(lock) if lock.is_file() else None,
        "depends_on": {d: dep_digests.get(d) for d in entry.depends_on},
    }
    rec["digest"] = hashlib.sha256(json.dumps(rec, sort_keys=True, default=str).encode()
                                   ).hexdigest()
    return rec


def read_stamp(entry: Entry) -> dict | None:
    """The stamp on disk, or None."""
    try:
        return json.loads(entry.stamp_path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def is_up_to_date(entry: Entry, stamp: dict) -> bool:
    """True if the stamp on disk matches ``stamp`` and every output exists and is non-empty."""
    old = read_stamp(entry)
    if not old or old.get("digest") != stamp["digest"] or not entry.output.is_file():
        return False
    return all((paths.GENERATED / o).is_file() and (paths.GENERATED / o).stat().st_size > 0
               for o in entry.outputs)


# ====================================================================== execution
_ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")


_DISPLAY_TAGS = {"remove-cell", "remove-input", "remove-output", "hide-cell", "hide-input",
                 "hide-output", "show-input"}


def prepare_for_book(nb, title: str) -> None:
    """Adapt an executed notebook for its page (in place).

    * ``# title`` (the manifest's) becomes the first heading, replacing the source's H1;
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
        f"{SETUP_HEADING}\n\nThe provenance of this page (code, environment, ephemeris, "
        "notebook and parameters), then the parameters and the code that computed it.")
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
def execute_entry(entry: Entry, parameters: dict, stamp: dict, timeout: float | None) -> dict:
    """Run one entry with papermill (in a worker process). Returns a result dict, never raises."""
    paths.ensure_dirs()
    tmp = paths.GENERATED / f".{entry.name}.tmp.ipynb"
    t0 = time.perf_counter()
    # The kernel inherits this process's stderr: send it (ipykernel's start-up chatter,
    # or a crash message) to a log, quoted in the error report if the run fails.
    errlog = paths.GENERATED / f".{entry.name}.stderr.log"
    _RUNNING_FILES[:] = [tmp, errlog]
    saved = os.dup(2)
    with open(errlog, "w") as fh:
        os.dup2(fh.fileno(), 2)
    try:
        return _execute(entry, parameters, stamp, timeout, tmp, t0, errlog)
    finally:
        os.dup2(saved, 2)
        os.close(saved)
        _RUNNING_FILES.clear()


def _stderr_tail(errlog: Path, n: int = 10) -> str:
    try:
        lines = [ln for ln in errlog.read_text(errors="replace").splitlines()
                 if ln.strip() and "running over TCP without encryption" not in ln]
    except OSError:
        return ""
    return ("\n--- kernel stderr (last lines) ---\n" + "\n".join(lines[-n:])) if lines else ""


def _execute(entry, parameters, stamp, timeout, tmp, t0, errlog) -> dict:
    import nbformat
    import papermill as pm
    from papermill.exceptions import PapermillExecutionError

    started = time.time() - 1.0  # declared outputs must be written by this run
    try:
        pm.execute_notebook(str(entry.notebook), str(tmp), parameters=parameters,
                            kernel_name=KERNEL, cwd=str(entry.notebook.parent),
                            progress_bar=False, log_output=False,
                            request_save_on_cell_execute=False, execution_timeout=timeout)
        nb = nbformat.read(str(tmp), as_version=4)
        prepare_for_book(nb, entry.title)
        nbformat.write(nb, str(tmp))
        missing = [o for o in entry.outputs if not (paths.GENERATED / o).is_file()
                   or (paths.GENERATED / o).stat().st_size == 0
                   or (paths.GENERATED / o).stat().st_mtime < started]
        if missing:
            os.replace(tmp, entry.failed_path)
            return {"ok": False, "seconds": time.perf_counter() - t0,
                    "error": f"the notebook ran but did not write its declared outputs {missing} "
                             "(paths below book/generated; fix the manifest's 'outputs' or the "
                             "notebook)"}
        os.replace(tmp, entry.output)
        errlog.unlink(missing_ok=True)
        stamp = dict(stamp, executed_utc=time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
                     seconds=round(time.perf_counter() - t0, 2))
        paths.write_text_atomic(entry.stamp_path, json.dumps(stamp, indent=2, default=str))
        if entry.failed_path.exists():
            entry.failed_path.unlink()
        return {"ok": True, "seconds": time.perf_counter() - t0}
    except PapermillExecutionError as exc:
        tb = _ANSI.sub("", "\n".join(exc.traceback or []))
        msg = (f"cell [{exc.exec_count}] raised {exc.ename}: {exc.evalue}\n"
               f"--- cell source ---\n{exc.source}\n--- traceback (last lines) ---\n"
               + "\n".join(tb.splitlines()[-12:]))
    except Exception as exc:  # kernel died, timeout, bad notebook, ...
        msg = f"{type(exc).__name__}: {_ANSI.sub('', str(exc))}" + _stderr_tail(errlog)
    if tmp.exists():
        os.replace(tmp, entry.failed_path)
    return {"ok": False, "seconds": time.perf_counter() - t0, "error": msg}


def run_entries(entries: list[Entry], quick: bool = False, jobs: int = 2, force: bool = False,
                timeout: float | None = None, log=print) -> bool:
    """Execute ``entries`` in dependency order, up to ``jobs`` at a time.

    Returns
    -------
    bool
        True if every entry ran (or was up to date); False after the first failure.
    """
    todo = {e.name: e for e in entries}
    all_names = {e.name for e in entries}
    digests: dict[str, str] = {}
    for e in entries:  # dependencies outside the selection contribute their current stamp
        for d in e.depends_on:
            if d not in all_names:
                old = read_stamp(Entry(d, "", e.notebook, {}, {}, (), ()))
                digests[d] = (old or {}).get("digest")
    n_total, n_done = len(entries), 0
    jobs = max(1, jobs)
    running: dict[cf.Future, tuple[Entry, dict]] = {}
    failed: list[tuple[Entry, str]] = []
    ctx = multiprocessing.get_context("spawn")
    pool = cf.ProcessPoolExecutor(max_workers=jobs, mp_context=ctx, initializer=_worker_init)
    started = time.time() - 1.0
    try:
        while True:
            busy = {e.name for e, _ in running.values()}
            progressed = not failed
            while progressed:  # launch (or skip) every entry whose dependencies are done
                progressed = False
                for e in list(todo.values()):
                    if len(running) >= jobs:
                        break
                    if any(d in todo or d in busy for d in e.depends_on):
                        continue
                    del todo[e.name]
                    stamp = stamp_for(e, quick, digests)
                    if not force and is_up_to_date(e, stamp):
                        n_done += 1
                        digests[e.name] = stamp["digest"]
                        log(f"[{n_done}/{n_total}] {e.name} ... up to date (skipped)")
                        progressed = True
                        continue
                    log(f"      running {e.name} ...")
                    fut = pool.submit(execute_entry, e, e.effective_parameters(quick), stamp,
                                      timeout)
                    running[fut] = (e, stamp)
                    busy.add(e.name)
            if not running:
                break
            done, _ = cf.wait(list(running), return_when=cf.FIRST_COMPLETED)
            for fut in done:
                e, stamp = running.pop(fut)
                try:
                    res = fut.result()
                except Exception as exc:  # the worker process itself died
                    res = {"ok": False, "seconds": 0.0, "error": f"worker crashed: {exc!r}"}
                n_done += 1
                if res["ok"]:
                    digests[e.name] = stamp["digest"]
                    log(f"[{n_done}/{n_total}] {e.name} ... ok {res['seconds']:.1f} s")
                else:
                    log(f"[{n_done}/{n_total}] {e.name} ... FAILED {res['seconds']:.1f} s")
                    failed.append((e, res["error"]))
    except BaseException as exc:  # Interrupted, KeyboardInterrupt, or a bug here
        if isinstance(exc, Interrupted):
            exc.stopped = sorted(e.name for e, _ in running.values())
        stop_workers(pool)
        remove_temporaries(started)
        raise
    pool.shutdown(wait=True)
    if failed and todo:
        log(f"not run because of the failure: {sorted(todo)}")
    for e, err in failed:
        rel = e.failed_path.relative_to(paths.ROOT) if e.failed_path.exists() else None
        log(f"\nerror: entry {e.name!r} ({e.notebook.relative_to(paths.ROOT)}) failed: {err}")
        if rel:
            log(f"the executed notebook with the error is {rel}")
        log(f"other outputs in {_shown(paths.GENERATED)} were left as they were.")
    return not failed


# ====================================================================== book build
def _generated_digest(entries: list[Entry]) -> str:
    h = hashlib.sha256()
    for e in entries:
        s = read_stamp(e) or {}
        h.update(f"{e.name}:{s.get('digest')}:{s.get('executed_utc')}\n".encode())
    return h.hexdigest()


def _shown(path: Path) -> str:
    """``path`` relative to the repository when below it (as a reader types it)."""
    path = Path(path)
    return path.relative_to(paths.ROOT).as_posix() if path.is_relative_to(paths.ROOT) \
        else str(path)


def build_book(entries: list[Entry], log=print) -> bool:
    """Run jupyter-book on the book being built (execution off); True on success.

    The book is :data:`lunarcap.repro.paths.BOOK`: ``book/``, or ``book/_build/quick/`` for
    a quick build. The full jupyter-book output goes to ``_build/jupyter-book.log`` below
    it; on failure its warnings and errors are printed.
    """
    missing = [e.name for e in entries if not e.output.is_file()]
    if missing:
        log(f"error: cannot build the book: no executed notebook for {missing}; run "
            f"`python -m lunarcap.report.build build` (without --only) first")
        return False
    digest = _generated_digest(entries)
    marker = paths.BUILD / ".generated-digest"
    full = not (paths.HTML / "index.html").is_file() or not marker.is_file() or \
        marker.read_text().strip() != digest
    jb = Path(sys.executable).with_name("jupyter-book")
    cmd = [str(jb) if jb.exists() else "jupyter-book", "build", str(paths.BOOK), "-W", "-n",
           "--keep-going"] + (["--all"] if full else [])
    log(f"      building the book ({'full' if full else 'incremental'}): "
        f"{' '.join(Path(c).name if i == 0 else c for i, c in enumerate(cmd))}")
    t0 = time.perf_counter()
    paths.BUILD.mkdir(parents=True, exist_ok=True)
    proc = subprocess.run(cmd, cwd=paths.ROOT, capture_output=True, text=True)
    out = _ANSI.sub("", proc.stdout + proc.stderr)
    paths.write_text_atomic(paths.BUILD / "jupyter-book.log", out)
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        lines = [ln for ln in out.splitlines()
                 if re.search(r"WARNING|ERROR|Error|Exception|Traceback", ln)]
        log(f"      jupyter-book ... FAILED {dt:.1f} s")
        log("\n".join(lines[-40:]) or "\n".join(out.splitlines()[-40:]))
        log(f"full log: {_shown(paths.BUILD / 'jupyter-book.log')}")
        marker.unlink(missing_ok=True)
        return False
    paths.write_text_atomic(marker, digest)
    log(f"      jupyter-book ... ok {dt:.1f} s")
    return True


# ====================================================================== CLI
def build_parser() -> argparse.ArgumentParser:
    """The argument parser."""
    p = argparse.ArgumentParser(prog="python -m lunarcap.report.build",
                                description="Execute the notebook manifest and build the book.")
    sub = p.add_subparsers(dest="command", required=True)
    b = sub.add_parser("build", help="execute notebooks (papermill) and build the HTML book")
    b.add_argument("--quick", action="store_true",
                   help="use each entry's quick_parameters (coarse, for CI)")
    b.add_argument("--jobs", "-j", type=int, default=2, help="parallel notebook executions")
    b.add_argument("--only", nargs="+", metavar="NAME",
                   help="execute only these entries (and stale dependencies)")
    b.add_argument("--force", action="store_true", help="re-execute even if up to date")
    b.add_argument("--no-build", action="store_true", help="execute only; skip jupyter-book")
    b.add_argument("--timeout", type=float, default=None,
                   help="per-cell execution timeout, s (default: none)")
    sub.add_parser("check", help="validate the manifest and the table of contents")
    return p


def main(argv=None) -> int:
    """Entry point; returns the exit status."""
    args = build_parser().parse_args(argv)
    t0 = time.perf_counter()
    try:
        entries = load_manifest()
        check_toc(entries)
        if args.command == "check":
            print(f"manifest ok: {len(entries)} entries; table of contents matches")
            return 0
        if args.jobs < 1:
            raise ManifestError("--jobs must be at least 1")
        chosen = select(entries, args.only)
    except ManifestError as exc:
        print(f"lunarcap.report.build: error: {exc}", file=sys.stderr)
        return 2
    mode = "quick" if args.quick else "full"
    if args.quick and not os.environ.get("LUNARCAP_BOOK_DIR"):
        paths.use_book(paths.stage_quick_book())  # never over the full book's results
    print(f"lunarcap.report.build: {len(chosen)} of {len(entries)} entries, {mode} parameters, "
          f"up to {args.jobs} in parallel", flush=True)
    stage = "notebooks"
    try:
        with interruptible():
            ok = run_entries(chosen, quick=args.quick, jobs=args.jobs, force=args.force,
                             timeout=args.timeout)
            if ok and not args.no_build:
                stage = "book"
                ok = build_book(entries)
                if ok:
                    print(f"book: {(paths.HTML / 'index.html')}")
    except Interrupted as exc:
        if stage == "book":  # the next run rebuilds the whole book
            (paths.BUILD / ".generated-digest").unlink(missing_ok=True)
            what = "the jupyter-book build was stopped"
        else:
            stopped = getattr(exc, "stopped", [])
            what = (f"stopped {len(stopped)} running notebook(s) ({', '.join(stopped)})"
                    if stopped else "no notebook was running")
        print(f"lunarcap.report.build: interrupted by {exc} after "
              f"{time.perf_counter() - t0:.1f} s: {what}; completed outputs in "
              f"{_shown(paths.GENERATED)} are kept, nothing half-written is left",
              file=sys.stderr, flush=True)
        return exc.exit_status
    print(f"total {time.perf_counter() - t0:.1f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
