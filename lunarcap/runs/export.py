"""A solved plan out to other tools: CCSDS OEM, SPICE SPK, attitude and maneuver files.

:func:`export_plan` writes, for the verified, re-flown capture of a plan, from the
arrival to one revolution of the final orbit:

* ``<name>.oem``: CCSDS OEM 2.0 (KVN), Moon-centred ICRF, TDB (or UTC), one segment per
  arc (the approach, each burn, each coast, the final orbit), so that no interpolation
  crosses an ignition or a cut-off; states every :data:`COAST_STEP_S` on coasts and
  :data:`BURN_STEP_S` in burns, where the file's own interpolation (Lagrange, degree 7,
  declared in the file) is checked against the propagated states half-way between them;
* ``<name>.bsp``: the same states as an SPK (type 9), spacecraft ID
  :data:`lunarcap.exchange.spk.DEFAULT_OBJECT_ID` (-310001) unless given;
* ``<name>_attitude.csv`` and ``<name>_maneuvers.csv`` (:mod:`lunarcap.exchange.burns`).

The arcs are the solutions' flights (:class:`lunarcap.optim.flight.Flight`), re-flown by
:class:`lunarcap.optim.flight.Arc`: each burn interval by interval with the steering the
verification flew, from the same states; each coast from the flown cut-off state, in the
burn's own dynamics (its ephemeris fit), to the next ignition. States at the file's
epochs are propagated there (CVODES, rtol 1e-13), not interpolated, and nothing is
re-optimised. The approach starts
:data:`APPROACH_MIN` before the first ignition (or at the state of a state arrival).
"""

from __future__ import annotations

import os
import re
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.exchange.burns import mean_direction, write_attitude, write_maneuvers
from lunarcap.exchange.ccsds import (
    OemSegment,
    interpolation_error,
    reference_comments,
    write_oem,
)
from lunarcap.exchange.spk import DEFAULT_OBJECT_ID, write_spk
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
                      ChebyshevFit.fit(eph, t_a - 3600.0, fb.t[0] + 3600.0))
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


def burn_samples(sol, arc: Arc, pole: str, step_s: float = ATTITUDE_STEP_S) -> dict:
    """Thrust direction (ICRF), mass and epochs of a burn every ``step_s`` (its cut-off last)."""
    burn = BurnPlan.of(sol.raw)
    t0, t1 = arc.span
    t = _grid(t0, t1, step_s)
    x = arc.states(t)
    u_rtn = np.column_stack([burn.direction(tj, x[:, j]) for j, tj in enumerate(t)])
    ir, it, i_n = (np.array(a) for a in rtn_from_mee(x[3], x[4], x[5]))
    u_mme = u_rtn[0] * ir + u_rtn[1] * it + u_rtn[2] * i_n
    u = icrf_from_mme(u_mme / np.linalg.norm(u_mme, axis=0), pole)
    return {"t_s": t, "u_icrf": u, "thrust_N": arc.thrust_N, "mass_kg": x[MASS]}


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


def export_plan(result, out_dir, time_system: str = "TDB", object_id: int = DEFAULT_OBJECT_ID,
                coast_step_s: float = COAST_STEP_S, burn_step_s: float = BURN_STEP_S,
                approach_min: float = APPROACH_MIN) -> Export:
    """Write the OEM, SPK, attitude and maneuver files of a solved plan into ``out_dir``.

    Parameters
    ----------
    result : lunarcap.runs.chain.PlanResult, or a CapturePlan (then solved, cached)
    out_dir : directory (created if missing)
    time_system : {"TDB", "UTC"}
        Of the epochs written (SPK epochs are always ET, i.e. TDB).
    object_id : the spacecraft's NAIF ID in the SPK and the OEM's OBJECT_ID
    """
    from lunarcap.mission.plan import CapturePlan
    from lunarcap.runs.chain import plan_result

    out = check_export_dir(out_dir)
    if isinstance(result, CapturePlan):
        result = plan_result(result, impulsive=False)
    if not all(b.solution.verification.passed for b in result.burns):
        raise InputError(f"plan {result.plan.name}: not exported: a burn failed verification")
    start = time.perf_counter()
    plan = result.plan
    ts = time_system.upper()
    sols = [b.solution for b in result.burns]
    pole = plan.lunar_pole
    arrival_state = getattr(plan.arrival, "state", None)
    t_start = None if arrival_state is None else arrival_state.epoch_s
    arcs = flight_arcs(sols, approach_min, t_start, plan.ephemeris_model())
    stem = safe_name(plan.name)
    segs, report = [], []
    for arc in arcs:
        seg, err = segment_of(arc, pole, burn_step_s if arc.thrust_N else coast_step_s)
        segs.append(seg)
        report.append({"name": arc.name, "start_s": float(seg.t_s[0]),
                       "stop_s": float(seg.t_s[-1]), "states": int(seg.t_s.size),
                       "interpolation_error_m": err})
    leap = leap_second_table()
    comments = [f"lunarcap plan {plan.name}: {plan.engine.thrust_N:g} N / "
                f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics, {plan.n_burns} burn(s), "
                f"verified re-flown capture from the arrival to one revolution of the final "
                f"orbit",
                "One segment per arc (approach, burns, coasts, final orbit); states "
                f"every {burn_step_s:g} s in burns and {coast_step_s:g} s on coasts; the "
                f"Lagrange interpolation of degree 7 is within "
                f"{max(r['interpolation_error_m'] for r in report):.2g} m of the "
                f"propagated states at mid-steps",
                f"ICRF axes (lunarcap M-MME2000 rotated with lunar pole {pole}); SPK "
                f"object ID {object_id}"]
    if ts == "UTC":
        comments.append(f"UTC from TDB with ERFA and {leap['source']} (expires "
                        f"{leap['expires']}, TAI-UTC {leap['tai_minus_utc_s']:g} s)")
    files = {"oem": out / f"{stem}.oem", "spk": out / f"{stem}.bsp",
             "attitude": out / f"{stem}_attitude.csv",
             "maneuvers": out / f"{stem}_maneuvers.csv"}
    write_oem(files["oem"], segs, plan.name, str(object_id), ts, comments=comments)
    write_spk(files["spk"], segs, object_id, comments=comments)
    burn_arcs = [a for a in arcs if a.thrust_N]
    samples = [burn_samples(s, a, pole) for s, a in zip(sols, burn_arcs)]
    write_attitude(files["attitude"], samples, ts)
    rows = []
    for s, smp in zip(sols, samples):
        rows.append({"t_ign_s": smp["t_s"][0], "duration_s": s.raw.t1_s,
                     "thrust_N": smp["thrust_N"], "isp_s": s.problem.model.isp_s,
                     "m_start_kg": smp["mass_kg"][0], "m_end_kg": smp["mass_kg"][-1],
                     "delta_v_mps": s.flight.delta_v_mps,
                     "dir_icrf": mean_direction(smp["t_s"], smp["u_icrf"], smp["thrust_N"],
                                                smp["mass_kg"])})
    write_maneuvers(files["maneuvers"], rows, ts)
    seconds = time.perf_counter() - start
    sizes = {k: p.stat().st_size for k, p in files.items()}
    return Export(files, sizes, seconds, object_id, ts, report)
