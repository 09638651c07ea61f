"""Command-line interface: ``lunarcap <command> ...`` (also ``python -m lunarcap``).

Every user error (bad input, a failed solve) prints one line ``lunarcap: error: ...``
to stderr and exits with status 2 (bad input) or 3 (solve failed); nothing already
written is lost.

lunarcap's own commands are one function each in this package (:data:`COMMANDS`:
:mod:`.plan`, :mod:`.solve`, :mod:`.impulsive`, :mod:`.plans`, :mod:`.bench`); every
registered study is a command too (:mod:`lunarcap.studies.registry`, run by
:mod:`.studies`). The parser is :mod:`.parser`; here, :func:`main` runs the command asked
and turns its errors and Ctrl-C into one line and an exit status.
"""

from __future__ import annotations

import contextlib
import sys

from lunarcap.cli import parser as cli_parser
from lunarcap.cli import studies as study_commands
from lunarcap.cli.bench import cmd_bench
from lunarcap.cli.impulsive import cmd_impulsive
from lunarcap.cli.plan import cmd_plan
from lunarcap.cli.plans import cmd_plans
from lunarcap.cli.solve import cmd_solve
from lunarcap.errors import InputError, LunarcapError, SolveError

#: The exit status of each error type, the first the error is an instance of: bad input 2,
#: a solve that did not converge or failed verification 3 (the API raises the same types).
EXIT_STATUS = ((InputError, 2), (SolveError, 3), (LunarcapError, 2))


def exit_status(exc: LunarcapError) -> int:
    """The command line's exit status for ``exc`` (:data:`EXIT_STATUS`)."""
    return next(code for cls, code in EXIT_STATUS if isinstance(exc, cls))


#: lunarcap's own commands (the studies' follow them, :mod:`lunarcap.studies.registry`).
COMMANDS = {"plan": cmd_plan, "solve": cmd_solve, "impulsive": cmd_impulsive,
            "plans": cmd_plans, "bench": cmd_bench}


def build_parser():
    """The argument parser of every subcommand (:func:`lunarcap.cli.parser.build_parser`)."""
    return cli_parser.build_parser(COMMANDS, __doc__.splitlines()[0], study_commands.command)


@contextlib.contextmanager
def _interrupt_outside_casadi():
    """Within the block, Ctrl-C raises KeyboardInterrupt, but never inside a CasADi call.

    CasADi checks for Ctrl-C during IPOPT and CVODES, and turns the KeyboardInterrupt it
    finds into a solver status (``NonIpopt_Exception_Thrown``) and a ``CasADi - WARNING``
    line; the command then carried on with the next mesh, or ended in a "failed solve".
    Here a SIGINT that arrives within a CasADi call (the handler's frame is CasADi's
    Python wrapper) is raised 0.1 s after the call returns (SIGALRM rechecks). Main
    thread only; the previous handlers are restored at the end.
    """
    import os
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        if frame is not None and f"{os.sep}casadi{os.sep}" in frame.f_code.co_filename:
            signal.setitimer(signal.ITIMER_REAL, 0.1)  # again once the call has returned
            return
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        raise KeyboardInterrupt

    old = {s: signal.signal(s, handler) for s in (signal.SIGINT, signal.SIGALRM)}
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        for s, h in old.items():
            signal.signal(s, h)


def main(argv=None) -> int:
    """Entry point; returns the exit status."""
    args = cli_parser.parse_args(build_parser(), argv)
    code = _run(args)
    if code == 130:
        _leave_abandoned_calls()
    return code


def _leave_abandoned_calls() -> None:
    """After Ctrl-C, exit at once (status 130) if a CasADi call still runs in a thread.

    Such a call (an NLP build, an IPOPT solve: :mod:`lunarcap.optim.interrupt`) may last
    seconds more, and tearing the interpreter down under it crashes (a segmentation fault
    instead of status 130): the streams are flushed and the process leaves with
    ``os._exit``; every ``finally`` of the command has run.
    """
    import os

    from lunarcap.optim.interrupt import busy

    if busy():
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(130)


def _run(args) -> int:
    """The command of ``args``, its errors turned into one line and an exit status."""
    from lunarcap.repro.cache import caching

    # --no-cache: the one cache switch, off for the whole command (studies ship its
    # position to their workers); without it the environment decides (LUNARCAP_NO_CACHE)
    no_cache = getattr(args, "no_cache", False)
    try:
        with _interrupt_outside_casadi(), caching(False) if no_cache else contextlib.nullcontext():
            return args.func(args)
    except BrokenPipeError:  # e.g. `lunarcap impulsive --json | head`
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except LunarcapError as exc:   # bad input or a failed solve: one line, its status
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return exit_status(exc)
    except KeyboardInterrupt:  # Ctrl-C (a study's says how to resume: _resumable)
        print("lunarcap: interrupted", file=sys.stderr)
        return 130
