"""Tests of lunarcap.exchange without an optimisation: OPM and OEM files, interpolation.

Round trips through our writers and readers, and through a third-party parser (``oem``
from PyPI), on states made here.
"""

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.exchange import ccsds
from lunarcap.physics.epochs import seconds_from_calendar

T0 = seconds_from_calendar("2017-02-20 02:31:26 TDB")


def _circle(t):
    """A circular 100 km lunar orbit in ICRF (km, km/s) at epochs t (s)."""
    r, w = 1837.4, np.sqrt(4902.800066 / 1837.4 ** 3)
    a = w * (np.asarray(t) - T0)
    return (np.vstack([r * np.cos(a), r * np.sin(a), 0 * a]),
            np.vstack([-r * w * np.sin(a), r * w * np.cos(a), 0 * a]))


def _segments():
    out = []
    for k, (t0, step, n) in enumerate(((T0, 60.0, 40), (T0 + 2340.0, 10.0, 30))):
        t = t0 + step * np.arange(n)
        out.append(ccsds.OemSegment(t, *_circle(t), name=f"arc {k + 1}"))
    return out


@pytest.mark.parametrize("scale", ["TDB", "UTC"])
def test_oem_read_by_third_party_parser_equals_written_states(tmp_path, scale):
    from oem import OrbitEphemerisMessage

    segs = _segments()
    path = ccsds.write_oem(tmp_path / "x.oem", segs, "test", "-310001", scale)
    theirs = OrbitEphemerisMessage.open(path)
    assert len(theirs.segments) == len(segs)
    for mine, seg in zip(segs, theirs.segments):
        assert seg.metadata["CENTER_NAME"] == "MOON" and seg.metadata["REF_FRAME"] == "ICRF"
        assert seg.metadata["TIME_SYSTEM"] == scale
        states = list(seg.states)
        t = np.array([(s.epoch.tdb.jd1 - 2451545.0 + s.epoch.tdb.jd2) * 86400.0
                      for s in states])
        r = np.array([s.position for s in states]).T
        v = np.array([s.velocity for s in states]).T
        # epochs: to the microsecond written (UTC through ERFA here, astropy there)
        assert np.max(np.abs(t - mine.t_s)) < 2e-6
        assert np.max(np.abs(r - mine.r_km)) <= 5e-7      # km, 6 decimals written
        assert np.max(np.abs(v - mine.v_kmps)) <= 5e-10   # km/s, 9 decimals
    # and our own reader agrees
    back = ccsds.read_oem(path)
    assert [s.name for s in back] == ["arc 1", "arc 2"]
    assert np.max(np.abs(back[1].r_km - segs[1].r_km)) <= 5e-7


def test_lagrange_interpolation_of_the_file():
    # degree 7 through 60 s steps of a 100 km circle: far below a metre; degree 1: not
    seg = _segments()[0]
    err7 = ccsds.interpolation_error(seg, lambda t: _circle(t)[0])
    err1 = ccsds.interpolation_error(seg, lambda t: _circle(t)[0], degree=1)
    assert err7 < 1e-3 and err1 > 100.0


def test_opm_round_trip_and_refusals(tmp_path):
    r, v = _circle(T0 + 100.0)
    sv = ccsds.StateVector(T0 + 100.0, tuple(r[:, 0]), tuple(v[:, 0]), "ICRF", 650.0)
    for scale in ("TDB", "UTC"):
        path = ccsds.write_opm(tmp_path / f"a_{scale}.opm", sv, "probe", "-310001", scale)
        back = ccsds.read_opm(path)
        assert abs(back.epoch_s - sv.epoch_s) <= 1e-6 and back.mass_kg == 650.0
        assert np.allclose(back.r_km, sv.r_km, atol=1e-9)
        assert back.epoch_text.endswith(scale)
    text = path.read_text()
    for old, new, cause in (("CENTER_NAME = MOON", "CENTER_NAME = EARTH", "Moon-centred"),
                            ("REF_FRAME = ICRF", "REF_FRAME = TEME", "REF_FRAME = TEME"),
                            ("TIME_SYSTEM = UTC", "TIME_SYSTEM = GPS", "TIME_SYSTEM = GPS")):
        bad = tmp_path / "bad.opm"
        bad.write_text(text.replace(old, new))
        with pytest.raises(InputError, match=cause) as exc:
            ccsds.read_opm(bad)
        assert "\n" not in str(exc.value)
    bad.write_text("\n".join(x for x in text.splitlines() if not x.startswith("Y_DOT")))
    with pytest.raises(InputError, match="Y_DOT missing"):
        ccsds.read_opm(bad)
