"""The export writers: one module per format, registered here in one line each.

A writer is a function ``write(flown) -> dict`` of a module in this folder: it receives
the :class:`~lunarcap.capture.export.FlownCapture` that :func:`lunarcap.capture.export.
export_plan` prepared once (the arcs, the OEM segments, the burns' samples, the comment
lines, the time system, the object ID, the directory and file stem), writes its file(s)
with :mod:`lunarcap.exchange` and returns their paths under keys unique across writers
(the keys of :attr:`lunarcap.capture.export.Export.files`). Adding a format: a module
beside these with its ``write``, and its line in :data:`WRITERS`. One module per format
rather than one module of writer functions, so that a format is added, read and removed
as one file, as the exporter never changes for it.
"""

from lunarcap.capture.writers import attitude_csv, gmat_script, maneuvers_csv, oem_file, spk_file

#: The registered writers, by name, in the order their files are written and listed.
WRITERS: dict = {
    "oem": oem_file.write,
    "spk": spk_file.write,
    "attitude": attitude_csv.write,
    "maneuvers": maneuvers_csv.write,
    "gmat": gmat_script.write,
}
