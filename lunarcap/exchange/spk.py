"""SPICE SPK files of a trajectory: written and read with NAIF's toolkit (``spiceypy``).

One SPK segment per arc (type 9: Lagrange interpolation of the states at unequal steps,
degree 7, the OEM's interpolation), the spacecraft relative to the Moon (NAIF ID 301) in
the ``J2000`` frame (ICRF axes, see :mod:`lunarcap.physics.frames`), epochs as ephemeris
time ET, which is lunarcap's own epoch: TDB seconds past J2000 (no leap-second kernel is
needed to write or read the file).

The spacecraft's NAIF ID is :data:`DEFAULT_OBJECT_ID`, -310001, unless the caller gives
another: a negative ID, as NAIF reserves for spacecraft, in a range no NAIF-registered
mission uses (registered ones are minus a NORAD-like three-digit number, e.g. LRO -85).
A viewer needs only the ID (or a name bound to it in a frames/ID kernel of its own).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.exchange.ccsds import reference_comments

#: NAIF ID of the spacecraft in lunarcap's SPK files (see the module docstring).
DEFAULT_OBJECT_ID = -310001
#: NAIF ID of the Moon, the centre of every segment.
MOON_ID = 301
FRAME = "J2000"
SPK_DEGREE = 7


def write_spk(path, segments, object_id: int = DEFAULT_OBJECT_ID,
              degree: int = SPK_DEGREE, comments=()) -> Path:
    """Write segments (:class:`lunarcap.exchange.ccsds.OemSegment`, ICRF, TDB) as an SPK.

    Each segment becomes an SPK type 9 segment named after it (at most 40 characters);
    The file's comment area (``commnt`` shows it) holds
    :func:`lunarcap.exchange.ccsds.reference_comments` and ``comments``.
    """
    import spiceypy as sp

    path = Path(path)
    if path.exists():
        path.unlink()
    if not (isinstance(object_id, (int, np.integer)) and object_id < 0):
        raise InputError(f"an SPK spacecraft ID is a negative integer, got {object_id!r}")
    handle = sp.spkopn(str(path), "lunarcap", 4096)
    try:
        for seg in segments:
            t = np.asarray(seg.t_s, float)
            states = np.ascontiguousarray(np.vstack([seg.r_km, seg.v_kmps]).T)
            sp.spkw09(handle, int(object_id), MOON_ID, FRAME, float(t[0]), float(t[-1]),
                      (seg.name or "lunarcap")[:40], degree, t.size, states, t)
        lines = [c[i:i + 80] for c in (*reference_comments(), *comments)
                 for i in range(0, max(len(c), 1), 80)]
        sp.dafac(handle, lines)
    finally:
        sp.spkcls(handle)
    return path


def read_spk(path, t_s, object_id: int = DEFAULT_OBJECT_ID) -> np.ndarray:
    """States (6, M) of ``object_id`` relative to the Moon in J2000 at ET ``t_s`` (M,).

    Through SPICE itself (``spkgeo``): the file is loaded for the call and unloaded after.
    """
    import spiceypy as sp

    path = str(Path(path))
    sp.furnsh(path)
    try:
        return np.array([sp.spkgeo(int(object_id), float(t), FRAME, MOON_ID)[0]
                         for t in np.atleast_1d(t_s)]).T
    finally:
        sp.unload(path)


def coverage(path, object_id: int = DEFAULT_OBJECT_ID) -> list:
    """The file's coverage windows of ``object_id``, [(start, stop)] in ET (s)."""
    import spiceypy as sp

    cell = sp.spkcov(str(path), int(object_id))
    return [tuple(sp.wnfetd(cell, i)) for i in range(sp.wncard(cell))]
