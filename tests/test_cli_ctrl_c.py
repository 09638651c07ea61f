"""Ctrl-C in ``lunarcap plan``, ``burns`` and ``missed``, as a user presses it.

Each command runs as a real process in its own session (``python -m lunarcap``, two-body
dynamics, no disk cache, small grids), and SIGINT goes to its whole process group, as a
terminal sends it: to the command and to every Dask worker process it started. Required
of each: exit status 130, exactly one line on stderr, no traceback from any process (the
workers share the command's stderr), no process of the group left behind.

The signal is sent once the work is under way: for ``plan``, after the table's header
(stdout unbuffered) and into the first solve; for the studies (no progress bar, so that
stderr holds only what the interrupt prints), once the cluster's worker processes exist
and one of them is solving its case. The studies have one case for two workers:
an idle worker dies at once on SIGINT, printing its traceback (~30 lines) before the
command can close the cluster; a busy one only once its case ends, usually after the
command has already stopped it.
"""

import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import psutil
import pytest

ROOT = Path(__file__).resolve().parents[1]

pytestmark = pytest.mark.slow

STUDY_LINE = ("lunarcap: interrupted; finished {} are in the table, run the same command "
              "again to resume")


class Command:
    """A ``python -m lunarcap`` process in its own session, its output read as it comes."""

    def __init__(self, args, tmp_path):
        env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "PYTHONUNBUFFERED": "1",
               "HOME": str(tmp_path), "LUNARCAP_CACHE_DIR": str(tmp_path / "cache")}
        self.proc = subprocess.Popen([sys.executable, "-m", "lunarcap", *args], cwd=ROOT,
                                     env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                     text=True, start_new_session=True)
        self.pid = self.proc.pid
        self.out, self.err = [], []
        self.readers = [threading.Thread(target=self._read, args=(f, buf), daemon=True)
                        for f, buf in ((self.proc.stdout, self.out),
                                       (self.proc.stderr, self.err))]
        for t in self.readers:
            t.start()

    @staticmethod
    def _read(f, buf):
        for line in f:
            buf.append(line)

    def poll(self):
        return self.proc.poll()

    def output(self):
        for t in self.readers:
            t.join(timeout=10)
        return "".join(self.out), "".join(self.err)


def _wait_for(proc, ready, timeout_s=60.0):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if proc.poll() is not None:
            out, err = proc.output()
            pytest.fail(f"finished before it could be interrupted ({proc.poll()}):\n"
                        f"{out}\n{err}")
        if ready():
            return
        time.sleep(0.05)
    _kill_group(proc.pid)
    pytest.fail("never got under way")


def _group(pgid):
    """The live processes of group ``pgid``: a zombie has exited (a compiler the command
    started, orphaned when it left by ``os._exit``: its reaping is the init process's,
    which takes 1-2 s in some containers), so it is not one."""
    out = []
    for p in psutil.process_iter():
        try:
            if os.getpgid(p.pid) == pgid and p.status() != psutil.STATUS_ZOMBIE:
                out.append(p)
        except (ProcessLookupError, psutil.Error):
            pass
    return out


def _kill_group(pgid):
    try:
        os.killpg(pgid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def _interrupt(proc, timeout_s=60.0):
    """SIGINT to the process group; (exit status, stdout, stderr, processes left)."""
    os.killpg(proc.pid, signal.SIGINT)
    try:
        proc.proc.wait(timeout=timeout_s)
    except subprocess.TimeoutExpired:
        _kill_group(proc.pid)
        pytest.fail(f"still running {timeout_s:g} s after Ctrl-C:\n{proc.output()[1]}")
    deadline = time.monotonic() + 5.0
    left = _group(proc.pid)
    while left and time.monotonic() < deadline:
        time.sleep(0.1)
        left = _group(proc.pid)
    names = [f"{p.pid} {' '.join(p.cmdline())[:120]}" for p in left if p.is_running()]
    _kill_group(proc.pid)
    out, err = proc.output()
    return proc.poll(), out, err, names


def _check(code, out, err, left, line):
    assert "Traceback" not in out + err, err
    assert err.splitlines() == [line], err
    assert code == 130, err
    assert left == [], left


def test_ctrl_c_in_plan(tmp_path):
    proc = Command(["plan", "song2011-150N", "--dynamics", "two-body", "--no-cache",
                    "--quiet"], tmp_path)
    _wait_for(proc, lambda: any(line.startswith("burn  target") for line in proc.out))
    time.sleep(0.5)  # into the first burn's solve
    code, out, err, left = _interrupt(proc)
    _check(code, out, err, left, "lunarcap: interrupted")


def test_ctrl_c_while_the_nlps_are_built_acts_within_1_s(tmp_path):
    # issue 24: during the NLP builds (seconds each in C++, in full dynamics) Ctrl-C took
    # 6-13 s to act; the builds now run in threads the command does not wait for
    proc = Command(["plan", "song2011-150N", "--no-cache"], tmp_path)
    _wait_for(proc, lambda: any(ln.startswith("building ") for ln in proc.err))
    time.sleep(0.3)  # into the builds (4 of them, 1-5 s each by the machine's load)
    built = sum(ln.startswith("  ") for ln in proc.err)
    assert built < 4, proc.err  # some still being built
    t0 = time.monotonic()
    code, out, err, left = _interrupt(proc)
    acted_s = time.monotonic() - t0
    assert "Traceback" not in out + err, err
    assert err.splitlines()[1:] == ["lunarcap: interrupted"], err
    assert code == 130 and left == [], (code, left)
    assert acted_s < 1.0, acted_s


def _workers(pid):
    """The Dask worker processes below ``pid`` (not multiprocessing's resource tracker)."""
    out = []
    for p in psutil.Process(pid).children(recursive=True):
        try:
            if "resource_tracker" not in " ".join(p.cmdline()):
                out.append(p)
        except psutil.Error:  # gone, or a zombie
            pass
    return out


def _case_running(proc, n, cpu_s=3.0):
    """True once ``n`` worker processes exist and one has used ``cpu_s`` of CPU.

    Starting a worker (importing lunarcap, CasADi and Dask) takes about 2 s of CPU: past
    3 s, a case is being solved, and the other worker is idle.
    """
    def ready():
        workers = _workers(proc.pid)
        cpu = []
        for p in workers:
            try:
                t = p.cpu_times()
                cpu.append(t.user + t.system)
            except psutil.Error:
                pass
        return len(workers) >= n and max(cpu, default=0.0) >= cpu_s
    return ready


@pytest.mark.parametrize("argv, unit", [
    (["burns", "song2011-150N", "--counts", "5"], "counts"),
    # several cases: one two-body recovery now takes a few seconds, over before Ctrl-C
    (["missed", "song2011-150N", "--fractions", "0.25,0.5,0.75,0.9", "--delays-min",
      "30,120"], "cases"),
    (["dispersions", "song2011-150N", "--samples", "200", "--thrust-sigma-pct", "1",
      "--pointing-sigma-deg", "0.3"], "samples"),
])
def test_ctrl_c_in_a_study(argv, unit, tmp_path):
    proc = Command([*argv, "--dynamics", "two-body", "--no-cache", "--no-progress",
                   "--workers", "2", "--out", str(tmp_path / "t.csv")], tmp_path)
    _wait_for(proc, _case_running(proc, 2))
    code, out, err, left = _interrupt(proc)
    _check(code, out, err, left, STUDY_LINE.format(unit))


def test_ctrl_c_during_an_ipopt_solve_is_raised_once_it_returns(capfd):
    # CasADi turns a KeyboardInterrupt met during IPOPT into the status
    # NonIpopt_Exception_Thrown and a warning, and the command carried on; under the CLI's
    # handler the solve ends as it would have and Ctrl-C is raised right after
    import threading

    import casadi as ca

    from lunarcap.cli import _interrupt_outside_casadi

    n = 3000
    x = ca.MX.sym("x", n)
    f = 100 * ca.sumsqr(x[1:] - x[:-1] ** 2) + ca.sumsqr(1 - x[:-1])  # Rosenbrock
    solver = ca.nlpsol("s", "ipopt", {"x": x, "f": f}, {
        "ipopt.print_level": 0, "print_time": 0, "ipopt.max_iter": 300, "ipopt.tol": 1e-30})
    statuses = []
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    with pytest.raises(KeyboardInterrupt):
        with _interrupt_outside_casadi():
            timer.start()
            t0 = time.monotonic()
            solver(x0=[-1.2] * n)
            statuses.append((solver.stats()["return_status"], time.monotonic() - t0))
            time.sleep(5.0)  # the deferred interrupt comes here
    timer.join()
    assert len(statuses) == 1 and statuses[0][1] > 0.3, statuses  # SIGINT during the solve
    assert statuses[0][0] == "Maximum_Iterations_Exceeded", statuses
    assert "KeyboardInterrupt" not in "".join(capfd.readouterr())
