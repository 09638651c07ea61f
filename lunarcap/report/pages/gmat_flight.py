"""The "Flown in GMAT" page (notebooks/gmat_flight.ipynb): lunarcap's capture in NASA's GMAT.

:func:`build` exports each case's verified capture with its GMAT script
(:func:`lunarcap.capture.gmat_flight.fly_in_gmat`, into
``book/generated/export/<output_name>_<k>/``, so the book serves the files), runs the script in
GMAT (the ``gmatpy`` wheel, in a child process) and tabulates GMAT's states against lunarcap's
(:func:`comparison_table`,
:func:`final_table`). It reads GMAT's own defaults from GMAT
(:func:`lunarcap.exchange.gmat.gmat_defaults`) and lists what the exported script sets
instead, with what each default costs the first case's capture, flown in lunarcap
(:func:`lunarcap.capture.gmat_flight.default_costs`; :func:`settings_table`).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pandas as pd

from lunarcap.capture.chain import plan_result
from lunarcap.capture.export import capture_arcs
from lunarcap.capture.gmat_flight import (
    TOL_BURN_POSITION_M,
    TOL_BURN_SPEED_MPS,
    TOL_FINAL_RADII_M,
    default_costs,
    lunarcap_events,
)
from lunarcap.exchange import gmat
from lunarcap.physics import constants as C
from lunarcap.physics.epochs import calendar_from_seconds, leap_second_table, seconds_from_calendar
from lunarcap.physics.forces import force_model
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.page import Page
from lunarcap.repro import paths

NOTEBOOK = "notebooks/gmat_flight.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 140, (
    Execution(
        "gmat_flight", "Flown in GMAT",
        parameters=dict(cases=[  # [plan, dynamics or None (the plan's own)]
            ["song2011-150N", None],
            ["song2011-150N", dict(gravity="LP165P", degree=20, order=20,
                                   third_bodies=["earth", "sun"])]]),
        quick_parameters=dict(cases=[["song2011-150N", None]]),
        depends_on=("table3", "real_moon"),  # their solves: 150 N chain, 20x20 re-design
        expected_s=11,  # measured 10.5 s wall, 9.8 s CPU (the 20x20 burns cached)
        outputs=table_files("gmat_flight", "comparison", "final", "files", "settings")),
))
#: How the comparison table names GMAT's events (its reports' codes).
EVENTS = {gmat.IGNITION: "ignition", gmat.CUTOFF: "cut-off", gmat.END: "end"}


def case_label(plan) -> str:
    """A case as the tables name it: the plan and its forces."""
    return f"{plan.name} ({force_model(plan.dynamics)})"


def comparison_table(c, label: str) -> pd.DataFrame:
    """GMAT against lunarcap for one case: per burn, per coast, the whole capture.

    ``c``: a :class:`lunarcap.capture.gmat_flight.GmatComparison`. One row per burn flown from
    lunarcap's ignition state (at its cut-off), per coast flown from lunarcap's cut-off
    (at its end), and per event of the whole capture flown open loop from the arrival:
    GMAT's position (m), velocity (mm/s) and mass (g) minus lunarcap's.
    """
    rows = []

    def add(flight, r):
        rows.append({"case": label, "flight": flight, "position_diff_m": r["position_diff_m"],
                     "velocity_diff_mmps": r["velocity_diff_mmps"],
                     "mass_diff_g": r["mass_diff_kg"] * 1e3})
    for b in c.burns:
        add(f"burn {b['burn']} from lunarcap's ignition state, at its cut-off", b)
    for r in c.coasts:
        to = f"burn {r['burn']}'s ignition" if r["event"] == gmat.IGNITION else \
            "one revolution of the final orbit"
        add(f"coast {r['burn'] - (r['event'] == gmat.IGNITION)} from lunarcap's cut-off, "
            f"to {to}", r)
    for r in c.capture:
        if (r["burn"], r["event"]) == (0, gmat.IGNITION):
            continue   # the arrival: GMAT's first state is lunarcap's
        what = "end (one revolution after the last cut-off)" if r["event"] == gmat.END \
            else f"burn {r['burn']} {EVENTS[r['event']]}"
        add(f"whole capture from the arrival: {what}", r)
    return pd.DataFrame(rows)


def final_table(cases: dict) -> pd.DataFrame:
    """The final orbit's perilune and apolune altitudes (km), lunarcap's and GMAT's, per case.

    Columns: ``final_rp_altitude_km``, ``final_ra_altitude_km`` (lunarcap's), their
    ``gmat_`` versions, and ``final_rp_diff_m``, ``final_ra_diff_m`` (GMAT's radius minus
    lunarcap's), glossary names (:mod:`lunarcap.quantities`).
    """
    rows = []
    for label, c in cases.items():
        for f in c.final_orbit:
            rows.append({"case": label, "at": f["at"],
                         "final_rp_altitude_km": f["rp_km"] - C.R_MOON,
                         "final_ra_altitude_km": f["ra_km"] - C.R_MOON,
                         "gmat_final_rp_altitude_km": f["rp_gmat_km"] - C.R_MOON,
                         "gmat_final_ra_altitude_km": f["ra_gmat_km"] - C.R_MOON,
                         "final_rp_diff_m": f["rp_diff_m"], "final_ra_diff_m": f["ra_diff_m"]})
    return pd.DataFrame(rows)


def script_line(text: str, pattern: str) -> str:
    """The first line of a script matching ``pattern`` (a regular expression), stripped."""
    for ln in text.splitlines():
        if re.search(pattern, ln):
            return ln.split("%")[0].strip()
    raise ValueError(f"no line of the script matches {pattern!r}")


def tdb_minus_tai_s(t_s: float) -> float:
    """TDB − TAI at an epoch (s): TDB − UTC (ERFA, through lunarcap's epochs) less TAI − UTC."""
    utc = calendar_from_seconds(t_s, 6, scale="UTC")
    tdb_minus_utc = t_s - seconds_from_calendar(utc.replace(" UTC", " TDB"))
    return tdb_minus_utc - leap_second_table()["tai_minus_utc_s"]


def inclination_icrf_deg(state) -> float:
    """Inclination (deg) of an ICRF state's orbit to the ICRF equator (GMAT's MJ2000Eq INC)."""
    h = np.cross(np.asarray(state.r_km, float), np.asarray(state.v_kmps, float))
    return float(np.degrees(np.arccos(h[2] / np.linalg.norm(h))))


def length_text(m: float, sign: str = "") -> str:
    """A length in metres as prose writes it: m below 1 km, else km (3 digits).

    >>> length_text(4.407), length_text(-2252.9, "+"), length_text(0.0657)
    ('4.41 m', '-2.25 km', '0.0657 m')
    """
    return f"{m / 1e3:{sign}.3g} km" if abs(m) >= 1e3 else f"{m:{sign}.3g} m"


def speed_text(mmps: float) -> str:
    """A speed in mm/s as prose writes it: mm/s below 1 m/s, else m/s (3 digits).

    >>> speed_text(12.05), speed_text(1296.2)
    ('12.1 mm/s', '1.3 m/s')
    """
    return f"{mmps / 1e3:.3g} m/s" if abs(mmps) >= 1e3 else f"{mmps:.3g} mm/s"


def _cost(c: dict | None, what: str) -> str:
    if c is None:
        return "not flown: the plan's J2 is not about its frame's pole"
    return (f"{what}: burn 1's cut-off {length_text(c['burn1_m'])}, "
            f"{speed_text(c['burn1_mmps'])} off; the final orbit's perilune "
            f"{length_text(c['rp_m'], '+')}, apolune {length_text(c['ra_m'], '+')}")


def settings_table(script: str, defaults: dict, costs: dict, facts: dict) -> pd.DataFrame:
    """The eight settings GMAT needs: what the exported script sets, GMAT's default, its cost.

    ``script``: the script's text; ``defaults``: GMAT's
    (:func:`lunarcap.exchange.gmat.gmat_defaults`); ``costs``:
    :func:`lunarcap.capture.gmat_flight.default_costs`; ``facts``: ``tdb_minus_tai_s``, ``mjd_days``
    (the usual MJD against GMAT's), ``inc_icrf_deg`` and ``inc_deg`` (an orbit's
    inclination to the ICRF and to the lunar equator), ``segments`` (thrust-direction
    segments in the script), ``propagates`` (its Propagate commands).
    """
    d, k = defaults, facts
    rows = [
        ("the thruster's standard gravity", script_line(script, r"Engine\.GravitationalAccel"),
         f"{d['g0_mps2']:g} m/s²", _cost(costs.get("g0"), "flown with it")),
        ("epochs: TDB, GMAT's modified Julian date", script_line(script, r"\.DateFormat ="),
         f"{d['date_format']}",
         f"epochs off by {k['tdb_minus_tai_s']:.3f} s (TAI for TDB), or by {k['mjd_days']:g} "
         "days (an MJD of JD − 2400000.5 for GMAT's JD − 2430000)"),
        ("axes: MJ2000Eq, as lunarcap's ICRF (DE405's)", script_line(script, r"MoonEq\.Axes"),
         f"{d['coordinate_system']} (spacecraft); thrust in {d['thrust_frame']} "
         f"{d['thrust_axes']}",
         f"the numbers go in unchanged; but GMAT's INC there is to the Earth's equator: "
         f"{k['inc_icrf_deg']:.2f} deg for lunarcap's {k['inc_deg']:.2f} deg orbit"),
        ("the lunar J2 about the plan's fixed pole (a body the script creates)",
         script_line(script, r"SpinAxisDECConstant|Dynamics\.CentralBody"),
         "Luna, turned with the DE405 librations (its pole of date)",
         _cost(costs.get("pole"), "J2 about the pole of date")),
        ("the Moon's GM and radius (lunarcap's)", script_line(script, r"\.Mu = 49"),
         f"{d['luna_mu_km3s2']:.10g} km³/s², {d['luna_radius_km']:g} km",
         _cost(costs.get("gm"), "GMAT's GM")),
        ("a gravity file with lunarcap's GM and radius (GMAT reads them there)",
         script_line(script, r"PotentialFile"),
         "LP165P.cof" + ("" if d["lunar_field_file"] else ", which this GMAT does not have"),
         "GMAT stops: a field names a file that must exist"),
        ("the thrust direction in segments of at most 10 s",
         script_line(script, r"ThrustDirection1 = -?\d\.\d"),
         "one direction per burn", _cost(costs.get("one-direction"), "one mean direction "
                                          "per burn")),
        ("each Propagate to an absolute TDB epoch", script_line(script, r"^Propagate Prop"),
         "a duration (ElapsedSecs)",
         f"each of the {k['propagates']} Propagates ends a fraction of a microsecond early; "
         "not flown by lunarcap (GMAT's arithmetic)"),
    ]
    return pd.DataFrame(rows, columns=["setting", "script", "gmat_default", "cost"])


def files_table(files: dict) -> pd.DataFrame:
    """The GMAT files of a case, with a download link to each (served by the book)."""
    what = {"gmat_script": "the GMAT script", "gmat_gravity": "the gravity field it reads",
            "gmat_moon": "the Moon's states it reads (SPK)",
            "gmat_runner": "the command that runs it (a field in GMAT's Luna)"}
    return pd.DataFrame([{"file": Path(p).name, "what": what[k], "download":
                          f"{{download}}`{Path(p).name} <{paths.relative_to_page(Path(p))}>`"}
                         for k, p in files.items() if k in what])


def export_dir(output_name: str = "gmat_flight", k: int = 1):
    """Where the book keeps case ``k``'s exported and GMAT files (a Path), which it links to.

    ``book/generated/export/<output_name>_<k>/``: the notebook flies case k there.
    """
    return paths.export_dir(f"{output_name}_{k}")


def build(results, flights, output_name: str = "gmat_flight", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The page of the captures flown in GMAT in the notebook (see the module docstring).

    Parameters
    ----------
    results : list of lunarcap.CaptureResult
        :func:`lunarcap.solve`'s capture of each case (``impulsive=False``); the first's is
        the one whose GMAT settings' costs are flown here.
    flights : list of lunarcap.GmatFlight
        ``results[k - 1].fly_in_gmat(export_dir(output_name, k))`` for each case k.
    output_name, quick : prefix of the tables and export folders; recorded in provenance
    parameters : dict, optional
        The notebook's parameters (``cases``), shown in the page's provenance.
    """
    plans = [r.plan for r in results]
    page = Page(NOTEBOOK, dict(parameters or {}), output_name, quick,
                ephemeris=plans[0].ephemeris_model())
    flown, tables, files = {}, [], []
    for k, (res, flight) in enumerate(zip(results, flights), 1):
        c = flight.comparison
        label = case_label(res.plan)
        flown[label] = c
        tables.append(comparison_table(c, label))
        files.append(files_table(c.files).assign(case=label))
        page.expect(f"{label}: GMAT within the gates", not c.failures(), "; ".join(c.failures()))
        _case_values(page, k, c, res)
    comp = pd.concat(tables, ignore_index=True)
    page.table("comparison", comp, caption=(
        "GMAT's states minus lunarcap's: each burn (at its cut-off) and coast (at its end) "
        "flown by GMAT from lunarcap's state at its start, and the whole capture flown open "
        "loop from the arrival."),
        columns={"case": "case", "flight": "flight", "position_diff_m": "position (m)",
                 "velocity_diff_mmps": "velocity (mm/s)", "mass_diff_g": "mass (g)"},
        floatfmt={"position_diff_m": ".3g", "velocity_diff_mmps": ".3g", "mass_diff_g": "+.2g"})
    page.table("final", final_table(flown), caption=(
        "The final orbit of the whole capture flown open loop, at the last cut-off and one "
        "revolution later: osculating perilune and apolune altitudes, lunarcap's and GMAT's "
        f"(km), and GMAT's minus lunarcap's (m; gate {TOL_FINAL_RADII_M:g} m)."),
        columns={"case": "case", "at": "at", "final_rp_altitude_km": "perilune (km)",
                 "final_ra_altitude_km": "apolune (km)",
                 "gmat_final_rp_altitude_km": "GMAT perilune (km)",
                 "gmat_final_ra_altitude_km": "GMAT apolune (km)",
                 "final_rp_diff_m": "Δ perilune (m)", "final_ra_diff_m": "Δ apolune (m)"},
        floatfmt={"final_rp_altitude_km": ".4f", "final_ra_altitude_km": ".4f",
                  "gmat_final_rp_altitude_km": ".4f", "gmat_final_ra_altitude_km": ".4f",
                  "final_rp_diff_m": "+.3g", "final_ra_diff_m": "+.3g"})
    page.table("files", pd.concat(files, ignore_index=True), caption=(
        "The files GMAT runs, per case, as `lunarcap plan ... --export DIR` writes them "
        "(download each from its link); GMAT's reports and OEM are written beside them."),
        columns={"case": "case", "download": "file", "what": "what"},
        show_columns=["case", "download", "what"])
    _settings(page, plans[0], flown[case_label(plans[0])])
    page.note("second_case", _second_case(page, plans))
    _headline(page, plans)
    return page


def _second_case(page: Page, plans) -> str:
    """The prose of the second case (a plan in a gravity field), or why there is none."""
    if len(plans) < 2:
        return (f"(One case was flown in this run{', the quick book' if page.quick else ''}; "
                "the book's full run adds a plan designed in a lunar gravity field.)")
    t = page.text
    return (f"For {t('case2_name')} in {t('case2_forces')} (GMAT's `Luna` carries the field "
            "in its DE405 body frame, as lunarcap does) every burn ends within "
            f"{t('case2_burn_max_m', '.2g', ' m')} and {t('case2_burn_max_mmps', '.2g', ' mm/s')}"
            f" of lunarcap's cut-off, every coast within {t('case2_coast_max_m', '.2g', ' m')}, "
            f"and the whole capture {t('case2_end_m', '.2g', ' m')} from lunarcap at the end, "
            f"on a final orbit within {t('case2_final_max_m', '.2g', ' m')} of lunarcap's.")


def _case_values(page: Page, k: int, c, res) -> None:
    burns = pd.DataFrame(c.burns)
    page.value(f"case{k}_name", res.plan.name)
    page.value(f"case{k}_forces", str(force_model(res.plan.dynamics)))
    page.value(f"case{k}_burn_max_m", float(burns.position_diff_m.max()))
    page.value(f"case{k}_burn_max_mmps", float(burns.velocity_diff_mmps.max()))
    page.value(f"case{k}_mass_max_g", float(np.abs(burns.mass_diff_kg).max() * 1e3))
    page.value(f"case{k}_coast_max_m", max(r["position_diff_m"] for r in c.coasts))
    end = c.capture[-1]
    page.value(f"case{k}_end_m", end["position_diff_m"])
    page.value(f"case{k}_end_mmps", end["velocity_diff_mmps"])
    page.value(f"case{k}_final_max_m", max(max(abs(f["rp_diff_m"]), abs(f["ra_diff_m"]))
                                           for f in c.final_orbit))
    page.value(f"case{k}_gmat_s", c.gmat_wall_s)
    last = c.final_orbit[-1]
    page.value(f"case{k}_final_rp_km", last["rp_gmat_km"] - C.R_MOON)
    page.value(f"case{k}_final_ra_km", last["ra_gmat_km"] - C.R_MOON)
    page.value("gate_burn_m", TOL_BURN_POSITION_M)
    page.value("gate_burn_mmps", TOL_BURN_SPEED_MPS * 1e3)
    page.value("gate_final_m", TOL_FINAL_RADII_M)


def _settings(page: Page, plan, c) -> None:
    res = plan_result(plan, impulsive=False)
    defaults = gmat.gmat_defaults()
    costs = default_costs(res, defaults)
    script = Path(c.files["gmat_script"]).read_text(encoding="ascii")
    ev = lunarcap_events(res, capture_arcs(res))
    after1 = ev[(1, gmat.CUTOFF)]
    facts = {"tdb_minus_tai_s": tdb_minus_tai_s(after1.epoch_s),
             "mjd_days": gmat.GMAT_MJD_OFFSET_JD - 2400000.5,
             "inc_icrf_deg": inclination_icrf_deg(after1),
             "inc_deg": res.burns[0].solution.summary()["inc_end_deg"],
             "propagates": sum(ln.startswith("Propagate ") for ln in script.splitlines())}
    page.table("settings", settings_table(script, defaults, costs, facts), caption=(
        f"What GMAT must be told to fly lunarcap's dynamics ({plan.name}): the script's "
        "line, GMAT's default, and what leaving that one setting at the default costs the "
        "capture (flown in lunarcap)."),
        columns={"setting": "setting", "script": "the exported script",
                 "gmat_default": "GMAT's default", "cost": "left at the default"})
    page.value("g0_default", defaults["g0_mps2"])
    for key, name in (("g0", "g0"), ("gm", "gm"), ("one-direction", "one_direction"),
                      ("pole", "pole")):
        cst = costs.get(key)
        for q in ("burn1_m", "burn1_mmps", "rp_m", "end_m", "coast1_m"):
            page.value(f"cost_{name}_{q}", None if cst is None else cst[q],
                       why="the plan's J2 is not about its frame's pole")
    page.value("cost_g0_rp_km", None if "g0" not in costs else costs["g0"]["rp_m"] * 1e-3)
    page.value("cost_one_direction_burn1_km", costs["one-direction"]["burn1_m"] * 1e-3)
    page.value("inc_icrf_deg", facts["inc_icrf_deg"])
    page.value("inc_deg", facts["inc_deg"])
    page.value("tdb_minus_tai_s", facts["tdb_minus_tai_s"])
    page.value("n_propagates", facts["propagates"])


def _headline(page: Page, plans) -> None:
    t = page.text
    more = ""
    if len(plans) > 1:
        more = (f"; in {t('case2_forces')} ({t('case2_name')}) within "
                f"{t('case2_burn_max_m', '.2g', ' m')} and "
                f"{t('case2_burn_max_mmps', '.2g', ' mm/s')}, the final orbit within "
                f"{t('case2_final_max_m', '.2g', ' m')}")
    page.headline(
        f"NASA's GMAT flies lunarcap's exported script of {t('case1_name')} as lunarcap "
        f"does: every burn ends within {t('case1_burn_max_m', '.2g', ' m')} and "
        f"{t('case1_burn_max_mmps', '.2g', ' mm/s')} of lunarcap's cut-off, and the whole "
        f"capture flown open loop on a final orbit within "
        f"{t('case1_final_max_m', '.2g', ' m')} of lunarcap's{more}. Left at GMAT's "
        f"default, the thruster's g0 alone would move the final perilune by "
        f"{t('cost_g0_rp_km', '+.1f', ' km')}.")
