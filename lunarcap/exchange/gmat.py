"""A GMAT script that flies a capture: the burns from lunarcap's states, and the whole capture.

:func:`write_capture` writes, for a flown capture (:class:`Capture`), a script for NASA's
General Mission Analysis Tool (GMAT; run headless by the PyPI wheel ``gmatpy``, or in
GMAT's desktop application) that runs unmodified and sets explicitly every choice that
makes GMAT fly lunarcap's dynamics, and the files it reads:

* ``<stem>.script``: each burn flown from lunarcap's state at its ignition and each coast
  from lunarcap's state at the cut-off before it (per-arc comparisons), and the whole
  capture flown open loop from the arrival, burn after coast (an end-to-end one). When
  run it writes, next to itself (GMAT's paths ``./...`` are relative to the directory
  GMAT runs in; :func:`~lunarcap.exchange.gmat_run.run_script` runs it there):
  ``<stem>_gmat_burns.txt``, ``<stem>_gmat_coasts.txt`` and ``<stem>_gmat_capture.txt``,
  GMAT ReportFiles of the states at ignitions, cut-offs and the end (TDB modified Julian
  date, GMAT's JD - 2430000, then the Moon-centred position in km, velocity in km/s and
  mass in kg; :func:`~lunarcap.exchange.gmat_run.read_report`), and ``<stem>_gmat.oem``, GMAT's
  CCSDS OEM of the whole capture (UTC epochs: GMAT's OEM writer offers no TDB).
* ``<stem>_gravity.cof``: the central body's gravity field in GMAT's COF format
  (:func:`write_cof`): GMAT takes the GM and the reference radius of a field from its
  file, and the wheel ships no lunar field.
* ``<stem>_moon.bsp`` (unless the field turns with GMAT's ``Luna``): the Moon's geocentric
  states from lunarcap's ephemeris, an SPK (type 13, Hermite) read by the body the script
  creates.
* ``<stem>_gmat.py`` (only when the field turns with GMAT's ``Luna``): runs the script
  with ``gmatpy`` (``python <stem>_gmat.py``), GMAT's lunar field folder pointed to
  ``<stem>_gravity.cof`` (see below).

The settings GMAT would otherwise choose for itself, each of which moves the result by
metres to kilometres (measured by the check reported in the project's issue 25 and with
``tests/capture/test_gmat.py``):

* the thruster's g0 (``GravitationalAccel``; GMAT's default is 9.81 m/s^2, lunarcap's the
  standard 9.80665 m/s^2, :data:`lunarcap.physics.constants.G0_MPS2`), its thrust
  (``C1``, N) and specific impulse (``K1``, s) with every pressure and temperature
  coefficient zero, the whole mass in one tank sized from it (:func:`tank_volume_m3`:
  GMAT's default tank holds 945 kg);
* epochs as ``TDBModJulian`` (GMAT's modified Julian date is JD - 2430000.0, not the
  usual JD - 2400000.5), printed from exact decimal arithmetic on TDB seconds;
* axes ``MJ2000Eq``: GMAT reads DE405 in them, and lunarcap's ICRF states are DE405's axes
  (:mod:`lunarcap.physics.frames`), so the numbers go in unchanged;
* the central body's GM and radius (lunarcap's, not GMAT's 4902.8005821478 km^3/s^2), the
  Earth's and the Sun's GM, and DE405 as the ephemeris of the Earth and the Sun;
* the lunar J2 about a pole fixed at its J2000 direction, as lunarcap's M-MME2000 has it:
  GMAT's own ``Luna`` turns its field with the Moon's librations (DE405), whose pole is
  0.79 deg from it in 2017 and cannot be changed, so the script creates a body of its own
  (a ``Planet`` named :data:`FIXED_POLE_BODY`, whose orientation GMAT takes from the
  script: the ``Moon`` type would impose the IAU lunar model whatever the script says),
  placed by ``<stem>_moon.bsp``; about the IAU pole of date (:attr:`Gravity.frame`
  ``"iau-of-date"``) the body is a ``Moon`` orbiting the Earth, which GMAT orients by the
  IAU lunar model (pole and prime meridian); a field in the Moon's DE405 principal-axis
  frame (``"luna"``) is carried by GMAT's ``Luna`` itself, which turns with the DE
  file's libration angles (GMAT's ``DEFile`` rotation source: the only one this GMAT
  gives ``Luna``, no longer settable by a script, so the script says it in a comment and
  ``tests/exchange/test_gmat_frames.py`` checks the axes at the pole and the prime
  meridian);
* a field in ``Luna``: GMAT asks for its default lunar field file as soon as a force
  model names ``Luna`` among its primary bodies, before the script's ``PotentialFile``
  replaces it, and the PyPI wheel ships none (nor can a script point GMAT elsewhere), so
  the export writes beside such a script ``<stem>_gmat.py``, the one command that runs it
  (:func:`~lunarcap.exchange.gmat_run.runner_text`);
* the steering: GMAT's thruster points along a direction fixed in the axes for as long
  as a ``Propagate`` lasts, so a burn is a sequence of segments inside one
  ``BeginFiniteBurn``/``EndFiniteBurn``, each setting the direction
  (``Sat.Engine.ThrustDirection1..3``) to the mean of lunarcap's unit thrust direction
  over the segment, then propagating to the segment's end epoch. An absolute epoch: stopped on
  ``ElapsedSecs`` instead, each ``Propagate`` of the 150 N capture ended about 0.2 us
  early, and the 247 segments of burn 1 put its cut-off 58 us early (with 2 s segments,
  160 us and 0.25 m off); on absolute epochs every cut-off is within 1 us.

What each force term needs in the script (the central field, point masses) the term says
itself (:func:`capture_forces`). This module imports :mod:`lunarcap.physics` only; running
GMAT and reading its reports is :mod:`lunarcap.exchange.gmat_run` (re-exported here).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from decimal import Decimal
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.exchange.ccsds import StateVector, reference_comments
from lunarcap.exchange.gmat_run import (  # noqa: F401  (running GMAT, re-exported)
    GMAT_MJD_OFFSET_JD,
    REPORT_FIELDS,
    GmatError,
    Row,
    epoch_from_gmat_mjd,
    gmat_defaults,
    read_report,
    run_script,
    runner_text,
)
from lunarcap.physics import constants as C
from lunarcap.physics.forces import MoonField, ThirdBody, zonal_c20

#: The body the script creates for a lunar field about a pole fixed in the axes.
FIXED_POLE_BODY = "LunarcapMoon"
#: NAIF ID of the Moon (its states in ``<stem>_moon.bsp``) and of the Earth (their centre).
MOON_NAIF_ID = 301
EARTH_NAIF_ID = 399
#: Step of the Moon's states in ``<stem>_moon.bsp``, s, and the margin of its span, s.
MOON_KERNEL_STEP_S = 3600.0
MOON_KERNEL_MARGIN_S = 86400.0
#: How the central body's field is oriented (see :class:`Gravity`).
FRAMES = ("fixed-pole", "iau-of-date", "luna")
#: Event codes of the report rows.
IGNITION, CUTOFF, END = 0, 1, 2
#: The tank's fuel density, kg/m^3 (GMAT's default, written out), and the factor by which
#: its volume exceeds the whole mass's (GMAT refuses a load above the volume at start).
TANK_DENSITY_KGM3 = 1260.0
TANK_MARGIN = 1.01


# ---------------------------------------------------------------------- the data
@dataclass
class Burn:
    """One burn as GMAT flies it: segments of a fixed direction between epochs.

    Attributes
    ----------
    start : lunarcap.exchange.ccsds.StateVector
        lunarcap's state at ignition (ICRF, with its mass), where the per-burn flight starts.
    durations_s : ndarray (N,)
        Segment durations, s, from ignition to cut-off.
    u_icrf : ndarray (3, N)
        Unit thrust direction of each segment, Moon-centred ICRF.
    thrust_N, isp_s : float
    """

    start: StateVector
    durations_s: np.ndarray
    u_icrf: np.ndarray
    thrust_N: float
    isp_s: float

    @property
    def bounds_s(self) -> np.ndarray:
        """Segment epochs (N+1,), TDB s past J2000, from ignition to cut-off."""
        return self.start.epoch_s + np.concatenate([[0.0], np.cumsum(self.durations_s)])

    @property
    def cutoff_s(self) -> float:
        """Cut-off epoch, TDB s past J2000."""
        return float(self.bounds_s[-1])


@dataclass(frozen=True)
class Gravity:
    """The central body's gravity field: GM, radius and fully normalised coefficients.

    Attributes
    ----------
    mu_km3s2, radius_km : float
    c, s : ndarray (n+1, n+1)
        Fully normalised C_nm and S_nm (row n, column m; degree 0 and 1 ignored).
    frame : {"fixed-pole", "iau-of-date", "luna"}
        ``fixed-pole``: body-fixed axes about the pole ``pole_radec_deg`` (right ascension,
        declination in the script's MJ2000Eq axes), fixed in time, which is all a zonal
        field needs; ``iau-of-date``: the IAU lunar rotation model (pole and prime
        meridian of date, with the periodic terms; Archinal et al. 2011), which GMAT
        imposes on a Moon orbiting the Earth; ``luna``: GMAT's own lunar body-fixed frame
        (DE405 librations).
    source : str
        Where the coefficients come from (written in the files).
    """

    mu_km3s2: float
    radius_km: float
    c: np.ndarray
    s: np.ndarray
    frame: str = "fixed-pole"
    pole_radec_deg: tuple = (0.0, 90.0)
    source: str = ""

    @property
    def degree(self) -> int:
        """Highest degree of the field."""
        return self.c.shape[0] - 1

    @property
    def order(self) -> int:
        """Highest order with a non-zero coefficient."""
        nz = np.flatnonzero(np.any((self.c[2:] != 0) | (self.s[2:] != 0), axis=0))
        return int(nz[-1]) if nz.size else 0

    @classmethod
    def zonal_j2(cls, mu_km3s2: float, radius_km: float, j2: float, pole_radec_deg,
                 source: str = "") -> "Gravity":
        """Point mass plus J2 (unnormalised) about a fixed pole: C_20 = -J2 / sqrt(5)."""
        c, s = zonal_c20(j2)
        return cls(mu_km3s2, radius_km, c, s, "fixed-pole",
                   tuple(float(a) for a in pole_radec_deg), source)

    @classmethod
    def of(cls, f: MoonField) -> "Gravity":
        """The field a force term asks for (:class:`lunarcap.physics.forces.MoonField`)."""
        return cls(f.mu_km3s2, f.radius_km, f.c, f.s, _FRAME_OF[f.frame],
                   tuple(float(a) for a in f.pole_radec_deg), f.source)


#: GMAT's orientation of each body-fixed frame a force term names.
_FRAME_OF = {"fixed-pole": "fixed-pole", "iau2009": "iau-of-date", "de405": "luna"}


def capture_forces(model, pole: str) -> tuple:
    """(central body's :class:`Gravity`, point masses) that fly a model's terms in GMAT.

    Each term of ``model.forces`` (a :class:`lunarcap.physics.dynamics.Model`) says what it
    needs (:meth:`lunarcap.physics.forces.Term.export`): the Moon's field (exactly one
    term gives it) or point masses ``((GMAT body name, GM km^3/s^2), ...)``. ``pole``: the
    plan's lunar pole. A term with no GMAT counterpart is refused, by name.
    """
    fields, masses = [], []
    for term in model.forces.terms:
        parts = term.export(model.forces, model, pole)
        if parts is None:
            raise InputError(f"GMAT script: the force term {term.name!r} "
                             f"({term.words(model.forces)}) has no GMAT counterpart")
        for part in parts:
            if isinstance(part, MoonField):
                fields.append(Gravity.of(part))
            elif isinstance(part, ThirdBody):
                masses.append((part.name, part.mu_km3s2))
            else:
                raise InputError(f"GMAT script: the force term {term.name!r} asks for "
                                 f"{type(part).__name__}, which the script cannot carry")
    if len(fields) != 1:
        raise InputError(f"GMAT script: {len(fields)} terms give the Moon's field "
                         f"({model.forces.label}); the script carries one")
    return fields[0], tuple(masses)


@dataclass
class Capture:
    """A flown capture handed to GMAT.

    Attributes
    ----------
    name : str
        The plan's name (comments).
    arrival : lunarcap.exchange.ccsds.StateVector
        Where the end-to-end flight starts (lunarcap's state, ICRF, with its mass).
    burns : list of Burn
    coasts : list of StateVector
        lunarcap's state at each cut-off, where the coast after each burn starts (each coast
        is also flown alone, to the next ignition or the end).
    end_s : float
        End of the flight (one revolution of the final orbit after the last cut-off), TDB s.
    gravity : Gravity
    third_bodies : tuple of (GMAT body name, GM km^3/s^2)
        Point masses (DE405 positions), e.g. ``(("Earth", 398600.441), ("Sun", ...))``.
    g0_mps2 : float
        Standard gravity of the engine's mass flow, m/s^2.
    ephemeris : lunarcap.physics.ephemeris.Ephemeris
        The plan's ephemeris (the Moon's states of the fixed-pole body).
    comments : list of str
    """

    name: str
    arrival: StateVector
    burns: list
    coasts: list
    end_s: float
    gravity: Gravity
    third_bodies: tuple = ()
    g0_mps2: float = C.G0_MPS2
    ephemeris: object = None
    comments: list = field(default_factory=list)


# ---------------------------------------------------------------------- numbers
def tank_volume_m3(mass_kg: float) -> float:
    """The volume of a tank that holds ``mass_kg`` of fuel at :data:`TANK_DENSITY_KGM3`, m^3.

    GMAT stops at load ("Fuel volume exceeds tank capacity") when a tank's fuel mass
    over its density exceeds its volume, and its default tank (0.75 m^3 at 1,260 kg/m^3)
    holds 945 kg; the script carries the whole spacecraft as fuel, so each tank is sized
    from its mass, :data:`TANK_MARGIN` over. The volume plays no other part in the
    flight: the tank is pressure-regulated and the thrust and Isp coefficients of pressure
    and temperature are zero.
    """
    return float(mass_kg) / TANK_DENSITY_KGM3 * TANK_MARGIN


def gmat_mjd(t_s: float) -> str:
    """GMAT's TDB modified Julian date (JD - 2430000) of TDB seconds past J2000, as text.

    Exact decimal arithmetic on the binary value of ``t_s``, 15 decimals of a day
    (86 ps): GMAT's own parsing is then the only rounding.

    Examples
    --------
    >>> gmat_mjd(0.0)
    '21545.000000000000000'
    >>> gmat_mjd(43200.0)
    '21545.500000000000000'
    """
    days = Decimal(float(t_s)) / Decimal(86400) + Decimal(C.JD_J2000 - GMAT_MJD_OFFSET_JD)
    return f"{days:.15f}"


def _num(x: float) -> str:
    """A float as GMAT reads it back bit for bit (shortest round trip)."""
    x = float(x)
    if not math.isfinite(x):
        raise InputError(f"a GMAT script number must be finite, got {x}")
    return repr(x)


# ---------------------------------------------------------------------- files it reads
def write_cof(path, gravity: Gravity, comments=()) -> Path:
    """Write a gravity field in GMAT's COF format (as GMAT's HarmonicGravityCof reads it).

    ``POTFIELD`` with the degree and order (columns 9-14), then the body flag, GM (m^3/s^2),
    the reference radius (m) and 1 (normalised); one ``RECOEF`` line per degree n >= 2
    and order m with C_nm in columns 18-38 and S_nm in columns 39-59 (fully normalised);
    ``END``. Comment lines start with ``C``.
    """
    n_max, m_max = gravity.degree, gravity.order
    if n_max > 999:
        raise InputError(f"a COF file holds degrees up to 999, got {n_max}")
    lines = ["COMMENT"] + [f"C {c}" for c in comments]
    lines.append(f"POTFIELD{n_max:3d}{m_max:3d}  0 {gravity.mu_km3s2 * 1e9:.14e} "
                 f"{gravity.radius_km * 1e3:.14e} {1.0:.14e}")
    for n in range(2, n_max + 1):
        for m in range(0, min(n, m_max) + 1):
            lines.append(f"RECOEF  {n:3d}{m:3d}   {gravity.c[n, m]:21.14e}"
                         f"{gravity.s[n, m]:21.14e}")
    lines.append("END")
    path = Path(path)
    path.write_text("\n".join(lines) + "\n", encoding="ascii")
    return path


def write_moon_kernel(path, ephemeris, t0_s: float, t1_s: float,
                      step_s: float = MOON_KERNEL_STEP_S) -> Path:
    """The Moon's geocentric states (ICRF, as SPICE's J2000) from ``ephemeris``, an SPK.

    ``ephemeris``: a :class:`lunarcap.physics.ephemeris.Ephemeris` (its M-MME2000 states
    rotated back to ICRF with its own rotation).

    Type 13 (Hermite interpolation of positions and velocities, window of 8 states) every
    ``step_s`` over [t0_s, t1_s] widened to whole steps.
    """
    import spiceypy as sp

    n = max(int(math.ceil((t1_s - t0_s) / step_s)), 8)
    t = t0_s + step_s * np.arange(n + 1)
    r, v = ephemeris.moon_geocentric_state(t)
    r, v = ephemeris.rotation.T @ r, ephemeris.rotation.T @ v
    path = Path(path)
    if path.exists():
        path.unlink()
    handle = sp.spkopn(str(path), "lunarcap Moon", 4096)
    try:
        states = np.ascontiguousarray(np.vstack([r, v]).T)
        sp.spkw13(handle, MOON_NAIF_ID, EARTH_NAIF_ID, "J2000", float(t[0]), float(t[-1]),
                  "lunarcap Moon (geocentric)", 7, t.size, states, t)
        sp.dafac(handle, [*reference_comments(),
                          f"The Moon (301) from the Earth (399), J2000 (ICRF axes), from "
                          f"{ephemeris.name}"[:80]])
    finally:
        sp.spkcls(handle)
    return path


# ---------------------------------------------------------------------- the script
def _body_lines(cap: Capture, stem: str) -> tuple:
    """(central body name, lines): the Sun's, Earth's and central body's settings."""
    g = cap.gravity
    out = ["% ---------- Ephemerides and constants (lunarcap's, not GMAT's defaults)",
           "SolarSystem.EphemerisSource = 'DE405';"]
    out += [f"{name}.Mu = {_num(mu)};" for name, mu in cap.third_bodies]
    if g.frame not in FRAMES:
        raise InputError(f"gravity frame must be one of {', '.join(FRAMES)}, got {g.frame!r}")
    if g.frame == "luna":
        out += ["% The field turns with GMAT's Luna: its principal axes from the libration angles",
                "% of GMAT's DE file (GMAT's DEFile rotation source, the only one it gives Luna;",
                "% a script no longer sets Luna.RotationDataSource). GMAT asks for its default",
                "% lunar field file as soon as Luna is a primary body: run this script with",
                f"% {stem}_gmat.py beside it, which points GMAT to ./{stem}_gravity.cof.",
                f"Luna.Mu = {_num(g.mu_km3s2)};", f"Luna.EquatorialRadius = {_num(g.radius_km)};"]
        return "Luna", out
    body = FIXED_POLE_BODY
    out += ["", "% ---------- The Moon of lunarcap's dynamics: placed at the Moon by the states of",
            "% lunarcap's ephemeris (DE405) in the kernel beside this script;"]
    if g.frame == "iau-of-date":
        out += ["% a Moon orbiting the Earth, which GMAT orients by the IAU lunar model of date",
                "% (pole and prime meridian with their periodic terms).",
                f"Create Moon {body};", f"{body}.CentralBody = Earth;"]
    else:
        out += ["% its pole fixed in the axes (lunarcap's M-MME2000 at J2000): a Planet, whose",
                "% orientation is the script's (GMAT imposes the IAU lunar model on a Moon",
                "% orbiting the Earth and on Luna).",
                f"Create Planet {body};", f"{body}.CentralBody = Sun;"]
    out += [f"{body}.PosVelSource = 'SPICE';",
            f"{body}.NAIFId = {MOON_NAIF_ID};",
            f"{body}.OrbitSpiceKernelName = {{'./{stem}_moon.bsp'}};",
            f"{body}.Mu = {_num(g.mu_km3s2)};",
            f"{body}.EquatorialRadius = {_num(g.radius_km)};",
            f"{body}.Flattening = 0;"]
    if g.frame == "fixed-pole":
        ra, dec = g.pole_radec_deg
        out += [f"{body}.OrientationDateFormat = TAIModJulian;",
                f"{body}.OrientationEpoch = 21545;",
                f"{body}.SpinAxisRAConstant = {_num(ra)};",
                f"{body}.SpinAxisRARate = 0;",
                f"{body}.SpinAxisDECConstant = {_num(dec)};",
                f"{body}.SpinAxisDECRate = 0;",
                f"{body}.RotationConstant = 0;",
                f"{body}.RotationRate = 13.17635815;   % deg/day (IAU 2009); a zonal field "
                f"ignores it"]
    return body, out


def _dynamics_lines(cap: Capture, body: str, stem: str) -> list:
    g = cap.gravity
    third = ", ".join(name for name, _ in cap.third_bodies)
    return ["", "% ---------- Axes and dynamics",
            "Create CoordinateSystem MoonEq;",
            f"MoonEq.Origin = {body};",
            "MoonEq.Axes = MJ2000Eq;",
            "",
            "Create ForceModel Dynamics;",
            f"Dynamics.CentralBody = {body};",
            f"Dynamics.PrimaryBodies = {{{body}}};",
            f"Dynamics.GravityField.{body}.Degree = {g.degree};",
            f"Dynamics.GravityField.{body}.Order = {g.order};",
            f"Dynamics.GravityField.{body}.PotentialFile = './{stem}_gravity.cof';",
            f"Dynamics.PointMasses = {{{third}}};",
            "Dynamics.Drag = None;",
            "Dynamics.SRP = Off;",
            "Dynamics.RelativisticCorrection = Off;",
            "Dynamics.ErrorControl = RSSStep;",
            "",
            "Create Propagator Prop;",
            "Prop.FM = Dynamics;",
            "Prop.Type = RungeKutta89;",
            "Prop.InitialStepSize = 10;",
            "Prop.Accuracy = 1e-13;",
            "Prop.MinStep = 0;",
            "Prop.MaxStep = 600;",
            "Prop.MaxStepAttempts = 50;",
            "Prop.StopIfAccuracyIsViolated = true;"]


def _spacecraft_lines(sc: str, state: StateVector, thrust_N: float | None = None,
                      isp_s: float = 0.0, g0: float = C.G0_MPS2) -> list:
    """A spacecraft at ``state``; with ``thrust_N`` its tank, engine and ``<sc>Fire``.

    Without an engine its whole mass is dry.
    """
    if state.frame != "ICRF" or state.mass_kg is None:
        raise InputError(f"{sc}: a GMAT spacecraft needs an ICRF state with its mass, got "
                         f"{state.frame} and mass {state.mass_kg}")
    out = ["", f"Create Spacecraft {sc};",
           f"{sc}.DateFormat = TDBModJulian;",
           f"{sc}.Epoch = '{gmat_mjd(state.epoch_s)}';",
           f"{sc}.CoordinateSystem = MoonEq;",
           f"{sc}.DisplayStateType = Cartesian;"]
    out += [f"{sc}.{k} = {_num(x)};"
            for k, x in zip(("X", "Y", "Z", "VX", "VY", "VZ"), (*state.r_km, *state.v_kmps))]
    if thrust_N is None:
        return out + [f"{sc}.DryMass = {_num(state.mass_kg)};"]
    out += [f"{sc}.DryMass = 0;",
            f"{sc}.Tanks = {{{sc}Tank}};",
            f"{sc}.Thrusters = {{{sc}Engine}};",
            f"Create ChemicalTank {sc}Tank;",
            f"{sc}Tank.FuelDensity = {_num(TANK_DENSITY_KGM3)};   % kg/m^3",
            f"{sc}Tank.Volume = {_num(tank_volume_m3(state.mass_kg))};   % m^3: the whole "
            f"mass, {100 * (TANK_MARGIN - 1):g} % spare",
            f"{sc}Tank.FuelMass = {_num(state.mass_kg)};   % kg: the whole mass",
            f"{sc}Tank.AllowNegativeFuelMass = false;",
            f"{sc}Tank.PressureModel = PressureRegulated;",
            f"Create ChemicalThruster {sc}Engine;",
            f"{sc}Engine.CoordinateSystem = MoonEq;",
            f"{sc}Engine.ThrustDirection1 = 1;",
            f"{sc}Engine.ThrustDirection2 = 0;",
            f"{sc}Engine.ThrustDirection3 = 0;",
            f"{sc}Engine.DutyCycle = 1;",
            f"{sc}Engine.ThrustScaleFactor = 1;",
            f"{sc}Engine.DecrementMass = true;",
            f"{sc}Engine.Tank = {{{sc}Tank}};",
            f"{sc}Engine.MixRatio = [1];",
            f"{sc}Engine.GravitationalAccel = {_num(g0)};   % m/s^2 (GMAT's default: 9.81)",
            f"{sc}Engine.C1 = {_num(thrust_N)};   % N"]
    out += [f"{sc}Engine.C{i} = 0;" for i in range(2, 17)]
    out += [f"{sc}Engine.K1 = {_num(isp_s)};   % s"]
    out += [f"{sc}Engine.K{i} = 0;" for i in range(2, 17)]
    out += [f"Create FiniteBurn {sc}Fire;", f"{sc}Fire.Thrusters = {{{sc}Engine}};"]
    return out


def _report_lines(name: str, filename: str) -> list:
    return [f"Create ReportFile {name};",
            f"{name}.Filename = './{filename}';",
            f"{name}.Precision = 16;",
            f"{name}.WriteHeaders = true;",
            f"{name}.LeftJustify = On;",
            f"{name}.ZeroFill = Off;",
            f"{name}.FixedWidth = true;",
            f"{name}.ColumnWidth = 26;"]


def _report(name: str, sc: str) -> str:
    cols = [f"{sc}.{f}" if f in ("TDBModJulian", "TotalMass") else f"{sc}.MoonEq.{f}"
            for f in REPORT_FIELDS]
    return f"Report {name} BurnNumber Event {' '.join(cols)};"


def _propagate_to(sc: str, t_s: float) -> str:
    return f"Propagate Prop({sc}) {{{sc}.TDBModJulian = {gmat_mjd(t_s)}}};"


def _burn_lines(sc: str, burn: Burn) -> list:
    """The segments of a burn flown by spacecraft ``sc`` (its engine ``<sc>Engine``)."""
    out = [f"BeginFiniteBurn {sc}Fire({sc});"]
    eng = f"{sc}.{sc}Engine"
    bounds = burn.bounds_s
    for j in range(burn.u_icrf.shape[1]):
        u = burn.u_icrf[:, j]
        out += [f"{eng}.ThrustDirection1 = {_num(u[0])};",
                f"{eng}.ThrustDirection2 = {_num(u[1])};",
                f"{eng}.ThrustDirection3 = {_num(u[2])};",
                _propagate_to(sc, bounds[j + 1])]
    out.append(f"EndFiniteBurn {sc}Fire({sc});")
    return out


def _header_lines(cap: Capture, stem: str) -> list:
    return [*[f"% {c}" for c in reference_comments()],
            f"% lunarcap: the capture {cap.name} flown in GMAT (written by lunarcap).",
            "% Run it unmodified where it lies, e.g. with the PyPI wheel gmatpy:",
            (f"%   cd <this folder> && python {stem}_gmat.py" if cap.gravity.frame == "luna"
             else f"%   cd <this folder> && python -c \"import gmatpy; "
                  f"gmatpy.run_script('{stem}.script', outputs={{}})\""),
            f"% It writes ./{stem}_gmat_burns.txt (each burn from lunarcap's state at its",
            f"% ignition), ./{stem}_gmat_coasts.txt (each coast from lunarcap's state at the",
            f"% cut-off before it), ./{stem}_gmat_capture.txt (the whole capture from the",
            f"% arrival, open loop) and ./{stem}_gmat.oem (the whole capture, CCSDS OEM, UTC).",
            "% Report columns: burn number, event (0 ignition or start, 1 cut-off, 2 end), TDB",
            "% modified Julian date (GMAT's: JD - 2430000), Moon-centred MJ2000Eq (DE405's",
            "% axes, lunarcap's ICRF) position km, velocity km/s, total mass kg.",
            *[f"% {c}" for c in cap.comments]]


def _output_lines(stem: str) -> list:
    out = ["", "% ---------- Outputs, next to this script",
           "Create Variable BurnNumber Event;"]
    out += _report_lines("BurnStates", f"{stem}_gmat_burns.txt")
    out += _report_lines("CoastStates", f"{stem}_gmat_coasts.txt")
    out += _report_lines("CaptureStates", f"{stem}_gmat_capture.txt")
    eph = "CaptureEphemeris"
    out += [f"Create EphemerisFile {eph};", f"{eph}.Spacecraft = Capture;",
            f"{eph}.Filename = './{stem}_gmat.oem';", f"{eph}.FileFormat = CCSDS-OEM;",
            f"{eph}.EpochFormat = UTCGregorian;   % GMAT's OEM offers no TDB",
            f"{eph}.InitialEpoch = InitialSpacecraftEpoch;",
            f"{eph}.FinalEpoch = FinalSpacecraftEpoch;", f"{eph}.StepSize = 60;",
            f"{eph}.Interpolator = Lagrange;", f"{eph}.InterpolationOrder = 7;",
            f"{eph}.StateType = Cartesian;", f"{eph}.CoordinateSystem = MoonEq;",
            f"{eph}.IncludeEventBoundaries = true;", f"{eph}.WriteEphemeris = true;"]
    return out


def _mission_lines(cap: Capture) -> list:
    out = ["", "BeginMissionSequence;"]
    for k, b in enumerate(cap.burns, 1):
        sc = f"Burn{k}"
        out += ["", f"% ---------- Burn {k} from lunarcap's state at its ignition",
                f"BurnNumber = {k};", f"Event = {IGNITION};", _report("BurnStates", sc)]
        out += _burn_lines(sc, b)
        out += [f"Event = {CUTOFF};", _report("BurnStates", sc)]
    n = len(cap.burns)
    for k, start in enumerate(cap.coasts, 1):
        sc = f"Coast{k}"
        end = cap.burns[k].start.epoch_s if k < n else cap.end_s
        out += ["", f"% ---------- Coast {k} from lunarcap's state at the cut-off of burn {k}",
                f"BurnNumber = {k};", f"Event = {CUTOFF};", _report("CoastStates", sc),
                _propagate_to(sc, end),
                f"BurnNumber = {min(k + 1, n)};", f"Event = {IGNITION if k < n else END};",
                _report("CoastStates", sc)]
    sc = "Capture"
    out += ["", "% ---------- The capture, open loop from the arrival",
            "BurnNumber = 0;", f"Event = {IGNITION};", _report("CaptureStates", sc)]
    for k, b in enumerate(cap.burns, 1):
        out += ["", f"% coast to burn {k}, burn {k}", _propagate_to(sc, b.start.epoch_s),
                f"BurnNumber = {k};", f"Event = {IGNITION};", _report("CaptureStates", sc)]
        out += _burn_lines(sc, b)
        out += [f"Event = {CUTOFF};", _report("CaptureStates", sc)]
    out += ["", "% the final orbit", _propagate_to(sc, cap.end_s),
            f"Event = {END};", _report("CaptureStates", sc)]
    return out


def script_text(cap: Capture, stem: str) -> str:
    """The text of the GMAT script of ``cap`` (files named after ``stem``)."""
    if not cap.burns:
        raise InputError("a GMAT script needs at least one burn")
    if len(cap.coasts) != len(cap.burns):
        raise InputError(f"a GMAT script needs a coast after each burn, got {len(cap.coasts)} "
                         f"coasts for {len(cap.burns)} burns")
    body, lines = _body_lines(cap, stem)
    lines = _header_lines(cap, stem) + [""] + lines + _dynamics_lines(cap, body, stem)
    lines += ["", "% ---------- Each burn from lunarcap's state at ignition"]
    for k, b in enumerate(cap.burns, 1):
        lines += _spacecraft_lines(f"Burn{k}", b.start, b.thrust_N, b.isp_s, cap.g0_mps2)
    lines += ["", "% ---------- Each coast from lunarcap's state at the cut-off before it"]
    for k, c in enumerate(cap.coasts, 1):
        lines += _spacecraft_lines(f"Coast{k}", c)
    lines += ["", "% ---------- The whole capture from the arrival"]
    b0 = cap.burns[0]
    lines += _spacecraft_lines("Capture", cap.arrival, b0.thrust_N, b0.isp_s, cap.g0_mps2)
    lines += _output_lines(stem) + _mission_lines(cap)
    return "\n".join(lines) + "\n"


def write_capture(out_dir, stem: str, cap: Capture) -> dict:
    """Write ``<stem>.script`` and the files it reads into ``out_dir``; returns their paths.

    Keys ``script``, ``gravity`` (``<stem>_gravity.cof``) and, unless the field turns with
    GMAT's ``Luna``, ``moon`` (``<stem>_moon.bsp``, covering the flight with
    :data:`MOON_KERNEL_MARGIN_S` each side); when it does, ``runner`` (``<stem>_gmat.py``,
    the command that runs the script: :func:`~lunarcap.exchange.gmat_run.runner_text`).
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files = {"script": out / f"{stem}.script", "gravity": out / f"{stem}_gravity.cof"}
    files["script"].write_text(script_text(cap, stem), encoding="ascii")
    g = cap.gravity
    write_cof(files["gravity"], g, [*reference_comments(), f"lunarcap plan {cap.name}: {g.source}",
                                    f"degree {g.degree}, order {g.order}, fully normalised"])
    if g.frame == "luna":
        files["runner"] = out / f"{stem}_gmat.py"
        files["runner"].write_text(runner_text(stem), encoding="ascii")
    else:
        if cap.ephemeris is None:
            raise InputError("a GMAT script with lunarcap's Moon needs the plan's ephemeris")
        files["moon"] = write_moon_kernel(out / f"{stem}_moon.bsp", cap.ephemeris,
                                          cap.arrival.epoch_s - MOON_KERNEL_MARGIN_S,
                                          cap.end_s + MOON_KERNEL_MARGIN_S)
    return files
