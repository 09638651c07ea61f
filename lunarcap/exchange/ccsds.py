"""CCSDS Orbit Data Messages in KVN: OPM (one state) and OEM (an ephemeris).

The formats are CCSDS 502.0-B-3 ("Orbit Data Messages", the blue book): keyword = value
lines, ``COMMENT`` lines, an OEM made of segments, each a ``META_START`` ... ``META_STOP``
block followed by data lines ``epoch x y z vx vy vz`` (km, km/s). lunarcap writes OEM
2.0 with ``CENTER_NAME = MOON``, ``REF_FRAME = ICRF`` and ``TIME_SYSTEM = TDB`` (or
``UTC``), and declares the interpolation readers should use (Lagrange, degree 7);
:func:`lagrange_interpolate` is that interpolation, so the file's accuracy between its
states can be measured (:func:`interpolation_error`).

It reads an OPM (KVN) state for a plan's arrival: ``CENTER_NAME = MOON``, ``REF_FRAME``
ICRF (or EME2000, taken as ICRF: see :mod:`lunarcap.physics.frames`), ``TIME_SYSTEM``
TDB or UTC, the state vector, and the optional ``MASS``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics.constants import MU_MOON, R_MOON, R_MOON_IAU
from lunarcap.physics.epochs import SCALES, calendar_from_seconds, seconds_from_calendar

#: Frames accepted in a file (ICRF axes; EME2000/J2000 taken as ICRF) and the plan's own.
ICRF_NAMES = ("ICRF", "EME2000", "J2000")
#: The interpolation lunarcap declares in its OEM files.
OEM_INTERPOLATION = "LAGRANGE"
OEM_DEGREE = 7
_STATE_KEYS = ("X", "Y", "Z", "X_DOT", "Y_DOT", "Z_DOT")
_KVN = re.compile(r"^\s*([A-Z0-9_]+)\s*=\s*(.*?)\s*(?:\[[^\]]*\])?\s*$")


@dataclass(frozen=True)
class StateVector:
    """A Moon-centred state at an epoch, as read from or written to a file.

    Attributes
    ----------
    epoch_s : float
        TDB seconds past J2000.
    r_km, v_kmps : tuple of 3 floats
        Position (km) and velocity (km/s) in ``frame``.
    frame : str
        ``ICRF`` (files) or ``M-MME2000``.
    mass_kg : float or None
    epoch_text : str
        The epoch as written (with its scale), for messages and round trips.
    """

    epoch_s: float
    r_km: tuple
    v_kmps: tuple
    frame: str = "ICRF"
    mass_kg: float | None = None
    epoch_text: str = ""


@dataclass
class OemSegment:
    """One OEM segment, Moon-centred ICRF.

    Epochs (N,) TDB s past J2000, positions (3, N) km, velocities (3, N) km/s; ``name`` is
    written as a COMMENT (e.g. ``burn 1``).
    """

    t_s: np.ndarray
    r_km: np.ndarray
    v_kmps: np.ndarray
    name: str = ""
    meta: dict = field(default_factory=dict)

    @property
    def states(self) -> np.ndarray:
        """(6, N) positions and velocities."""
        return np.vstack([self.r_km, self.v_kmps])


def _kvn_lines(text: str, where: str):
    """(line number, key, value) of the KVN lines, COMMENT and blank lines left out."""
    for n, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if not s or s.startswith("COMMENT"):
            continue
        m = _KVN.match(s)
        yield n, (m[1], m[2]) if m else (None, s)


def _float(where: str, key: str, value: str) -> float:
    try:
        v = float(value)
    except ValueError:
        raise InputError(f"{where}: {key} = {value!r} is not a number") from None
    if not np.isfinite(v):
        raise InputError(f"{where}: {key} = {value!r} is not a finite number")
    return v


def read_opm(path) -> StateVector:
    """The state of a CCSDS OPM file (KVN), Moon-centred, in ICRF axes.

    Raises
    ------
    InputError
        Unreadable file, a missing keyword, another centre than the Moon, an unknown
        frame or time system; the message names the file and the keyword.
    """
    path = Path(path)
    where = f"OPM {path.name}"
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{where}: cannot read it: {exc}") from None
    kv = {}
    for n, (key, value) in _kvn_lines(text, where):
        if key is None:
            raise InputError(f"{where}, line {n}: not a 'KEYWORD = value' line: {value!r}")
        kv.setdefault(key, value)
    if "CCSDS_OPM_VERS" not in kv:
        raise InputError(f"{where}: no CCSDS_OPM_VERS line: not an OPM in KVN")
    for key in ("CENTER_NAME", "REF_FRAME", "TIME_SYSTEM", "EPOCH") + _STATE_KEYS:
        if key not in kv:
            raise InputError(f"{where}: {key} missing")
    if kv["CENTER_NAME"].upper() != "MOON":
        raise InputError(f"{where}: CENTER_NAME = {kv['CENTER_NAME']}: lunarcap needs a "
                         f"Moon-centred state (CENTER_NAME = MOON)")
    frame = kv["REF_FRAME"].upper()
    if frame not in ICRF_NAMES:
        raise InputError(f"{where}: REF_FRAME = {kv['REF_FRAME']}: lunarcap reads "
                         f"{', '.join(ICRF_NAMES)} (ICRF axes)")
    scale = kv["TIME_SYSTEM"].upper()
    if scale not in SCALES:
        raise InputError(f"{where}: TIME_SYSTEM = {kv['TIME_SYSTEM']}: lunarcap reads "
                         f"{' or '.join(SCALES)}")
    try:
        epoch = seconds_from_calendar(kv["EPOCH"], scale=scale)
    except InputError as exc:
        raise InputError(f"{where}: EPOCH: {exc}") from None
    x = [_float(where, k, kv[k]) for k in _STATE_KEYS]
    mass = _float(where, "MASS", kv["MASS"]) if "MASS" in kv else None
    if mass is not None and not mass > 0:
        raise InputError(f"{where}: MASS = {kv['MASS']} must be positive (kg)")
    return StateVector(epoch, tuple(x[:3]), tuple(x[3:]), "ICRF", mass,
                       f"{kv['EPOCH']} {scale}")


def reference_comments() -> list:
    """The Moon's GM and radius behind lunarcap's numbers, as lines of at most 80 characters.

    Every file lunarcap exports starts with them (CCSDS ``COMMENT`` lines, the SPK's
    comment area, ``#`` lines of the CSV files): the states need no radius, but the
    altitudes lunarcap reports, and the orbits it plans, are measured with these.
    """
    return [f"Moon GM {MU_MOON:.3f} km^3/s^2, mean radius {R_MOON:.1f} km (Song et al. 2011, "
            "Sec. 3.1).",
            f"lunarcap's altitudes are |r| - {R_MOON:.1f} km; with the IAU mean radius "
            f"{R_MOON_IAU:.1f} km",
            f"(Seidelmann et al. 2007) the same states read {R_MOON - R_MOON_IAU:.1f} km "
            "higher."]


def _header(kind: str, version: str, originator: str, comments=()) -> list:
    """The KVN header: version, COMMENT lines (the Moon's constants first), date, originator."""
    import datetime as _dt

    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%S")
    return [f"CCSDS_{kind}_VERS = {version}",
            *[f"COMMENT {c}" for c in (*reference_comments(), *comments)],
            f"CREATION_DATE = {now}", f"ORIGINATOR = {originator}", ""]


def write_opm(path, state: StateVector, object_name: str, object_id: str,
              time_system: str = "TDB", originator: str = "lunarcap", comments=()) -> Path:
    """Write one ICRF state as a CCSDS OPM 2.0 (KVN).

    The header's COMMENT lines are :func:`reference_comments` and ``comments``.
    """
    if state.frame != "ICRF":
        raise InputError(f"an OPM is written in ICRF, got a state in {state.frame}")
    path = Path(path)
    lines = _header("OPM", "2.0", originator, comments) + [
        f"OBJECT_NAME = {object_name}", f"OBJECT_ID = {object_id}", "CENTER_NAME = MOON",
        "REF_FRAME = ICRF", f"TIME_SYSTEM = {time_system.upper()}", "",
        f"EPOCH = {calendar_from_seconds(state.epoch_s, 6, time_system, iso=True)}"]
    for k, val in zip(_STATE_KEYS, (*state.r_km, *state.v_kmps)):
        lines.append(f"{k} = {val:.9f} [{'km' if '_DOT' not in k else 'km/s'}]")
    if state.mass_kg is not None:
        lines += ["", f"MASS = {state.mass_kg:.6f} [kg]"]
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    return path


def write_oem(path, segments, object_name: str, object_id: str, time_system: str = "TDB",
              originator: str = "lunarcap", comments=(), degree: int = OEM_DEGREE) -> Path:
    """Write ICRF segments as a CCSDS OEM 2.0 (KVN), one META block per segment.

    The header's COMMENT lines are :func:`reference_comments` and ``comments``. Epochs are
    written to the microsecond in ``time_system`` (TDB or UTC), positions to
    the millimetre (km, 6 decimals) and velocities to the nanometre per second (km/s, 9
    decimals). Each segment declares ``INTERPOLATION = LAGRANGE`` of ``degree``.
    """
    ts = time_system.upper()
    if ts not in SCALES:
        raise InputError(f"time system {time_system!r}: lunarcap writes TDB or UTC")
    path = Path(path)
    out = _header("OEM", "2.0", originator, comments)
    for seg in segments:
        t = np.asarray(seg.t_s, float)
        if t.size < degree + 1 or np.any(np.diff(t) <= 0):
            raise InputError(f"OEM segment {seg.name!r}: needs at least {degree + 1} "
                             f"increasing epochs, got {t.size}")
        def cal(x):  # noqa: E306
            return calendar_from_seconds(x, 6, ts, iso=True)
        out += ["" if out[-1] else None, "META_START", f"OBJECT_NAME = {object_name}",
                f"OBJECT_ID = {object_id}", "CENTER_NAME = MOON", "REF_FRAME = ICRF",
                f"TIME_SYSTEM = {ts}", f"START_TIME = {cal(t[0])}", f"STOP_TIME = {cal(t[-1])}",
                f"INTERPOLATION = {OEM_INTERPOLATION}", f"INTERPOLATION_DEGREE = {degree}",
                "META_STOP", ""]
        if seg.name:
            out.append(f"COMMENT {seg.name}")
        x = seg.states
        out += [f"{cal(t[j])} {x[0, j]:.6f} {x[1, j]:.6f} {x[2, j]:.6f} "
                f"{x[3, j]:.9f} {x[4, j]:.9f} {x[5, j]:.9f}" for j in range(t.size)]
    path.write_text("\n".join(line for line in out if line is not None) + "\n",
                    encoding="ascii")
    return path


def read_oem(path) -> list:
    """The segments of a CCSDS OEM (KVN) file (ICRF, TDB seconds; see :class:`OemSegment`).

    Reads what :func:`write_oem` writes and OEMs like it (no covariance blocks).
    """
    path = Path(path)
    where = f"OEM {path.name}"
    segs, meta, rows, name, in_meta = [], None, [], "", False

    def close():
        if meta is not None and rows:
            scale = meta.get("TIME_SYSTEM", "").upper()
            t = np.array([seconds_from_calendar(r[0], scale=scale) for r in rows])
            x = np.array([[float(v) for v in r[1:7]] for r in rows]).T
            segs.append(OemSegment(t, x[:3], x[3:6], name, dict(meta)))

    for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        s = line.strip()
        if s == "META_START":
            close()
            meta, rows, name, in_meta = {}, [], "", True
        elif s == "META_STOP":
            in_meta = False
            if meta.get("CENTER_NAME", "").upper() != "MOON" or \
                    meta.get("REF_FRAME", "").upper() not in ICRF_NAMES:
                raise InputError(f"{where}, line {n}: a Moon-centred ICRF segment expected")
        elif s.startswith("COMMENT"):
            if meta is not None and not in_meta and not rows:
                name = s[len("COMMENT"):].strip()
        elif in_meta:
            m = _KVN.match(s)
            if m:
                meta[m[1]] = m[2]
        elif s and meta is not None and "=" not in s:
            parts = s.split()
            if len(parts) < 7:
                raise InputError(f"{where}, line {n}: an ephemeris line needs an epoch and "
                                 f"six numbers")
            rows.append(parts)
    close()
    return segs


# ---------------------------------------------------------------------- interpolation
def lagrange_interpolate(t_nodes, values, t_query, degree: int = OEM_DEGREE) -> np.ndarray:
    """Lagrange interpolation of ``degree`` as an OEM reader does it, within one segment.

    For each query epoch the ``degree + 1`` nodes nearest to it (a window centred on it,
    shifted inside the segment at its ends) define the polynomial.

    Parameters
    ----------
    t_nodes : (N,) increasing epochs, s
    values : (n, N)
    t_query : (M,) epochs inside [t_nodes[0], t_nodes[-1]]

    Returns
    -------
    ndarray (n, M)
    """
    t = np.asarray(t_nodes, float)
    y = np.asarray(values, float)
    tq = np.atleast_1d(np.asarray(t_query, float))
    m = degree + 1
    if t.size < m:
        raise InputError(f"Lagrange interpolation of degree {degree} needs {m} nodes, "
                         f"got {t.size}")
    j = np.searchsorted(t, tq)
    lo = np.clip(j - m // 2, 0, t.size - m)
    out = np.empty((y.shape[0], tq.size))
    for q in range(tq.size):
        idx = slice(lo[q], lo[q] + m)
        tn, yn = t[idx] - tq[q], y[:, idx]
        w = np.ones(m)
        for a in range(m):
            for b in range(m):
                if a != b:
                    w[a] *= (0.0 - tn[b]) / (tn[a] - tn[b])
        out[:, q] = yn @ w
    return out


def interpolation_error(segment: OemSegment, truth, degree: int = OEM_DEGREE) -> float:
    """Largest position error (m) of the file's interpolation at the segment's mid-steps.

    ``truth(t)`` gives the (3 or more, M) positions (km) the states were taken from (a
    dense trajectory): the interpolant through the segment's states is compared with it
    half-way between consecutive epochs, where an interpolation error is largest.
    """
    t = segment.t_s
    mid = 0.5 * (t[1:] + t[:-1])
    guess = lagrange_interpolate(t, segment.r_km, mid, degree)
    return float(np.max(np.linalg.norm(guess - np.asarray(truth(mid))[:3], axis=0)) * 1e3)
