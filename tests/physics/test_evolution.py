"""Tests of lunarcap.physics.evolution: the orbit after the capture, revolution by revolution.

* Two-body: every revolution's lowest and highest points are the ellipse's perilune and
  apolune (closed form) to a millimetre, its inclination the constant one, and the number
  of revolutions the days over the Kepler period.
* In a 20x20 field the '100 km' polar circle does not stay one (the field must show).
"""

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.physics import constants as C
from lunarcap.physics.elements import mee_from_coe, period
from lunarcap.physics.ephemeris import default_ephemeris
from lunarcap.physics.evolution import evolve

EPH = default_ephemeris()
T0 = 5.4e8   # 2017-02-10


def _state(rp_km, ra_km, inc_deg):
    a, e = 0.5 * (rp_km + ra_km), (ra_km - rp_km) / (ra_km + rp_km)
    return np.array([*mee_from_coe(a, e, np.radians(inc_deg), 0.3, 1.1, 2.0), 500.0])


@pytest.mark.parametrize("rp,ra,inc", [(1838.2, 1838.2 + 300.0, 90.0), (1900.0, 5200.0, 35.0)])
def test_two_body_revolutions_are_the_ellipse(rp, ra, inc):
    x0 = _state(rp, ra, inc)
    ev = evolve("two-body", EPH, T0, x0, 1.5)
    n = int(1.5 * 86400 / period(*x0[:3], C.MU_MOON))
    assert ev.perilune_altitude_km.size in (n - 1, n)
    np.testing.assert_allclose(ev.perilune_altitude_km + C.R_MOON, rp, rtol=0, atol=1e-6)
    np.testing.assert_allclose(ev.apolune_altitude_km + C.R_MOON, ra, rtol=0, atol=1e-6)
    # the perilunes come one Kepler period apart
    np.testing.assert_allclose(np.diff(ev.perilune_epoch_s), period(*x0[:3], C.MU_MOON),
                               rtol=0, atol=1e-3)
    assert np.abs(ev.inclination_deg - inc).max() < 1e-9
    d = ev.to_dict()
    assert d["after_revolutions"] == len(d["revolutions"]) == ev.perilune_altitude_km.size


def test_a_field_spreads_the_circle():
    # the 100 km polar circle in LP165P 20x20 for 2 days: its lowest and highest points part
    # by kilometres (J2 alone keeps them within 0.6 km: see the book's page)
    x0 = _state(1838.2, 1838.2, 90.0)
    ev = evolve({"gravity": "LP165P", "degree": 20, "third_bodies": []}, EPH, T0, x0, 2.0)
    j2 = evolve({"gravity": "j2", "pole": "frame", "third_bodies": []}, EPH, T0, x0, 2.0)
    spread = ev.apolune_altitude_km - ev.perilune_altitude_km
    assert spread.max() > 3.0
    assert (j2.apolune_altitude_km - j2.perilune_altitude_km).max() < 1.0


def test_bad_durations_are_refused():
    x0 = _state(1838.2, 1838.2 + 300.0, 90.0)
    for days in (0.0, -1.0, 61.0, float("nan")):
        with pytest.raises(InputError, match="--after-days"):
            evolve("two-body", EPH, T0, x0, days)
