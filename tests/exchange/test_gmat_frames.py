"""The Moon the GMAT script creates, in GMAT itself: its place and its axes are lunarcap's.

One GMAT run (gmatpy, in a child process) of a script made of the module's own body
lines: spacecraft placed on lunarcap's lunar pole, of J2000 and of date, read back in the
body-fixed axes of the fixed-pole body and of the IAU body; a spacecraft at the Earth's
centre, read from each Moon, is minus lunarcap's geocentric Moon.
"""

import numpy as np
import pytest

from lunarcap.exchange import gmat
from lunarcap.exchange.ccsds import StateVector
from lunarcap.physics import constants as C
from lunarcap.physics.ephemeris import default_ephemeris
from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.physics.frames import moon_pole_icrf, moon_pole_radec_deg

pytestmark = pytest.mark.slow

T = seconds_from_calendar("2017-02-20 03:41:26 TDB")


def _body_script(frame: str, sats: dict, stem: str) -> str:
    grav = gmat.Gravity.zonal_j2(C.MU_MOON, C.R_MOON, C.J2_MOON, moon_pole_radec_deg())
    grav = gmat.Gravity(grav.mu_km3s2, grav.radius_km, grav.c, grav.s, frame,
                        grav.pole_radec_deg)
    start = StateVector(T, (1.0, 0, 0), (0, 1.0, 0), mass_kg=1.0)
    cap = gmat.Capture("probe", start, [], [], T, grav)
    body, lines = gmat._body_lines(cap, stem)
    lines += ["Create CoordinateSystem MoonEq;", f"MoonEq.Origin = {body};",
              "MoonEq.Axes = MJ2000Eq;", "Create CoordinateSystem MoonFixed;",
              f"MoonFixed.Origin = {body};", "MoonFixed.Axes = BodyFixed;",
              "Create CoordinateSystem MoonIcrf;", f"MoonIcrf.Origin = {body};",
              "MoonIcrf.Axes = ICRF;", "Create CoordinateSystem EarthEq;",
              "EarthEq.Origin = Earth;", "EarthEq.Axes = MJ2000Eq;"]
    for name, (cs, r) in sats.items():
        lines += [f"Create Spacecraft {name};", f"{name}.DateFormat = TDBModJulian;",
                  f"{name}.Epoch = '{gmat.gmat_mjd(T)}';", f"{name}.CoordinateSystem = {cs};"]
        lines += [f"{name}.{k} = {gmat._num(x)};" for k, x in zip("XYZ", r)]
        lines += [f"{name}.VX = 0;", f"{name}.VY = 0;", f"{name}.VZ = 0.001;"]
    lines += ["Create ReportFile Out;", f"Out.Filename = './{stem}.txt';", "Out.Precision = 16;",
              "Out.WriteHeaders = false;", "BeginMissionSequence;"]
    cols = " ".join(f"{n}.{cs}.{k}" for n in sats for cs in ("MoonFixed", "MoonEq", "MoonIcrf")
                    for k in "XYZ")
    return "\n".join(lines + [f"Report Out {cols};"]) + "\n"


@pytest.mark.parametrize("frame", ["fixed-pole", "iau-of-date"])
def test_gmat_body_has_lunarcaps_pole_and_place(frame, tmp_path):
    eph = default_ephemeris()
    gmat.write_moon_kernel(tmp_path / "p_moon.bsp", eph, T - 86400, T + 86400)
    jd = C.JD_J2000 + T / 86400.0
    pole = moon_pole_icrf(*(moon_pole_radec_deg() if frame == "fixed-pole" else
                            moon_pole_radec_deg("iau2009-j2000", jd)))
    moon_geo, _ = eph.moon_geocentric_state([T])
    moon_geo = (eph.rotation.T @ moon_geo)[:, 0]
    sats = {"OnPole": ("MoonEq", 2000.0 * pole), "AtEarth": ("EarthEq", np.zeros(3))}
    script = tmp_path / "p.script"
    script.write_text(_body_script(frame, sats, "p"))
    gmat.run_script(script)
    v = np.array([float(x) for x in (tmp_path / "p.txt").read_text().split()]).reshape(2, 3, 3)
    on_pole_fixed, (_, at_earth_eq, at_earth_icrf) = v[0, 0], v[1]
    # the pole: the spacecraft on lunarcap's pole is on the body's z axis
    tilt = np.hypot(*on_pole_fixed[:2]) / 2000.0
    assert tilt < 1e-9, f"{frame}: pole {np.degrees(tilt):.3g} deg from lunarcap's"
    assert on_pole_fixed[2] == pytest.approx(2000.0, rel=1e-12)
    # the place: the Earth's centre seen from the body is minus lunarcap's geocentric Moon,
    # in ICRF axes: GMAT reads an SPK in ICRF (DE405's axes, lunarcap's) and a DE file in
    # MJ2000Eq, 17 mas apart, so in MJ2000Eq the body is 45 m from DE405's Moon with
    # respect to DE405's Earth (a tidal error below 1e-14 km/s^2 on the spacecraft)
    assert np.linalg.norm(at_earth_icrf + moon_geo) * 1e3 < 0.05
    bias_m = np.linalg.norm(at_earth_eq + moon_geo) * 1e3
    assert 20 < bias_m < 80
    # and the other frame's pole is not (the test sees a wrong pole): 0.79 deg apart
    other = moon_pole_icrf(*(moon_pole_radec_deg("iau2009-j2000", jd) if frame == "fixed-pole"
                             else moon_pole_radec_deg()))
    assert np.degrees(np.arccos(other @ pole)) > 0.5
