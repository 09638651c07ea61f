"""The Fig. 1 page (notebooks/fig1_geometry.ipynb): the thrust angles in the RTN frame.

:func:`build` places an illustrative thrust direction (angles alpha, beta of Eq. (14))
at a point of a capture ellipse (:func:`lunarcap.report.figdata.fig1_geometry`, with the
RTN basis of the dynamics, :func:`lunarcap.physics.frames.rtn_basis`), draws it
(:func:`lunarcap.report.figures.plot_fig1_geometry`) and lists the drawn vectors. No
ephemeris and no solver are used.
"""

from __future__ import annotations

import math

import matplotlib.pyplot as plt

from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import constants as C
from lunarcap.report import figdata, figures
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.page import Page

NOTEBOOK = "notebooks/fig1_geometry.ipynb"
BOOK = BookPage(NOTEBOOK, "The paper's figures", 10, (
    Execution(
        "fig1_geometry", "Fig. 1: thrust angles in the RTN frame",
        parameters=dict(alpha_deg=55.0, beta_deg=30.0, true_anomaly_deg=-40.0, period_h=12.235),
        outputs=figure_files("fig1_geometry", "rtn") + table_files("fig1_geometry", "vectors")),
))


def build(alpha_deg: float = 55.0, beta_deg: float = 30.0, true_anomaly_deg: float = -40.0,
          period_h: float = 12.235, output_name: str = "fig1_geometry",
          quick: bool = False) -> Page:
    """The page of Fig. 1 (see the module docstring).

    Parameters
    ----------
    alpha_deg, beta_deg : float
        In-plane and out-of-plane thrust angles of the drawn direction, deg.
    true_anomaly_deg : float
        Spacecraft position on the ellipse, deg (negative: before perilune).
    period_h : float
        Period of the drawn ellipse (100 km perilune altitude), h.
    output_name : str
        Prefix of the figure and CSV files.
    quick : bool
        Recorded in the provenance only (nothing here is coarsened).
    """
    params = dict(alpha_deg=alpha_deg, beta_deg=beta_deg, true_anomaly_deg=true_anomaly_deg,
                  period_h=period_h)
    page = Page(NOTEBOOK, params, output_name, quick, ephemeris=False)
    geo = figdata.fig1_geometry(alpha_deg=alpha_deg, beta_deg=beta_deg,
                                true_anomaly_deg=true_anomaly_deg, period_h=period_h)
    fig = figures.plot_fig1_geometry(geo)
    plt.close(fig)  # saved and shown by page.show, not as a stray output of the build cell
    page.figure(
        "rtn", fig,
        caption=(
            "Thrust geometry of Song et al. (2011), Fig. 1, redrawn. "
            f"(a) The capture ellipse of period {period_h:g} h with a "
            f"{paper_scenario().perilune_altitude_km:g} km perilune altitude, in its orbit "
            "plane, in lunar "
            f"units (1 LU = R<sub>Moon</sub> = {C.LU_KM:g} km), x towards perilune. The "
            f"spacecraft is at true anomaly {true_anomaly_deg:g}°; shown are the radial and "
            "tangential unit vectors $\\hat\\imath_r$, $\\hat\\imath_t$, the velocity "
            f"direction $\\mathbf{{v}}$ (flight-path angle γ = {geo.flight_path_angle_deg:.1f}°: "
            "$\\mathbf{v}$ and $\\hat\\imath_t$ coincide only at perilune and apolune) and the "
            "in-plane projection of the thrust direction $\\hat u$. "
            "(b) The RTN frame at the spacecraft (dimensionless unit vectors, not to scale "
            f"with (a)): α = {geo.alpha_deg:.1f}° from $\\hat\\imath_t$ towards "
            f"$\\hat\\imath_r$ (Eq. (14a)), β = {geo.beta_deg:.1f}° from the orbit plane "
            "towards $\\hat\\imath_n$ (Eq. (14b)). Angles in degrees."),
        alt=("Orbit plane with the RTN unit vectors at the spacecraft, and a 3-D view of the "
             "RTN frame with the thrust vector and the angles alpha and beta"),
        paper="Fig. 1")
    page.table(
        "vectors", geo.vectors_table(),
        caption=("The vectors drawn above, in the perifocal frame of the ellipse (x towards "
                 "perilune, z along the angular momentum): the position in LU and unit "
                 f"vectors (dimensionless). In RTN, û = ({geo.u_rtn[0]:.4f}, "
                 f"{geo.u_rtn[1]:.4f}, {geo.u_rtn[2]:.4f})."),
        floatfmt=".4f")
    page.value("alpha_deg", float(geo.alpha_deg))
    page.value("beta_deg", float(geo.beta_deg))
    page.value("gamma_deg", float(geo.flight_path_angle_deg))
    # headline checks: Eq. (14) inverts the construction of the drawn thrust direction
    page.expect("Eq. (14) gives back the drawn alpha and beta",
                abs(geo.alpha_deg - alpha_deg % 360.0) < 1e-9
                and abs(geo.beta_deg - beta_deg) < 1e-9,
                f"alpha {geo.alpha_deg:.12g} deg, beta {geo.beta_deg:.12g} deg")
    page.expect("the out-of-plane component of u is sin(beta)",
                abs(geo.u @ geo.rtn[2] - math.sin(math.radians(beta_deg))) < 1e-12)
    page.data["geometry"] = geo
    t = page.text
    page.headline(f"Eq. (14) recovers α = {t('alpha_deg', '.1f')}° and β = {t('beta_deg', '.1f')}° "
                  f"from the drawn thrust direction, with the RTN frame of the dynamics.")
    return page
