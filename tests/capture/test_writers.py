"""An export format is one writer module plus one line in the registry (issue 35).

A toy format (a CSV of the exported epochs and ICRF positions) is written in a temporary
package, outside lunarcap; registering it is the only other step. ``lunarcap plan
--export DIR`` then writes it beside the built-in files and lists it, and its rows are
the OEM's states.
"""

import sys
import textwrap
from types import SimpleNamespace

import numpy as np
import pytest

from lunarcap.capture import export
from lunarcap.capture.writers import WRITERS
from lunarcap.exchange import ccsds

TOY = '''
"""A toy export format: every exported epoch (TDB s) and ICRF position (km), CSV."""


def write(flown):
    path = flown.path("_positions.csv")
    rows = ["et_s,x_km,y_km,z_km"]
    for seg in flown.segments:
        rows += [",".join(repr(float(q)) for q in (t, *r)) for t, r in zip(seg.t_s, seg.r_km.T)]
    path.write_text("\\n".join(rows) + "\\n")
    return {"positions": path}
'''


@pytest.fixture
def toy_writer(tmp_path, monkeypatch):
    """The toy format's module, imported from a temporary package on sys.path."""
    pkg = tmp_path / "toy_formats"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "positions.py").write_text(textwrap.dedent(TOY))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, "toy_formats", raising=False)
    monkeypatch.delitem(sys.modules, "toy_formats.positions", raising=False)
    import toy_formats.positions

    return toy_formats.positions


def _fake_flown(tmp_path):
    seg = ccsds.OemSegment(np.arange(3.0), np.arange(9.0).reshape(3, 3),
                           np.zeros((3, 3)), "arc")
    return SimpleNamespace(segments=[seg], path=lambda suffix: tmp_path / f"toy{suffix}")


def test_the_writers_are_walked_in_order_and_a_registered_one_is_listed(tmp_path,
                                                                         toy_writer):
    def other(flown):
        path = flown.path(".txt")
        path.write_text("other\n")
        return {"other": path}

    files = export.write_files(_fake_flown(tmp_path),
                               {"positions": toy_writer.write, "other": other})
    assert list(files) == ["positions", "other"]
    assert files["positions"].read_text().splitlines()[1] == "0.0,0.0,3.0,6.0"
    assert files["other"].read_text() == "other\n"


def test_two_writers_listing_the_same_file_are_refused(tmp_path, toy_writer):
    with pytest.raises(ValueError, match="'again' returns \\['positions'\\]"):
        export.write_files(_fake_flown(tmp_path),
                           {"positions": toy_writer.write, "again": toy_writer.write})


@pytest.mark.slow
def test_a_registered_writer_is_written_by_plan_export_and_listed(tmp_path, monkeypatch,
                                                                  capsys, toy_writer):
    from lunarcap.cli import main

    monkeypatch.setitem(WRITERS, "positions", toy_writer.write)   # the one registration
    out = tmp_path / "out"
    rc = main(["plan", "song2011-150N", "--dynamics", "two-body", "--no-impulsive", "--quiet",
               "--export", str(out)])
    assert rc == 0
    printed = capsys.readouterr().out
    listed = [line.split()[0] for line in printed.splitlines() if line.startswith("  /")]
    assert listed[-1] == str(out / "song2011-150N_positions.csv")
    assert str(out / "song2011-150N.oem") in listed   # beside the built-in files
    # its rows are the OEM's states (written to the mm there)
    toy = np.loadtxt(out / "song2011-150N_positions.csv", delimiter=",", skiprows=1)
    oem = ccsds.read_oem(out / "song2011-150N.oem")
    t = np.concatenate([s.t_s for s in oem])
    r = np.hstack([s.r_km for s in oem])
    assert toy.shape == (t.size, 4)
    assert np.max(np.abs(toy[:, 0] - t)) < 1e-5
    assert np.max(np.abs(toy[:, 1:].T - r)) < 1e-6
