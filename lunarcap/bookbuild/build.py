"""Execute the book's notebooks with papermill, then build the HTML book.

Usage::

    python -m lunarcap.bookbuild.build build [--quick] [--jobs N] [--only NAME ...] [--force]
                                             [--no-build] [--scheduler tcp://host:port]
    python -m lunarcap.bookbuild.build check   # validate the pages and the table of contents

What runs is the manifest: one entry per execution of a notebook, declared by the page
modules (:mod:`lunarcap.report.contents`; see :mod:`lunarcap.bookbuild.manifest`). Every
entry also receives ``quick`` (bool) and ``output_name`` (its name). Entries run in
dependency order, independent ones in parallel on up to ``--jobs`` worker processes, each
running its entries in one kernel emptied before each (:mod:`lunarcap.bookbuild.kernels`).
An executed notebook is moved into place only on success; a failure stops the run,
names the entry and cell and keeps ``book/generated/<name>.failed.ipynb``. An entry is
skipped when its stamp (``book/generated/<name>.stamp.json``: notebook, parameters, quick
flag, lunarcap source, lock, title, dependencies) matches and its outputs exist.

The book is then built with ``jupyter-book build book -W -n --keep-going`` with execution
off (``--all`` whenever the generated notebooks changed, since pages quote each other's
glued numbers), with the table of contents generated from the pages in ``_build/_toc.yml``
(beside it ``_build/manifest.yml``, what the build executed). ``--quick`` builds a
separate book in ``book/_build/quick/`` (:func:`lunarcap.repro.paths.stage_quick_book`),
so ``make test`` never replaces the full book. A full build refuses, before running
anything, a page whose parameters are below the floors its page declares (the sizes its
claims need, :func:`lunarcap.bookbuild.manifest.check_floors`); the quick book is exempt
and says so at the top of each of its pages. SIGINT or SIGTERM stop the run within
seconds, leaving nothing half-written (:mod:`lunarcap.bookbuild.execution`).

The book's studies (entries whose parameters set ``workers``) share one local Dask cluster
of ``--jobs`` workers, or run on an existing cluster with ``--scheduler`` (``make book
SCHEDULER=tcp://host:port``), checked before any entry runs.

Exit status: 0 success, 1 an entry or the book build failed, 2 invalid manifest or usage,
130 interrupted by SIGINT, 143 interrupted by SIGTERM.
"""

from __future__ import annotations

import argparse
import hashlib
import os
import re
import subprocess
import sys
import time
from pathlib import Path

from lunarcap.bookbuild.execution import (  # noqa: F401  (the API of this module too)
    _ANSI,
    SETUP_HEADING,
    Interrupted,
    _alive,
    _kill_all,
    _shown,
    descendants,
    execute_entry,
    interruptible,
    longest_first,
    move_setup_to_end,
    only_shows,
    prepare_for_book,
    remove_temporaries,
    run_entries,
    stop_workers,
)
from lunarcap.bookbuild.manifest import (  # noqa: F401  (the API of this module too)
    ENTRY_KEYS,
    INJECTED,
    KERNEL,
    REQUIRED_KEYS,
    STAMP_VERSION,
    Entry,
    ManifestError,
    check_floors,
    check_toc,
    find_cycle,
    is_up_to_date,
    load_manifest,
    notebook_parameters,
    read_stamp,
    select,
    stamp_for,
    toc_files,
    validate_manifest,
    write_contents,
)
from lunarcap.repro import paths


# ====================================================================== book build
def _generated_digest(entries: list[Entry]) -> str:
    h = hashlib.sha256()
    for e in entries:
        s = read_stamp(e) or {}
        h.update(f"{e.name}:{s.get('digest')}:{s.get('executed_utc')}\n".encode())
    return h.hexdigest()


def build_book(entries: list[Entry], log=print) -> bool:
    """Run jupyter-book on the book being built (execution off); True on success.

    The book is :data:`lunarcap.repro.paths.BOOK`: ``book/``, or ``book/_build/quick/`` for
    a quick build. The full jupyter-book output goes to ``_build/jupyter-book.log`` below
    it; on failure its warnings and errors are printed.
    """
    missing = [e.name for e in entries if not e.output.is_file()]
    if missing:
        log(f"error: cannot build the book: no executed notebook for {missing}; run "
            f"`python -m lunarcap.bookbuild.build build` (without --only) first")
        return False
    digest = _generated_digest(entries)
    marker = paths.BUILD / ".generated-digest"
    full = not (paths.HTML / "index.html").is_file() or not marker.is_file() or \
        marker.read_text().strip() != digest
    toc = write_contents(paths.BUILD)
    jb = Path(sys.executable).with_name("jupyter-book")
    cmd = [str(jb) if jb.exists() else "jupyter-book", "build", str(paths.BOOK), "-W", "-n",
           "--keep-going"] + (["--toc", str(toc)] if toc else []) + (["--all"] if full else [])
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
    log(f"      jupyter-book ... ok {dt:.1f} s")
    from lunarcap.bookbuild.bookcheck import check_pages

    said_nan = check_pages(paths.HTML, toc_files())
    if said_nan:
        log(f"error: {len(said_nan)} built page(s) print \"nan\" where a value is missing "
            f"(glue it as missing with its reason, Page.value(name, v, why=...)):")
        for page, contexts in said_nan.items():
            log(f"  {page}: " + " | ".join(repr(c) for c in contexts[:3]))
        return False
    paths.write_text_atomic(marker, digest)
    return True


# ====================================================================== CLI
def use_scheduler(address: str, timeout_s: float = 20.0) -> str:
    """Run the book's studies on the Dask cluster at ``address`` (checked before any work).

    The address goes to every study's kernel as
    :data:`lunarcap.studies.campaign.SCHEDULER_ENV` (as the CLI's ``--scheduler``): the
    book's own local cluster is not started. ManifestError (exit 2) if it is no address,
    or no scheduler with at least one worker answers there within ``timeout_s``.
    """
    from lunarcap.errors import InputError
    from lunarcap.studies.campaign import SCHEDULER_ENV, check_scheduler

    try:
        address = check_scheduler(address)
    except InputError as exc:
        raise ManifestError(f"--scheduler: {exc}") from None
    address = address.strip()
    from dask.distributed import Client

    try:
        with Client(address, timeout=f"{timeout_s:g}s") as client:
            workers = len(client.scheduler_info().get("workers", {}))
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        raise ManifestError(f"--scheduler {address}: no Dask scheduler answers there "
                            f"({_one_line(exc)})") from None
    if not workers:
        raise ManifestError(f"--scheduler {address}: the scheduler has no worker to run "
                            f"the studies")
    os.environ[SCHEDULER_ENV] = address
    return address


def _one_line(exc) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    return text[:200]


def build_parser() -> argparse.ArgumentParser:
    """The argument parser."""
    p = argparse.ArgumentParser(prog="python -m lunarcap.bookbuild.build",
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
    b.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run the book's studies on this existing Dask cluster "
                        "(tcp://host:port; its workers need lunarcap importable) instead of "
                        "local worker processes")
    sub.add_parser("check", help="validate the pages (or manifest) and the table of contents")
    return p


def main(argv=None) -> int:
    """Entry point; returns the exit status."""
    args = build_parser().parse_args(argv)
    t0 = time.perf_counter()
    try:
        entries = load_manifest()
        check_toc(entries)
        if args.command == "check":
            check_floors(entries)
            print(f"manifest ok: {len(entries)} entries; table of contents matches; every "
                  f"page at or above its floors")
            return 0
        if args.jobs < 1:
            raise ManifestError("--jobs must be at least 1")
        chosen = select(entries, args.only)
        if not args.quick:  # the quick book may stay small: each of its pages says so
            check_floors(chosen)
        if args.scheduler is not None:
            use_scheduler(args.scheduler)
    except ManifestError as exc:
        print(f"lunarcap.bookbuild.build: error: {exc}", file=sys.stderr)
        return 2
    mode = "quick" if args.quick else "full"
    if args.quick and not os.environ.get("LUNARCAP_BOOK_DIR"):
        paths.use_book(paths.stage_quick_book())  # never over the full book's results
    print(f"lunarcap.bookbuild.build: {len(chosen)} of {len(entries)} entries, {mode} parameters, "
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
        print(f"lunarcap.bookbuild.build: interrupted by {exc} after "
              f"{time.perf_counter() - t0:.1f} s: {what}; completed outputs in "
              f"{_shown(paths.GENERATED)} are kept, nothing half-written is left",
              file=sys.stderr, flush=True)
        return exc.exit_status
    print(f"total {time.perf_counter() - t0:.1f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
