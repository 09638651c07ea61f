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


@pytest.mark.parametrize("frame,source", [("iau-of-date", "iau2009"), ("luna", "de405")])
def test_gmat_body_fixed_axes_are_lunarcaps_at_the_pole_and_the_prime_meridian(frame, source,
                                                                                tmp_path):
    # a field in the iau2009 body frame flies in the script's own Moon (GMAT's IAU lunar
    # model), one in de405 in GMAT's Luna (the DE file's librations, GMAT's only rotation
    # source for Luna, which a script no longer sets): spacecraft placed on lunarcap's
    # body x, y and z axes read back in GMAT's BodyFixed axes lie on them, |off| / r <
    # 1e-9 (a pole alone would leave the prime meridian unchecked: the IAU and the DE405
    # frames' prime meridians are 92-109 arcsec, 5e-4 rad, apart in 2017)
    from lunarcap.physics.frames import rotation_313

    eph = default_ephemeris()
    if frame != "luna":
        gmat.write_moon_kernel(tmp_path / "p_moon.bsp", eph, T - 86400, T + 86400)
    rot = np.array(rotation_313(*eph.body_angles([T], source)[:, 0]))   # ICRF -> body
    other = np.array(rotation_313(*eph.body_angles([T], "de405" if source == "iau2009"
                                                   else "iau2009")[:, 0]))
    r = 2000.0
    sats = {f"On{a.upper()}": ("MoonEq", r * rot[i]) for i, a in enumerate("xyz")}
    script = tmp_path / "p.script"
    script.write_text(_body_script(frame, sats, "p"))
    gmat.run_script(script)
    v = np.array([float(x) for x in (tmp_path / "p.txt").read_text().split()]).reshape(3, 3, 3)
    fixed = v[:, 0]                                   # each spacecraft in MoonFixed
    np.testing.assert_allclose(fixed, r * np.eye(3), atol=1e-9 * r)
    # the other frame's axes are not GMAT's (the test sees a wrong prime meridian)
    assert np.abs(other @ rot.T - np.eye(3)).max() > 1e-4


def _bplane_script(states: list, stem: str) -> str:
    """Spacecraft at Moon-centred MJ2000Eq (lunarcap's ICRF) states, their BdotT, BdotR."""
    lines = ["SolarSystem.EphemerisSource = 'DE405';", f"Luna.Mu = {gmat._num(C.MU_MOON)};",
             "Create CoordinateSystem MoonEq;", "MoonEq.Origin = Luna;",
             "MoonEq.Axes = MJ2000Eq;"]
    for j, (r, v) in enumerate(states):
        sc = f"S{j}"
        lines += [f"Create Spacecraft {sc};", f"{sc}.DateFormat = TDBModJulian;",
                  f"{sc}.Epoch = '{gmat.gmat_mjd(T)}';", f"{sc}.CoordinateSystem = MoonEq;",
                  f"{sc}.DisplayStateType = Cartesian;"]
        lines += [f"{sc}.{k} = {gmat._num(x)};"
                  for k, x in zip(("X", "Y", "Z", "VX", "VY", "VZ"), (*r, *v))]
    lines += ["Create ReportFile Out;", f"Out.Filename = './{stem}.txt';", "Out.Precision = 16;",
              "Out.WriteHeaders = false;", "BeginMissionSequence;"]
    cols = " ".join(f"S{j}.MoonEq.BdotT S{j}.MoonEq.BdotR" for j in range(len(states)))
    return "\n".join(lines + [f"Report Out {cols};"]) + "\n"


def test_gmat_bdott_bdotr_are_lunarcaps_b_plane_about_eme2000(tmp_path):
    # GMAT's BdotT and BdotR of a state in a Moon-centred MJ2000Eq coordinate system (the
    # B-plane in that system's axes, T = S x z / |S x z|: GMAT User Guide, "Calculation
    # Parameters"; GmatCalcUtil::CalculateBPlaneData) are lunarcap's B-plane about EME2000,
    # from the ICRF state and from the same state in M-MME2000 about EME2000's pole there;
    # about the lunar equator they are not. States: the paper's arrival perilune and
    # generated arrivals (other inclinations, v_inf, hemispheres, approaches), and points
    # of their hyperbolas away from the perilune.
    from lunarcap.mission.arrival import arrival_state
    from lunarcap.physics.bplane import bplane_from_rv, reference_pole
    from lunarcap.physics.frames import icrf_from_mme

    pole = "iau2009-j2000"
    rng = np.random.default_rng(37)
    cases = [arrival_state()]
    for inc, hemi, vinf in ((35.0, "south", 0.6), (150.0, "north", 1.4), (90.0, "south", 2.2)):
        lon, lat = rng.uniform(0, 2 * np.pi), rng.uniform(-0.08, 0.08)
        s = [np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)]
        cases.append(arrival_state(inclination_deg=inc, hemisphere=hemi, v_inf_kmps=vinf,
                                   approach=s))
    mme = []
    for a in cases:
        mme.append((a.r_km, a.v_kmps))
        # and the inbound point of its hyperbola at true anomaly -100 deg (conic in the
        # perifocal axes P, Q: r = p / (1 + e cos f), v = sqrt(mu / p) (-sin f, e + cos f))
        rp, vp = np.linalg.norm(a.r_km), np.linalg.norm(a.v_kmps)
        e, p = rp * vp ** 2 / C.MU_MOON - 1, (rp * vp) ** 2 / C.MU_MOON
        q_p, q_q, f = a.r_km / rp, a.v_kmps / vp, np.radians(-100.0)
        mme.append((p / (1 + e * np.cos(f)) * (np.cos(f) * q_p + np.sin(f) * q_q),
                    np.sqrt(C.MU_MOON / p) * (-np.sin(f) * q_p + (e + np.cos(f)) * q_q)))
    icrf = [(icrf_from_mme(r, pole), icrf_from_mme(v, pole)) for r, v in mme]
    script = tmp_path / "b.script"
    script.write_text(_bplane_script(icrf, "b"))
    gmat.run_script(script)
    got = np.array([float(x) for x in (tmp_path / "b.txt").read_text().split()]).reshape(-1, 2)
    k_eme = reference_pole("EME2000", "M-MME2000", pole)
    for (r, v), (ri, vi), (bt, br) in zip(mme, icrf, got):
        ours = bplane_from_rv(ri, vi, C.MU_MOON)
        assert ours.b_t_km == pytest.approx(bt, abs=1e-6) and ours.b_r_km == pytest.approx(
            br, abs=1e-6), (ours, bt, br)
        there = bplane_from_rv(r, v, C.MU_MOON, k_eme)
        assert there.b_t_km == pytest.approx(bt, abs=1e-6)
        assert there.b_r_km == pytest.approx(br, abs=1e-6)
        lunar = bplane_from_rv(r, v, C.MU_MOON)
        assert np.hypot(lunar.b_t_km - bt, lunar.b_r_km - br) > 100.0
