"""The "Hand the plan to other tools" page (notebooks/exchange.ipynb).

:func:`build` solves a plan (cached), exports it with :func:`lunarcap.capture.export.export_plan`
into ``book/generated/export/<output_name>/`` and reads the files back: the OEM with
lunarcap's reader for the picture, the SPK through SPICE against the OEM, the OEM in UTC
against the OEM in TDB. Its tables list the files (size) and the OEM's segments (states,
interpolation error); its values are the export time and the round trips' residuals.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.exchange import ccsds, spk
from lunarcap.exchange.burn_files import read_maneuvers
from lunarcap.physics import constants as C
from lunarcap.physics.epochs import calendar_from_seconds, leap_second_table
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.figures import exchange as draw
from lunarcap.report.page import Page
from lunarcap.repro import paths

NOTEBOOK = "notebooks/exchange.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 120, (
    Execution(
        "exchange", "Hand the plan to other tools",
        parameters=dict(plan="song2011-150N", dynamics=None),
        quick_parameters=dict(dynamics="two-body"),
        outputs=(table_files("exchange", "files", "segments")
                 + figure_files("exchange", "trajectory"))),
))

#: What each exported file is, for the files table.
FILE_KINDS = {"oem": "CCSDS OEM 2.0 (KVN): states, one segment per arc",
              "spk": "SPICE SPK (type 9): the same states",
              "attitude": "thrust direction (ICRF), thrust and mass every 1 s of each burn",
              "maneuvers": "one row per burn: ignition, duration, ΔV and its mean direction",
              "gmat_script": "GMAT script: each burn, then the whole capture, in GMAT",
              "gmat_gravity": "the lunar field the script reads (GMAT's COF format)",
              "gmat_moon": "the Moon's states (SPK) for the script's fixed-pole Moon",
              "gmat_runner": "the command that runs the script (a field in GMAT's Luna)"}


def files_table(export) -> pd.DataFrame:
    """The exported files: kind, name, size (kB), what each holds, a link to download it.

    The files are written below ``book/generated/export/``, so the built book serves them:
    ``download`` is the MyST link to each (the CSV keeps the plain name in ``file``).
    """
    return pd.DataFrame([{"kind": k, "file": p.name, "size_kB": export.sizes_bytes[k] / 1e3,
                          "what": FILE_KINDS[k],
                          "download": f"{{download}}`{p.name} <{paths.relative_to_page(p)}>`"}
                         for k, p in export.files.items()])


def segments_table(export) -> pd.DataFrame:
    """The OEM's segments: name, start and stop (TDB), states and interpolation error (m)."""
    return pd.DataFrame([{"segment": s["name"],
                          "start_tdb": calendar_from_seconds(s["start_s"], 0),
                          "stop_tdb": calendar_from_seconds(s["stop_s"], 0),
                          "states": s["states"],
                          "interpolation_error_m": s["interpolation_error_m"]}
                         for s in export.segments])


def spk_against_oem_m(oem_path, spk_path, object_id: int = spk.DEFAULT_OBJECT_ID) -> float:
    """Largest distance (m) between the SPK, read through SPICE, and the OEM's states."""
    worst = 0.0
    for seg in ccsds.read_oem(oem_path):
        inner = seg.t_s[1:-1]   # inside the segment: SPICE may take a neighbour at its ends
        x = spk.read_spk(spk_path, inner, object_id)
        worst = max(worst, float(np.max(np.linalg.norm(x[:3] - seg.r_km[:, 1:-1], axis=0))))
    return worst * 1e3


def utc_against_tdb_s(oem_tdb, oem_utc) -> float:
    """Largest difference (s) between the epochs of the same states written in TDB and UTC."""
    a, b = ccsds.read_oem(oem_tdb), ccsds.read_oem(oem_utc)
    return float(max(np.max(np.abs(x.t_s - y.t_s)) for x, y in zip(a, b)))


def trajectory_arcs(oem_path) -> list:
    """(name, xyz (3, N) km ICRF, is_burn) of each OEM segment, for the figure."""
    return [(s.name, s.r_km, s.name.startswith("burn")) for s in ccsds.read_oem(oem_path)]


def export_dir(output_name: str = "exchange"):
    """Where the book keeps this page's exported files (a Path): the links of its tables.

    ``book/generated/export/<output_name>/``: the notebook exports the capture there.
    """
    return paths.export_dir(output_name)


def build(result, ex, ex_utc, output_name: str = "exchange", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The page of a capture exported in the notebook (see the module docstring).

    Parameters
    ----------
    result : lunarcap.CaptureResult
        :func:`lunarcap.solve`'s verified capture (its plan names the page's files).
    ex, ex_utc : lunarcap.capture.export.Export
        ``result.export(export_dir(output_name))`` and the same in UTC
        (``export_dir(output_name) / "utc"``, ``time_system="UTC"``).
    output_name : prefix of the tables and figures, and the export directory's name
    quick : recorded in the provenance only
    parameters : dict, optional
        The notebook's parameters (``plan``: the name shown; ``dynamics``: the plan's),
        shown in the page's provenance.
    """
    p = result.plan
    params = dict(parameters or {})
    plan = params.get("plan", p.name)
    page = Page(NOTEBOOK, params, output_name, quick)
    page.table("files", files_table(ex),
               caption=(f"The files `lunarcap plan {plan} --export DIR` writes "
                        f"({p.dynamics} dynamics), their sizes (kB) and contents; each "
                        "can be downloaded from its link."),
               columns={"kind": "kind", "download": "file", "size_kB": "size (kB)",
                        "what": "contents"}, floatfmt={"size_kB": ".1f"},
               show_columns=["kind", "download", "size_kB", "what"])
    page.table("segments", segments_table(ex),
               caption=("The OEM's segments (TDB) and the largest error of the file's own "
                        "interpolation (Lagrange, degree 7) half-way between its states, "
                        "against the propagated trajectory (m)."),
               columns={"segment": "segment", "start_tdb": "start (TDB)",
                        "stop_tdb": "stop (TDB)", "states": "states",
                        "interpolation_error_m": "interpolation error (m)"},
               floatfmt={"interpolation_error_m": ".1e"})
    page.figure("trajectory", draw.plot_exported_trajectory(trajectory_arcs(ex.files["oem"]),
                                                       C.R_MOON),
                caption=(f"The capture of {p.name} as read back from the exported OEM: "
                         "Moon-centred ICRF, x-y and x-z projections (km); "
                         f"{draw.burn_colour_words(p.n_burns)}."),
                alt="Two projections of the exported capture trajectory around the Moon")
    man = read_maneuvers(ex.files["maneuvers"])
    leap = leap_second_table()
    page.value("plan", p.name)
    page.value("dynamics", p.dynamics)
    page.value("export_s", ex.seconds)
    page.value("total_kB", sum(ex.sizes_bytes.values()) / 1e3)
    for k in ex.files:
        page.value(f"{k}_kB", ex.sizes_bytes[k] / 1e3)
    page.value("max_interpolation_error_m", ex.max_interpolation_error_m)
    page.value("spk_vs_oem_m", spk_against_oem_m(ex.files["oem"], ex.files["spk"]))
    page.value("utc_vs_tdb_s", utc_against_tdb_s(ex.files["oem"], ex_utc.files["oem"]))
    page.value("object_id", ex.object_id)
    page.value("n_segments", len(ex.segments))
    page.value("first_ignition_tdb", calendar_from_seconds(man[0]["ignition_et_s"], 3))
    page.value("first_ignition_utc", calendar_from_seconds(man[0]["ignition_et_s"], 3,
                                                           scale="UTC"))
    page.value("leap_expires", leap["expires"])
    page.value("tai_utc_s", leap["tai_minus_utc_s"])
    page.expect("the OEM's interpolation is within 1 m", ex.max_interpolation_error_m < 1.0)
    page.expect("the SPK read through SPICE is within 1 m of the OEM",
                page.values["spk_vs_oem_m"] < 1.0)
    page.expect("UTC and TDB files hold the same instants (their microsecond roundings)",
                page.values["utc_vs_tdb_s"] < 1.2e-6)
    t = page.text
    page.headline(f"`{plan}` exported as a CCSDS OEM, a SPICE SPK, attitude and maneuver "
                  f"files: the OEM's interpolation stays within "
                  f"{t('max_interpolation_error_m', '.1g', ' m')} of the propagated states, and "
                  f"the SPK within {t('spk_vs_oem_m', '.1g', ' m')} of the OEM.")
    return page
