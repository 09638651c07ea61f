"""Shared fixtures: the paper's mission window and arrival state, and a loopback Dask cluster.

The window is the one a capture of the paper's plan spans: from 6 h before the first
perilune (2017-02-20 03:41:26 TDB) to 6 h after the last (12.235 h + 3.525 h +
117.848 min later), the margin every burn's ephemeris fit keeps.
"""

import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics.ephemeris import ChebyshevFit, default_ephemeris
from lunarcap.physics.epochs import seconds_from_calendar

T_ARRIVAL_S = seconds_from_calendar(paper_scenario().epoch_tdb)
T_LAST_PERILUNE_S = T_ARRIVAL_S + sum(paper_scenario().capture_periods_s)


#: The repository and the venv's dask command (the loopback cluster of the Dask tests).
ROOT = Path(__file__).resolve().parents[1]
DASK = Path(sys.executable).parent / "dask"


@pytest.fixture(scope="session")
def mission_fit():
    """Chebyshev fit of the Earth and Sun over the paper's capture, +-6 h."""
    return ChebyshevFit.fit(default_ephemeris(), T_ARRIVAL_S - 6 * 3600.0,
                            T_LAST_PERILUNE_S + 6 * 3600.0)


@pytest.fixture(scope="session")
def paper_arrival():
    """The reconstructed arrival state of the paper's plans (north hemisphere)."""
    from lunarcap.mission.arrival import arrival_state

    return arrival_state()


@pytest.fixture(scope="session")
def third_burn():
    """Where the paper's third burn starts: (perilune epoch s, circle epoch s, orbit(height_m)).

    The nominal perilune before it (TDB s), the circle's epoch one printed period
    (117.848 min) later, and ``orbit(height_m)``: the paper's second capture orbit (3.525
    h, polar) at that perilune as MEE (7,), placed where the paper's arrival perilune is
    (its plane and longitude), its perilune ``height_m`` above the 100 km circle, 500 kg.
    """
    import numpy as np

    from lunarcap.mission.arrival import arrival_state
    from lunarcap.physics import constants as C
    from lunarcap.physics.elements import semi_major_axis_from_period

    periods = paper_scenario().capture_periods_s
    t0 = T_ARRIVAL_S + sum(periods[:2])
    x = np.asarray(arrival_state().state, float)
    a = float(semi_major_axis_from_period(periods[1], C.MU_MOON))

    def orbit(height_m: float = 0.0):
        rp = C.R_MOON + 100.0 + height_m * 1e-3
        e, L = 1.0 - rp / a, x[5]
        return np.array([rp * (1 + e), e * np.cos(L), e * np.sin(L), x[3], x[4], L, 500.0])

    return t0, t0 + 117.848 * 60.0, orbit


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def dask_cluster(tmp_path):
    """A dask scheduler and one worker on 127.0.0.1 (processes of the shared venv)."""
    port = _free_port()
    env = dict(os.environ, PYTHONPATH=str(ROOT), LUNARCAP_NO_CACHE="1")
    log = open(tmp_path / "dask.log", "w")
    sched = subprocess.Popen([str(DASK), "scheduler", "--host", "127.0.0.1", "--port",
                              str(port), "--no-dashboard"], env=env, stdout=log, stderr=log)
    addr = f"tcp://127.0.0.1:{port}"
    worker = subprocess.Popen([str(DASK), "worker", addr, "--nworkers", "1",
                               "--nthreads", "1", "--no-dashboard", "--host", "127.0.0.1"],
                              env=env, stdout=log, stderr=log)
    try:
        from dask.distributed import Client

        deadline = time.monotonic() + 60
        while True:
            try:
                with Client(addr, timeout="5s") as c:
                    if c.scheduler_info()["workers"]:
                        break
            except OSError:
                pass
            assert time.monotonic() < deadline, (tmp_path / "dask.log").read_text()
            time.sleep(0.5)
        yield addr
    finally:
        for p in (worker, sched):
            p.terminate()
        for p in (worker, sched):
            try:
                p.wait(10)
            except subprocess.TimeoutExpired:
                p.kill()
        log.close()
