"""The numerical libraries' messages during a missed-thrust solve: counted and logged.

CasADi reports a function evaluation that returned an infinite or undefined value as a
warning line written to Python's ``sys.stderr`` (``CasADi - <time> WARNING("arc:daeF
failed: Inf detected for output ode ...")``), and SUNDIALS CVODES its step-size troubles
(``Internal t = ... and h = ... are such that t + h = t``, ``At t = ... repeated
recoverable right-hand side function errors``). In a
recovery they come from guesses, not from answers: a guess that flies the nominal's
steering (made for a perilune, mostly along the track) far from the Moon, where the
transverse speed is small, removes the whole angular momentum; the orbit degenerates
(p -> 0), the modified equinoctial elements' right-hand side becomes infinite, CVODES
gives up, and that start fails (as it should) while the next is tried. Dozens of such
lines per case told the user nothing. :func:`counted` keeps them off the terminal for
the duration of a solve in this thread, counts them (the case's ``solver_warnings``) and
passes each to the logger ``lunarcap.studies.missed`` at DEBUG; every other line written
to ``sys.stderr`` meanwhile reaches it unchanged.
"""

from __future__ import annotations

import logging
import re
import sys
import threading
from contextlib import contextmanager

LOG = logging.getLogger("lunarcap.studies.missed")

#: The lines counted: CasADi's warnings and CVODES's messages (every one of which begins
#: with the integrator's time, "At t = " or "Internal t = ", or names CVODES).
SOLVER_LINE = re.compile(r"^(CasADi - .*WARNING\(|Internal t = |At t = |The above warning has "
                         r"been issued|\[CVODES)")


class Tally:
    """The solver lines met in one :func:`counted` block: their number and the first one."""

    def __init__(self) -> None:
        self.count = 0
        self.first = ""
        self._part = ""

    def feed(self, text: str, stream) -> None:
        """Take ``text`` written to stderr: count and log solver lines, pass the rest on."""
        lines = (self._part + text).split("\n")
        self._part = lines.pop()
        for line in lines:
            self._line(line, stream)

    def close(self, stream) -> None:
        """The last, unterminated line."""
        if self._part:
            self._line(self._part, stream, end="")
            self._part = ""

    def _line(self, line: str, stream, end: str = "\n") -> None:
        if SOLVER_LINE.match(line):
            self.count += 1
            self.first = self.first or line
            LOG.debug("%s", line)
        else:
            stream.write(line + end)


class _Stderr:
    """``sys.stderr`` while a :func:`counted` block runs: a thread's writes go to its tally."""

    def __init__(self, stream) -> None:
        self.stream = stream
        self.local = threading.local()
        self.users = 0   # the blocks running in any thread

    def write(self, text: str) -> int:
        tally = getattr(self.local, "tally", None)
        if tally is None:
            return self.stream.write(text)
        tally.feed(text, self.stream)
        return len(text)

    def flush(self) -> None:
        self.stream.flush()

    def __getattr__(self, name):
        return getattr(self.stream, name)


_LOCK = threading.Lock()


@contextmanager
def counted():
    """A block whose solver lines on ``sys.stderr`` are counted, not printed: its :class:`Tally`.

    Installed over ``sys.stderr`` while any thread is in such a block (and removed when
    the last leaves); nested blocks of one thread share the outer tally.
    """
    with _LOCK:
        wrapper = sys.stderr if isinstance(sys.stderr, _Stderr) else _Stderr(sys.stderr)
        sys.stderr = wrapper
        wrapper.users += 1
    outer = getattr(wrapper.local, "tally", None)
    tally = outer or Tally()
    wrapper.local.tally = tally
    try:
        yield tally
    finally:
        wrapper.local.tally = outer
        if outer is None:
            tally.close(wrapper.stream)
        with _LOCK:
            wrapper.users -= 1
            if wrapper.users == 0 and sys.stderr is wrapper:
                sys.stderr = wrapper.stream
