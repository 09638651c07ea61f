"""Engine trade study: finite-burn loss of the capture chain against thrust-to-weight ratio.

For every engine (thrust T, specific impulse Isp) of a grid, the whole capture chain is
solved with :func:`lunarcap.capture.chain.solve_case`: LOI 1, 2 and 3 each with a free
ignition time (``start_min="free"``), each starting from the previous LOI's optimum.
The thrusts are log-spaced (default 30 points from 50 N to 2000 N), the Isp a short list
(default 200, 250, 300 s). Beside each optimum the table gives the Eq. (19) burn
duration and Robbins' analytic loss estimate (:mod:`lunarcap.physics.losses`).

Definitions
-----------
Thrust-to-weight ratio
    ``thrust_to_weight = T / (m0 g0)``, with m0 = 524.895 kg the mass at the first
    perilune, before LOI 1 (Song 2011, Sec. 3.2.1) and g0 = 9.80665 m/s^2 standard
    gravity (the g0 of the rocket equation and of Eq. (19)). This is the conventional,
    Earth-weight ratio: the paper's engines (150, 300, 450 N) have 0.0291, 0.0583 and
    0.0874. The same ratio for the lunar weight, ``T / (m0 g_moon)`` with
    g_moon = mu / R^2 = 1.6227 m/s^2 (:data:`G_MOON_MPS2`), is 6.04 times larger and is
    tabulated as ``thrust_to_lunar_weight``. Both use the arrival mass for every LOI,
    so one engine has one abscissa.
Loss
    Measured against the impulsive limit of the same burn in the same dynamics, from the
    same orbit (:func:`lunarcap.capture.chain.impulsive_limit`: one impulse at the best
    epoch, as the limit of ever shorter burns), so it goes to zero as the thrust grows.
    ``objective_loss_mps`` is the objective-based loss (:func:`lunarcap.capture.chain.burn_loss`):
    Eq. (9)'s delta-V plus the speed at the next perilune, finite minus impulsive, i.e.
    the extra delta-V of the burn plus the extra speed it leaves for the next one. It is
    never negative for an optimal burn and, unlike the delta-V difference, is well
    conditioned where the optimum is flat along the ignition epoch (a per-burn delta-V
    may move by ~0.2 m/s between two near-equal optima; the objective by ~0.003 m/s).
    ``delta_v_loss_mps`` is the plain delta-V difference the paper tabulates; for LOI 3
    (a circle: the end speed is fixed) the two agree. Percentages are of the impulsive
    delta-V. The sequence row sums the three burns (% of the summed impulsive delta-Vs).

Execution
---------
One Dask task per engine computes its three-LOI chain (the task imports lunarcap in the
worker). By default a :class:`dask.distributed.LocalCluster` of ``workers`` processes
with one thread each is started; ``scheduler="tcp://host:port"`` uses an existing
cluster instead (its workers need lunarcap installed). Solutions are also cached on disk
by joblib inside the workers (:mod:`lunarcap.repro.cache`), so a later study or notebook that
needs the same engine reuses them.

Results go to one CSV table (default ``STUDY.default_table_path()``, below the cache
directory), four rows per engine (``part`` = LOI1, LOI2, LOI3, sequence), appended as
each task completes: the table is rewritten to a temporary file and moved into place,
so it is never half-written. Rows carry :func:`lunarcap.repro.cache.code_version`; a rerun
skips every engine (thrust, Isp, dynamics) already present for the current code
version, so an interrupted study resumes where it stopped. A failed engine is recorded
(``status`` "failed" with IPOPT's status, or "task error"), not dropped and not retried
(unless ``retry_failed``). Each run appends its wall time, counts and the machine's load
to ``<table stem>.runs.json`` next to the table (:func:`runs_path`), also when it is
interrupted. A lock file keeps two runs from writing the same table at once.

Examples
--------
>>> spec = StudySpec(thrust_min_N=100, thrust_max_N=1000, points=3, isp_s=(250,))
>>> spec.thrusts_N
(100.0, 316.2, 1000.0)
>>> round(thrust_to_weight(150.0), 4)
0.0291
"""

from __future__ import annotations

import datetime as _dt
import os
import socket
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from lunarcap.errors import InputError, integer, number_list, positive_number
from lunarcap.physics.forces import PRESETS
from lunarcap.physics.losses import schuler_rate_rad_s
from lunarcap.studies import campaign as _campaign
from lunarcap.studies.engine_trade.theory import (  # noqa: F401  (this module's API too)
    G_MOON_MPS2,
    PERILUNE_RADIUS_KM,
    capture_chain_estimate,
    paper_points,
    thrust_from_weight_ratio,
    thrust_to_weight,
)
from lunarcap.studies.study import Study, check_workers

# The machinery the studies share (lunarcap.studies.campaign); runs_path and read_runs are
# this module's API too.
runs_path = _campaign.runs_path
read_runs = _campaign.read_runs

#: Default grid: thrust range (N), number of log-spaced thrusts, specific impulses (s).
DEFAULT_THRUST_MIN_N = 50.0
DEFAULT_THRUST_MAX_N = 2000.0
DEFAULT_POINTS = 30
DEFAULT_ISP_S = (200.0, 250.0, 300.0)
DYNAMICS = PRESETS

#: Significant digits kept in grid thrusts (so that table keys survive a CSV round trip).
THRUST_DIGITS = 4

#: The four rows of an engine.
PARTS = ("LOI1", "LOI2", "LOI3", "sequence")

#: Columns of the study table (units in the names).
COLUMNS = (
    "thrust_N", "isp_s", "dynamics", "part", "status",
    "thrust_to_weight", "thrust_to_lunar_weight",
    "start_min", "burn_duration_min", "eq19_duration_min", "burn_to_eq19_ratio",
    "delta_v_mps", "impulsive_limit_mps", "objective_loss_mps", "objective_loss_percent",
    "delta_v_loss_mps", "delta_v_loss_percent", "impulsive_verified", "impulsive_limit_reason",
    "analytic_eq19_duration_min", "analytic_loss_mps", "analytic_loss_percent",
    "m_start_kg", "m_end_kg", "fuel_kg",
    "ipopt_status", "ipopt_iterations", "verified", "mesh", "solve_wall_s",
    "task_wall_s", "worker", "code_version", "completed_utc", "error",
)

#: Row statuses: solved and verified; SolveError (see ``ipopt_status``); skipped because
#: an earlier LOI failed; an unexpected exception in the task; the Dask task itself
#: failed (worker lost); a sequence with a failed LOI.
STATUSES = ("ok", "failed", "not run", "error", "task error", "incomplete")

#: The study table as a campaign table: one case per engine (thrust, Isp, dynamics), four
#: rows per case told apart by ``part``.
TABLE = _campaign.TableFormat(
    key=("thrust_N", "isp_s", "dynamics"), columns=COLUMNS,
    text_columns=("dynamics", "part", "ipopt_status", "mesh", "impulsive_limit_reason"),
    row_key=("part",),
    name="study table")


# ====================================================================== definitions
# ====================================================================== parameters
def parse_isp_list(value) -> tuple:
    """Specific impulses from ``"200,250,300"`` or a sequence of numbers, s.

    :func:`lunarcap.errors.number_list`: InputError naming ``--isp`` on an empty list or
    item, a non-numeric or non-positive value, or a duplicate.
    """
    return number_list("--isp", value, "s", positive=True, distinct=True)


def thrust_grid(thrust_min_N: float, thrust_max_N: float, points: int) -> tuple:
    """Log-spaced thrusts from min to max inclusive, rounded to 4 significant digits, N."""
    tmin = positive_number("--thrust-min", thrust_min_N, "N")
    tmax = positive_number("--thrust-max", thrust_max_N, "N")
    n = integer("--points", points, 2)
    if tmin > tmax:
        raise InputError(f"minimum thrust {tmin:g} N is above the maximum {tmax:g} N")
    if tmin == tmax:
        raise InputError(f"the thrust range {tmin:g}-{tmax:g} N is empty: the maximum must "
                         f"exceed the minimum")
    grid = tuple(float(f"{t:.{THRUST_DIGITS}g}") for t in np.geomspace(tmin, tmax, n))
    grid = (tmin,) + grid[1:-1] + (tmax,)  # endpoints exactly as given
    if len(set(grid)) != n:
        raise InputError(f"{n} log-spaced points between {tmin:g} and {tmax:g} N are not "
                         f"distinct at {THRUST_DIGITS} significant digits: use fewer points "
                         f"or a wider range")
    return grid


@dataclass(frozen=True)
class StudySpec:
    """The grid of a trade study (validated on construction; InputError if bad).

    Attributes
    ----------
    thrust_min_N, thrust_max_N : float
        Thrust range, N (0 < min < max).
    points : int
        Number of log-spaced thrusts (at least 2).
    isp_s : tuple of float
        Specific impulses, s (a list, or text "200,250,300").
    dynamics : str
        "full", "j2" or "two-body", or the forces named as a plan's ``dynamics`` mapping
        (a dict, or its JSON or YAML text: ``{gravity: LP165P, degree: 8}``), kept as the
        canonical JSON of that mapping (:func:`dynamics_key`).
    """

    thrust_min_N: float = DEFAULT_THRUST_MIN_N
    thrust_max_N: float = DEFAULT_THRUST_MAX_N
    points: int = DEFAULT_POINTS
    isp_s: tuple = DEFAULT_ISP_S
    dynamics: str = "full"

    def __post_init__(self):
        grid = thrust_grid(self.thrust_min_N, self.thrust_max_N, self.points)
        object.__setattr__(self, "thrust_min_N", grid[0])
        object.__setattr__(self, "thrust_max_N", grid[-1])
        object.__setattr__(self, "points", len(grid))
        object.__setattr__(self, "isp_s", parse_isp_list(self.isp_s))
        object.__setattr__(self, "dynamics", dynamics_key(self.dynamics))

    @property
    def thrusts_N(self) -> tuple:
        """The grid's thrusts, N."""
        return thrust_grid(self.thrust_min_N, self.thrust_max_N, self.points)

    @property
    def engines(self) -> list:
        """(thrust N, Isp s) of every grid point, Isp-major, thrust ascending."""
        return [(t, isp) for isp in self.isp_s for t in self.thrusts_N]

    def to_dict(self) -> dict:
        """Plain dict (JSON-ready)."""
        d = asdict(self)
        d["isp_s"] = list(self.isp_s)
        return d


def dynamics_key(spec) -> str:
    """The trade study's dynamics as its table keeps it: a preset word or a mapping's JSON.

    ``spec``: "full", "j2", "two-body", a plan's ``dynamics`` mapping, or its text (JSON or
    YAML flow, ``{gravity: LP165P, degree: 8}``). The mapping is checked as a plan's is
    (InputError naming ``--dynamics``) and written back in full
    (:meth:`lunarcap.physics.forces.ForceModel.to_plan`, keys sorted), so one model is one
    key whatever its spelling.
    """
    import json

    import yaml

    from lunarcap.physics.forces import force_model

    if isinstance(spec, str) and spec in DYNAMICS:
        return spec
    if isinstance(spec, str):
        try:
            spec = yaml.safe_load(spec)
        except yaml.YAMLError as exc:
            raise InputError(f"--dynamics: one of {', '.join(DYNAMICS)} or a mapping of the "
                             f"forces, got {spec!r} ({exc.problem})") from None
    if not isinstance(spec, dict):
        raise InputError(f"--dynamics: one of {', '.join(DYNAMICS)} or a mapping of the "
                         f"forces ({{gravity: LP165P, degree: 8}}), got {spec!r}")
    try:
        model = force_model(spec)
    except InputError as exc:
        raise InputError(f"--{exc}") from None
    return json.dumps(model.to_plan(), sort_keys=True)


def study_dynamics(key: str):
    """The dynamics of a :func:`dynamics_key`: the preset word, or its ForceModel."""
    import json

    from lunarcap.physics.forces import force_model

    return key if key in DYNAMICS else force_model(json.loads(key))


def _case(thrust_N, isp_s, dynamics) -> dict:
    """The key columns of one engine's case."""
    return {"thrust_N": float(thrust_N), "isp_s": float(isp_s), "dynamics": str(dynamics)}


# ====================================================================== rows
def engine_rows(thrust_N: float, isp_s: float, dynamics: str, summaries: list,
                failure: dict | None = None, task_wall_s: float = float("nan"),
                worker: str = "", code_version: str = "") -> list[dict]:
    """The four table rows (LOI1, LOI2, LOI3, sequence) of one engine.

    Parameters
    ----------
    thrust_N, isp_s, dynamics : the engine and the dynamics
    summaries : list of dict
        :meth:`lunarcap.optim.solution.Solution.summary` of the LOIs solved, in chain order
        (fewer than three if one failed).
    failure : dict, optional
        ``{"loi": n or None, "status": "failed" | "error" | "task error",
        "ipopt_status": str, "error": str}`` for the LOI that failed (None: the whole
        task failed).
    task_wall_s, worker, code_version : recorded as given.

    Returns
    -------
    list of dict, keys :data:`COLUMNS`
    """
    base = {"thrust_N": float(thrust_N), "isp_s": float(isp_s), "dynamics": dynamics,
            "thrust_to_weight": thrust_to_weight(thrust_N),
            "thrust_to_lunar_weight": thrust_to_weight(thrust_N, g_mps2=G_MOON_MPS2),
            "task_wall_s": task_wall_s, "worker": worker, "code_version": code_version,
            "completed_utc": _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S")}
    theory = capture_chain_estimate(thrust_N, isp_s)
    rows = []
    for i in range(3):
        row = dict.fromkeys(COLUMNS, np.nan)
        row.update(base, part=PARTS[i],
                   analytic_eq19_duration_min=theory[i]["eq19_duration_min"],
                   analytic_loss_mps=theory[i]["analytic_loss_mps"],
                   analytic_loss_percent=theory[i]["analytic_loss_percent"], ipopt_status="",
                   mesh="", impulsive_limit_reason="", error="")
        if i < len(summaries):
            s = summaries[i]
            row.update({k: s[k] for k in ("start_min", "burn_duration_min", "eq19_duration_min",
                                          "delta_v_mps", "impulsive_limit_mps",
                                          "objective_loss_mps",
                                          "objective_loss_percent", "delta_v_loss_mps",
                                          "delta_v_loss_percent", "m_start_kg", "m_end_kg",
                                          "fuel_kg", "ipopt_status", "ipopt_iterations", "mesh",
                                          "solve_wall_s")})
            row["burn_to_eq19_ratio"] = s["burn_duration_min"] / s["eq19_duration_min"]
            # in a gravity field a burn may have no impulsive limit (its reason kept): no loss
            row["impulsive_verified"] = s["impulsive_verified"]
            row["impulsive_limit_reason"] = s.get("impulsive_limit_reason", "")
            row["verified"] = bool(s["verification"]["passed"]
                                   and s["impulsive_verified"] is not False)
            row["status"] = "ok" if row["verified"] else "failed"
        elif failure is not None and (failure.get("loi") in (None, i + 1)):
            row.update(status=failure["status"], ipopt_status=failure.get("ipopt_status", ""),
                       error=_one_line(failure.get("error", "")), verified=False)
        else:
            row.update(status="not run", verified=False,
                       error=f"LOI {failure['loi']} failed" if failure else "no solution")
        rows.append(row)
    rows.append(_sequence_row(base, theory, rows))
    return rows


def _sequence_row(base: dict, theory: list, rows: list) -> dict:
    """The sequence row of :func:`engine_rows`: sums of the three LOI rows, or why not."""
    seq = dict.fromkeys(COLUMNS, np.nan)
    seq.update(base, part="sequence", ipopt_status="", mesh="", impulsive_limit_reason="",
               error="")
    seq.update(analytic_eq19_duration_min=sum(t["eq19_duration_min"] for t in theory),
               analytic_loss_mps=sum(t["analytic_loss_mps"] for t in theory))
    # Robbins' estimate is relative to the two-body impulses it is built on
    seq["analytic_loss_percent"] = 100.0 * seq["analytic_loss_mps"] / sum(
        t["paper_impulsive_delta_v_mps"] for t in theory)
    if all(r["status"] == "ok" for r in rows):
        for k in ("burn_duration_min", "eq19_duration_min", "delta_v_mps", "objective_loss_mps",
                  "delta_v_loss_mps", "impulsive_limit_mps", "fuel_kg", "ipopt_iterations",
                  "solve_wall_s"):   # a burn without an impulsive limit leaves no total loss
            seq[k] = np.nan if any(r[k] is None for r in rows) else sum(r[k] for r in rows)
        seq["impulsive_limit_reason"] = "; ".join(
            f"{r['part']}: {r['impulsive_limit_reason']}" for r in rows
            if r["impulsive_limit_reason"])
        seq["objective_loss_percent"] = \
            100.0 * seq["objective_loss_mps"] / seq["impulsive_limit_mps"]
        seq["delta_v_loss_percent"] = 100.0 * seq["delta_v_loss_mps"] / seq[
            "impulsive_limit_mps"]
        seq["impulsive_verified"] = not any(r["impulsive_verified"] is False for r in rows)
        seq["burn_to_eq19_ratio"] = seq["burn_duration_min"] / seq["eq19_duration_min"]
        seq.update(m_start_kg=rows[0]["m_start_kg"], m_end_kg=rows[-1]["m_end_kg"],
                   verified=True, status="ok")
    else:
        bad = next(r for r in rows if r["status"] != "ok")
        seq.update(status="incomplete", verified=False,
                   error=f"{bad['part']}: {bad['status']}"
                         + (f" ({bad['ipopt_status']})" if bad["ipopt_status"] else ""))
    return seq


def _one_line(text: str, limit: int = 500) -> str:
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[:limit - 3] + "..."


def solve_engine(thrust_N: float, isp_s: float, dynamics: str = "full") -> list[dict]:
    """Dask task: the free-ignition chain LOI 1, 2, 3 of one engine, as table rows.

    Imports lunarcap inside the worker. A :class:`~lunarcap.errors.SolveError` stops the
    chain and is recorded (status "failed" with IPOPT's status); any other exception is
    recorded as "error". Never raises for a solver failure.
    """
    from lunarcap.capture.chain import burn_loss, impulsive_limit, solve_burn
    from lunarcap.errors import SolveError
    from lunarcap.mission.plan import paper_plan
    from lunarcap.repro.cache import code_version

    t0 = time.perf_counter()
    summaries, failure = [], None
    plan = paper_plan(thrust_N, isp_s, starts=("free",) * 3, dynamics=study_dynamics(dynamics))
    for loi in (1, 2, 3):
        try:
            sol = solve_burn(plan.key(loi))
            imp = impulsive_limit(plan.key(loi))
        except SolveError as exc:
            failure = {"loi": loi, "status": "failed", "ipopt_status": exc.status or "",
                       "error": str(exc)}
            break
        except Exception as exc:  # a bug must not lose the rest of the study
            failure = {"loi": loi, "status": "error", "ipopt_status": "",
                       "error": f"{type(exc).__name__}: {exc}"}
            break
        s = sol.summary()
        loss = burn_loss(s, imp)
        s.update(impulsive_limit_mps=loss["impulsive_limit_mps"],
                 objective_loss_mps=loss["objective_loss_mps"],
                 objective_loss_percent=loss["objective_loss_percent"],
                 delta_v_loss_mps=loss["delta_v_loss_mps"],
                 delta_v_loss_percent=loss["delta_v_loss_percent"],
                 impulsive_verified=imp["verification_passed"],
                 impulsive_limit_reason=imp.get("reason") or "")
        summaries.append(s)
    return engine_rows(thrust_N, isp_s, dynamics, summaries, failure,
                       task_wall_s=time.perf_counter() - t0,
                       worker=f"{socket.gethostname()}:{os.getpid()}",
                       code_version=code_version())


# ====================================================================== table I/O
def read_table(path: str | os.PathLike) -> pd.DataFrame:
    """The study table at ``path`` with :data:`COLUMNS` (empty if the file is absent).

    Raises
    ------
    InputError
        If ``path`` is a directory, unreadable, or not a study table.
    """
    return _campaign.read_table(path, TABLE)


def select(table: pd.DataFrame, spec: StudySpec, code_version: str | None = None
           ) -> pd.DataFrame:
    """Rows of ``table`` on the grid of ``spec``, sorted by Isp, thrust and part.

    The last attempt at each engine with ``code_version`` (None: the current
    :func:`lunarcap.repro.cache.code_version`).
    """
    if code_version is None:
        from lunarcap.repro.cache import code_version as _cv
        code_version = _cv()
    have = _campaign.latest(table, TABLE, code_version)
    rows = [r for t, i in spec.engines
            for r in have.get(TABLE.case_key(_case(t, i, spec.dynamics)), [])]
    return _in_grid_order(pd.DataFrame(rows, columns=list(COLUMNS)))


def _in_grid_order(t: pd.DataFrame) -> pd.DataFrame:
    """Study rows sorted by Isp, thrust and part (LOI1, LOI2, LOI3, sequence)."""
    if t.empty:
        return t.reset_index(drop=True)
    t = t.assign(_part=t.part.map({p: i for i, p in enumerate(PARTS)}))
    return t.sort_values(["isp_s", "thrust_N", "_part"]).drop(columns="_part") \
        .reset_index(drop=True)


# ====================================================================== running
@dataclass
class StudyResult:
    """What :func:`run_study` returns.

    Attributes
    ----------
    table : pandas.DataFrame
        The grid's rows (four per engine; columns :data:`COLUMNS`).
    path : Path
        The table file.
    run : dict
        This run's record (also appended to :func:`runs_path`).
    """

    table: pd.DataFrame
    path: Path
    run: dict

    @property
    def failures(self) -> pd.DataFrame:
        """LOI rows whose status is not "ok"."""
        t = self.table
        return t[(t.part != "sequence") & (t.status != "ok")].reset_index(drop=True)

    def wide(self) -> pd.DataFrame:
        """One row per engine (see :func:`wide_table`)."""
        return wide_table(self.table)


def run_study(spec: StudySpec | None = None, out: str | os.PathLike | None = None,
              workers=2, scheduler: str | None = None, retry_failed: bool = False,
              progress: bool = True, lock_wait_s: float = 0.0, task=None,
              processes: bool = True) -> StudyResult:
    """Run (or resume) an engine trade study on Dask.

    Parameters
    ----------
    spec : StudySpec
        The grid (default: 50-2000 N, 30 points, Isp 200, 250, 300 s, full dynamics).
    out : path, optional
        The CSV table (default ``<cache>/study/engine_trade.csv``).
    workers : int
        Worker processes of the local cluster (one thread each); ignored with
        ``scheduler``.
    scheduler : str, optional
        Address of an existing Dask scheduler (``tcp://host:8786``).
    retry_failed : bool
        Recompute engines whose earlier attempt failed (default: keep their rows).
    progress : bool
        Show a tqdm progress bar on stderr.
    lock_wait_s : float
        How long to wait for another run writing the same table (default: fail at once).
    task : callable, optional
        The per-engine function ``(thrust_N, isp_s, dynamics) -> rows`` (default
        :func:`solve_engine`; tests substitute a stub).
    processes : bool
        Local workers as processes (default) or threads (tests).

    Returns
    -------
    StudyResult

    Raises
    ------
    InputError
        Bad parameters, an unusable table path, a table in use (after ``lock_wait_s``),
        or an unreachable scheduler; always before any engine is solved.
    """
    spec = spec if spec is not None else StudySpec()
    if not isinstance(spec, StudySpec):
        raise InputError(f"spec must be a StudySpec, got {type(spec).__name__}")
    workers = check_workers(workers)
    # slow (low-thrust) engines first, for better packing on few workers
    cases = [(_case(t, i, spec.dynamics), (t, i, spec.dynamics))
             for t, i in sorted(spec.engines, key=lambda e: e[0])]
    res = STUDY.run(cases, out, task=task, workers=workers, scheduler=scheduler,
                    progress=progress, retry_failed=retry_failed, lock_wait_s=lock_wait_s,
                    processes=processes,
                    describe={"engines": len(spec.engines), "grid": spec.to_dict()})
    # res.table: the last attempt at each engine of the grid, this code version
    return StudyResult(_in_grid_order(res.table), res.path, res.run)


def _task_error_rows(key: dict, message: str) -> list[dict]:
    """The four rows of an engine whose task raised or whose worker was lost."""
    return engine_rows(key["thrust_N"], key["isp_s"], key["dynamics"], [], {
        "loi": None, "status": "task error", "ipopt_status": "", "error": message})


# ====================================================================== summaries
def wide_table(table: pd.DataFrame) -> pd.DataFrame:
    """One row per engine: loss (% per LOI and sequence), durations, status.

    Columns: thrust_N, isp_s, thrust_to_weight, objective_loss_percent_loi1..3,
    objective_loss_percent_sequence,
    objective_loss_mps_sequence, analytic_loss_percent_sequence, burn_duration_min_loi1..3,
    eq19_duration_min_loi1..3, status (the sequence row's), failed_part.
    """
    if table.empty:
        return pd.DataFrame()
    out = []
    for (t, i), g in table.groupby(["thrust_N", "isp_s"], sort=True):
        g = g.set_index("part")
        row = {"thrust_N": t, "isp_s": i, "thrust_to_weight": thrust_to_weight(t)}
        for p in PARTS[:3]:
            row[f"objective_loss_percent_{p.lower()}"] = \
                g.loc[p, "objective_loss_percent"] if p in g.index else np.nan
        seq = g.loc["sequence"] if "sequence" in g.index else None
        row["objective_loss_percent_sequence"] = \
            np.nan if seq is None else seq["objective_loss_percent"]
        row["objective_loss_mps_sequence"] = np.nan if seq is None else seq["objective_loss_mps"]
        row["analytic_loss_percent_sequence"] = np.nan if seq is None else \
            seq["analytic_loss_percent"]
        for p in PARTS[:3]:
            row[f"burn_duration_min_{p.lower()}"] = g.loc[p, "burn_duration_min"] \
                if p in g.index else np.nan
        for p in PARTS[:3]:
            row[f"eq19_duration_min_{p.lower()}"] = g.loc[p, "eq19_duration_min"] \
                if p in g.index else np.nan
        row["status"] = "missing" if seq is None else seq["status"]
        row["failed_part"] = "" if seq is None or seq["status"] == "ok" else seq["error"]
        out.append(row)
    return pd.DataFrame(out).sort_values(["isp_s", "thrust_N"]).reset_index(drop=True)


def format_summary(result: StudyResult) -> str:
    """The CLI's text: one line per engine, failures, and the wall time."""
    w = result.wide()
    lines = [f"Engine trade study: {len(w)} engines, free ignition for every LOI, "
             f"{study_dynamics(result.run['grid']['dynamics'])} dynamics; loss (objective, "
             f"Eq. 9) vs the impulsive limit in the same dynamics; T/W = T / (524.895 kg x "
             f"9.80665 m/s^2)",
             f"{'thrust N':>9} {'Isp s':>6} {'T/W':>7} | {'loss %: LOI1':>12} {'LOI2':>6} "
             f"{'LOI3':>6} {'seq':>6} {'seq m/s':>8} | {'burn/Eq.19 LOI1':>15} | status"]
    for r in w.itertuples(index=False):
        ratio = r.burn_duration_min_loi1 / r.eq19_duration_min_loi1
        lines.append(
            f"{r.thrust_N:9.4g} {r.isp_s:6.4g} {r.thrust_to_weight:7.4f} | "
            f"{_f(r.objective_loss_percent_loi1, 12)} {_f(r.objective_loss_percent_loi2, 6)} "
            f"{_f(r.objective_loss_percent_loi3, 6)} {_f(r.objective_loss_percent_sequence, 6)} "
            f"{_f(r.objective_loss_mps_sequence, 8)} | {_f(ratio, 15)} | "
            + (r.status if r.status == "ok" else f"{r.status}: {r.failed_part}"))
    t = result.table
    for r in t[(t.part == "sequence") & (t.impulsive_limit_reason.fillna("") != "")] \
            .itertuples(index=False):   # in a gravity field: a burn no impulse reaches
        lines.append(f"no loss at {r.thrust_N:g} N / {r.isp_s:g} s: "
                     f"{r.impulsive_limit_reason}")
    n_bad = int((w.status != "ok").sum()) if len(w) else 0
    return "\n".join(lines + STUDY.run_lines(result, failed=n_bad))


def _f(v, width: int, fmt: str = ".3f") -> str:
    return f"{'—':>{width}}" if v is None or not np.isfinite(v) else f"{v:{width}{fmt}}"


def analytic_curves(thrusts_N, isp_s) -> pd.DataFrame:
    """Robbins' estimate and the Eq. (19) duration on a (dense) thrust grid, per Isp.

    Columns: thrust_N, isp_s, thrust_to_weight, part, eq19_duration_min, analytic_loss_mps,
    analytic_loss_percent (closed form, :func:`lunarcap.physics.losses.capture_chain_estimate`),
    omega_t_rad: the expansion variable omega_s t_b of Robbins' estimate (Schuler rate at
    the perilune times the Eq. (19) duration; for the sequence the largest of the three).
    """
    w = float(schuler_rate_rad_s(PERILUNE_RADIUS_KM))
    rows = []
    for isp in parse_isp_list(list(isp_s)):
        for t in np.asarray(thrusts_N, dtype=float):
            est = capture_chain_estimate(float(t), isp)
            for e in est:
                rows.append({"thrust_N": float(t), "isp_s": isp, "part": f"LOI{e['loi']}",
                             "eq19_duration_min": e["eq19_duration_min"],
                             "analytic_loss_mps": e["analytic_loss_mps"],
                             "analytic_loss_percent": e["analytic_loss_percent"],
                             "omega_t_rad": w * 60.0 * e["eq19_duration_min"]})
            loss = sum(e["analytic_loss_mps"] for e in est)
            imp = sum(e["paper_impulsive_delta_v_mps"] for e in est)
            rows.append({"thrust_N": float(t), "isp_s": isp, "part": "sequence",
                         "eq19_duration_min": sum(e["eq19_duration_min"] for e in est),
                         "analytic_loss_mps": loss, "analytic_loss_percent": 100.0 * loss / imp,
                         "omega_t_rad": w * 60.0 * max(e["eq19_duration_min"] for e in est)})
    df = pd.DataFrame(rows)
    df.insert(2, "thrust_to_weight", thrust_to_weight(df.thrust_N.to_numpy()))
    return df


#: The study, declared once (:class:`lunarcap.studies.study.Study`): one case per engine,
#: four rows (LOI1, LOI2, LOI3, sequence); its rows depend on the whole numerical code.
STUDY = Study("engine_trade", TABLE, solve_engine, STATUSES, ("ok",), "engine",
              "trade study", text=format_summary, guarded=False, error_rows=_task_error_rows)
