"""Running a GMAT script (``gmatpy``, in a child process) and reading the reports it writes.

The script itself, and the files it reads, are written by :mod:`lunarcap.exchange.gmat`;
its reports are GMAT ReportFiles of :data:`REPORT_FIELDS` after a burn number and an event
code (:func:`read_report`), epochs in GMAT's TDB modified Julian date (JD - 2430000).
Running GMAT needs the ``gmatpy`` package (a test dependency, see the README).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics import constants as C

#: GMAT's modified Julian date is the Julian date minus this (GMAT Mathematical
#: Specifications, "Time Systems"): its MJD of J2000.0 is 21545.0.
GMAT_MJD_OFFSET_JD = 2430000.0
#: Columns of the report files (after the burn number and event code).
REPORT_FIELDS = ("TDBModJulian", "X", "Y", "Z", "VX", "VY", "VZ", "TotalMass")


class GmatError(RuntimeError):
    """GMAT could not be started, or refused or failed a script (the message quotes its log)."""


#: What marks a line of GMAT's log as its complaint about a script: GMAT writes refusals as
#: "**** ERROR ****", "... Exception Thrown: ..." (a tank over its volume: "Hardware
#: Exception Thrown: Fuel volume exceeds tank capacity") or "... failed ...".
GMAT_COMPLAINT = r"error|exception|fail|not permitted|does not exist|cannot|invalid"

#: The command that runs a script in GMAT (``gmatpy``), as the file ``<stem>_gmat.py``
#: beside a script whose field turns with ``Luna`` and as lunarcap's own runner. Only the
#: standard library and gmatpy: a reader runs it without lunarcap.
_RUNNER = r"""{doc}
import os
import re
import shutil
import sys
import tempfile

import gmatpy

STEM = {stem!r}
COMPLAINT = re.compile({complaint!r}, re.IGNORECASE)


def complaints(log):
    # GMAT's own words about what it refused: its error lines and the script lines quoted
    out, after = [], False
    with open(log, encoding="utf-8", errors="replace") as fh:
        for line in fh:
            text = line.strip()
            if COMPLAINT.search(text) or (after and text.startswith('"')):
                out.append(text)
                after = True
            else:
                after = False
    return out


def main(argv):
    here = os.path.dirname(os.path.abspath(argv[0])) if STEM else os.getcwd()
    script = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(here, STEM + ".script"))
    stem = os.path.splitext(script)[0]
    log = os.path.abspath(argv[2] if len(argv) > 2 else stem + "_gmat.log")
    os.chdir(os.path.dirname(script))   # the script's files are ./...
    with tempfile.TemporaryDirectory() as tmp, gmatpy.native_session() as gmat:
        gmat.UseLogFile(log)
        files = gmat.FileManager.Instance()
        if not os.path.exists(files.GetFullPathname("LP165P_FILE")) and \
                os.path.exists(stem + "_gravity.cof"):
            # GMAT's default lunar field, asked for whenever Luna is a primary body
            shutil.copyfile(stem + "_gravity.cof", os.path.join(tmp, "LP165P.cof"))
            files.SetAbsPathname("LUNA_POT_PATH", tmp + os.sep)
        ok = bool(gmat.LoadScript(script)) and bool(gmat.RunScript())
        gmat.UseLogFile(os.devnull)   # closes the log
    if not ok:
        said = complaints(log)
        print("GMAT refused or failed " + os.path.basename(script) + ": "
              + (" | ".join(said[-8:]) or "no message in " + log), file=sys.stderr)
    return 0 if ok else 3


if __name__ == "__main__":
    sys.exit(main(sys.argv))
"""


def runner_text(stem: str = "") -> str:
    """The text of ``<stem>_gmat.py``: runs ``<stem>.script`` beside it in GMAT (``gmatpy``).

    ``python <stem>_gmat.py [SCRIPT [LOG]]``: loads and runs the script unmodified, in its
    own directory (its files are ``./...``), GMAT's log in ``<stem>_gmat.log``. GMAT asks
    for its default lunar field (``LP165P.cof``) as soon as a force model names ``Luna``
    among its primary bodies, before the script's own ``PotentialFile`` replaces it; the
    wheel ships no lunar field and a script cannot point GMAT to another folder, so where
    GMAT has none this points GMAT's lunar field folder to a temporary one holding the
    script's ``<stem>_gravity.cof`` under that name. A script GMAT refuses or a mission
    that fails: GMAT's own error lines on stderr, exit status 3. With ``stem`` empty the
    script is the first argument (lunarcap's :func:`run_script` runs that text).
    """
    what = f"{stem}.script" if stem else "a GMAT script"
    name = stem or "<stem>"
    doc = (f'"""Runs {what} in NASA\'s GMAT (the PyPI wheel gmatpy), unmodified, where it '
           f'lies.\n\nWritten by lunarcap. Usage: python {stem or "runner"}_gmat.py [SCRIPT '
           f'[LOG]]\n\nGMAT asks for its default lunar field file (LP165P.cof) as soon as a '
           f'force model names\nLuna among its primary bodies, before the script\'s own '
           f'PotentialFile replaces it, and the\nwheel ships none: this points GMAT\'s lunar '
           f'field folder to a temporary one holding\n{name}_gravity.cof under that name. '
           f'GMAT\'s log: {name}_gmat.log; on failure its error\nlines go to stderr and the '
           f'exit status is 3.\n"""')
    return _RUNNER.format(doc=doc, stem=stem, complaint=GMAT_COMPLAINT)


def gmat_complaints(log) -> list:
    """GMAT's error lines in its log (and the script lines it quotes with them)."""
    pattern, out, after = re.compile(GMAT_COMPLAINT, re.IGNORECASE), [], False
    path = Path(log)
    for line in (path.read_text(errors="replace").splitlines() if path.exists() else []):
        text = line.strip()
        if pattern.search(text) or (after and text.startswith('"')):
            out.append(text)
            after = True
        else:
            after = False
    return out


def run_script(script, python: str | None = None, timeout_s: float = 1800.0) -> Path:
    """Run a GMAT script with ``gmatpy`` in a child process, in the script's directory.

    The child runs :func:`runner_text` (the text of the ``<stem>_gmat.py`` the export
    writes beside a script whose field turns with ``Luna``): the script loaded and run
    unmodified, GMAT's default lunar field pointed to ``<stem>_gravity.cof`` where GMAT
    has none.

    Parameters
    ----------
    script : path of the ``.script``
    python : the interpreter that has ``gmatpy`` (default: this one)
    timeout_s : s

    Returns
    -------
    Path of GMAT's log, ``<stem>_gmat.log`` beside the script.

    Raises
    ------
    GmatError
        gmatpy missing, a script GMAT refuses, a mission that fails, or the timeout; the
        message quotes GMAT's own error lines from its log (:func:`gmat_complaints`).
    """
    script = Path(script).resolve()
    log = script.with_name(f"{script.stem}_gmat.log")
    cmd = [python or sys.executable, "-c", runner_text(), str(script), str(log)]
    try:
        proc = subprocess.run(cmd, cwd=script.parent, capture_output=True, text=True,
                              timeout=timeout_s, env=dict(os.environ, PYTHONUNBUFFERED="1"))
    except subprocess.TimeoutExpired:
        raise GmatError(f"GMAT did not finish {script.name} within {timeout_s:g} s") from None
    if proc.returncode != 0:
        said = gmat_complaints(log)
        why = " | ".join(said[-8:]) or \
            (proc.stderr.strip().splitlines() or ["no output"])[-1]
        raise GmatError(f"GMAT refused or failed {script.name} (exit {proc.returncode}): "
                        f"{why}")
    return log


_DEFAULTS = """
import json, os, sys
import gmatpy

with gmatpy.native_session() as gmat:
    thruster = gmat.Construct("ChemicalThruster", "Thruster")
    craft = gmat.Construct("Spacecraft", "Craft")
    forces = gmat.Construct("ForceModel", "Forces")
    luna = gmat.GetObject("Luna")
    out = {k: obj.GetField(f) for k, obj, f in (
        ("g0_mps2", thruster, "GravitationalAccel"), ("thrust_frame", thruster, "CoordinateSystem"),
        ("thrust_axes", thruster, "Axes"), ("date_format", craft, "DateFormat"),
        ("coordinate_system", craft, "CoordinateSystem"), ("central_body", forces, "CentralBody"),
        ("luna_mu_km3s2", luna, "Mu"), ("luna_radius_km", luna, "EquatorialRadius"))}
    out["lunar_field_file"] = os.path.exists(
        gmat.FileManager.Instance().GetFullPathname("LP165P_FILE"))
print(json.dumps(out))
"""


def gmat_defaults(python: str | None = None, timeout_s: float = 300.0) -> dict:
    """GMAT's own defaults of what the exported script sets, read from GMAT (``gmatpy``).

    In a child process, as :func:`run_script`: a new ChemicalThruster's standard gravity
    (``g0_mps2``, m/s^2) and thrust axes (``thrust_frame``, ``thrust_axes``), a new
    Spacecraft's epoch format and coordinate system, a new ForceModel's central body,
    ``Luna``'s GM (km^3/s^2) and radius (km), and whether GMAT has its lunar field file
    (``lunar_field_file``). Numbers as floats, the rest as GMAT writes them.

    Raises
    ------
    GmatError
        gmatpy missing or failing, or the timeout.
    """
    import json

    cmd = [python or sys.executable, "-c", _DEFAULTS]
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout_s)
    except subprocess.TimeoutExpired:
        raise GmatError(f"GMAT did not report its defaults within {timeout_s:g} s") from None
    if proc.returncode != 0:
        why = (proc.stderr.strip().splitlines() or ["no output"])[-1]
        raise GmatError(f"GMAT could not report its defaults: {why}")
    out = json.loads(proc.stdout.strip().splitlines()[-1])
    for k in ("g0_mps2", "luna_mu_km3s2", "luna_radius_km"):
        out[k] = float(out[k])
    return out


@dataclass(frozen=True)
class Row:
    """One row of a report written by the script: burn number, event code, GMAT's state."""

    burn: int
    event: int
    epoch_s: float
    r_km: np.ndarray
    v_kmps: np.ndarray
    mass_kg: float


def epoch_from_gmat_mjd(mjd: float) -> float:
    """TDB seconds past J2000 of GMAT's TDB modified Julian date (JD - 2430000)."""
    return (mjd - (C.JD_J2000 - GMAT_MJD_OFFSET_JD)) * 86400.0


def read_report(path) -> list:
    """The rows of ``<stem>_gmat_burns.txt`` or ``<stem>_gmat_capture.txt`` (:class:`Row`).

    Header lines (GMAT repeats one before every row) are skipped; a data line has the
    burn number, the event, then :data:`REPORT_FIELDS`.
    """
    path = Path(path)
    rows = []
    for n, line in enumerate(path.read_text(encoding="ascii").splitlines(), 1):
        parts = line.split()
        if not parts or not parts[0][0].isdigit():
            continue
        if len(parts) != 2 + len(REPORT_FIELDS):
            raise InputError(f"{path.name}, line {n}: {len(parts)} columns, expected "
                             f"{2 + len(REPORT_FIELDS)}")
        v = [float(p) for p in parts]
        rows.append(Row(int(v[0]), int(v[1]), epoch_from_gmat_mjd(v[2]), np.array(v[3:6]),
                        np.array(v[6:9]), v[9]))
    return rows
