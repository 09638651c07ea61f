"""Tests of lunarcap.exchange.gmat without GMAT: epochs, the COF gravity file, the script.

The run in GMAT itself, against lunarcap's flight, is tests/capture/test_gmat.py.
"""

import math
from decimal import Decimal

import numpy as np
import pytest

from lunarcap.errors import InputError
from lunarcap.exchange import gmat
from lunarcap.exchange.ccsds import StateVector
from lunarcap.physics import constants as C
from lunarcap.physics.epochs import seconds_from_calendar


def _read_cof(path):
    """A COF file read by GMAT's column rules (HarmonicGravityCof::Load, written again here).

    ``POTFIELD``: degree in columns 9-11, order 12-14, then body flag, GM (m^3/s^2),
    radius (m) and the normalisation flag; ``RECOEF``: n in 9-11, m in 12-14, C in
    18-38, S in 39-59; lines starting with ``C`` are comments; ``END`` stops.
    """
    head, coef = None, {}
    for line in open(path):
        line = line.rstrip("\r\n")
        if line.startswith("C"):
            continue
        key = line[:8].strip()
        if key == "END":
            break
        if key == "POTFIELD":
            flag, mu, a, norm = line[14:].split()
            head = (int(line[8:11]), int(line[11:14]), float(mu), float(a), float(norm))
        elif key == "RECOEF":
            s = line[38:59].strip()
            coef[int(line[8:11]), int(line[11:14])] = (float(line[17:38]),
                                                      float(s) if s else 0.0)
    return head, coef


def test_gmat_mjd_is_jd_minus_2430000_to_the_nanosecond():
    # the paper's first perilune, 2017-02-20 03:41:26 TDB = JD 2457804.65377315 TDB
    t = seconds_from_calendar("2017-02-20 03:41:26 TDB")
    text = gmat.gmat_mjd(t)
    exact = Decimal(t) / 86400 + Decimal("21545")
    assert abs(Decimal(text) - exact) < Decimal("1e-14")      # days: < 1 ns
    assert text.startswith("27804.65377314814")
    assert abs(gmat.epoch_from_gmat_mjd(float(text)) - t) < 1e-6
    rng = np.random.default_rng(25)
    for t in rng.uniform(-3e9, 3e9, 50):
        assert abs(Decimal(gmat.gmat_mjd(t)) - (Decimal(float(t)) / 86400 + 21545)) \
            < Decimal("1e-14")


def test_cof_as_gmat_reads_it_matches_the_field_and_lp165p_layout(tmp_path):
    rng = np.random.default_rng(7)
    n = 20
    c, s = rng.normal(0, 1e-5, (n + 1, n + 1)), rng.normal(0, 1e-5, (n + 1, n + 1))
    c, s = np.tril(c), np.tril(s)
    s[:, 0] = 0.0
    field = gmat.Gravity(4902.80105600, 1738.0, c, s, "luna")
    path = gmat.write_cof(tmp_path / "f.cof", field, ["a test field"])
    (deg, order, mu, a, norm), coef = _read_cof(path)
    assert (deg, order, norm) == (20, 20, 1.0)
    assert mu == pytest.approx(4902.801056e9, rel=1e-15) and a == 1738.0e3
    assert len(coef) == sum(k + 1 for k in range(2, n + 1))
    for (k, m), (cnm, snm) in coef.items():
        assert cnm == pytest.approx(c[k, m], rel=1e-14, abs=1e-300)
        assert snm == pytest.approx(s[k, m], rel=1e-14, abs=1e-300)
    # the columns of GMAT's own lunar field file (LP165P.cof, lines of degree 2 and 20)
    field = gmat.Gravity(1.0, 1.0, np.zeros((21, 21)), np.zeros((21, 21)))
    field.c[2, 2], field.s[2, 2] = 3.46354993722000e-05, 1.67294905383000e-08
    field.c[20, 20], field.s[20, 20] = 2.89171406037000e-08, -3.84505895118000e-07
    text = gmat.write_cof(tmp_path / "g.cof", field).read_text()
    assert "RECOEF    2  2    3.46354993722000e-05 1.67294905383000e-08\n" in text
    assert "RECOEF   20 20    2.89171406037000e-08-3.84505895118000e-07\n" in text


def test_j2_field_is_the_unnormalised_j2_of_the_paper(tmp_path):
    field = gmat.Gravity.zonal_j2(C.MU_MOON, C.R_MOON, C.J2_MOON, (266.8577, 65.6411))
    (deg, order, mu, a, _), coef = _read_cof(gmat.write_cof(tmp_path / "j2.cof", field))
    assert (deg, order) == (2, 0) and set(coef) == {(2, 0)}
    assert mu == C.MU_MOON * 1e9 and a == C.R_MOON * 1e3
    assert -coef[2, 0][0] * math.sqrt(5) == pytest.approx(C.J2_MOON, rel=1e-14)


def _capture(frame="fixed-pole", n_seg=3):
    t0 = seconds_from_calendar("2017-02-20 03:31:26 TDB")
    start = StateVector(t0, (1800.0, 10.0, -5.0), (0.1, 2.0, 0.3), mass_kg=500.0)
    u = np.tile(np.array([[0.6], [0.0], [0.8]]), n_seg)
    burn = gmat.Burn(start, np.full(n_seg, 10.0), u, 150.0, 200.0)
    grav = gmat.Gravity.zonal_j2(4902.8, 1738.2, 2.027e-4, (266.8577, 65.6411))
    if frame == "luna":
        grav = gmat.Gravity(4902.8, 1738.2, grav.c, grav.s, "luna")
    coast = StateVector(t0 + 10.0 * n_seg, (1800.0, 10.0, -5.0), (0.1, 2.0, 0.3), mass_kg=499.0)
    return gmat.Capture("test", start, [burn], [coast], t0 + 3600.0, grav,
                        (("Earth", 398600.441), ("Sun", 1.32712440018e11)))


def test_script_states_every_setting_explicitly():
    cap = _capture()
    text = gmat.script_text(cap, "x")
    for line in ["SolarSystem.EphemerisSource = 'DE405';", "Earth.Mu = 398600.441;",
                 "Sun.Mu = 132712440018.0;", "Create Planet LunarcapMoon;",
                 "LunarcapMoon.Mu = 4902.8;", "LunarcapMoon.EquatorialRadius = 1738.2;",
                 "LunarcapMoon.SpinAxisRAConstant = 266.8577;",
                 "LunarcapMoon.SpinAxisDECConstant = 65.6411;",
                 "LunarcapMoon.SpinAxisRARate = 0;", "LunarcapMoon.SpinAxisDECRate = 0;",
                 "MoonEq.Axes = MJ2000Eq;", "Dynamics.PointMasses = {Earth, Sun};",
                 "Dynamics.GravityField.LunarcapMoon.Degree = 2;",
                 "Dynamics.GravityField.LunarcapMoon.PotentialFile = './x_gravity.cof';",
                 "Dynamics.RelativisticCorrection = Off;", "Dynamics.SRP = Off;",
                 "Burn1.DateFormat = TDBModJulian;",
                 f"Burn1.Epoch = '{gmat.gmat_mjd(cap.arrival.epoch_s)}';",
                 "Burn1Engine.GravitationalAccel = 9.80665;   % m/s^2 (GMAT's default: 9.81)",
                 "Burn1Engine.C1 = 150.0;   % N", "Burn1Engine.K1 = 200.0;   % s",
                 "Burn1Engine.C16 = 0;", "Burn1Engine.K16 = 0;",
                 "Burn1Engine.CoordinateSystem = MoonEq;", "Burn1.DryMass = 0;",
                 "Burn1Tank.FuelMass = 500.0;   % kg: the whole mass"]:
        assert line in text.splitlines(), line
    # each segment: a direction, then a propagation to its absolute end epoch
    seg = [ln for ln in text.splitlines() if ln.startswith("Propagate Prop(Burn1)")]
    assert seg == [f"Propagate Prop(Burn1) {{Burn1.TDBModJulian = "
                   f"{gmat.gmat_mjd(cap.arrival.epoch_s + 10.0 * k)}}};" for k in (1, 2, 3)]
    assert text.count("Burn1.Burn1Engine.ThrustDirection3 = 0.8;") == 3
    # the whole capture: the same segments again, after the coast to the ignition
    assert text.count("Capture.CaptureEngine.ThrustDirection1 = 0.6;") == 3
    luna = gmat.script_text(_capture("luna"), "x")
    assert "Planet" not in luna and "Dynamics.CentralBody = Luna;" in luna.splitlines()


def test_capture_files_and_refusals(tmp_path):
    with pytest.raises(InputError, match="ephemeris"):
        gmat.write_capture(tmp_path, "x", _capture())
    files = gmat.write_capture(tmp_path, "x", _capture("luna"))
    assert set(files) == {"script", "gravity", "runner"}
    cap = _capture()
    cap.burns = []
    with pytest.raises(InputError, match="at least one burn"):
        gmat.script_text(cap, "x")
    with pytest.raises(InputError, match="finite"):
        gmat.script_text(_capture_with_nan(), "x")


def _capture_with_nan():
    cap = _capture()
    cap.burns[0].u_icrf[0, 1] = np.nan
    return cap


def _forces_model(spec):
    from lunarcap.mission.scenario import paper_scenario
    from lunarcap.physics.dynamics import Model, fit_for
    from lunarcap.physics.ephemeris import default_ephemeris

    t = seconds_from_calendar(paper_scenario().epoch_tdb)
    return Model(spec, 150.0, 200.0, fit_for(spec, default_ephemeris(), t - 3600, t + 3600))


@pytest.mark.parametrize("spec,frame,j2,third", [
    ("full", "fixed-pole", C.J2_MOON, ("Earth", "Sun")),
    ("j2", "fixed-pole", C.J2_MOON, ()),
    ("two-body", "fixed-pole", 0.0, ()),
    ({"gravity": "j2", "pole": "of-date", "third_bodies": ["sun"]}, "iau-of-date", C.J2_MOON,
     ("Sun",)),
])
def test_each_term_says_what_gmat_flies_zonal(spec, frame, j2, third):
    # the central field and the point masses the terms ask for: the paper's J2 about the
    # plan's pole (fixed: GMAT's own Luna would turn with the librations), J2 of date in
    # GMAT's IAU Moon, the bodies with lunarcap's GMs
    from lunarcap.physics.frames import moon_pole_radec_deg

    grav, masses = gmat.capture_forces(_forces_model(spec), "iau2009-j2000")
    assert grav.frame == frame and (grav.degree, grav.order) == (2, 0)
    assert (grav.mu_km3s2, grav.radius_km) == (C.MU_MOON, C.R_MOON)
    assert grav.c[2, 0] == -j2 / math.sqrt(5.0) and not grav.s.any()
    assert grav.pole_radec_deg == tuple(float(a) for a in moon_pole_radec_deg("iau2009-j2000"))
    assert masses == tuple((b, {"Earth": C.MU_EARTH, "Sun": C.MU_SUN}[b]) for b in third)
    assert ("+ J2" in grav.source) is (j2 != 0.0)


@pytest.mark.parametrize("body_frame,frame", [("de405", "luna"), ("iau2009", "iau-of-date")])
def test_each_term_says_what_gmat_flies_field(body_frame, frame):
    # a field goes whole (its C20 too) to its degree and order, the orders above zeroed, in
    # GMAT's Luna (DE405 librations) or its IAU Moon, scaled by lunarcap's GM
    from lunarcap.physics.gravity import packaged_field

    spec = {"gravity": "LP165P", "degree": 6, "order": 3, "body_frame": body_frame,
            "third_bodies": ["earth"]}
    grav, masses = gmat.capture_forces(_forces_model(spec), "iau2009-j2000")
    lp = packaged_field()
    assert grav.frame == frame and (grav.degree, grav.order) == (6, 3)
    assert (grav.mu_km3s2, grav.radius_km) == (C.MU_MOON, lp.radius_km)
    np.testing.assert_array_equal(grav.c[:, :4], lp.C[:7, :4])
    np.testing.assert_array_equal(grav.s[:, :4], lp.S[:7, :4])
    assert not grav.c[:, 4:].any() and not grav.s[:, 4:].any()
    assert masses == (("Earth", C.MU_EARTH),)


@pytest.mark.parametrize("mass_kg", [150.0, 524.895, 945.0, 1200.0, 5000.0, 80000.0])
def test_each_tank_holds_its_spacecraft_whole(mass_kg):
    # GMAT stops at load when FuelMass / FuelDensity > Volume ("Fuel volume exceeds tank
    # capacity"); its default tank (0.75 m^3 at 1,260 kg/m^3) holds 945 kg. Each tank the
    # script creates is sized from the mass it carries, as GMAT reads the numbers back.
    cap = _capture()
    cap.burns[0].start = StateVector(cap.burns[0].start.epoch_s, cap.burns[0].start.r_km,
                                     cap.burns[0].start.v_kmps, mass_kg=mass_kg)
    cap.arrival = cap.burns[0].start
    lines = gmat.script_text(cap, "x").splitlines()
    for sc in ("Burn1", "Capture"):
        field = {ln.split("=")[0].strip(): float(ln.split("=")[1].split(";")[0])
                 for ln in lines if ln.startswith(f"{sc}Tank.") and "=" in ln
                 and ln.split("=")[1].split(";")[0].strip()[0].isdigit()}
        assert field[f"{sc}Tank.FuelMass"] == mass_kg
        held = field[f"{sc}Tank.Volume"] * field[f"{sc}Tank.FuelDensity"]
        assert mass_kg < held < 1.02 * mass_kg       # room for it, and no more than 2 %
        # the tank is declared before the mass it holds is set (GMAT checks at load)
        order = [ln.split(".")[1].split()[0] for ln in lines if ln.startswith(f"{sc}Tank.")]
        assert order.index("Volume") < order.index("FuelMass")


def test_a_field_in_luna_gets_its_runner_and_no_other(tmp_path):
    # only a field turning with GMAT's Luna needs the runner (GMAT asks for its default
    # lunar field file when Luna is a primary body); it is plain Python that names the
    # script and the field beside it, and the script's header says to run it
    files = gmat.write_capture(tmp_path, "x", _capture("luna"))
    assert set(files) == {"script", "gravity", "runner"}
    text = files["runner"].read_text()
    compile(text, files["runner"].name, "exec")
    assert "STEM = 'x'" in text and '"LP165P.cof"' in text and "LUNA_POT_PATH" in text
    assert "%   cd <this folder> && python x_gmat.py" in files["script"].read_text()
    # lunarcap's own runner is the same text, the script named on its command line
    assert gmat.runner_text("") == text.replace("STEM = 'x'", "STEM = ''").replace(
        text.split('"""')[1], gmat.runner_text("").split('"""')[1])
