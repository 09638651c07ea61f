"""Each burn's thrust direction in time (ICRF), thrust and mass: ``<stem>_attitude.csv``.

Samples every :data:`lunarcap.capture.export.ATTITUDE_STEP_S` from ignition to cut-off
of the steering the verification flew (:mod:`lunarcap.exchange.burn_files`).
"""

from __future__ import annotations

from lunarcap.exchange.burn_files import write_attitude


def write(flown) -> dict:
    """Write ``<stem>_attitude.csv`` of a :class:`~lunarcap.capture.export.FlownCapture`.

    Returns ``{"attitude": path}``.
    """
    path = flown.path("_attitude.csv")
    write_attitude(path, flown.samples, flown.time_system)
    return {"attitude": path}
