"""The "Design your own capture in Python" page (notebooks/tutorial.ipynb): a worked example.

The notebook's own cells compute everything through the public API (``import
lunarcap``): a plan for a spacecraft that is not the paper's, solved and verified, its
table and figure, one missed-thrust case, a small dispersion run, the export and the
flight in NASA's GMAT. This module only does what formats the book: :func:`start` makes
the page (its provenance block) and :func:`finish` reads the results the cells computed
into the numbers the prose quotes (glue) and the physical truths the build asserts
(:meth:`lunarcap.report.page.Page.check`): every burn verified, the targets met on the
re-flown capture, GMAT's flight of the exported script within its gates, the studies
answered from the same nominal.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from lunarcap.capture.gmat_flight import TOL_FINAL_RADII_M
from lunarcap.optim import gate as V
from lunarcap.physics import constants as C
from lunarcap.report.contents import BookPage, Execution
from lunarcap.report.page import Page, solver_description

NOTEBOOK = "notebooks/tutorial.ipynb"
BOOK = BookPage(NOTEBOOK, "Results", 15, (
    Execution(
        "tutorial", "Design your own capture in Python",
        # the plan's own dynamics (full: J2, Earth and Sun) and a small dispersion run;
        # the quick book flies it in two-body dynamics with two samples
        parameters=dict(dynamics=None, samples=20, workers=2),
        quick_parameters=dict(dynamics="two-body", samples=2, workers=1),
        expected_s=80),  # measured alone: 80 s with its NLPs compiled, 29 s without (load 2-4)
))

#: Two solves of one plan agree to this (m/s): the dispersions' nominal is the plan solved.
SAME_NOMINAL_MPS = 0.01
#: A study's nominal, with free periods, may not cost more than the plan itself (m/s).
FREE_PERIODS_TOL_MPS = 0.05


def start(parameters: dict, output_name: str, quick: bool) -> Page:
    """The tutorial's page, before anything is computed: its provenance and parameters.

    Parameters
    ----------
    parameters : dict
        The notebook's parameters as run (``dynamics``, ``samples``, ``workers``), named
        in the provenance block.
    output_name : str
        The page's output name (its glue and files).
    quick : bool
        A quick-book run (two-body dynamics, two samples).
    """
    return Page(NOTEBOOK, dict(parameters), output_name, quick, solver=solver_description())


def finish(page: Page, res, missed, disp, files, flight) -> Page:
    """Quote and check what the tutorial's cells computed; remove the exported files.

    Parameters
    ----------
    page : Page
        From :func:`start`.
    res : lunarcap.CaptureResult
        The plan solved (:func:`lunarcap.solve`).
    missed : lunarcap.StudyResult
        One missed-thrust case (:func:`lunarcap.missed`).
    disp : lunarcap.StudyResult
        The dispersion run (:func:`lunarcap.dispersions`).
    files : dict of str to Path
        The exported files (``res.export(...).files``); their directory is removed once
        read if it lies below the system's temporary directory (the notebook's
        ``tempfile.mkdtemp``; the book's export page keeps its files for download).
    flight : lunarcap.GmatFlight
        The capture flown in GMAT (:meth:`lunarcap.CaptureResult.fly_in_gmat`).

    Returns
    -------
    Page
        ``page``, its values, headline and checks set (glue, then check, in the notebook).
    """
    _capture(page, res)
    _missed(page, res, missed)
    _dispersions(page, res, disp)
    _gmat(page, files, flight)
    page.headline(
        f"A plan of your own through the Python API: {page.text('thrust_N', '.0f')} N "
        f"on {page.text('mass_kg', '.0f')} kg captured in {page.text('n_burns', '.0f')} "
        f"burns for {page.text('total_delta_v_mps', '.1f', ' m/s')} "
        f"(loss {page.text('total_delta_v_loss_mps', '.1f', ' m/s')}), then flown again "
        f"in GMAT to within {page.text('gmat_final_radii_m', '.2g', ' m')} of lunarcap's "
        f"final orbit.")
    _remove_temporary({Path(p).parent for p in files.values()})
    return page


def _remove_temporary(dirs) -> None:
    """Remove the directories below the system's temporary directory (the notebook's).

    Any other directory is left alone: a reader who exported into their own keeps it.
    """
    tmp = Path(tempfile.gettempdir()).resolve()
    for d in dirs:
        d = Path(d).resolve()
        if d != tmp and d.is_relative_to(tmp):
            shutil.rmtree(d, ignore_errors=True)


def _capture(page: Page, res) -> None:
    """The plan's engine and totals; its burns verified and its targets met as flown."""
    plan, tot, rows = res.plan, res.totals(), res.rows()
    page.value("plan_name", plan.name)
    page.value("thrust_N", plan.engine.thrust_N)
    page.value("isp_s", plan.engine.isp_s)
    page.value("mass_kg", plan.arrival.mass_kg)
    page.value("n_burns", plan.n_burns)
    page.value("first_target", plan.burns[0].describe())
    page.value("dynamics_named", plan.dynamics if isinstance(plan.dynamics, str)
               else "the plan's named forces")
    for k in ("total_delta_v_mps", "total_impulsive_limit_mps", "total_delta_v_loss_mps",
              "total_delta_v_loss_percent", "total_fuel_kg", "final_mass_kg",
              "time_to_final_orbit_h"):
        page.value(k, tot[k])
    circle_km = C.R_MOON + plan.arrival.perilune_altitude_km
    page.value("final_altitude_km", plan.arrival.perilune_altitude_km)
    page.expect("every burn solved and verified by re-propagation", res.verified,
                f"{len(res.burns)} of {plan.n_burns} burns")
    worst = max(abs(tot["final_rp_km"] - circle_km), abs(tot["final_ra_km"] - circle_km))
    page.expect(f"the re-flown final orbit is the {circle_km:.1f} km circle within "
                f"{V.TOL_RP_M:g} m", worst * 1e3 <= V.TOL_RP_M, f"{worst * 1e3:.3g} m")
    period = [r.get("verification_period_error_s") for r in rows[:-1]]
    page.expect(f"every ellipse's period met within {V.TOL_PERIOD_S:g} s as flown",
                all(p is not None and abs(p) <= V.TOL_PERIOD_S for p in period), str(period))
    page.expect("a finite burn costs more than its impulse", tot["total_delta_v_loss_mps"] > 0,
                f"{tot['total_delta_v_loss_mps']:.3f} m/s")


def _missed(page: Page, res, missed) -> None:
    """The missed-thrust case: answered, recovered to the same final orbit."""
    row = missed.to_frame().iloc[0]
    for k in ("fraction", "delay_min", "penalty_mps", "recovery_delta_v_mps",
              "time_to_final_orbit_h", "nominal_remaining_delta_v_mps",
              "nominal_time_to_final_orbit_h"):
        page.value(f"missed_{k}", row[k])
    page.value("missed_status", row["status"])
    page.expect("the missed-thrust case is answered and recovered",
                missed.answered and row["status"] == "recovered", f"{row['status']}: "
                f"{row['reason']}")
    page.expect("the study's nominal (free periods) costs no more than the plan",
                row["nominal_remaining_delta_v_mps"]
                <= res.totals()["total_delta_v_mps"] + FREE_PERIODS_TOL_MPS,
                f"{row['nominal_remaining_delta_v_mps']:.3f} m/s")


def _dispersions(page: Page, res, disp) -> None:
    """The dispersion run: every sample answered, its nominal the plan solved."""
    s = disp.to_dict()["summary"]
    page.value("samples", s["samples"])
    page.value("captured", s["captured_and_corrected"])
    for k in ("mean_above_nominal_mps", "mean_above_nominal_se_mps", "trim_max_mps",
              "final_max_abs_rp_error_km"):
        page.value(f"disp_{k}", s[k])
    page.expect("every dispersed sample captured and corrected",
                disp.answered and s["captured_and_corrected"] == s["samples"],
                f"{s['captured_and_corrected']} of {s['samples']}")
    gap = abs(s["nominal_delta_v_mps"] - res.totals()["total_delta_v_mps"])
    page.expect("the dispersions' nominal is the plan solved",
                gap <= SAME_NOMINAL_MPS, f"{gap:.3g} m/s apart")


def _gmat(page: Page, files: dict, flight) -> None:
    """The export and GMAT's flight of it: within the gates, final orbit within 50 m."""
    page.value("files", ", ".join(f"`{Path(p).name}`" for p in files.values()))
    page.value("n_files", len(files))
    c = flight.comparison
    burn_m = max(b["position_diff_m"] for b in c.burns)
    end = c.capture[-1]
    radii_m = max(max(abs(f["rp_diff_m"]), abs(f["ra_diff_m"])) for f in c.final_orbit)
    page.value("gmat_burn_max_m", burn_m)
    page.value("gmat_end_m", end["position_diff_m"])
    page.value("gmat_final_radii_m", radii_m)
    page.value("gmat_gate_final_m", TOL_FINAL_RADII_M)
    page.value("gmat_s", c.gmat_wall_s)
    page.expect("GMAT flies the exported script within every gate", flight.passed,
                "; ".join(flight.failures()))
    page.expect(f"GMAT's final orbit within {TOL_FINAL_RADII_M:g} m of lunarcap's",
                radii_m < TOL_FINAL_RADII_M, f"{radii_m:.3g} m")
    page.expect("the export holds the OEM and the GMAT script",
                {"oem", "gmat_script"} <= set(files), str(sorted(files)))
