"""A GMAT script that flies the capture, with the gravity file and Moon kernel it reads.

``<stem>.script``, ``<stem>_gravity.cof`` and ``<stem>_moon.bsp``, or for a field that
turns with GMAT's ``Luna`` ``<stem>_gmat.py``, the command that runs it
(:func:`lunarcap.exchange.gmat.write_capture`): each burn flown from lunarcap's state at
its ignition and the whole capture from the arrival, the thrust direction in segments of
:data:`lunarcap.capture.export.GMAT_SEGMENT_S` (the exporter's
:func:`~lunarcap.capture.export.gmat_capture`).
"""

from __future__ import annotations

from lunarcap.exchange import gmat


def write(flown) -> dict:
    """Write the GMAT files of a :class:`~lunarcap.capture.export.FlownCapture`.

    Returns ``{"gmat_script": ..., "gmat_gravity": ..., "gmat_moon": ...}``; for a field
    that turns with GMAT's own Moon ``gmat_runner`` (``<stem>_gmat.py``) instead of
    ``gmat_moon``.
    """
    written = gmat.write_capture(flown.out, flown.stem, flown.gmat)
    return {f"gmat_{k}": p for k, p in written.items()}
