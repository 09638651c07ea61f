"""The "real Moon" page (notebooks/real_moon.ipynb): the capture in the lunar gravity field.

The paper's dynamics are the Moon as a point mass plus J2 (with the Earth and the Sun);
the Moon's gravity is lumpier. The notebook computes with the public API: the paper's
150 N capture as designed (J2, its verified burns: :func:`lunarcap.solve`); the same plan
designed again in LP165P (Konopliv et al. 2001) cut to a degree (:func:`lunarcap.
load_plan` with ``dynamics=field(degree)``); the design flown open loop through the field
of several degrees, held in RTN or inertial axes, from its arrival or its first ignition
(:meth:`lunarcap.CaptureResult.fly_open_loop`); its final orbit flown for days in J2 and
the fields (:meth:`lunarcap.CaptureResult.fly_final_orbit`). :func:`build` sets them out:
the final orbits and misses of the open loop (:func:`miss_table`), the re-design beside
the design, burn by burn (:func:`redesign_table`), per revolution of the final orbit the
lowest and highest altitude and the inclination (:func:`evolution_table`,
:func:`histories`, the figure), and how far the field's frame (DE405's principal axes) is
from the IAU (2009) body frame over the capture's year (:func:`frames_distance`, a fact
of the frames the prose quotes).
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.capture.chain import PlanResult
from lunarcap.physics import constants as C
from lunarcap.physics.elements import rv_from_mee
from lunarcap.physics.ephemeris import default_ephemeris
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.forces import force_model
from lunarcap.physics.frames import rotation_313
from lunarcap.report.contents import (
    BookPage,
    Execution,
    at_least,
    figure_files,
    includes,
    one_of,
    table_files,
)
from lunarcap.report.figures import real_moon as draw
from lunarcap.report.page import Page, solver_description

NOTEBOOK = "notebooks/real_moon.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 130, (
    Execution(
        "real_moon", "The real Moon: the capture in the lunar gravity field",
        parameters=dict(
            plan="song2011-150N",  # the J2 design
            # LP165P cut to these degrees (x the same order; "2x0": C20 alone), the design
            # flown open loop in each
            degrees=["2x0", 2, 8, 20, 50],
            compare_degree=20,
            design_degree=20,  # designed again in LP165P 20x20 (its burns)
            redesign_limits=True,  # its impulsive limits and losses in the field
            after_days=7.0, evolve_degrees=[2, 8, 20, 50], approach_min=60.0),
        quick_parameters=dict(degrees=["2x0", 2, 20],
                              design_degree=None,  # quick: no re-design (NLPs and solves)
                              after_days=1.0, evolve_degrees=[20]),
        depends_on=("table3",),  # the design's impulsive limits are table3's chain's
        expected_s=75,  # measured alone: 166 s wall, 73 s CPU at load 6-12 (50x50: 22 s)
        outputs=(table_files("real_moon", "miss", "opens", "redesign", "after")
                 + figure_files("real_moon", "evolution")),
        floors=dict(
            degrees=includes(["2x0", 2, 8, 20, 50], "the miss converged in degree, and C20 "
                                                     "alone beside the whole degree 2"),
            evolve_degrees=includes([2, 8, 20, 50], "the days after the capture converged "
                                                    "in degree"),
            design_degree=at_least(20, "the capture designed again in the field the page "
                                       "quotes"),
            redesign_limits=one_of([True], "the losses in the field"),
            after_days=at_least(7.0, "a week of the final orbit"))),
))
#: The packaged lunar field and the third bodies every model of the page carries.
FIELD, THIRD_BODIES = "LP165P", ["earth", "sun"]
#: The steering holds of the open-loop flights (:mod:`lunarcap.capture.openloop`).
HOLD_NAMES = {"rtn": "RTN", "inertial": "inertial"}
#: Tolerance of the days after the capture: 1e-10 moved the perilunes of 7 days in LP165P
#: 20x20 by 3 mm from 1e-13's, at half the CPU (the 50x50 field: 28 s at 1e-13).
EVOLUTION_RTOL = 1e-10


def degree_order(spec) -> tuple[int, int]:
    """``(degree, order)`` of a field as the page's parameters name it.

    An integer ``n`` is the field to degree and order ``n``; ``"NxM"`` to degree N and
    order M (``"2x0"``: C20 alone, the oblateness about the body's pole).

    >>> degree_order(20), degree_order("2x0")
    ((20, 20), (2, 0))
    """
    if isinstance(spec, str):
        deg, sep, order = spec.partition("x")
        if not (sep and deg.isdigit() and order.isdigit()) or int(order) > int(deg):
            raise ValueError(f"a field is a degree (20) or degree x order (\"2x0\"), the "
                             f"order at most the degree; got {spec!r}")
        return int(deg), int(order)
    if isinstance(spec, bool) or not isinstance(spec, (int, np.integer)) or spec < 2:
        raise ValueError(f"a field's degree is an integer >= 2; got {spec!r}")
    return int(spec), int(spec)


def field(spec) -> dict:
    """The plan ``dynamics`` of LP165P cut to ``spec`` (:func:`degree_order`), Earth and Sun."""
    degree, order = degree_order(spec)
    return {"gravity": FIELD, "degree": degree, "order": order,
            "third_bodies": THIRD_BODIES}


def model_name(dynamics) -> str:
    """How the tables name a model: "J2 (the design's)" or "LP165P 20x20"."""
    f = force_model(dynamics)
    return f"{f.field.name} {f.degree}x{f.order}" if f.is_field else "J2 (the design's)"


def frames_distance(t0_s: float, t1_s: float, n: int = 366,
                    altitude_km: float = 100.0) -> dict:
    """How far DE405's lunar principal axes are from the IAU (2009) body frame.

    At ``n`` epochs over [t0_s, t1_s]: the angle of the rotation between the two frames
    (arcsec) and the distance it moves a point at ``altitude_km`` (km); their least and
    largest.
    """
    t = np.linspace(t0_s, t1_s, n)
    eph = default_ephemeris()
    a, b = eph.body_angles(t, "de405"), eph.body_angles(t, "iau2009")
    ang = np.empty(n)
    for j in range(n):
        d = np.asarray(rotation_313(*a[:, j])) @ np.asarray(rotation_313(*b[:, j])).T
        ang[j] = np.arccos(np.clip((np.trace(d) - 1.0) / 2.0, -1.0, 1.0))
    km = 2.0 * (C.R_MOON + altitude_km) * np.sin(ang / 2.0)
    arcsec = np.degrees(ang) * 3600.0
    return {"min_arcsec": float(arcsec.min()), "max_arcsec": float(arcsec.max()),
            "min_km": float(km.min()), "max_km": float(km.max())}


def miss_row(label: str, ol, start: str) -> dict:
    """One open-loop flight as a row: model, hold, start, final orbit, miss.

    The final orbit's ``final_rp_altitude_km`` and ``final_ra_altitude_km``, its
    ``open_loop_inc_change_deg`` against the design's, and ``open_loop_miss_km``,
    ``open_loop_miss_mps`` (glossary names, :mod:`lunarcap.quantities`).
    """
    f = ol.final
    return {"model": label, "hold": HOLD_NAMES[ol.hold], "start": start,
            "final_rp_altitude_km": f["rp_alt_km"], "final_ra_altitude_km": f["ra_alt_km"],
            "open_loop_inc_change_deg": f["inc_deg"] - f["design_inc_deg"],
            "open_loop_miss_km": f["miss_km"], "open_loop_miss_mps": f["miss_mps"]}


def miss_table(flights: dict, start: str = "arrival") -> pd.DataFrame:
    """Rows of :func:`miss_row`: ``{(model label, hold): OpenLoop}`` flown from ``start``."""
    return pd.DataFrame([miss_row(label, ol, start) for (label, _), ol in flights.items()])


def redesign_table(design, redesign) -> pd.DataFrame:
    """Per burn (and the total): delta-V as designed and re-designed, limits and losses (m/s).

    ``design``, ``redesign``: PlanResults with impulsive limits; a burn with no limit
    says why in ``no_limit_reason``. The columns are the glossary's quantities with its
    ``design_`` and ``redesign_`` prefixes (``redesign_impulsive_limit_mps``, ...) and
    ``delta_v_change_mps``.
    """
    rows = []
    for k, (a, b) in enumerate(zip(design.table().to_dict("records"),
                                   redesign.table().to_dict("records")), 1):
        rows.append({"burn": str(k), "design_delta_v_mps": a["delta_v_mps"],
                     "design_delta_v_loss_mps": a["delta_v_loss_mps"],
                     "redesign_delta_v_mps": b["delta_v_mps"],
                     "delta_v_change_mps": b["delta_v_mps"] - a["delta_v_mps"],
                     "redesign_impulsive_limit_mps": b["impulsive_limit_mps"],
                     "redesign_delta_v_loss_mps": b["delta_v_loss_mps"],
                     "no_limit_reason": _text(b.get("impulsive_limit_reason"))})
    df = pd.DataFrame(rows)
    total = {"burn": "total", "no_limit_reason": ""}
    for c in ("design_delta_v_mps", "design_delta_v_loss_mps", "redesign_delta_v_mps",
              "delta_v_change_mps", "redesign_impulsive_limit_mps",
              "redesign_delta_v_loss_mps"):
        v = pd.to_numeric(df[c])
        total[c] = float(v.sum()) if v.notna().all() else float("nan")
    return pd.concat([df, pd.DataFrame([total])], ignore_index=True)


def _text(v) -> str:
    """A table's text cell: the string, or "" for a missing one (None or NaN)."""
    return v if isinstance(v, str) else ""


def revolution_days(ev) -> np.ndarray:
    """Where each revolution of an Evolution lies in days after the cut-off, evenly spaced.

    A revolution is a turn of the true longitude (:func:`lunarcap.physics.evolution.
    revolutions`); its perilune wanders through the turn as the orbit's argument of
    perilune turns, so two successive perilunes may lie minutes apart where one crosses
    the turn's start, and a curve drawn at the perilune epochs shows a step there that the
    orbit does not make. The revolutions are placed instead at the straight line fitted
    to their perilune epochs against their number (the mean revolution period).
    """
    d = (np.asarray(ev.perilune_epoch_s, float) - ev.t0_s) / C.DAY_S
    if d.size < 2:
        return d
    n = np.arange(d.size)
    return np.polyval(np.polyfit(n, d, 1), n)


def histories(evolutions: dict) -> dict:
    """Per model label, per revolution: its days, perilune and apolune altitude (km), inc (deg).

    The days are :func:`revolution_days`; the inclination is the revolution's mean.
    """
    out = {}
    for label, ev in evolutions.items():
        out[label] = {"days": revolution_days(ev),
                      "perilune_km": ev.perilune_altitude_km,
                      "apolune_km": ev.apolune_altitude_km, "inc_deg": ev.inclination_deg}
    return out


def evolution_table(evolutions: dict) -> pd.DataFrame:
    """Per model: revolutions, lowest perilune, highest apolune (km), inclination change (deg)."""
    rows = []
    for label, ev in evolutions.items():
        s = ev.summary()
        rows.append({"model": label, "after_revolutions": s["after_revolutions"],
                     "after_min_perilune_altitude_km": s["after_min_perilune_altitude_km"],
                     "after_max_apolune_altitude_km": s["after_max_apolune_altitude_km"],
                     "after_last_perilune_altitude_km": s["after_last_perilune_altitude_km"],
                     "after_last_apolune_altitude_km": s["after_last_apolune_altitude_km"],
                     "after_inclination_change_deg": s["after_inclination_change_deg"]})
    return pd.DataFrame(rows)


def end_distance_km(a, b) -> float:
    """Distance (km) between the end states of two open-loop flights (or evolutions)."""
    xa = a.final_state if hasattr(a, "final_state") else a.end.x
    xb = b.final_state if hasattr(b, "final_state") else b.end.x
    ra, rb = (np.array(rv_from_mee(*x[:6], C.MU_MOON)[0], float) for x in (xa, xb))
    return float(np.linalg.norm(ra - rb))


def _shown(v, why: str, spec: str = ".3f") -> str:
    """A table cell: the number, or why there is none."""
    return why if v is None or not np.isfinite(v) else format(float(v), spec)


def _year(epoch_s: float) -> tuple:
    """(start, end) of the calendar year of an epoch, TDB s past J2000."""
    y = int(calendar_from_seconds(epoch_s)[:4])
    return (seconds_from_calendar(f"{y}-01-01 00:00:00 TDB"),
            seconds_from_calendar(f"{y + 1}-01-01 00:00:00 TDB"))


def build(design, redesign, afters: dict, arrival: dict, ignition: dict,
          compare_degree: int = 20, approach_min: float = 60.0, output_name: str = "real_moon",
          quick: bool = False, redesign_limits: bool = True) -> Page:
    """The page of what the notebook computed (module docstring); nothing is flown here.

    Parameters
    ----------
    design : lunarcap.CaptureResult
        The design (:func:`lunarcap.solve` of a plan in its own J2), with its impulsive
        limits if ``redesign`` is given.
    redesign : lunarcap.CaptureResult or None
        The same plan solved in an LP165P field (:func:`lunarcap.load_plan` with
        ``dynamics=field(degree)``), ``impulsive=redesign_limits``; None: not done.
    afters : dict
        The design's final orbit flown the same days in each model
        (:meth:`lunarcap.CaptureResult.fly_final_orbit`, ``rtol`` :data:`EVOLUTION_RTOL`)
        by the field's degree (:func:`degree_order`; None: the design's own, required).
    arrival : dict
        The design flown open loop from ``approach_min`` before its first ignition
        (:meth:`lunarcap.CaptureResult.fly_open_loop`) by ``(degree, hold)``, the degrees
        as in ``afters`` (None required), each held in ``"rtn"`` and ``"inertial"``, in
        the order of the table's rows.
    ignition : dict
        The same from the first ignition in the field of ``compare_degree`` (one of
        ``arrival``'s), by hold.
    approach_min : float
        Where the flights of ``arrival`` started, min before the first ignition.
    redesign_limits : bool
        Whether ``redesign`` has its impulsive limits (two finite-burn solves per burn).
    output_name, quick : the tables' prefix; recorded in the provenance, whose ``plan``,
        ``design_degree``, ``degrees``, ``after_days`` and ``evolve_degrees`` are read
        from what was computed.
    """
    p = design.plan
    design_degree = _check_captures(design, redesign, redesign_limits)
    after_days, evolve_degrees = _check_afters(afters)
    degrees = _check_flights(arrival, ignition, compare_degree)
    page = Page(NOTEBOOK, dict(plan=p.name, degrees=degrees, compare_degree=compare_degree,
                               design_degree=design_degree, after_days=after_days,
                               evolve_degrees=list(evolve_degrees), approach_min=approach_min,
                               redesign_limits=redesign_limits),
                output_name, quick, solver=solver_description(), ephemeris=p.ephemeris_model())
    _frames(page, design)
    _misses(page, p, arrival, ignition, compare_degree)
    _redesign(page, design, redesign, design_degree, redesign_limits)
    _evolution(page, p, afters)
    page.note("scope", scope_text(page, degrees, evolve_degrees, design_degree,
                                  redesign_limits, after_days))
    _headline(page, compare_degree, after_days)
    return page


def _check_flights(arrival: dict, ignition: dict, compare) -> list:
    """The fields' degrees of ``arrival`` (see :func:`build`), once checked.

    Each model (None: the design's own, and the fields) held both ways, and the compared
    field among them, from the first ignition too: the tables set each beside the others.
    """
    holds, models = set(HOLD_NAMES), list(dict.fromkeys(d for d, _ in arrival))
    degrees = [d for d in models if d is not None]
    for d in degrees + [compare]:
        degree_order(d)   # each field named right
    if None not in models or compare not in degrees or set(ignition) != holds or any(
            {h for m, h in arrival if m == d} != holds for d in models):
        raise ValueError(f"arrival: the design's own dynamics (None) and the fields, each "
                         f"held in {sorted(holds)}, the compared field ({compare!r}) among "
                         f"them and in ignition, held both ways; got {list(arrival)}, "
                         f"{list(ignition)}")
    return degrees


def _check_afters(afters: dict) -> tuple:
    """``(days, degrees)`` of the final orbits (see :func:`build`), once checked."""
    days = {ev.days for ev in afters.values()}
    if None not in afters or len(days) != 1:
        raise ValueError(f"afters: the design's own dynamics (None) and the fields, flown "
                         f"the same days; got {list(afters)}, days {sorted(days)}")
    return days.pop(), [d for d in afters if d is not None]


def _check_captures(design, redesign, limits: bool):
    """The re-design's field (degree, or "NxM"; None: none), once checked.

    The design's plan in an LP165P field, both complete, with the limits the losses need.
    """
    if not design.complete:
        raise ValueError(f"design: every burn of {design.plan.name} solved (lunarcap.solve)")
    if redesign is None:
        return None
    f = force_model(redesign.plan.dynamics)
    if not f.is_field or redesign.plan != design.plan.with_dynamics(redesign.plan.dynamics):
        raise ValueError("redesign: the design's plan with an LP165P field as its dynamics "
                         "(lunarcap.load_plan(plan, dynamics=field(degree)))")
    if not redesign.complete or any(b.impulsive is None for b in design.burns) or (
            limits and any(b.impulsive is None for b in redesign.burns)):
        raise ValueError("redesign: every burn solved, the design's with its impulsive "
                         "limits (lunarcap.solve(..., impulsive=True)), the re-design's too "
                         "if redesign_limits")
    return f.degree if f.order == f.degree else f"{f.degree}x{f.order}"


def _frames(page: Page, design) -> None:
    t0 = design.burns[0].solution.flight.burn.t[0]
    d = frames_distance(*_year(t0))
    page.value("frames_year", calendar_from_seconds(t0)[:4])
    for k, v in d.items():
        page.value(f"frames_{k}", v)


def _misses(page: Page, p, arrival: dict, ignition: dict, compare) -> None:
    """The open-loop flights (see :func:`build`): the miss and opens tables, values, prose."""
    flights = {(model_name(p.dynamics if d is None else field(d)), hold): ol
               for (d, hold), ol in arrival.items()}
    degrees = [d for d in dict.fromkeys(d for d, _ in arrival) if d is not None]
    miss = miss_table(flights)
    fmt = {"final_rp_altitude_km": ".3f", "final_ra_altitude_km": ".3f",
           "open_loop_inc_change_deg": "+.4f", "open_loop_miss_km": ".3f",
           "open_loop_miss_mps": ".2f"}
    heads = {"model": "model", "hold": "steering held in",
             "final_rp_altitude_km": "perilune (km)", "final_ra_altitude_km": "apolune (km)",
             "open_loop_inc_change_deg": "Δi (deg)", "open_loop_miss_km": "miss (km)",
             "open_loop_miss_mps": "miss (m/s)", "start": "from"}
    page.table("miss", miss, caption=(
        f"The paper's J2 capture ({p.name}) flown open loop from "
        f"{page.parameters['approach_min']:g} min before the first ignition in LP165P of "
        "each degree, with the Earth and the Sun: the final orbit and its miss from the "
        "design where the design's circle holds. First rows: the design's own model."),
        columns=heads, floatfmt=fmt,
        show_columns=["model", "hold", "final_rp_altitude_km", "final_ra_altitude_km",
                      "open_loop_inc_change_deg", "open_loop_miss_km", "open_loop_miss_mps"])
    c = model_name(field(compare))
    opens = pd.concat([miss[miss.model == c],
                       miss_table({(c, h): ol for h, ol in ignition.items()},
                                  start="first ignition")],
                      ignore_index=True)
    page.table("opens", opens, caption=(
        f"Where the loop opens, {c}: flown from the arrival the approach too is in the "
        "field (the perilune and the first burn's cut-off move), flown from the design's "
        "state at the first ignition it is not. Final orbit as in the table above."),
        columns=heads, floatfmt=fmt,
        show_columns=["start", "hold", "final_rp_altitude_km", "final_ra_altitude_km",
                      "open_loop_miss_km", "open_loop_miss_mps"])
    row = {(r.model, r.hold, r.start): r for r in opens.itertuples()}
    for hold in ("rtn", "inertial"):
        h = HOLD_NAMES[hold]
        for start, key in (("arrival", "arrival"), ("first ignition", "ignition")):
            r = row[(c, h, start)]
            page.value(f"miss_{key}_{hold}_km", r.open_loop_miss_km)
            page.value(f"rp_{key}_{hold}_km", r.final_rp_altitude_km)
            page.value(f"ra_{key}_{hold}_km", r.final_ra_altitude_km)
    j2 = miss[miss.model == model_name(p.dynamics)].set_index("hold").open_loop_miss_km * 1e3
    page.value("j2_self_rtn_m", j2[HOLD_NAMES["rtn"]])
    page.value("j2_self_inertial_m", j2[HOLD_NAMES["inertial"]])
    page.expect("the design flown open loop (RTN) in its own model ends within 1 m of its "
                "verified flight", j2[HOLD_NAMES["rtn"]] < 1.0, f"{j2[HOLD_NAMES['rtn']]:.3g} m")
    page.value("compare_model", c)
    inertial = miss[miss.hold == HOLD_NAMES["inertial"]].set_index("model").open_loop_miss_km
    page.note("degree2_text", degree2_text(page, inertial, c))
    top = max(degrees, key=degree_order)
    if degree_order(top) != degree_order(compare):
        a = flights[(c, "inertial")]
        b = flights[(model_name(field(top)), "inertial")]
        page.value("top_vs_compare_km", end_distance_km(a, b))
        page.note("deeper", f"{c} and {model_name(field(top))} end "
                            f"{page.text('top_vs_compare_km', '.2f', ' km')} apart there.")
    else:
        page.value("top_vs_compare_km", None, why="no deeper field flown")
        page.note("deeper", f"no field deeper than {c} was flown in this run.")


def degree2_text(page: Page, inertial: pd.Series, compare: str) -> str:
    """How much of the compared field's miss degree 2 makes, C20 alone and with C22.

    ``inertial``: the open-loop miss (km) held in inertial axes, by model label. LP165P
    2x0 is C20 alone about the body's pole: against the design's J2 it moves the axis
    (the pole of the principal axes, of date, instead of the design's fixed pole) and
    takes LP165P's C20 and reference radius. 2x2 adds the other degree-2 terms, in the
    principal axes chiefly the C22 ellipticity. The shares are of the compared field's
    miss (the misses are distances, not additive vectors: the shares say how far each
    field alone takes the capture, not a sum). The sentence's comparison is computed.
    """
    share = {}
    for key, spec in (("2x0", "2x0"), ("2x2", 2)):
        name = model_name(field(spec))
        v = 100.0 * inertial[name] / inertial[compare] if name in inertial.index else None
        page.value(f"share_{key}_percent", v, why=f"{name} not flown in this run")
        share[key] = v
    t = page.text
    if share["2x0"] is None or share["2x2"] is None:
        flown = [k for k, v in share.items() if v is not None]
        return (f"LP165P {flown[0]} alone makes {t(f'share_{flown[0]}_percent', '.0f', ' %')} "
                "of that miss." if flown else "")
    more = ("most of degree 2's share comes with C22" if share["2x2"] - share["2x0"]
            > share["2x0"] else "most of degree 2's share is C20's alone")
    return (f"C20 alone about the body's pole (LP165P 2x0: the design's J2 moved to the "
            f"pole of the field's frame, with LP165P's C20 and radius) makes "
            f"{t('share_2x0_percent', '.1f', ' %')} of that miss, the whole degree 2 (2x2, "
            f"adding the C22 ellipticity) {t('share_2x2_percent', '.0f', ' %')}: {more}.")


def no_limit_text(page: Page, redesign) -> str:
    """Why a burn of the re-design has no impulsive limit (its numbers glued), or that all do.

    For a circle out of reach of every impulse (:mod:`lunarcap.mission.reach`): how far
    below the orbit before the burn the circle flown back lies, and the row's reason.
    """
    burns = [(k, b.impulsive) for k, b in enumerate(redesign.burns, 1)
             if b.impulsive is not None and b.impulsive.get("reason")]
    if not burns:
        return "Every burn of the re-designed capture has an impulsive limit in the field."
    k, imp = burns[0]
    gap = imp.get("circle_gap_m")
    page.value("circle_gap_m", gap, why="the finite-burn limit failed instead")
    page.value("no_limit_burn", k)
    text = (f"Burn {k} has no impulsive limit in the field, and so no loss. ")
    if gap is not None:
        text += (
            "Its circle is asked at a fixed epoch, one period after the perilune where the "
            "burn is made; an impulse changes the velocity but not the position, so it "
            "reaches the circle only if some circle of the radius and inclination asked, "
            "flown back from that epoch to the burn, passes through the spacecraft's "
            "position. In J2 that circle, flown back over its one period, passes within "
            "centimetres of the perilune of the orbit before the burn (whose perilune is the "
            "circle's radius): the impulse is tangential there. In the field the circle "
            f"flown back lies {page.text('circle_gap_m', '.0f', ' m')} below that perilune, "
            "the lowest point of the orbit before the burn: no impulse from that orbit can "
            "reach it. A finite burn gets there by thrusting partly inward, and the shorter "
            "the burn the more that costs, so the limit of ever shorter burns does not "
            "exist. lunarcap finds this before solving anything (a few propagations of the "
            "circle backward) and says so: ")
    return text + f"\n\n> {imp['reason']}"


#: Why the re-design's limits and losses are missing when the run did not ask for them.
NO_LIMITS_REASON = "not computed in this run (`redesign_limits: false`)"


def _redesign(page: Page, design, redesign, degree, limits: bool = True) -> None:
    """The re-design's table, totals, losses and notes (``redesign`` None: why it lacks).

    ``design``, ``redesign``: lunarcap.CaptureResult (the notebook's solves); ``degree``:
    the re-design's field (:func:`_check_captures`).
    """
    why = page.missing_reason
    if degree is None:
        why = f"not designed again in this run ({why})" if not page.quick else why
    no_limit = why if degree is None else NO_LIMITS_REASON
    design = PlanResult(design.plan, design.burns)
    if degree is not None:
        redesign = PlanResult(redesign.plan, redesign.burns)
        df = redesign_table(design, redesign)
        page.expect("the re-designed capture is verified in its field",
                    redesign.totals()["all_verified"])
        page.value("redesign_model", model_name(redesign.plan.dynamics))
        page.note("no_limit_text", no_limit_text(page, redesign) if limits else
                  "(Whether each burn has an impulsive limit in the field at all is found "
                  "with the limits.)")
    else:
        df = redesign_table(design, design)
        for c in ("redesign_delta_v_mps", "delta_v_change_mps", "redesign_impulsive_limit_mps",
                  "redesign_delta_v_loss_mps"):
            df[c] = np.nan
        df["no_limit_reason"] = ""
        page.value("redesign_model", None, why=why)
        page.note("no_limit_text", f"(The capture was not designed again: {why}.)")
    computed = degree is not None and limits
    df["limit_shown"] = [
        _shown(v, no_limit if not computed else "none: no impulse reaches the circle"
               if r else "none: a burn has no limit")
        for v, r in zip(df.redesign_impulsive_limit_mps, df.no_limit_reason)]
    df["loss_shown"] = [_shown(v, no_limit if not computed else "undefined (no limit)")
                        for v in df.redesign_delta_v_loss_mps]
    for c in ("redesign_delta_v_mps", "delta_v_change_mps"):
        df[c + "_shown"] = [_shown(v, why, "+.3f" if "change" in c else ".3f") for v in df[c]]
    df["design_delta_v_loss_mps"] = pd.to_numeric(df.design_delta_v_loss_mps)
    df["design_loss_shown"] = [_shown(v, page.missing_reason)
                               for v in df.design_delta_v_loss_mps]
    _redesign_shown(page, df, page.values["redesign_model"] if degree is not None else why,
                    None if computed or degree is None else no_limit)
    tot = df.iloc[-1]
    page.value("design_total_mps", tot.design_delta_v_mps)
    page.value("redesign_total_mps", tot.redesign_delta_v_mps)
    page.value("redesign_change_mps", tot.delta_v_change_mps)
    for k in range(len(df) - 1):
        page.value(f"redesign_loss_{k + 1}_mps", df.redesign_delta_v_loss_mps.iloc[k],
                   why=no_limit if not computed else "no impulsive limit in the field")
        page.value(f"design_loss_{k + 1}_mps", df.design_delta_v_loss_mps.iloc[k])
    page.note("loss_text", loss_text(page, df, computed, no_limit))


def _redesign_shown(page: Page, df: pd.DataFrame, model: str, no_limits: str | None
                    ) -> None:
    """The re-design's table; ``no_limits``: why its limit and loss columns are left out."""
    show = ["burn", "design_delta_v_mps", "design_loss_shown", "redesign_delta_v_mps_shown",
            "delta_v_change_mps_shown"] + ([] if no_limits else ["limit_shown", "loss_shown"])
    page.table("redesign", df, caption=(
        f"The capture designed again in the field (the same plan, targets and ignitions; "
        f"{model}) beside the J2 design: each burn's ΔV (m/s) and its finite-burn loss "
        "against the impulsive limit in the same dynamics (m/s)"
        + (f"; in the field those limits and losses were {no_limits}." if no_limits
           else ".")),
        columns={"burn": "burn", "design_delta_v_mps": "ΔV, J2 (m/s)",
                 "design_loss_shown": "loss, J2 (m/s)",
                 "redesign_delta_v_mps_shown": "ΔV, field (m/s)",
                 "delta_v_change_mps_shown": "change (m/s)",
                 "limit_shown": "impulsive limit, field (m/s)",
                 "loss_shown": "loss, field (m/s)"},
        floatfmt={"design_delta_v_mps": ".3f"}, show_columns=show)


def loss_text(page: Page, df: pd.DataFrame, computed: bool, why: str) -> str:
    """The losses of the re-design beside the J2 design's, per burn that has both, or why not.

    ``df``: :func:`redesign_table` (its burns' rows, then the total); ``computed``: the
    re-design's limits were computed (else ``why`` says why not).
    """
    burns = df.iloc[:-1]
    if not computed:
        j2 = pd.to_numeric(burns.design_delta_v_loss_mps)
        if not np.isfinite(j2).all():   # the design's own limits not computed either
            return f"Its finite-burn losses in the field are {why}."
        return (f"Its finite-burn losses in the field are {why}; the J2 design's are "
                + ", ".join(f"{v:.3f}" for v in j2) + " m/s.")
    has = burns[np.isfinite(pd.to_numeric(burns.redesign_delta_v_loss_mps))]
    if has.empty:
        return "No burn of the re-design has a finite-burn loss in the field."
    pairs = [f"burn {b}: {f:.3f} m/s ({j:.3f} in J2)" for b, f, j in
             zip(has.burn, has.redesign_delta_v_loss_mps, has.design_delta_v_loss_mps)]
    return "Against their impulsive limits in the field the burns lose " + "; ".join(pairs) + "."


def scope_text(page: Page, degrees, evolve_degrees, design_degree, limits: bool,
               days: float) -> str:
    """What this run flew and what it left out, with the parameters that add it.

    The book flies the fields to 50x50 and computes the re-design's limits (its floors);
    a run with less (the quick book, or a reader's) says what it left out and which
    parameters add it.
    """
    text = (f"This run ({'the quick book' if page.quick else 'the book'}'s parameters) flies "
            f"the design in LP165P {_degrees(degrees)}, follows its final orbit {_days(days)} "
            f"in J2{' and LP165P ' + _degrees(evolve_degrees) if evolve_degrees else ''}, and ")
    if design_degree is None:
        text += "does not design it again in the field."
    else:
        text += (f"designs it again in {model_name(field(design_degree))}"
                 + ("" if limits else ", without that design's impulsive limits") + ".")
    left = []
    if max(degree_order(d)[0] for d in list(degrees) + list(evolve_degrees)) < 50:
        left.append("`-y \"degrees: [2x0, 2, 8, 20, 50]\" -y \"evolve_degrees: [2, 8, 20, "
                    "50]\"` adds the 50x50 field")
    if design_degree is not None and not limits:
        left.append("`-p redesign_limits true` the re-design's limits and losses")
    if not left:
        return text
    return (text + " Deeper fields and the limits cost most of the page's time and are left "
            "out of this run; the book runs them, as does the notebook run with papermill "
            "(as in *Reproduce*): " + "; ".join(left) + ".")


def _evolution(page: Page, p, afters: dict) -> None:
    """The final orbits flown (``afters``, see :func:`build`): figure, table, prose."""
    days = next(iter(afters.values())).days
    evs = {model_name(p.dynamics if d is None else field(d)): ev for d, ev in afters.items()}
    page.figure("evolution", draw.plot_evolution(histories(evs)), caption=(
        f"The final orbit of the J2 design flown {_days(days)} after its last cut-off in "
        "each model: each revolution's lowest and highest altitude (km, solid and dashed) "
        "and its mean inclination (deg, about the plan's frame's pole), the revolutions "
        "evenly spaced at their mean period."),
        alt="Perilune, apolune and inclination of the final orbit over days, per gravity "
            "model")
    table = evolution_table(evs)
    page.table("after", table, caption=(
        f"The final orbit over {_days(days)} in each model: revolutions, the lowest perilune "
        "and highest apolune altitudes (km), those of the last revolution, and the change "
        "of the mean inclination from the first revolution to the last (deg)."),
        columns={"model": "model", "after_revolutions": "revolutions",
                 "after_min_perilune_altitude_km": "lowest perilune (km)",
                 "after_max_apolune_altitude_km": "highest apolune (km)",
                 "after_last_perilune_altitude_km": "last perilune (km)",
                 "after_last_apolune_altitude_km": "last apolune (km)",
                 "after_inclination_change_deg": "Δi (deg)"},
        floatfmt={"after_min_perilune_altitude_km": ".2f", "after_max_apolune_altitude_km": ".2f",
                  "after_last_perilune_altitude_km": ".2f", "after_last_apolune_altitude_km": ".2f",
                  "after_inclination_change_deg": "+.3f"})
    page.value("after_days", days)
    page.value("after_days_word", _days(days))
    page.note("after_text", after_text(page, table, model_name(p.dynamics),
                                      page.values["compare_model"], evs))
    page.expect("every model flew whole revolutions", bool((table.after_revolutions > 0).all()))


def _degrees(degrees) -> str:
    """Fields as prose lists them: "2x0, 2x2, 8x8 and 20x20"."""
    names = ["{}x{}".format(*degree_order(d)) for d in degrees]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]


def _days(days: float) -> str:
    return f"{days:g} day{'s' * (days != 1)}"


def after_text(page: Page, table: pd.DataFrame, j2: str, compare: str, evs: dict) -> str:
    """The prose of the days after the capture, from the evolution table (its values glued).

    J2's lowest perilune and inclination change; the compared field's; the other fields'
    lowest perilunes beside it; how far apart the two deepest end (km).
    """
    t = table.set_index("model")
    v = page.value
    v("j2_min_perilune_km", t.loc[j2, "after_min_perilune_altitude_km"])
    v("j2_inc_change_deg", t.loc[j2, "after_inclination_change_deg"])
    text = (f"In J2 the 100 km polar orbit stays near its circle (lowest perilune "
            f"{page.text('j2_min_perilune_km', '.2f', ' km')}, inclination change "
            f"{page.text('j2_inc_change_deg', '+.2f', ' deg')}).")
    if compare not in t.index:
        v("compare_min_perilune_km", None, why="the compared field not flown in this run")
        v("compare_inc_change_deg", None, why="the compared field not flown in this run")
        return text
    v("compare_min_perilune_km", t.loc[compare, "after_min_perilune_altitude_km"])
    v("compare_inc_change_deg", t.loc[compare, "after_inclination_change_deg"])
    text += (f" In {compare} its perilune comes down to "
             f"{page.text('compare_min_perilune_km', '.1f', ' km')} and its plane turns by "
             f"{page.text('compare_inc_change_deg', '+.2f', ' deg')}.")
    others = [m for m in t.index if m not in (j2, compare)]
    if others:
        text += " Cut elsewhere, the field gives " + "; ".join(
            f"{m}: {t.loc[m, 'after_min_perilune_altitude_km']:.1f} km, "
            f"{t.loc[m, 'after_inclination_change_deg']:+.2f} deg" for m in others) + "."
    fields = [m for m in evs if m != j2]
    if len(fields) >= 2:
        a, b = fields[-2], fields[-1]
        v("deepest_apart_km", end_distance_km(evs[a], evs[b]))
        lowest = t["after_min_perilune_altitude_km"]
        text += (f" The two deepest, {a} and {b}, end "
                 f"{page.text('deepest_apart_km', '.1f', ' km')} apart after "
                 f"{_days(page.values['after_days'])}, their lowest perilunes "
                 f"{abs(lowest[a] - lowest[b]):.2f} km apart.")
    return text


def _headline(page: Page, compare: int, days: float) -> None:
    t = page.text
    page.headline(
        f"Flown open loop through LP165P to degree {compare}, the paper's J2 "
        f"capture ends on a {t('rp_arrival_inertial_km', '.1f')} × "
        f"{t('ra_arrival_inertial_km', '.1f', ' km')} orbit, "
        f"{t('miss_arrival_inertial_km', '.1f', ' km')} from its design; re-designed in the "
        f"field its ΔV changes by {t('redesign_change_mps', '+.2f', ' m/s')}, and over "
        f"{_days(days)} "
        f"the field takes the 100 km orbit's perilune down to "
        f"{t('compare_min_perilune_km', '.1f', ' km')} and turns its plane by "
        f"{t('compare_inc_change_deg', '.2f', ' deg')} (J2: "
        f"{t('j2_min_perilune_km', '.1f', ' km')}, {t('j2_inc_change_deg', '.2f', ' deg')}).")
