"""The Fig. 1 page (notebooks/fig1_geometry.ipynb): the thrust angles in the RTN frame.

:func:`build` places an illustrative thrust direction (angles alpha, beta of Eq. (14))
at a point of a capture ellipse (:func:`fig1_geometry`, with the RTN basis of the
dynamics, :func:`lunarcap.physics.frames.rtn_basis`), draws it
(:func:`lunarcap.report.figures.fig1_geometry.plot_fig1_geometry`) and lists the drawn
vectors. No ephemeris and no solver are used.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.mission.scenario import paper_scenario
from lunarcap.physics import constants as C
from lunarcap.physics.elements import rv_from_coe, semi_major_axis_from_period
from lunarcap.physics.frames import rtn_basis, thrust_angles_deg, thrust_direction_rtn
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.figures import fig1_geometry as draw
from lunarcap.report.page import Page

NOTEBOOK = "notebooks/fig1_geometry.ipynb"
BOOK = BookPage(NOTEBOOK, "The paper's figures", 10, (
    Execution(
        "fig1_geometry", "Fig. 1: thrust angles in the RTN frame",
        parameters=dict(alpha_deg=55.0, beta_deg=30.0, true_anomaly_deg=-40.0, period_h=12.235),
        outputs=figure_files("fig1_geometry", "rtn") + table_files("fig1_geometry", "vectors")),
))


# ---------------------------------------------------------------------- the figure's data
@dataclass
class Fig1Geometry:
    """Data of Fig. 1: an orbit, the RTN frame at the spacecraft and the thrust angles.

    The drawing frame is the orbit's perifocal frame (x to perilune, z along the
    angular momentum), in lunar units (1 LU = R_Moon). Unit vectors are dimensionless.

    Attributes
    ----------
    orbit_LU : ndarray, shape (3, N)
        The orbit (one revolution, or the bound part for a hyperbola).
    r_LU, v_hat : ndarray, shape (3,)
        Spacecraft position (LU) and velocity direction.
    rtn : ndarray, shape (3, 3)
        Rows i_r, i_t, i_n in the drawing frame (Eq. A5, :func:`lunarcap.physics.frames.rtn_basis`).
    u_rtn : ndarray, shape (3,)
        Thrust direction in RTN.
    u, u_plane : ndarray, shape (3,)
        Thrust direction and its unit projection on the orbit plane, drawing frame.
    alpha_deg, beta_deg : float
        Angles recovered from ``u_rtn`` with Eq. (14).
    flight_path_angle_deg : float
        Angle between v and i_t (zero at perilune and apolune).
    alpha_arc, beta_arc : ndarray, shape (3, M)
        Unit-radius arcs from i_t to ``u_plane`` (alpha) and from ``u_plane`` to ``u`` (beta).
    """

    orbit_LU: np.ndarray
    r_LU: np.ndarray
    v_hat: np.ndarray
    rtn: np.ndarray
    u_rtn: np.ndarray
    u: np.ndarray
    u_plane: np.ndarray
    alpha_deg: float
    beta_deg: float
    flight_path_angle_deg: float
    alpha_arc: np.ndarray
    beta_arc: np.ndarray

    def vectors_table(self):
        """The vectors of the figure as a DataFrame (name, x, y, z in the drawing frame)."""
        import pandas as pd

        rows = [("r (LU)", *self.r_LU), ("v/|v|", *self.v_hat), ("i_r", *self.rtn[0]),
                ("i_t", *self.rtn[1]), ("i_n", *self.rtn[2]), ("u", *self.u),
                ("u projected on orbit plane (unit)", *self.u_plane)]
        return pd.DataFrame(rows, columns=["vector", "x", "y", "z"])


def _arc(a: np.ndarray, b: np.ndarray, angle: float, n: int = 60) -> np.ndarray:
    """Unit-radius arc from unit vector ``a`` through ``angle`` (rad) towards ``b`` (a.b = 0)."""
    s = np.linspace(0.0, angle, n)
    return np.outer(a, np.cos(s)) + np.outer(b, np.sin(s))


def fig1_geometry(u_rtn=None, alpha_deg: float = 55.0, beta_deg: float = 30.0,
                  true_anomaly_deg: float = -40.0,
                  period_h: float = paper_scenario().capture_periods_s[0] / 3600,
                  altitude_km: float = paper_scenario().perilune_altitude_km,
                  mu: float = C.MU_MOON) -> Fig1Geometry:
    """Compute the data of Fig. 1 for a thrust direction on an example capture ellipse.

    Parameters
    ----------
    u_rtn : array_like, shape (3,), optional
        Thrust direction in RTN; by default from ``alpha_deg``, ``beta_deg``.
    alpha_deg, beta_deg : float
        Thrust angles (deg) used when ``u_rtn`` is not given.
    true_anomaly_deg : float
        Spacecraft position on the orbit, deg.
    period_h : float
        Orbit period, h (default: the paper's first capture ellipse, 12.235 h).
    altitude_km : float
        Perilune altitude, km.
    mu : float
        Gravitational parameter, km^3/s^2.

    Returns
    -------
    Fig1Geometry
    """
    if u_rtn is None:
        u_rtn = thrust_direction_rtn(alpha_deg, beta_deg)
    u_rtn = np.asarray(u_rtn, dtype=float)
    if u_rtn.shape != (3,) or not np.isfinite(u_rtn).all() or np.linalg.norm(u_rtn) == 0:
        raise ValueError("u_rtn must be a finite non-zero 3-vector")
    u_rtn = u_rtn / np.linalg.norm(u_rtn)
    rp = C.R_MOON + altitude_km
    a = semi_major_axis_from_period(period_h * 3600.0, mu)
    e = 1.0 - rp / a
    nu = math.radians(true_anomaly_deg)
    r, v = rv_from_coe(a, e, 0.0, 0.0, 0.0, nu, mu)
    r, v = np.asarray(r, float).ravel(), np.asarray(v, float).ravel()
    q = rtn_basis(r, v)  # rows i_r, i_t, i_n
    u = q.T @ u_rtn
    u_inplane = u - (u @ q[2]) * q[2]
    alpha, beta = thrust_angles_deg(u_rtn)
    alpha, beta = float(alpha), float(beta)
    nrm = np.linalg.norm(u_inplane)
    u_plane = u_inplane / nrm if nrm > 1e-12 else q[1].copy()
    alpha_arc = _arc(q[1], q[0], math.radians(alpha))
    beta_arc = _arc(u_plane, q[2], math.radians(beta))
    nus = np.linspace(-math.pi, math.pi, 361)
    orbit = np.array([np.asarray(rv_from_coe(a, e, 0.0, 0.0, 0.0, th, mu)[0], float).ravel()
                      for th in nus]).T / C.LU_KM
    vhat = v / np.linalg.norm(v)
    gamma = math.degrees(math.atan2(vhat @ q[0], vhat @ q[1]))
    return Fig1Geometry(orbit, r / C.LU_KM, vhat, q, u_rtn, u, u_plane, alpha, beta, gamma,
                        alpha_arc, beta_arc)


# ---------------------------------------------------------------------- the page
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
    geo = fig1_geometry(alpha_deg=alpha_deg, beta_deg=beta_deg,
                                true_anomaly_deg=true_anomaly_deg, period_h=period_h)
    fig = draw.plot_fig1_geometry(geo)
    plt.close(fig)  # saved and shown by page.show, not as a stray output of the build cell
    page.figure(
        "rtn", fig,
        caption=(
            f"(a) The ellipse of period {period_h:g} h (LU), the spacecraft at true anomaly "
            f"{true_anomaly_deg:g}°: RTN axes, velocity (γ = {geo.flight_path_angle_deg:.1f}°) "
            f"and thrust in plane. (b) The RTN frame: α = {geo.alpha_deg:.1f}° (Eq. 14a), "
            f"β = {geo.beta_deg:.1f}° (Eq. 14b)."),
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
