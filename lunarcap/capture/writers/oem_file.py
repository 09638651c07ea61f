"""The flown capture as a CCSDS OEM 2.0 (KVN), Moon-centred ICRF: ``<stem>.oem``.

One segment per arc (so no interpolation crosses an ignition or a cut-off), each
declaring the Lagrange interpolation of degree :data:`lunarcap.exchange.ccsds.OEM_DEGREE`
that the exporter checked against the propagated states half-way between epochs.
"""

from __future__ import annotations

from lunarcap.exchange.ccsds import write_oem


def write(flown) -> dict:
    """Write ``<stem>.oem`` of a :class:`~lunarcap.capture.export.FlownCapture`.

    Epochs in its time system; OBJECT_NAME the plan's name, OBJECT_ID its NAIF ID.
    Returns ``{"oem": path}``.
    """
    path = flown.path(".oem")
    write_oem(path, flown.segments, flown.plan.name, str(flown.object_id), flown.time_system,
              comments=flown.comments)
    return {"oem": path}
