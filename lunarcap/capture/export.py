"""A solved plan out to other tools: the flown capture, prepared once, and its writers.

:func:`export_plan` re-flies the verified capture of a plan from the arrival to one
revolution of the final orbit (:func:`flight_arcs`: each burn interval by interval with
the steering the verification flew, each coast from the flown cut-off, states propagated
at the files' epochs, not interpolated, nothing re-optimised), prepares it once as a
:class:`FlownCapture` (OEM segments every :data:`COAST_STEP_S` on coasts and
:data:`BURN_STEP_S` in burns, one per arc so that no interpolation crosses an ignition or
a cut-off; the comment lines; the burns' samples and GMAT's record on demand) and hands it
to each writer of :data:`lunarcap.capture.writers.WRITERS`: CCSDS OEM, SPICE SPK, the
attitude and maneuver CSV files and a GMAT script. A new format is one writer module and
one line there.
"""

from __future__ import annotations

import os
import re
import tempfile
import time
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import numpy as np

from lunarcap.capture.chain import plan_result
from lunarcap.capture.writers import WRITERS
from lunarcap.errors import InputError
from lunarcap.exchange import gmat
from lunarcap.exchange.ccsds import (
    OEM_DEGREE,
    OemSegment,
    StateVector,
    interpolation_error,
    lagrange_interpolate,
    reference_comments,
)
from lunarcap.exchange.spk import DEFAULT_OBJECT_ID
from lunarcap.mission.plan import CapturePlan
from lunarcap.optim.flight import Arc, BurnPlan, burn_arc, coast_arc
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model, rtn_from_mee
from lunarcap.physics.elements import orbit_summary, period_from_semi_major_axis, rv_from_mee
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.epochs import leap_second_table
from lunarcap.physics.frames import icrf_from_mme
from lunarcap.physics.propagate import N_X
from lunarcap.physics.state import MASS, State

#: Step of the exported states on coasts and in burns, s.
COAST_STEP_S = 60.0
BURN_STEP_S = 10.0
#: Step of the attitude file's samples, s.
ATTITUDE_STEP_S = 1.0
#: The approach exported before the first ignition (v_inf arrivals), min.
APPROACH_MIN = 60.0
#: Longest thrust-direction segment of the GMAT script, s, and the Gauss-Legendre points
#: of each segment's mean direction. Flying the 150 N capture's segments in lunarcap's
#: own propagator, 10 s segments end burn 1 within 4.5 cm and 0.035 mm/s of the flown burn
#: (2 s: 2 mm; the error is second order in the segment); GMAT's run time grows faster
#: than the number of Propagate commands (the whole script: 17 s at 10 s, 350-450 s at 2 s).
GMAT_SEGMENT_S = 10.0
GMAT_NODES = 4


def _grid(t0: float, t1: float, step: float) -> np.ndarray:
    n = max(int(np.ceil((t1 - t0) / step - 1e-9)), 8)
    return t0 + (t1 - t0) * np.arange(n + 1) / n


def flight_arcs(solutions, approach_min: float = APPROACH_MIN, t_start_s: float | None = None,
                eph=None) -> list:
    """The arcs of a solved chain: approach, burn 1, coast 1, ..., burn n, final orbit.

    ``solutions``: the :class:`~lunarcap.optim.solution.Solution` of each burn in order.
    The approach starts at ``t_start_s`` if given (a state arrival's epoch), else
    ``approach_min`` before the first ignition; the final orbit lasts one osculating period
    after the last cut-off.
    """
    arcs = []
    first = solutions[0]
    fb = first.flight.burn
    t_a = fb.t[0] - 60.0 * approach_min if t_start_s is None else float(t_start_s)
    model = first.problem.model
    if model.fit is not None and t_a < model.fit.t0_s:
        model = Model(model.mode, 0.0, model.isp_s,
                      ChebyshevFit.fit(eph, t_a - 3600.0, fb.t[0] + 3600.0,
                                       body_frame=model.fit.body_frame))
    if t_a < fb.t[0]:
        arcs.append(coast_arc("approach", model, State(fb.t[0], fb.x[:N_X, 0]), t_a - fb.t[0]))
    for i, sol in enumerate(solutions):
        prob, flight = sol.problem, sol.flight
        arcs.append(burn_arc(f"burn {i + 1}", sol.raw, flight))
        cutoff = flight.cutoff
        if i + 1 < len(solutions):
            t_next = solutions[i + 1].flight.burn.t[0]
            arcs.append(coast_arc(f"coast {i + 1}", prob.model, cutoff, t_next - cutoff.t_s))
        else:
            o = orbit_summary(cutoff.x, C.MU_MOON)
            a = 0.5 * (o["rp_km"] + o["ra_km"])
            period = float(period_from_semi_major_axis(a, C.MU_MOON))
            arcs.append(coast_arc("final orbit", prob.model, cutoff, period))
    return arcs


def icrf_states(x, pole: str) -> tuple:
    """Positions (3, N) km and velocities (3, N) km/s in ICRF of MEE states (7 or 6, N)."""
    r, v = rv_from_mee(*np.asarray(x)[:6], C.MU_MOON)
    return icrf_from_mme(np.array(r), pole), icrf_from_mme(np.array(v), pole)


def segment_of(arc: Arc, pole: str, step_s: float) -> tuple:
    """The OEM segment of an arc and its interpolation error (m) at the mid-steps."""
    t0, t1 = arc.span
    t = _grid(t0, t1, step_s)
    r, v = icrf_states(arc.states(t), pole)
    seg = OemSegment(t, r, v, arc.name)
    mid = 0.5 * (t[1:] + t[:-1])
    truth_mid = icrf_states(arc.states(mid), pole)[0]
    err = interpolation_error(seg, lambda q: truth_mid)
    return seg, err


def flown_directions(sol, arc: Arc, pole: str, t) -> tuple:
    """Unit thrust directions (3, N) in ICRF and states (7, N) of a burn at epochs ``t``.

    The steering the verification flew (:meth:`lunarcap.optim.flight.BurnPlan.direction`),
    on the states of the burn's arc at ``t`` (increasing, within the burn).
    """
    burn = BurnPlan.of(sol.raw)
    x = arc.states(t)
    u_rtn = np.column_stack([burn.direction(tj, x[:, j]) for j, tj in enumerate(t)])
    ir, it, i_n = (np.array(a) for a in rtn_from_mee(x[3], x[4], x[5]))
    u_mme = u_rtn[0] * ir + u_rtn[1] * it + u_rtn[2] * i_n
    return icrf_from_mme(u_mme / np.linalg.norm(u_mme, axis=0), pole), x


def burn_samples(sol, arc: Arc, pole: str, step_s: float = ATTITUDE_STEP_S) -> dict:
    """Thrust direction (ICRF), mass and epochs of a burn every ``step_s`` (its cut-off last)."""
    t0, t1 = arc.span
    t = _grid(t0, t1, step_s)
    u, x = flown_directions(sol, arc, pole, t)
    return {"t_s": t, "u_icrf": u, "thrust_N": arc.thrust_N, "mass_kg": x[MASS]}


def icrf_state(arc: Arc, t_s: float, pole: str) -> StateVector:
    """The state of an arc at ``t_s``: ICRF position and velocity, and mass."""
    x = arc.states(np.array([t_s]))
    r, v = icrf_states(x, pole)
    return StateVector(float(t_s), tuple(r[:, 0]), tuple(v[:, 0]), "ICRF", float(x[MASS, 0]))


def after_segment(after, start: StateVector, pole: str, step_s: float = COAST_STEP_S
                  ) -> tuple:
    """The evolution after the capture as an OEM segment, and its interpolation error (m).

    ``after``: the :class:`~lunarcap.physics.evolution.Evolution` of the final orbit from
    its last cut-off; ``start``: the state where the segment starts (the end of the final
    orbit's segment, so that the two meet), ICRF. Then the evolution's samples every
    ``step_s`` from its start, after ``start``, and its last: states propagated there (in
    the evolution's forces), not interpolated. The file's interpolation (Lagrange,
    :data:`lunarcap.exchange.ccsds.OEM_DEGREE`) is checked at the evolution's samples
    nearest half-way between these (its samples are 10 s apart).
    """
    t, x = after.trajectory.t, after.trajectory.x
    n = (t - t[0]) / step_s
    keep = np.flatnonzero((t > start.epoch_s + 1e-6) & (np.abs(n - np.round(n)) < 1e-6))
    if keep.size == 0 or keep[-1] != t.size - 1:
        keep = np.append(keep, t.size - 1)
    r, v = icrf_states(x[:, keep], pole)
    seg = OemSegment(np.concatenate([[start.epoch_s], t[keep]]),
                     np.column_stack([start.r_km, r]), np.column_stack([start.v_kmps, v]),
                     "after capture")
    mids = np.unique(np.clip(np.searchsorted(t, 0.5 * (t[keep][1:] + t[keep][:-1])),
                             0, t.size - 1))
    if not mids.size:
        return seg, 0.0
    guess = lagrange_interpolate(seg.t_s, seg.r_km, t[mids], OEM_DEGREE)
    truth = icrf_states(x[:, mids], pole)[0]
    return seg, float(np.max(np.linalg.norm(guess - truth, axis=0)) * 1e3)


def gmat_burn(sol, arc: Arc, pole: str, segment_s: float = GMAT_SEGMENT_S,
              nodes: int = GMAT_NODES) -> gmat.Burn:
    """A burn as the GMAT script flies it: segments of the mean flown direction.

    Each mesh interval of the burn (where the steering is smooth) is cut into equal
    segments of at most ``segment_s``; a segment's direction is the mean of the unit
    thrust direction over it (Gauss-Legendre, ``nodes`` points), normalised. (Scaling the
    thrust by the length of that mean, 1 - 5e-6 for 10 s near a perilune, changed the
    150 N plan's cut-offs in GMAT by less than 1 cm and 0.01 mm/s: it is not done.)
    """
    durations = []
    for _, _, dur, _ in arc.pieces:
        n = max(int(np.ceil(dur / segment_s - 1e-9)), 1)
        durations += [dur / n] * n
    durations = np.array(durations)
    bounds = arc.pieces[0][0] + np.concatenate([[0.0], np.cumsum(durations)])
    xg, wg = np.polynomial.legendre.leggauss(nodes)
    mid, half = 0.5 * (bounds[1:] + bounds[:-1]), 0.5 * durations
    u, _ = flown_directions(sol, arc, pole, (mid[:, None] + half[:, None] * xg).ravel())
    mean = (u.reshape(3, -1, nodes) * wg).sum(axis=2) / wg.sum()
    model = sol.problem.model
    return gmat.Burn(icrf_state(arc, bounds[0], pole), durations,
                     mean / np.linalg.norm(mean, axis=0), model.thrust_N, model.isp_s)


def gmat_gravity(model: Model, pole: str) -> gmat.Gravity:
    """The central body's gravity of a model for GMAT (:class:`lunarcap.exchange.gmat.Gravity`).

    The lunar GM of the dynamics always, and the field its terms ask for
    (:func:`lunarcap.exchange.gmat.capture_forces`): the paper's J2 (or none) about the
    pole of the plan's frame, fixed; J2 about the IAU pole of date; or a field to its
    degree and order (the orders above zeroed) in the Moon's DE405 frame (GMAT's ``Luna``)
    or the IAU one.
    """
    return gmat.capture_forces(model, pole)[0]


def gmat_capture(plan, sols, arcs) -> gmat.Capture:
    """The flown capture (its arcs, :func:`flight_arcs`) handed to GMAT (:mod:`exchange.gmat`).

    Its model is the burns' (:func:`gmat_gravity`), and the Earth and the Sun as point
    masses where the dynamics have them.
    """
    pole = plan.lunar_pole
    model = sols[0].problem.model
    gravity = gmat_gravity(model, pole)
    third = gmat.capture_forces(model, pole)[1]
    burn_arcs = [a for a in arcs if a.thrust_N]
    burns = [gmat_burn(s, a, pole) for s, a in zip(sols, burn_arcs)]
    coasts = [icrf_state(a, a.span[1], pole) for a in burn_arcs]
    comments = [f"{plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} s, {plan.dynamics} "
                f"dynamics ({gravity.source}; third bodies: "
                f"{', '.join(n for n, _ in third) or 'none'}), ephemeris "
                f"{plan.ephemeris_model().name}",
                f"Thrust direction in segments of at most {GMAT_SEGMENT_S:g} s, each the "
                f"mean of the flown direction over it"]
    return gmat.Capture(plan.name, icrf_state(arcs[0], arcs[0].span[0], pole), burns,
                        coasts, arcs[-1].span[1], gravity, third, C.G0_MPS2,
                        plan.ephemeris_model(), comments)


def capture_arcs(result, approach_min: float = APPROACH_MIN) -> list:
    """The arcs of a solved plan (:func:`flight_arcs`), from its arrival's state if it has one."""
    plan = result.plan
    arrival_state = getattr(plan.arrival, "state", None)
    t_start = None if arrival_state is None else arrival_state.epoch_s
    return flight_arcs([b.solution for b in result.burns], approach_min, t_start,
                       plan.ephemeris_model())


def safe_name(name: str) -> str:
    """A plan name as a file name (letters, digits, '.', '_', '-')."""
    return re.sub(r"[^A-Za-z0-9._-]+", "_", name).strip("_") or "plan"


@dataclass
class Export:
    """What :func:`export_plan` wrote and measured."""

    files: dict
    sizes_bytes: dict
    seconds: float
    object_id: int
    time_system: str
    segments: list = field(default_factory=list)   # per segment: name, start, stop, n, error

    @property
    def reference(self) -> list:
        """The Moon's GM and radius behind the files, as at the head of each."""
        return reference_comments()

    @property
    def max_interpolation_error_m(self) -> float:
        """Largest error of the OEM's Lagrange interpolation at the mid-steps, m."""
        return max(s["interpolation_error_m"] for s in self.segments)

    def to_dict(self) -> dict:
        """JSON-ready."""
        return {"files": {k: str(v) for k, v in self.files.items()},
                "sizes_bytes": self.sizes_bytes, "export_s": self.seconds,
                "object_id": self.object_id, "time_system": self.time_system,
                "max_interpolation_error_m": self.max_interpolation_error_m,
                "segments": self.segments, "reference": self.reference}


def check_export_dir(out_dir, what: str = "export directory") -> Path:
    """The export directory, created if missing; InputError if no file can be written in it.

    Checked before any solve (``lunarcap plan --export DIR``) by creating and removing a
    file there, so a read-only mount, a path under a file or a file in the way is refused
    with the reason even for a user whom permissions do not stop.

    Raises
    ------
    InputError
        ``"<what> <dir>: cannot write files there (<reason>)"``.
    """
    out = Path(out_dir).expanduser()
    try:
        if out.exists() and not out.is_dir():
            raise NotADirectoryError(0, f"{out} is a file, not a directory")
        out.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=out, prefix=".lunarcap-probe-")
        os.close(fd)
        os.unlink(probe)
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        blocking = next((p for p in out.parents if p.exists() and not p.is_dir()), None)
        if blocking is not None:
            reason = f"{blocking} is a file, not a directory"
        raise InputError(f"{what} {out}: cannot write files there ({reason})") from None
    return out


@dataclass(frozen=True)
class FlownCapture:
    """A solved plan's verified capture as every export writer receives it.

    Built once per export by :func:`flown_capture`; each writer of
    :data:`lunarcap.capture.writers.WRITERS` reads what its format needs. What only some
    writers need (the burns' samples, GMAT's record) is computed on first use, once.

    Attributes
    ----------
    plan : CapturePlan
    solutions : list of Solution
        The verified solution of each burn, in order.
    arcs : list of Arc
        The flown capture (:func:`flight_arcs`): approach, burn 1, coast 1, ..., final orbit.
    segments : list of OemSegment
        One per arc, ICRF km and km/s at TDB epochs, and the evolution after the capture
        (``after capture``) if one was given.
    report : list of dict
        Per segment: ``name``, ``start_s``, ``stop_s``, ``states`` and the file's
        ``interpolation_error_m`` at the mid-steps.
    comments : list of str
        The lines each file carries after the Moon's GM and radius: what was flown, the
        steps, the axes and ID, the time scale.
    time_system : {"TDB", "UTC"}
        Of the epochs written as text.
    object_id : int
        The spacecraft's NAIF ID.
    out : Path
        The directory written.
    stem : str
        The plan's name as a file name (:func:`safe_name`): ``<stem>.oem``, ...
    """

    plan: CapturePlan
    solutions: list
    arcs: list
    segments: list
    report: list
    comments: list
    time_system: str
    object_id: int
    out: Path
    stem: str

    def path(self, suffix: str) -> Path:
        """The file ``<out>/<stem><suffix>`` (``suffix``: ``".oem"``, ``"_attitude.csv"``)."""
        return self.out / f"{self.stem}{suffix}"

    @property
    def pole(self) -> str:
        """The lunar pole fixing the plan's M-MME2000 (:mod:`lunarcap.physics.frames`)."""
        return self.plan.lunar_pole

    @cached_property
    def burn_arcs(self) -> list:
        """The arcs that thrust, one per burn, in order."""
        return [a for a in self.arcs if a.thrust_N]

    @cached_property
    def samples(self) -> list:
        """Per burn, thrust direction (ICRF), thrust, mass every :data:`ATTITUDE_STEP_S`."""
        return [burn_samples(s, a, self.pole) for s, a in zip(self.solutions, self.burn_arcs)]

    @cached_property
    def gmat(self) -> gmat.Capture:
        """The capture as the GMAT script flies it (:func:`gmat_capture`)."""
        return gmat_capture(self.plan, self.solutions, self.arcs)


def _segment_row(seg: OemSegment, err: float) -> dict:
    """A segment's line of the export's report (epochs s, states, interpolation error m)."""
    return {"name": seg.name, "start_s": float(seg.t_s[0]), "stop_s": float(seg.t_s[-1]),
            "states": int(seg.t_s.size), "interpolation_error_m": err}


def _segments(plan, arcs: list, steps_s: tuple, after) -> tuple:
    """(OEM segments, report rows) of the arcs, then of the evolution ``after`` (or None).

    ``steps_s``: (coast, burn) steps of the states, s. InputError if the evolution does
    not start at the last cut-off or ends within the final orbit's revolution.
    """
    coast_step_s, burn_step_s = steps_s
    pole = plan.lunar_pole
    segs, report = [], []
    for arc in arcs:
        seg, err = segment_of(arc, pole, burn_step_s if arc.thrust_N else coast_step_s)
        segs.append(seg)
        report.append(_segment_row(seg, err))
    if after is not None:
        end = arcs[-1].span[1]
        if not after.t0_s <= end < after.trajectory.t[-1]:
            raise InputError(f"plan {plan.name}: the evolution after the capture must start "
                             f"at its last cut-off and end after its final orbit's revolution")
        seg, err = after_segment(after, icrf_state(arcs[-1], end, pole), pole, coast_step_s)
        segs.append(seg)
        report.append(_segment_row(seg, err))
    return segs, report


def _comments(plan, steps_s: tuple, report: list, object_id: int, time_system: str,
              after) -> list:
    """The lines every file carries: what was flown, its steps and accuracy, axes, scale."""
    coast_step_s, burn_step_s = steps_s
    comments = [f"lunarcap plan {plan.name}: {plan.engine.thrust_N:g} N / "
                f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics, {plan.n_burns} burn(s), "
                f"verified re-flown capture from the arrival to one revolution of the final "
                f"orbit",
                "One segment per arc (approach, burns, coasts, final orbit); states "
                f"every {burn_step_s:g} s in burns and {coast_step_s:g} s on coasts; the "
                f"Lagrange interpolation of degree 7 is within "
                f"{max(r['interpolation_error_m'] for r in report):.2g} m of the "
                f"propagated states at mid-steps",
                f"ICRF axes (lunarcap M-MME2000 rotated with lunar pole {plan.lunar_pole}); "
                f"SPK object ID {object_id}"]
    if after is not None:
        comments.append(f"Last segment: the final orbit {after.days:g} days after the last "
                        f"cut-off, in {after.forces} dynamics")
    if time_system == "UTC":
        leap = leap_second_table()
        comments.append(f"UTC from TDB with ERFA and {leap['source']} (expires "
                        f"{leap['expires']}, TAI-UTC {leap['tai_minus_utc_s']:g} s)")
    return comments


def flown_capture(result, out: Path, time_system: str = "TDB",
                  object_id: int = DEFAULT_OBJECT_ID, steps_s: tuple = (COAST_STEP_S, BURN_STEP_S),
                  approach_min: float = APPROACH_MIN, after=None) -> FlownCapture:
    """What the writers receive of a solved plan (:class:`FlownCapture`), for ``out``.

    The arcs from the arrival (:func:`capture_arcs`), their OEM segments every
    ``steps_s`` = (coast, burn) seconds with the evolution ``after`` appended, and the
    comment lines; see :func:`export_plan` for the parameters.
    """
    plan = result.plan
    ts = time_system.upper()
    arcs = capture_arcs(result, approach_min)
    segs, report = _segments(plan, arcs, steps_s, after)
    return FlownCapture(plan, [b.solution for b in result.burns], arcs, segs, report,
                        _comments(plan, steps_s, report, object_id, ts, after), ts, object_id,
                        Path(out), safe_name(plan.name))


def write_files(flown: FlownCapture, writers: dict | None = None) -> dict:
    """Run each writer (default :data:`lunarcap.capture.writers.WRITERS`) on ``flown``, in order.

    Returns every file written, ``{key: path}`` in the writers' order. ValueError if a
    writer returns a key an earlier one wrote (a file would be listed once for two).
    """
    files = {}
    for name, write in (WRITERS if writers is None else writers).items():
        written = write(flown)
        clash = sorted(set(written) & set(files))
        if clash:
            raise ValueError(f"export writer {name!r} returns {clash}, already written by "
                             f"an earlier writer")
        files.update(written)
    return files


def export_plan(result, out_dir, time_system: str = "TDB", object_id: int = DEFAULT_OBJECT_ID,
                coast_step_s: float = COAST_STEP_S, burn_step_s: float = BURN_STEP_S,
                approach_min: float = APPROACH_MIN, after=None, writers: dict | None = None
                ) -> Export:
    """Write the files of every registered writer for a solved plan into ``out_dir``.

    The writers (:data:`lunarcap.capture.writers.WRITERS`, in order: OEM, SPK, attitude,
    maneuvers, GMAT script) each receive the same :class:`FlownCapture` and return the
    paths they wrote; :class:`Export` lists them under the writers' keys.

    Parameters
    ----------
    result : lunarcap.capture.chain.PlanResult, or a CapturePlan (then solved, cached)
    out_dir : directory (created if missing)
    time_system : {"TDB", "UTC"}
        Of the epochs written (SPK epochs are always ET, i.e. TDB).
    object_id : the spacecraft's NAIF ID in the SPK and the OEM's OBJECT_ID
    coast_step_s, burn_step_s : float
        Step of the OEM's and the SPK's states on coasts and in burns, s.
    approach_min : float
        The approach exported before the first ignition, min (unless the arrival is a state).
    after : Evolution, optional
        The final orbit's evolution from the last cut-off
        (:func:`lunarcap.capture.chain.after_capture`): the files then go on to its end
        (:func:`after_segment`).
    writers : dict, optional
        ``{name: write}``, a selection of the registered writers (default all).

    Raises
    ------
    InputError
        A burn failed verification, an evolution that does not follow the capture, or a
        writer's refusal (a time system other than TDB or UTC, a positive SPK ID).
    """
    out = check_export_dir(out_dir)
    if isinstance(result, CapturePlan):
        result = plan_result(result, impulsive=False)
    if not all(b.solution.verification.passed for b in result.burns):
        raise InputError(f"plan {result.plan.name}: not exported: a burn failed verification")
    start = time.perf_counter()
    flown = flown_capture(result, out, time_system, object_id, (coast_step_s, burn_step_s),
                          approach_min, after)
    files = write_files(flown, writers)
    seconds = time.perf_counter() - start
    sizes = {k: Path(p).stat().st_size for k, p in files.items()}
    return Export(files, sizes, seconds, object_id, flown.time_system, flown.report)
