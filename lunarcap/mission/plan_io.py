"""A capture plan to and from the mapping of its YAML file.

:func:`plan_fields` reads the file's structure (which keys, which kind of arrival and
target, paths relative to the file) and hands the values on as written: the plan checks
them once, when it is built (:func:`lunarcap.mission.plan_checks.validate`). An unknown or
missing key is refused here, naming it; burns are numbered from 1 as in every message.
"""

from __future__ import annotations

from pathlib import Path

from lunarcap.errors import InputError
from lunarcap.mission.arrival import StateArrival
from lunarcap.mission.plan_checks import (
    PlanError,
    choice,
    default_pole,
    err,
    frame_epoch,
    keys,
    num,
)
from lunarcap.mission.targets import CIRCULAR, PERILUNE
from lunarcap.physics.bplane import DEFAULT_REFERENCE, REFERENCE_PLANES
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.forces import force_model
from lunarcap.physics.frames import pole_of_date

#: The dynamics of a plan that names none: the Moon's J2 about its axis of date, the
#: Earth and the Sun (the paper's words keep the paper's J2000 pole; see the plan docs).
DEFAULT_DYNAMICS = {"gravity": "j2", "pole": "of-date", "third_bodies": ["earth", "sun"]}

TOP_KEYS = {"name", "description", "arrival", "engine", "dynamics", "burns", "ephemeris",
            "lunar_pole", "start", "formulation"}
START_KEYS = {"epoch", "mee", "mass_kg", "first_coast_min"}
ARRIVAL_KEYS = {"epoch", "perilune_altitude_km", "inclination_deg", "v_inf_kmps",
                "impulsive_loi1_mps", "hemisphere", "approach_dir", "mass_kg",
                "bplane_reference"}
STATE_ARRIVAL_KEYS = {"epoch", "frame", "position_km", "velocity_kmps", "mass_kg",
                      "bplane_reference"}
BPLANE_ARRIVAL_KEYS = {"epoch", "frame", "b_r_km", "b_t_km", "v_inf_kmps", "approach_dir",
                       "mass_kg", "bplane_reference"}
#: The keys an arrival of any kind must give (``bplane_reference`` may be left out).
BPLANE_OPTIONAL = {"bplane_reference"}
ENGINE_KEYS = {"thrust_N", "isp_s"}
BURN_KEYS = {"target", "target_period_h", "target_apolune_altitude_km", "start_min",
             "coast_min", "steering", "start_bounds_min"}


def _times(value, factor: float):
    """A number of the file's unit in s (h or min times ``factor``); anything else as is."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return value * factor
    return value


def plan_fields(d, base_dir=None, default_name: str = "") -> dict:
    """The :class:`~lunarcap.mission.plan.CapturePlan` keyword arguments of a YAML mapping.

    ``base_dir`` resolves a relative ``ephemeris`` or ``arrival.opm`` path (the plan file's
    directory).
    """
    from lunarcap.mission.plan import Engine

    keys("", d, TOP_KEYS, {"arrival", "engine", "burns"})
    name = d.get("name", default_name)
    if not isinstance(name, str) or not name.strip():
        raise err("name", f"must be a non-empty text, got {name!r}")
    a = d["arrival"]
    arrival = _bplane_arrival(a) if isinstance(a, dict) and "b_r_km" in a else \
        _state_arrival(a, base_dir)
    if arrival is None:
        arrival = _perilune_arrival(a)
    e = d["engine"]
    keys("engine", e, ENGINE_KEYS, ENGINE_KEYS)
    burns_in = d["burns"]
    if not isinstance(burns_in, list) or not burns_in:
        raise err("burns", "must be a list of at least one burn")
    eph = d.get("ephemeris")
    if eph is not None:
        if not isinstance(eph, str):
            raise err("ephemeris", f"must be the path of an SPK file, got {eph!r}")
        p = Path(eph).expanduser()
        if not p.is_absolute() and base_dir is not None:
            p = Path(base_dir) / p
        eph = str(p.resolve())
    desc = d.get("description", "")
    if not isinstance(desc, str):
        raise err("description", f"must be a text, got {desc!r}")
    dyn = _dynamics(d.get("dynamics", DEFAULT_DYNAMICS), base_dir)
    pole = d.get("lunar_pole", default_pole(dyn))   # "of-date" resolved by the checks
    return dict(name=name.strip(), arrival=arrival, engine=Engine(e["thrust_N"], e["isp_s"]),
                burns=tuple(_burn(i, b) for i, b in enumerate(burns_in)),
                dynamics=dyn, ephemeris=eph, lunar_pole=pole,
                impulsive_loi1_mps=a.get("impulsive_loi1_mps"), description=desc.strip(),
                start=None if d.get("start") is None else _start(d["start"]),
                formulation=d.get("formulation", "orbit"))


def _dynamics(value, base_dir):
    """A plan's ``dynamics``: a word as written, a mapping as its ForceModel (paths resolved)."""
    from lunarcap.physics.forces import from_mapping

    if isinstance(value, dict):
        try:
            return from_mapping(value, base_dir)
        except InputError as exc:
            raise PlanError(str(exc)) from None
    return value   # a word (checked by the plan)


def _burn(i: int, b):
    """Burn ``i`` (0-based) as written: its target's kind and keys (values checked later)."""
    from lunarcap.mission.plan import Burn

    where = f"burns[{i + 1}]"
    keys(where, b, BURN_KEYS, {"start_min"})
    given = [k for k in ("target_period_h", "target_apolune_altitude_km") if k in b]
    common = dict(start_min=b["start_min"], steering=b.get("steering", "optimal"),
                  start_bounds_min=b.get("start_bounds_min"))
    if isinstance(b.get("target"), dict):
        if given or "coast_min" in b:
            raise err(f"{where}.target", "an ellipse given by both altitudes takes no "
                                         "period, apolune or coast_min of its own")
        t = b["target"]
        both = {"perilune_altitude_km", "apolune_altitude_km"}
        keys(f"{where}.target", t, both, both)
        return Burn(PERILUNE, perilune_altitude_km=t["perilune_altitude_km"],
                    apolune_altitude_km=t["apolune_altitude_km"], **common)
    kind = b.get("target", PERILUNE if given else None)
    if kind not in (PERILUNE, CIRCULAR):
        raise err(f"{where}.target", f"must be 'circular', an ellipse "
                                     f"{{perilune_altitude_km, apolune_altitude_km}}, or "
                                     f"'perilune' (or give target_period_h / "
                                     f"target_apolune_altitude_km), got {kind!r}")
    if kind == CIRCULAR:
        if given:
            raise err(f"{where}.{given[0]}", "a circular target takes no period or apolune")
        return Burn(CIRCULAR, coast_s=_times(b.get("coast_min"), 60.0), **common)
    if len(given) != 1:
        raise err(f"{where}.target_period_h", "give exactly one of target_period_h and "
                                              "target_apolune_altitude_km")
    if "coast_min" in b:
        raise err(f"{where}.coast_min", "only a circular target takes coast_min (an "
                                        "ellipse's coast lasts its period)")
    if given[0] == "target_period_h":
        return Burn(PERILUNE, period_s=_times(b["target_period_h"], 3600.0), **common)
    return Burn(PERILUNE, apolune_altitude_km=b["target_apolune_altitude_km"], **common)


def _perilune_arrival(a):
    """The ``arrival`` of a plan given by its perilune (v_inf and the reconstructed geometry)."""
    from lunarcap.mission.arrival import ArrivalSpec

    keys("arrival", a, ARRIVAL_KEYS, {"epoch", "perilune_altitude_km", "inclination_deg",
                                      "mass_kg"})
    if ("v_inf_kmps" in a) == ("impulsive_loi1_mps" in a):
        raise err("arrival.v_inf_kmps", "give exactly one of v_inf_kmps and "
                                        "impulsive_loi1_mps")
    approach = a.get("approach_dir")
    if approach is not None and (not isinstance(approach, (list, tuple)) or len(approach) != 3):
        raise err("arrival.approach_dir", f"must be a list of three numbers (M-MME2000), got "
                                          f"{approach!r}")
    return ArrivalSpec(epoch=a["epoch"], perilune_altitude_km=a["perilune_altitude_km"],
                       inclination_deg=a["inclination_deg"], mass_kg=a["mass_kg"],
                       v_inf_kmps=a.get("v_inf_kmps"), hemisphere=a.get("hemisphere", "north"),
                       approach_dir=None if approach is None else tuple(approach),
                       bplane_reference=bplane_reference(a))


def bplane_reference(a) -> str:
    """An arrival's ``bplane_reference`` (default EME2000), checked (PlanError names it).

    The plane the arrival's B-plane T axis lies in (:mod:`lunarcap.physics.bplane`): its
    B-plane target's, and a B-plane covariance's in the dispersions study.
    """
    return choice("arrival.bplane_reference", a.get("bplane_reference", DEFAULT_REFERENCE),
                  REFERENCE_PLANES)


def _epoch_and_frame(a, epoch_form: str) -> None:
    """Check an arrival's ``epoch`` (a calendar epoch that exists) and ``frame``.

    The frame is one of :data:`lunarcap.mission.arrival.STATE_FRAMES`; ``epoch_form`` says
    what the epoch must be, in the message.
    """
    from lunarcap.mission.arrival import STATE_FRAMES

    if not isinstance(a["epoch"], str):
        raise err("arrival.epoch", f"must be {epoch_form}, got {a['epoch']!r}")
    try:
        seconds_from_calendar(a["epoch"])
    except InputError as exc:
        raise err("arrival.epoch", str(exc)) from None
    if a["frame"] not in STATE_FRAMES:
        raise err("arrival.frame", f"must be one of {', '.join(STATE_FRAMES)}, got "
                                   f"{a['frame']!r}")


def _bplane_arrival(a):
    """The ``arrival`` of a plan given as its B-plane target (the perilune derived later)."""
    from lunarcap.mission.arrival import ArrivalSpec, BPlaneArrival

    keys("arrival", a, BPLANE_ARRIVAL_KEYS, BPLANE_ARRIVAL_KEYS - BPLANE_OPTIONAL)
    _epoch_and_frame(a, "the epoch of closest approach as a text like "
                        "'2017-02-20 03:41:26 TDB'")
    s = a["approach_dir"]
    if not isinstance(s, (list, tuple)) or len(s) != 3:
        raise err("arrival.approach_dir", f"must be a list of three numbers (the incoming "
                                          f"asymptote in {a['frame']}), got {s!r}")
    s = tuple(num(f"arrival.approach_dir[{j + 1}]", x, "", positive=False)
              for j, x in enumerate(s))
    if not any(s):
        raise err("arrival.approach_dir", "must not be zero")
    b = BPlaneArrival(a["epoch"], a["frame"],
                      num("arrival.b_r_km", a["b_r_km"], "km", positive=False),
                      num("arrival.b_t_km", a["b_t_km"], "km", positive=False),
                      num("arrival.v_inf_kmps", a["v_inf_kmps"], "km/s"), s,
                      bplane_reference(a))
    return ArrivalSpec(epoch=b.epoch, perilune_altitude_km=100.0, inclination_deg=90.0,
                       mass_kg=a["mass_kg"], v_inf_kmps=b.v_inf_kmps, bplane=b,
                       bplane_reference=b.reference)


def _state_arrival(a, base_dir):
    """The ``arrival`` of a plan given as a state or an OPM file (None: a perilune arrival).

    The perilune numbers are placeholders until the plan derives them in its dynamics
    (:meth:`CapturePlan._derive_state_arrival`).
    """
    from lunarcap.mission.arrival import ArrivalSpec

    if not isinstance(a, dict) or not ({"opm", "position_km", "velocity_kmps"} & set(a)):
        return None
    mass = a.get("mass_kg")
    if "opm" in a:
        state, mass = _opm_state(a, base_dir)
    else:
        state = _given_state(a)
    # placeholders (a valid perilune), replaced by the derivation in the plan's dynamics
    return ArrivalSpec(epoch=state.epoch, perilune_altitude_km=100.0, inclination_deg=90.0,
                       mass_kg=mass, v_inf_kmps=1.0, state=state,
                       bplane_reference=bplane_reference(a))


def _opm_state(a, base_dir) -> tuple:
    """(StateArrival, mass) of ``arrival: {opm: FILE, mass_kg: ...}``."""
    from lunarcap.exchange.ccsds import read_opm

    keys("arrival", a, {"opm", "mass_kg", "bplane_reference"}, {"opm"})
    path = a["opm"]
    if not isinstance(path, str):
        raise err("arrival.opm", f"must be the path of a CCSDS OPM file, got {path!r}")
    p = Path(path).expanduser()
    if not p.is_absolute() and base_dir is not None:
        p = Path(base_dir) / p
    try:
        sv = read_opm(p)
    except InputError as exc:
        raise err("arrival.opm", str(exc)) from None
    mass = a.get("mass_kg")
    if mass is None:
        if sv.mass_kg is None:
            raise err("arrival.mass_kg", f"missing: the OPM {p.name} gives no MASS")
        mass = sv.mass_kg
    return StateArrival(sv.epoch_text, "ICRF", sv.r_km, sv.v_kmps, opm=str(path)), mass


def _given_state(a) -> StateArrival:
    """The StateArrival of ``arrival: {epoch, frame, position_km, velocity_kmps, mass_kg}``."""
    unknown = sorted(set(a) - STATE_ARRIVAL_KEYS)
    if unknown:
        raise err(f"arrival.{unknown[0]}",
                  f"a state arrival takes {', '.join(sorted(STATE_ARRIVAL_KEYS))}; "
                  f"{unknown[0]} belongs to an arrival given by its perilune")
    keys("arrival", a, STATE_ARRIVAL_KEYS, STATE_ARRIVAL_KEYS - BPLANE_OPTIONAL)
    _epoch_and_frame(a, "a text like '2017-02-20 03:11:26 UTC'")
    vecs = []
    for key, unit in (("position_km", "km"), ("velocity_kmps", "km/s")):
        val = a[key]
        if not isinstance(val, (list, tuple)) or len(val) != 3:
            raise err(f"arrival.{key}", f"must be a list of three numbers ({unit}), got "
                                        f"{val!r}")
        vecs.append(tuple(num(f"arrival.{key}[{j + 1}]", x, unit, positive=False)
                          for j, x in enumerate(val)))
    return StateArrival(a["epoch"], a["frame"], vecs[0], vecs[1])


def _start(d):
    """The ``start`` section: a known state (values checked by the plan)."""
    from lunarcap.mission.plan import Start

    keys("start", d, START_KEYS, START_KEYS)
    if not isinstance(d["epoch"], str):
        raise err("start.epoch", f"must be a text like '2017-02-20 03:41:26 TDB', got "
                                 f"{d['epoch']!r}")
    try:
        epoch = seconds_from_calendar(d["epoch"])
    except InputError as exc:
        raise err("start.epoch", str(exc)) from None
    mee = d["mee"]
    if not isinstance(mee, (list, tuple)) or len(mee) != 6:
        raise err("start.mee", f"must be six numbers (p km, f, g, h, k, L rad), got {mee!r}")
    return Start(epoch, tuple(mee) + (d["mass_kg"],), _times(d["first_coast_min"], 60.0))


def plan_dict(plan) -> dict:
    """The plan as a mapping with the YAML file's keys (round-trips :func:`plan_fields`)."""
    out = {"name": plan.name}
    if plan.description:
        out["description"] = plan.description
    out.update(arrival=_arrival_dict(plan),
               engine={"thrust_N": plan.engine.thrust_N, "isp_s": plan.engine.isp_s},
               dynamics=force_model(plan.dynamics).to_plan(),
               burns=[_burn_dict(b) for b in plan.burns])
    if plan.ephemeris is not None:
        out["ephemeris"] = plan.ephemeris
    default = default_pole(plan.dynamics)
    if default == "of-date":
        default = pole_of_date(frame_epoch(plan.arrival))
    if plan.lunar_pole != default:
        out["lunar_pole"] = plan.lunar_pole
    if plan.formulation != "orbit":
        out["formulation"] = plan.formulation
    if plan.start is not None:
        st = plan.start
        out["start"] = {"epoch": calendar_from_seconds(st.epoch_s, 6),
                        "mee": list(st.state[:6]), "mass_kg": st.mass_kg,
                        "first_coast_min": st.first_coast_s / 60.0}
    return out


def _arrival_dict(plan) -> dict:
    a = plan.arrival
    if a.bplane is not None:   # as given (the perilune is derived again on loading)
        b = a.bplane
        return {"epoch": b.epoch, "frame": b.frame, "bplane_reference": b.reference,
                "b_r_km": b.b_r_km, "b_t_km": b.b_t_km, "v_inf_kmps": b.v_inf_kmps,
                "approach_dir": list(b.approach_dir), "mass_kg": a.mass_kg}
    # any other arrival names its B-plane's reference only when not the default
    ref = ({} if a.bplane_reference == DEFAULT_REFERENCE else
           {"bplane_reference": a.bplane_reference})
    if a.state is not None:   # as given (the perilune is derived again on loading)
        st = a.state
        return ({"opm": st.opm} if st.opm else
                {"epoch": st.epoch, "frame": st.frame, "position_km": list(st.position_km),
                 "velocity_kmps": list(st.velocity_kmps)}) | {"mass_kg": a.mass_kg} | ref
    out = {"epoch": a.epoch, "perilune_altitude_km": a.perilune_altitude_km,
           "inclination_deg": a.inclination_deg}
    if plan.impulsive_loi1_mps is not None:
        out["impulsive_loi1_mps"] = plan.impulsive_loi1_mps
    else:
        out["v_inf_kmps"] = a.v_inf_kmps
    out["hemisphere"] = a.hemisphere
    if a.approach_dir is not None:
        out["approach_dir"] = list(a.approach_dir)
    out["mass_kg"] = a.mass_kg
    return out | ref


#: The keys of a plan file's burn that say its target (the rest: ignition and steering).
TARGET_KEYS = ("target", "target_period_h", "target_apolune_altitude_km", "coast_min")


def burn_with_target(i: int, b, target: dict):
    """Burn ``i`` (0-based) ``b`` with the target keys of ``target`` instead of its own.

    ``target``: a plan file burn's target keys (:data:`TARGET_KEYS`); read by the file's
    reader (:func:`_burn`), so errors name ``burns[i].<key>``.
    """
    if not isinstance(target, dict) or not target or set(target) - set(TARGET_KEYS):
        raise err(f"burns[{i + 1}]", f"a target is a mapping of {', '.join(TARGET_KEYS)}, "
                                     f"got {target!r}")
    row = {k: v for k, v in _burn_dict(b).items() if k not in TARGET_KEYS}
    return _burn(i, row | target)


def _burn_dict(b) -> dict:
    row = {}
    if b.target == CIRCULAR:
        row["target"] = CIRCULAR
        if b.coast_s is not None:
            row["coast_min"] = b.coast_s / 60.0
    elif b.perilune_altitude_km is not None:
        row["target"] = {"perilune_altitude_km": b.perilune_altitude_km,
                         "apolune_altitude_km": b.apolune_altitude_km}
    elif b.apolune_altitude_km is not None:
        row["target_apolune_altitude_km"] = b.apolune_altitude_km
    else:
        row["target_period_h"] = b.period_s / 3600.0
    row["start_min"] = b.start_min
    if b.steering != "optimal":
        row["steering"] = b.steering
    if b.start_bounds_min is not None:
        row["start_bounds_min"] = list(b.start_bounds_min)
    return row

