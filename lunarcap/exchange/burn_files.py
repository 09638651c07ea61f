"""The burns for other tools: an attitude file (thrust direction in time) and a maneuver file.

Both are CSV: first ``#`` comment lines (the Moon's GM and radius,
:func:`lunarcap.exchange.ccsds.reference_comments`; ``pandas.read_csv(path, comment="#")``
skips them), then one header line, units in the column names, one row per sample or per
burn; epochs twice: as text in the export's time system and as TDB seconds past J2000
(SPICE's ET), so no tool has to convert. Directions are unit vectors in Moon-centred ICRF.

``<plan>_attitude.csv``: :data:`ATTITUDE_COLUMNS`, per burn from ignition to cut-off:
the thrust direction, the thrust and the mass at each sample (1 s apart).

``<plan>_maneuvers.csv``: :data:`MANEUVER_COLUMNS`, one row per burn: ignition, duration,
thrust, Isp, masses before and after, the delta-V (the integral of T/m, m/s) and its mean
direction (the direction of the integral of the thrust acceleration vector).

:func:`fly_attitude` flies a burn of these files through :mod:`lunarcap.physics.propagate`
(the direction interpolated between samples), which is how the tests check them.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.exchange.ccsds import reference_comments
from lunarcap.physics.dynamics import Model
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.frames import DEFAULT_LUNAR_POLE, mme_from_icrf
from lunarcap.physics.propagate import propagate
from lunarcap.physics.steering import law

ATTITUDE_COLUMNS = ("burn", "epoch", "et_s", "ux_icrf", "uy_icrf", "uz_icrf", "thrust_N",
                    "mass_kg")
MANEUVER_COLUMNS = ("burn", "ignition_epoch", "ignition_et_s", "duration_s", "thrust_N",
                    "isp_s", "m_start_kg", "m_end_kg", "delta_v_mps", "dir_x_icrf",
                    "dir_y_icrf", "dir_z_icrf")


def mean_direction(t_s, u_icrf, thrust_N: float, mass_kg) -> np.ndarray:
    """Unit vector of the integral of the thrust acceleration T/m u over a burn (trapezoid)."""
    acc = np.asarray(u_icrf, float) * (thrust_N / np.asarray(mass_kg, float))
    dv = np.trapezoid(acc, np.asarray(t_s, float), axis=1)
    return dv / np.linalg.norm(dv)


def write_attitude(path, burns, time_system: str = "TDB") -> Path:
    """Write the attitude CSV.

    ``burns``: per burn a dict with ``t_s`` (N,), ``u_icrf`` (3, N), ``thrust_N`` and
    ``mass_kg`` (N,).
    """
    path = Path(path)
    with path.open("w", newline="", encoding="ascii") as fh:
        w = _writer(fh)
        w.writerow(ATTITUDE_COLUMNS)
        for i, b in enumerate(burns, 1):
            u = np.asarray(b["u_icrf"], float)
            for j, t in enumerate(np.asarray(b["t_s"], float)):
                w.writerow([i, calendar_from_seconds(t, 6, time_system, iso=True),
                            f"{t:.6f}", f"{u[0, j]:.12f}", f"{u[1, j]:.12f}",
                            f"{u[2, j]:.12f}", f"{b['thrust_N']:.6f}",
                            f"{b['mass_kg'][j]:.6f}"])
    return path


def write_maneuvers(path, rows, time_system: str = "TDB") -> Path:
    """Write the maneuver CSV.

    ``rows``: per burn a dict with ``t_ign_s``, ``duration_s``, ``thrust_N``, ``isp_s``,
    ``m_start_kg``, ``m_end_kg``, ``delta_v_mps`` and ``dir_icrf``.
    """
    path = Path(path)
    with path.open("w", newline="", encoding="ascii") as fh:
        w = _writer(fh)
        w.writerow(MANEUVER_COLUMNS)
        for i, r in enumerate(rows, 1):
            d = r["dir_icrf"]
            w.writerow([i, calendar_from_seconds(r["t_ign_s"], 6, time_system, iso=True),
                        f"{r['t_ign_s']:.6f}", f"{r['duration_s']:.6f}",
                        f"{r['thrust_N']:.6f}", f"{r['isp_s']:.6f}", f"{r['m_start_kg']:.6f}",
                        f"{r['m_end_kg']:.6f}", f"{r['delta_v_mps']:.6f}", f"{d[0]:.12f}",
                        f"{d[1]:.12f}", f"{d[2]:.12f}"])
    return path


def _writer(fh):
    """A CSV writer on ``fh`` after the ``#`` lines of the Moon's constants."""
    fh.writelines(f"# {c}\r\n" for c in reference_comments())
    return csv.writer(fh)


def _read(path, columns) -> list:
    path = Path(path)
    with path.open(newline="", encoding="ascii") as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    if not rows or tuple(rows[0]) != columns:
        raise InputError(f"{path.name}: expected the columns {', '.join(columns)}")
    return [{k: (v if k.endswith("epoch") else float(v)) for k, v in r.items()} for r in rows]


def read_attitude(path) -> dict:
    """The attitude CSV as {burn number: dict of arrays t_s, u_icrf (3, N), thrust_N, mass_kg}."""
    out = {}
    for r in _read(path, ATTITUDE_COLUMNS):
        b = out.setdefault(int(r["burn"]), {"t_s": [], "u": [], "thrust_N": r["thrust_N"],
                                            "mass_kg": []})
        b["t_s"].append(r["et_s"])
        b["u"].append((r["ux_icrf"], r["uy_icrf"], r["uz_icrf"]))
        b["mass_kg"].append(r["mass_kg"])
    return {k: {"t_s": np.array(v["t_s"]), "u_icrf": np.array(v["u"]).T,
                "thrust_N": v["thrust_N"], "mass_kg": np.array(v["mass_kg"])}
            for k, v in out.items()}


def read_maneuvers(path) -> list:
    """The maneuver CSV as a list of dicts (numbers as floats, epochs as text)."""
    return _read(path, MANEUVER_COLUMNS)


def fly_attitude(model: Model, x0, attitude: dict, pole: str = DEFAULT_LUNAR_POLE
                 ) -> np.ndarray:
    """Fly one burn of an attitude file; returns the state at its last sample.

    From the state ``x0`` (p, f, g, h, k, L, m) at its first sample, in ``model`` (its
    Isp; the file's thrust).

    Between consecutive samples the thrust keeps the normalised mean of their two
    directions, fixed in inertial space (the propagator's ``inertial`` steering): the
    midpoint rule, second order in the 1 s step.
    """
    t, u = attitude["t_s"], np.asarray(attitude["u_icrf"], float)
    x = np.asarray(x0, float)
    for j in range(t.size - 1):
        mid = u[:, j] + u[:, j + 1]
        direction = mme_from_icrf(mid / np.linalg.norm(mid), pole)
        x = propagate(model, t[j], x, None, u=law("inertial", direction),
                      thrust_N=attitude["thrust_N"], duration_s=t[j + 1] - t[j]).final
    return x
