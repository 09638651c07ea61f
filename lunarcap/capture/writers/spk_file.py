"""The flown capture as a SPICE SPK (type 9, Lagrange), centred on the Moon: ``<stem>.bsp``.

The OEM's segments, one SPK segment each, epochs ET (TDB) whatever the export's time
system; the spacecraft is the export's NAIF ID.
"""

from __future__ import annotations

from lunarcap.exchange.spk import write_spk


def write(flown) -> dict:
    """Write ``<stem>.bsp`` of a :class:`~lunarcap.capture.export.FlownCapture`.

    Returns ``{"spk": path}``.
    """
    path = flown.path(".bsp")
    write_spk(path, flown.segments, flown.object_id, comments=flown.comments)
    return {"spk": path}
