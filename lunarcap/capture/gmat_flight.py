"""A solved plan flown in GMAT: its exported script run, and GMAT's states against lunarcap's.

:func:`fly_in_gmat` exports the plan (:func:`lunarcap.capture.export.export_plan`, which
writes the GMAT script of :mod:`lunarcap.exchange.gmat`), runs the script with ``gmatpy``
in a child process and compares the states GMAT reports with lunarcap's flown arcs at
the same epochs:

* each burn flown from lunarcap's state at its ignition: the cut-off's position (m),
  velocity (mm/s) and mass (kg) against lunarcap's (gates :data:`TOL_BURN_POSITION_M`,
  :data:`TOL_BURN_SPEED_MPS`);
* each coast flown from lunarcap's state at the cut-off before it: the same at its end,
  the next ignition or one revolution of the final orbit (gates
  :data:`TOL_COAST_POSITION_M`, :data:`TOL_COAST_SPEED_MPS`: the dynamics alone);
* the whole capture flown open loop from the arrival: the same at each ignition, each
  cut-off and the end (one revolution of the final orbit after the last cut-off), and
  the final orbit's osculating perilune and apolune radii at the last cut-off and at the
  end (gate :data:`TOL_FINAL_RADII_M`). Nothing closes the loop, so a burn's residual
  grows along the coasts after it (a velocity error dv at a perilune moves the state by
  about 3 dv t along the track after a time t).
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from lunarcap.capture.export import APPROACH_MIN, capture_arcs, export_plan, icrf_state
from lunarcap.exchange import gmat
from lunarcap.physics.elements import mee_from_rv, orbit_summary

#: Gates of a burn flown in GMAT from lunarcap's ignition state, at its cut-off: position
#: (m) and velocity (m/s).
TOL_BURN_POSITION_M = 0.5
TOL_BURN_SPEED_MPS = 5e-4
#: Gates of a coast flown in GMAT from lunarcap's cut-off state, at its end: position (m)
#: and velocity (m/s). Measured: within 3.1 cm and 0.02 mm/s after the 12.2 h coast of the
#: 150 N plan; GMAT's default lunar GM (2e-7 larger than lunarcap's) alone moves that
#: coast's end by 35 m.
TOL_COAST_POSITION_M = 1.0
TOL_COAST_SPEED_MPS = 1e-3
#: Gate of the final orbit's perilune and apolune radii, whole capture flown open loop, m.
TOL_FINAL_RADII_M = 50.0
#: GMAT's reported epochs carry 16 significant digits of a modified Julian date (~1 us).
TOL_EPOCH_S = 1e-5


@dataclass
class GmatComparison:
    """GMAT's states against lunarcap's (m, mm/s, kg, s); see the module docstring.

    ``burns``: per burn flown from lunarcap's ignition state, its cut-off residuals.
    ``coasts``: per coast flown from lunarcap's cut-off state, its end residuals.
    ``capture``: the whole capture, residuals at each event (``burn``, ``event``).
    ``final_orbit``: per epoch (last cut-off, end) the perilune and apolune radii (km) of
    lunarcap and GMAT and their differences (m).
    """

    plan: str
    burns: list
    coasts: list
    capture: list
    final_orbit: list
    gmat_wall_s: float
    files: dict = field(default_factory=dict)

    def failures(self) -> list:
        """The gates missed, with the numbers."""
        out = []
        for b in self.burns:
            if not b["position_diff_m"] < TOL_BURN_POSITION_M:
                out.append(f"burn {b['burn']}: cut-off {b['position_diff_m']:.3g} m from "
                           f"lunarcap's (gate {TOL_BURN_POSITION_M:g} m)")
            if not b["velocity_diff_mmps"] < TOL_BURN_SPEED_MPS * 1e3:
                out.append(f"burn {b['burn']}: cut-off {b['velocity_diff_mmps']:.3g} mm/s "
                           f"from lunarcap's (gate {TOL_BURN_SPEED_MPS * 1e3:g} mm/s)")
        for c in self.coasts:
            if not (c["position_diff_m"] < TOL_COAST_POSITION_M
                    and c["velocity_diff_mmps"] < TOL_COAST_SPEED_MPS * 1e3):
                out.append(f"coast to burn {c['burn']} event {c['event']}: "
                           f"{c['position_diff_m']:.3g} m, {c['velocity_diff_mmps']:.3g} mm/s "
                           f"from lunarcap's (gates {TOL_COAST_POSITION_M:g} m, "
                           f"{TOL_COAST_SPEED_MPS * 1e3:g} mm/s)")
        for f in self.final_orbit:
            worst = max(abs(f["rp_diff_m"]), abs(f["ra_diff_m"]))
            if not worst < TOL_FINAL_RADII_M:
                out.append(f"final orbit at {f['at']}: perilune {f['rp_diff_m']:.3g} m, "
                           f"apolune {f['ra_diff_m']:.3g} m from lunarcap's (gate "
                           f"{TOL_FINAL_RADII_M:g} m)")
        for row in self.burns + self.capture:
            if not abs(row["epoch_diff_s"]) < TOL_EPOCH_S:
                out.append(f"GMAT's epoch {row['epoch_diff_s']:.3g} s from lunarcap's")
        return out

    def to_dict(self) -> dict:
        """JSON-ready."""
        d = asdict(self)
        d["files"] = {k: str(v) for k, v in self.files.items()}
        return d


def _residual(row: gmat.Row, ref) -> dict:
    return {"burn": row.burn, "event": row.event,
            "epoch_diff_s": row.epoch_s - ref.epoch_s,
            "position_diff_m": float(np.linalg.norm(row.r_km - np.array(ref.r_km)) * 1e3),
            "velocity_diff_mmps": float(np.linalg.norm(row.v_kmps - np.array(ref.v_kmps))
                                        * 1e6),
            "mass_diff_kg": row.mass_kg - ref.mass_kg}


def _radii(r, v, mu: float) -> tuple:
    o = orbit_summary(mee_from_rv(r, v, mu), mu)
    return o["rp_km"], o["ra_km"]


def lunarcap_events(result, arcs) -> dict:
    """The states of lunarcap's flight (ICRF :class:`~lunarcap.exchange.ccsds.StateVector`).

    Keys ``(burn, event)`` as in the script's reports: ``(0, IGNITION)`` the arrival,
    ``(k, IGNITION)`` and ``(k, CUTOFF)`` of burn k, ``(n, END)`` the end.
    """
    pole = result.plan.lunar_pole
    out = {(0, gmat.IGNITION): icrf_state(arcs[0], arcs[0].span[0], pole)}
    burn_arcs = [a for a in arcs if a.thrust_N]
    for k, a in enumerate(burn_arcs, 1):
        out[(k, gmat.IGNITION)] = icrf_state(a, a.span[0], pole)
        out[(k, gmat.CUTOFF)] = icrf_state(a, a.span[1], pole)
    out[(len(burn_arcs), gmat.END)] = icrf_state(arcs[-1], arcs[-1].span[1], pole)
    return out


def fly_in_gmat(result, out_dir, python: str | None = None) -> GmatComparison:
    """Export ``result`` into ``out_dir``, run its GMAT script and compare (module docstring).

    ``python``: the interpreter with ``gmatpy`` (default: this one).
    """
    ex = export_plan(result, out_dir)
    t0 = time.perf_counter()
    gmat.run_script(Path(ex.files["gmat_script"]), python)
    return gmat_comparison(result, ex.files, time.perf_counter() - t0)


def gmat_comparison(result, files: dict, gmat_wall_s: float = float("nan")) -> GmatComparison:
    """GMAT's reports of an exported script, already run, against lunarcap's flight.

    ``files``: the export's files (:attr:`lunarcap.capture.export.Export.files`; its
    ``gmat_script`` names the reports beside it), however GMAT was run (:func:`fly_in_gmat`,
    or the README's command); ``gmat_wall_s``: GMAT's wall time, s.
    """
    script = Path(files["gmat_script"])
    stem = script.stem
    ref = lunarcap_events(result, capture_arcs(result))
    burns = [_residual(r, ref[(r.burn, gmat.CUTOFF)])
             for r in gmat.read_report(script.with_name(f"{stem}_gmat_burns.txt"))
             if r.event == gmat.CUTOFF]
    coasts = [_residual(r, ref[(r.burn, r.event)])
              for r in gmat.read_report(script.with_name(f"{stem}_gmat_coasts.txt"))
              if r.event != gmat.CUTOFF]
    rows = gmat.read_report(script.with_name(f"{stem}_gmat_capture.txt"))
    capture = [_residual(r, ref[(r.burn, r.event)]) for r in rows]
    mu = result.burns[0].solution.problem.model.mu
    n = len(result.burns)
    final = []
    for key, at in (((n, gmat.CUTOFF), f"cut-off of burn {n}"), ((n, gmat.END), "end")):
        row = next(r for r in rows if (r.burn, r.event) == key)
        rp_l, ra_l = _radii(ref[key].r_km, ref[key].v_kmps, mu)
        rp_g, ra_g = _radii(row.r_km, row.v_kmps, mu)
        final.append({"at": at, "rp_km": rp_l, "ra_km": ra_l, "rp_gmat_km": rp_g,
                      "ra_gmat_km": ra_g, "rp_diff_m": (rp_g - rp_l) * 1e3,
                      "ra_diff_m": (ra_g - ra_l) * 1e3})
    if (len(burns), len(coasts), len(capture)) != (n, n, 2 * n + 2):
        raise gmat.GmatError(f"{stem}: GMAT reported {len(burns)} burns, {len(coasts)} "
                             f"coasts and {len(capture)} capture events, expected {n}, {n} "
                             f"and {2 * n + 2}")
    return GmatComparison(result.plan.name, burns, coasts, capture, final, gmat_wall_s,
                          dict(files))


#: What :func:`default_costs` changes, each to GMAT's default: the thruster's standard
#: gravity, the axis of the lunar J2 (GMAT's Moon turns with the Moon), the Moon's GM,
#: and the thrust direction (one per burn instead of segments).
DEFAULTS_FLOWN = ("g0", "pole", "gm", "one-direction")


def default_costs(result, defaults: dict) -> dict:
    """What each of GMAT's defaults would cost the capture, flown in lunarcap.

    The capture as the exported script flies it (:func:`lunarcap.capture.openloop.
    fly_open_loop`: from the arrival, the thrust in 10 s inertial segments) against the
    same with one setting left at GMAT's default (``defaults``:
    :func:`lunarcap.exchange.gmat.gmat_defaults`): ``g0`` the thruster's standard gravity;
    ``pole`` J2 about the Moon's pole of date (IAU; GMAT's ``Luna`` turns with the DE405
    librations) instead of the plan's fixed pole; ``gm`` GMAT's lunar GM; ``one-direction``
    one thrust direction per burn. Per change: the first burn's cut-off and the first
    coast's end (m, mm/s), and the final orbit's perilune and apolune (m) and the end state
    (m, mm/s), against the flight with the script's settings. lunarcap's flights of that
    script agree with GMAT's to centimetres (:func:`fly_in_gmat`), so these are GMAT's costs
    too.
    """
    from dataclasses import replace

    from lunarcap.capture.openloop import CUTOFF, END, apart, fly_open_loop
    from lunarcap.physics.forces import force_model

    app = 60.0 * APPROACH_MIN
    ref = fly_open_loop(result, hold="inertial", approach_s=app)
    f = force_model(result.plan.dynamics)
    of_date = replace(f, pole="of-date", name="") if f.gravity == "j2" else None
    flights = {"g0": fly_open_loop(result, hold="inertial", approach_s=app,
                                   g0_mps2=defaults["g0_mps2"]),
               "gm": fly_open_loop(result, hold="inertial", approach_s=app,
                                   mu=defaults["luna_mu_km3s2"]),
               "one-direction": fly_open_loop(result, hold="one-direction", approach_s=app)}
    if of_date is not None and f.pole == "frame":
        flights["pole"] = fly_open_loop(result, of_date, hold="inertial", approach_s=app)
    n = len(result.burns)
    out = {}
    for k, fl in flights.items():
        burn1 = apart(fl, ref, (1, CUTOFF))
        coast1 = apart(fl, ref, (2, "ignition") if n > 1 else (n, END))
        end = apart(fl, ref)
        out[k] = {"burn1_m": burn1["position_diff_m"], "burn1_mmps": burn1["velocity_diff_mmps"],
                  "coast1_m": coast1["position_diff_m"], "end_m": end["position_diff_m"],
                  "end_mmps": end["velocity_diff_mmps"], "rp_m": end["rp_diff_m"],
                  "ra_m": end["ra_diff_m"]}
    return out
