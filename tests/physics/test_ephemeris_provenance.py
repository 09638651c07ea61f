"""The ephemeris's provenance hash covers every file it reads (issue 37).

The book prints one SHA-256 per page for the ephemeris; the Moon's DE405 body frame (a
gravity field's orientation) reads the de405 package's libration angles, which the hash
left out: a changed libration file would have changed the real-Moon pages' numbers under
the same printed hash. Checked: the hash is SHA-256 over the files' bytes in order, computed
here by hashlib; one changed byte of the libration angles changes it.
"""

import hashlib
import os
import shutil

from lunarcap.physics.ephemeris import Ephemeris

NAMES = ("earthmoon", "moon", "sun", "librations")


def _sha(paths) -> str:
    h = hashlib.sha256()
    for p in paths:
        with open(p, "rb") as fh:
            h.update(fh.read())
    return h.hexdigest()


def test_the_hash_covers_the_positions_and_the_libration_angles():
    import de405

    eph = Ephemeris(None)
    pkg = os.path.dirname(de405.__file__)
    files = [os.path.join(pkg, f"jpl-{n}.npy") for n in NAMES]
    assert eph.data_files() == files
    assert eph.sha256 == _sha(files)
    assert eph.describe()["sha256"] == eph.sha256


def test_a_changed_libration_file_changes_the_hash(tmp_path):
    # the package's arrays copied; the copy of the libration angles changed by one byte
    for n in NAMES:
        shutil.copy(os.path.join(Ephemeris(None).path, f"jpl-{n}.npy"), tmp_path)
    before = Ephemeris(None)
    before.path = str(tmp_path)
    h0 = before.sha256
    assert h0 == Ephemeris(None).sha256                      # the copy: the same data
    lib = tmp_path / "jpl-librations.npy"
    data = bytearray(lib.read_bytes())
    data[-1] ^= 0xFF
    lib.write_bytes(bytes(data))
    after = Ephemeris(None)
    after.path = str(tmp_path)
    assert after.sha256 != h0


def test_an_spk_ephemeris_hashes_its_kernel_and_the_libration_angles(tmp_path):
    # an SPK gives positions only; the body frame still reads the package's librations
    import de405

    kernel = tmp_path / "k.bsp"
    kernel.write_bytes(b"an SPK's bytes")
    spk = Ephemeris.__new__(Ephemeris)          # the file is not read as a kernel here
    spk._kind, spk.path = "spk", str(kernel)
    lib = os.path.join(os.path.dirname(de405.__file__), "jpl-librations.npy")
    assert spk.data_files() == [str(kernel), lib]
    assert spk.sha256 == _sha([kernel, lib])
