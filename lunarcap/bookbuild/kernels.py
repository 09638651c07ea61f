"""One notebook kernel per build worker, kept from one entry to the next.

A fresh kernel for every page costs its start-up and imports again (about 2.5 s of CPU:
ipykernel, numpy, pandas, matplotlib, CasADi) and every NLP shape the page solves
(1.6 s of CPU each, see :mod:`lunarcap.optim.nlp`), although the pages of one build ask
for the same few shapes. So each worker of :func:`lunarcap.bookbuild.execution.run_entries`
starts one kernel and runs its entries in it, one after another. Before each entry a
prelude cell (:func:`prelude_cell`, removed from the page afterwards) empties the
namespace (``%reset -f``), closes the figures left open and sets the environment the
entry asks for (the shared study cluster's address), so a page sees what a fresh kernel
would show it, apart from the modules already imported and the NLPs already built: the
page's outputs are the same (a test compares them). The kernel is restarted after a
failed entry, when it has died, and when its memory passes :data:`RSS_LIMIT_BYTES`.

A reader who runs one notebook with papermill or Jupyter still gets a kernel of its own.
"""

from __future__ import annotations

import contextlib
import multiprocessing.util
import os
from pathlib import Path

#: Tag of the prelude cell (removed from the executed notebook, see :func:`drop_prelude`).
PRELUDE_TAG = "lunarcap-prelude"

#: Environment variables a prelude sets from the entry's ``env`` or removes when it has none.
MANAGED_ENV = ("LUNARCAP_DASK_SCHEDULER",)

#: A kernel whose resident memory passes this after an entry is restarted (bytes).
RSS_LIMIT_BYTES = 3 * 2**30

#: Name under which :class:`SharedKernelEngine` is registered with papermill.
ENGINE_NAME = "lunarcap-shared-kernel"

_STATE: dict = {"km": None}


def prelude_cell(env: dict):
    """The code cell run before an entry's own cells (a notebook cell, tagged)."""
    import nbformat

    lines = ["%reset -f",
             "import os as _os, sys as _sys, warnings as _warnings",
             "if 'matplotlib.pyplot' in _sys.modules:",
             "    _sys.modules['matplotlib.pyplot'].close('all')",
             "_warnings._filters_mutated()  # a warning shown by an earlier page shows again"]
    for key in MANAGED_ENV:
        lines.append(f"_os.environ[{key!r}] = {env[key]!r}" if key in env
                     else f"_os.environ.pop({key!r}, None)")
    lines.append("del _os, _sys, _warnings")
    cell = nbformat.v4.new_code_cell("\n".join(lines))
    cell.metadata["tags"] = [PRELUDE_TAG, "remove-cell"]
    return cell


def with_prelude(nb, env: dict):
    """``nb`` (a notebook node, changed in place) with the prelude as its first cell."""
    nb.cells.insert(0, prelude_cell(env))
    return nb


def drop_prelude(nb) -> None:
    """Remove the prelude and number the code cells' executions from 1, as a fresh kernel."""
    nb.cells = [c for c in nb.cells if PRELUDE_TAG not in c.get("metadata", {}).get("tags", [])]
    count = 0
    for cell in nb.cells:
        if cell.cell_type != "code" or cell.get("execution_count") is None:
            continue
        count += 1
        cell.execution_count = count
        for out in cell.get("outputs", []):
            if "execution_count" in out:
                out["execution_count"] = count


def _pid():
    km = _STATE["km"]
    proc = getattr(getattr(km, "provisioner", None), "process", None)
    return getattr(proc, "pid", None)


def _stat_fields(pid: int) -> list[str]:
    stat = Path(f"/proc/{pid}/stat").read_text()
    return stat[stat.rindex(")") + 2:].split()


def kernel_cpu_s() -> float:
    """CPU seconds (user + system, its finished children included) of the live kernel; 0 if none."""
    pid = _pid()
    if pid is None:
        return 0.0
    try:
        f = _stat_fields(pid)
    except (OSError, ValueError):
        return 0.0
    ticks = os.sysconf("SC_CLK_TCK")
    return sum(int(x) for x in f[11:15]) / ticks  # utime, stime, cutime, cstime


def kernel_rss_bytes() -> int:
    """Resident memory of the live kernel (bytes); 0 if none."""
    pid = _pid()
    if pid is None:
        return 0
    try:
        return int(_stat_fields(pid)[21]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError, IndexError):
        return 0


def shutdown() -> None:
    """Stop this worker's kernel, if any (the next entry starts a new one)."""
    km, _STATE["km"] = _STATE["km"], None
    if km is None or not km.has_kernel:
        return
    from jupyter_core.utils import run_sync

    with contextlib.suppress(Exception):
        run_sync(km.shutdown_kernel)(now=True)
    with contextlib.suppress(Exception):
        run_sync(km.cleanup_resources)()


def ready(kernel_name: str):
    """The kernel manager of this worker, fit for the next entry (nbclient starts it).

    A dead kernel or one over :data:`RSS_LIMIT_BYTES` is replaced. The kernel inherits
    this process's stderr when it starts (the caller points it at a log first).
    """
    from jupyter_client.manager import AsyncKernelManager
    from jupyter_core.utils import run_sync

    km = _STATE["km"]
    if km is not None and km.has_kernel:
        alive = False
        with contextlib.suppress(Exception):
            alive = run_sync(km.is_alive)()
        if not alive or kernel_rss_bytes() > RSS_LIMIT_BYTES:
            shutdown()
            km = None
    if km is None or not km.has_kernel:
        km = AsyncKernelManager(kernel_name=kernel_name)
        _STATE["km"] = km
        multiprocessing.util.Finalize(None, shutdown, exitpriority=10)
    return km


def _register() -> None:
    from papermill.clientwrap import PapermillNotebookClient
    from papermill.engines import NBClientEngine, papermill_engines
    from papermill.log import logger

    class SharedKernelEngine(NBClientEngine):
        """papermill's nbclient engine on this worker's kernel, its client closed after."""

        @classmethod
        def execute_managed_notebook(cls, nb_man, kernel_name, log_output=False,
                                     stdout_file=None, stderr_file=None, start_timeout=60,
                                     execution_timeout=None, **kwargs):
            client = PapermillNotebookClient(
                nb_man, km=_STATE["km"], timeout=execution_timeout,
                startup_timeout=start_timeout, kernel_name=kernel_name, log=logger,
                log_output=log_output, stdout_file=stdout_file, stderr_file=stderr_file)
            try:
                return client.execute()
            finally:
                if client.kc is not None:
                    client.kc.stop_channels()

    papermill_engines.register(ENGINE_NAME, SharedKernelEngine)


def engine_name() -> str:
    """The papermill engine running notebooks on this worker's kernel (registered once)."""
    from papermill.engines import papermill_engines

    if ENGINE_NAME not in papermill_engines._engines:
        _register()
    return ENGINE_NAME
