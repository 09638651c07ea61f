"""Figures and tables for the book: data functions, drawing functions and display helpers.

Each figure has a *data* function returning plain arrays (tested) and a *drawing*
function that only draws them (not tested pixel by pixel). The display helpers
write a table (CSV) or figure (PNG + SVG) below ``book/generated/`` through
:mod:`lunarcap.repro.paths` and show it in the notebook as a numbered MyST ``table`` or
``figure`` with a caption and a note naming the notebook and parameters that made it.

This module is presentation only: no physics is defined here (the RTN frame comes
from :func:`lunarcap.physics.frames.rtn_basis`, orbits from :mod:`lunarcap.physics.elements`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import matplotlib
import matplotlib.pyplot as plt
import numpy as np

from lunarcap.physics import constants as C
from lunarcap.repro import paths
from lunarcap.physics.elements import rv_from_coe, semi_major_axis_from_period
from lunarcap.physics.frames import rtn_basis, thrust_angles_deg, thrust_direction_rtn  # noqa: F401
from lunarcap.report.provenance import source_note

# Reproducible SVG output (no random ids, no date).
matplotlib.rcParams["svg.hashsalt"] = "lunarcap"


# =============================================================================== Fig. 1
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
                  period_h: float = C.CAPTURE_PERIODS_S[0] / 3600,
                  altitude_km: float = C.PERILUNE_ALTITUDE_KM,
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


def _text_align(vec) -> dict:
    """Horizontal/vertical alignment that puts a label beyond the tip of a 2-D arrow."""
    ha = "left" if vec[0] > 0.35 else ("right" if vec[0] < -0.35 else "center")
    va = "bottom" if vec[1] > 0.35 else ("top" if vec[1] < -0.35 else "center")
    return {"ha": ha, "va": va}


def plot_fig1_geometry(geo: Fig1Geometry, figsize=(7.0, 6.8)):
    """Draw Fig. 1: (a) the orbit plane with i_r, i_t, v and alpha; (b) the RTN triad, u, beta.

    Parameters
    ----------
    geo : Fig1Geometry from :func:`fig1_geometry`
    figsize : (width, height), inches

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = plt.figure(figsize=figsize, layout="constrained")
    gs = fig.add_gridspec(2, 1, height_ratios=(1.0, 0.9))
    ax = fig.add_subplot(gs[0])
    ax3 = fig.add_subplot(gs[1], projection="3d")
    col = {"r": "tab:red", "t": "tab:green", "n": "tab:blue", "u": "black", "v": "0.45"}

    # ---------------------------------------------------------------- (a) orbit plane
    ax.add_patch(plt.Circle((0, 0), 1.0, color="0.85", zorder=0))
    ax.text(0, 0, "Moon", ha="center", va="center", fontsize=9)
    ax.plot(geo.orbit_LU[0], geo.orbit_LU[1], color="0.3", lw=1, label="capture orbit")
    rx, ry = geo.r_LU[:2]
    ax.plot([0, rx], [0, ry], color="0.6", lw=0.8, ls=":")
    ax.plot(rx, ry, "o", color="black", ms=5, zorder=5)
    ax.annotate("spacecraft", (rx, ry), xytext=(-6, -6), textcoords="offset points", fontsize=9,
                ha="right", va="top")
    span = np.ptp(geo.orbit_LU[:2], axis=1).max()
    s = 0.22 * span
    tips = [(x, y) for x, y in geo.orbit_LU[:2].T]
    arrows = (("r", geo.rtn[0], r"$\hat\imath_r$"), ("t", geo.rtn[1], r"$\hat\imath_t$"),
              ("v", geo.v_hat, r"$\mathbf{v}$"), ("u", geo.u_plane, r"$\hat u$ projected"))
    for key, vec, lab in arrows:
        ls = "--" if key == "u" else "-"
        ax.annotate("", xy=(rx + s * vec[0], ry + s * vec[1]), xytext=(rx, ry),
                    arrowprops=dict(arrowstyle="-|>", color=col[key], lw=1.6, ls=ls),
                    annotation_clip=False)
        tips.append((rx + 1.25 * s * vec[0], ry + 1.25 * s * vec[1]))
        ax.text(rx + 1.06 * s * vec[0], ry + 1.06 * s * vec[1], lab, color=col[key],
                fontsize=11, **_text_align(vec))
    arc = 0.45 * s * geo.alpha_arc
    ax.plot(rx + arc[0], ry + arc[1], color="tab:purple", lw=1.2)
    mid = geo.alpha_arc[:, geo.alpha_arc.shape[1] // 2]
    ax.text(rx + 0.55 * s * mid[0], ry + 0.55 * s * mid[1], r"$\alpha$", color="tab:purple",
            fontsize=13, **_text_align(mid))
    tips = np.array(tips)
    pad = 0.05 * span
    ax.set_xlim(tips[:, 0].min() - pad, tips[:, 0].max() + 4 * pad)  # room for the labels
    ax.set_ylim(tips[:, 1].min() - pad, tips[:, 1].max() + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x, towards perilune (LU)")
    ax.set_ylabel("y (LU)")
    ax.set_title("(a) orbit plane", fontsize=11, loc="left")
    ax.grid(alpha=0.3)

    # ---------------------------------------------------------------- (b) RTN triad
    # Show the triad in its own axes (r, t, n) so the view is independent of the orbit.
    def rtn(vec):
        return geo.rtn @ np.asarray(vec)

    for key, e, lab in (("r", (1, 0, 0), r"$\hat\imath_r$"), ("t", (0, 1, 0), r"$\hat\imath_t$"),
                        ("n", (0, 0, 1), r"$\hat\imath_n$")):
        ax3.quiver(0, 0, 0, *e, color=col[key], arrow_length_ratio=0.08, lw=1.8)
        ax3.text(*(1.1 * np.array(e)), lab, color=col[key], fontsize=13, ha="center",
                 va="center")
    u = rtn(geo.u)
    up = rtn(geo.u_plane)
    ax3.quiver(0, 0, 0, *u, color=col["u"], arrow_length_ratio=0.08, lw=2.2)
    ax3.text(*(1.1 * u), r"$\hat u$", color=col["u"], fontsize=13, ha="center", va="center")
    ax3.plot([0, up[0]], [0, up[1]], [0, 0], color=col["u"], ls="--", lw=1.2)
    ax3.plot([up[0], u[0]], [up[1], u[1]], [0, u[2]], color="0.6", ls=":", lw=1)
    aa = 0.45 * (geo.rtn @ geo.alpha_arc)
    ba = 0.7 * (geo.rtn @ geo.beta_arc)
    ax3.plot(*aa, color="tab:purple", lw=1.4)
    ax3.plot(*ba, color="tab:orange", lw=1.4)
    am = aa[:, aa.shape[1] // 2] * 1.3
    bm = ba[:, ba.shape[1] // 2] * 1.15
    ax3.text(*am, r"$\alpha$", color="tab:purple", fontsize=13)
    ax3.text(*bm, r"$\beta$", color="tab:orange", fontsize=13)
    # the orbit plane (r-t plane) as a faint square
    sq = np.array([[-1, -1, 1, 1, -1], [-1, 1, 1, -1, -1], [0, 0, 0, 0, 0]]) * 1.05
    ax3.plot(*sq, color="0.8", lw=0.8)
    ax3.set_xlim(-1, 1)
    ax3.set_ylim(-1, 1)
    ax3.set_zlim(-0.2, 1.1)
    ax3.set_box_aspect((1, 1, 0.65), zoom=1.45)
    ax3.view_init(elev=25, azim=-70)
    ax3.set_axis_off()
    ax3.text2D(0.0, 0.88, "(b) RTN frame at the spacecraft", fontsize=11,
               transform=ax3.transAxes)
    return fig


# =============================================================================== output
def save_figure(fig, name: str, dpi: int = 150) -> dict:
    """Save ``fig`` as ``figures/<name>.png`` and ``.svg`` below ``book/generated`` atomically.

    Returns
    -------
    dict
        ``{"png": Path, "svg": Path}``.
    """
    out = {}
    for fmt in paths.FIGURE_FORMATS:
        path = paths.figure_path(name, fmt)
        meta = {"Date": None} if fmt == "svg" else {"Software": None}
        with paths.atomic_path(path) as tmp:
            fig.savefig(tmp, format=fmt, dpi=dpi, metadata=meta)
        out[fmt] = path
    return out


def markdown_table(df, floatfmt: str | dict = ".3f") -> str:
    """A Markdown pipe table of a DataFrame (numbers right-aligned).

    Parameters
    ----------
    df : pandas.DataFrame
    floatfmt : str or dict
        Format of float cells, one for all columns or per column name.
    """
    def fmt(col, v):
        if isinstance(v, (float, np.floating)):
            if not np.isfinite(v):
                return "—" if np.isnan(v) else ("∞" if v > 0 else "−∞")
            f = floatfmt.get(col, ".3f") if isinstance(floatfmt, dict) else floatfmt
            text = format(float(v), f)
            if text[:1] in "+-" and not any(ch in "123456789" for ch in text):
                text = text[1:]  # no "-0.00" for a value that rounds to zero
            return text
        return str(v).replace("|", "\\|")

    cols = list(df.columns)
    from pandas.api.types import is_numeric_dtype

    numeric = [is_numeric_dtype(df[c]) for c in cols]
    head = "| " + " | ".join(str(c).replace("|", "\\|") for c in cols) + " |"
    rule = "|" + "|".join("---:" if n else ":---" for n in numeric) + "|"
    body = ["| " + " | ".join(fmt(c, v) for c, v in zip(cols, row)) + " |"
            for row in df.itertuples(index=False)]
    return "\n".join([head, rule, *body])


def _display_markdown(text: str) -> None:
    from IPython.display import Markdown, display

    display(Markdown(text))


def show_table(df, name: str, caption: str, notebook: str, parameters: dict | None = None,
               floatfmt: str | dict = ".3f", labels: dict | None = None, label: str | None = None,
               display: bool = True) -> str:
    """Write ``df`` to ``tables/<name>.csv`` and show it as a numbered MyST table.

    Parameters
    ----------
    df : pandas.DataFrame
        Column names are those of the CSV: plain ``snake_case`` with the unit as suffix
        (``delta_v_mps``) is easiest for whoever reads the CSV back.
    name : str
        Output name (the CSV file name without extension).
    caption : str
        Caption (MyST Markdown; give units).
    notebook, parameters : the source notebook and the parameters of this run,
        named under the table (:func:`lunarcap.report.provenance.source_note`).
    floatfmt : str or dict
        Format of float cells in the displayed table, one for all or per column name
        (the CSV keeps full precision).
    labels : dict, optional
        Column name -> header shown in the book (with units), e.g.
        ``{"delta_v_mps": "ΔV (m/s)"}``.
    label : str, optional
        Cross-reference label (default ``tbl-<name>``), for ``{numref}`` from other pages.
    display : bool
        Display the Markdown (default) or only return it.

    Returns
    -------
    str
        The Markdown shown.
    """
    csv = paths.write_csv(df, name)
    label = label or f"tbl-{name}"
    rel = paths.relative_to_page(csv)
    shown = df.rename(columns=labels or {})
    if isinstance(floatfmt, dict) and labels:
        floatfmt = {labels.get(k, k): v for k, v in floatfmt.items()}
    text = (f":::{{table}} {caption}\n:name: {label}\n:align: center\n\n"
            f"{markdown_table(shown, floatfmt)}\n:::\n\n"
            f"{source_note(notebook, parameters)} Data: {{download}}`{csv.name} <{rel}>`.\n")
    if display:
        _display_markdown(text)
    return text


def show_figure(fig, name: str, caption: str, notebook: str, parameters: dict | None = None,
                alt: str | None = None, label: str | None = None, width: str = "100%",
                display: bool = True) -> str:
    """Save ``fig`` (PNG + SVG) and show the PNG as a numbered MyST figure with a caption.

    Parameters
    ----------
    fig : matplotlib.figure.Figure (closed after saving)
    name : str
        Output name (``figures/<name>.png`` and ``.svg``).
    caption : str
        Caption (MyST Markdown; give units).
    notebook, parameters : named in the caption (:func:`lunarcap.report.provenance.source_note`).
    alt : str, optional
        Alternative text (default: the caption's first sentence).
    label : str, optional
        Cross-reference label (default ``fig-<name>``).
    width : str
        Display width.
    display : bool
        Display the Markdown (default) or only return it.

    Returns
    -------
    str
        The Markdown shown.
    """
    files = save_figure(fig, name)
    plt.close(fig)
    label = label or f"fig-{name}"
    alt = alt or caption.split(". ")[0].replace("`", "").replace("$", "").replace("\\", "")
    png = paths.relative_to_page(files["png"])
    svg = paths.relative_to_page(files["svg"])
    text = (f":::{{figure}} {png}\n:name: {label}\n:alt: {alt}\n:width: {width}\n\n"
            f"{caption} {source_note(notebook, parameters)} "
            f"Files: {{download}}`PNG <{png}>`, {{download}}`SVG <{svg}>`.\n:::\n")
    if display:
        _display_markdown(text)
    return text


# =============================================================================== Figs. 2-5
# The capture sequence of Song 2011, Sec. 3.3: the whole capture (Fig. 2), the burn arcs
# (Fig. 3), the LOI-1 steering and mass (Fig. 4) and the LOI-1 thrust and velocity
# vectors (Fig. 5). The data functions sample verified Solutions (and propagate coasts
# with lunarcap.physics.propagate); the drawing functions only draw.

#: Colours of the capture-sequence figures: one per orbit, one per burn.
CAPTURE_COLOURS = {"hyperbola": "0.35", "coast1": "tab:blue", "coast2": "tab:green",
                   "coast3": "tab:purple", "burn": "tab:red",
                   "burn1": "#d62728", "burn2": "#ff7f0e", "burn3": "#8c2d04"}

_ORBIT_NAMES = {1: "1st capture orbit", 2: "2nd capture orbit", 3: "final circular orbit"}


def orbit_plane_basis(r_km, v_kmps) -> np.ndarray:
    """Projection basis of the orbit plane through ``r`` and ``v`` (M-MME2000).

    Rows ``e_x, e_y, e_n``: ``e_n`` along the angular momentum ``r x v``; ``e_y`` the
    M-MME2000 z axis projected on the orbit plane (for the paper's polar orbit, the
    z axis itself); ``e_x = e_y x e_n``, which for a polar orbit is the direction of the
    ascending node on the M-MME2000 equator. The basis is right-handed, so the orbit
    runs counter-clockwise in (x, y).

    Parameters
    ----------
    r_km, v_kmps : array_like, shape (3,)
        Position (km) and velocity (km/s), M-MME2000.

    Returns
    -------
    ndarray, shape (3, 3)
        Rows ``e_x, e_y, e_n`` (``xy = B[:2] @ r``).
    """
    r = np.asarray(r_km, float)
    v = np.asarray(v_kmps, float)
    h = np.cross(r, v)
    if not np.isfinite(h).all() or np.linalg.norm(h) == 0:
        raise ValueError("r and v must be finite and not parallel")
    e_n = h / np.linalg.norm(h)
    z = np.array([0.0, 0.0, 1.0])
    e_y = z - (z @ e_n) * e_n
    if np.linalg.norm(e_y) < 1e-9:   # equatorial orbit: use the direction of r instead
        e_y = r - (r @ e_n) * e_n
    e_y = e_y / np.linalg.norm(e_y)
    e_x = np.cross(e_y, e_n)
    return np.vstack([e_x, e_y, e_n])


@dataclass
class TrajectoryArc:
    """One piece of the capture trajectory, sampled.

    Attributes
    ----------
    kind : str
        "hyperbola" (arrival, up to LOI-1 ignition), "uncaptured" (the arrival hyperbola
        continued without LOI 1), "burn", "coast" (after a burn, up to the next ignition)
        or "final" (the extra revolution after the last coast).
    loi : int
        The LOI of a burn, or of the burn a coast follows (0 for the hyperbola).
    label : str
        Legend text.
    t_s : ndarray, shape (N,)
        Epochs, TDB s past J2000.
    r_km : ndarray, shape (3, N)
        Position, M-MME2000, km.
    xy_LU : ndarray, shape (2, N)
        Position projected on the drawing plane (:func:`orbit_plane_basis`), LU.
    out_of_plane_km : ndarray, shape (N,)
        Distance from the drawing plane, km.
    """

    kind: str
    loi: int
    label: str
    t_s: np.ndarray
    r_km: np.ndarray
    xy_LU: np.ndarray
    out_of_plane_km: np.ndarray

    @property
    def radius_km(self) -> np.ndarray:
        """Distance from the Moon's centre, km."""
        return np.linalg.norm(self.r_km, axis=0)

    @property
    def angle_deg(self) -> np.ndarray:
        """Polar angle in the drawing plane, deg (counter-clockwise from e_x)."""
        return np.degrees(np.arctan2(self.xy_LU[1], self.xy_LU[0]))


@dataclass
class CaptureGeometry:
    """Data of Figs. 2 and 3: the whole capture sequence projected on the orbit plane.

    Attributes
    ----------
    basis : ndarray, shape (3, 3)
        Rows e_x, e_y, e_n of the drawing plane in M-MME2000 (:func:`orbit_plane_basis`
        of the arrival perilune state).
    arcs : list of TrajectoryArc
        In time order (the "uncaptured" arc last).
    burns : pandas.DataFrame
        One row per LOI: ignition and cutoff epochs and polar angles, the pass's perilune
        (the flown point of least radius within 30 min of the nominal perilune epoch) and
        the angles of ignition and cutoff from it, the burn's radii.
    hyperbola_hours : float
        Length of the drawn arrival hyperbola before the arrival perilune, h.
    """

    basis: np.ndarray
    arcs: list
    burns: object
    hyperbola_hours: float

    def select(self, kind: str, loi: int | None = None) -> list:
        """The arcs of one kind (and LOI)."""
        return [a for a in self.arcs if a.kind == kind and (loi is None or a.loi == loi)]

    @property
    def max_out_of_plane_km(self) -> float:
        """Largest distance of any drawn point from the drawing plane, km."""
        return float(max(np.abs(a.out_of_plane_km).max() for a in self.arcs))


def _project(basis, r_km):
    r = np.asarray(r_km, float)
    return (basis[:2] @ r) / C.LU_KM, basis[2] @ r


def _make_arc(basis, kind, loi, label, t, r):
    xy, oop = _project(basis, r)
    return TrajectoryArc(kind, loi, label, np.asarray(t, float), np.asarray(r, float), xy, oop)


def _rv_of_states(x):
    """Positions (3, N) km from MEE states (7, N)."""
    from lunarcap.physics.elements import rv_from_mee

    r, _ = rv_from_mee(*np.asarray(x)[:6], C.MU_MOON)
    return np.array(r, float)


def _dense_grid(t0, t1, n, edge_s=1800.0):
    """Epochs from t0 to t1: n uniform plus n/2 within ``edge_s`` of each end (perilunes)."""
    lo, hi = min(t0, t1), max(t0, t1)
    parts = [np.linspace(lo, hi, n),
             np.linspace(lo, min(lo + edge_s, hi), n // 2),
             np.linspace(max(hi - edge_s, lo), hi, n // 2)]
    return np.unique(np.concatenate(parts))


def _wrap180(a):
    return (np.asarray(a, float) + 180.0) % 360.0 - 180.0


def capture_geometry(solutions, arrival, hyperbola_hours: float = 3.0,
                     uncaptured_hours: float | None = None, n_coast: int = 3000,
                     n_burn: int = 241, final_revolutions: float = 1.0,
                     perilune_window_s: float = 1800.0) -> CaptureGeometry:
    """Sample the capture sequence for Figs. 2 and 3.

    Parameters
    ----------
    solutions : list of Solution
        The chain LOI 1, 2, 3 (:func:`lunarcap.runs.chain.solve_sequence`).
    arrival : lunarcap.mission.arrival.Arrival
        The arrival perilune state (``Mission.arrival``); defines the drawing plane.
    hyperbola_hours : float
        The arrival hyperbola is drawn from this many hours before the arrival perilune
        (propagated backward from it, coasting, in the LOI-1 dynamics) to LOI-1 ignition.
    uncaptured_hours : float, optional
        Draw the hyperbola without LOI 1, from LOI-1 ignition to this many hours after
        the arrival perilune (default ``hyperbola_hours``; 0 to leave it out).
    n_coast, n_burn : int
        Samples per coast (plus extra near its ends) and per burn.
    final_revolutions : float
        Revolutions of the final orbit propagated after the last coast (coasting), in
        units of the paper's final period 117.848 min.
    perilune_window_s : float
        Half-width of the window around each nominal perilune epoch in which the flown
        perilune of a pass is looked for, s.

    Returns
    -------
    CaptureGeometry
    """
    import pandas as pd

    from lunarcap.physics.propagate import propagate

    sols = list(solutions)
    if not 1 <= len(sols) <= 3:
        raise ValueError("solutions must be the chain LOI 1[, 2[, 3]]")
    basis = orbit_plane_basis(arrival.r_km, arrival.v_kmps)
    arcs = []
    p1 = sols[0].problem
    model = p1.model
    t_peri = float(arrival.epoch_s)
    # arrival hyperbola: backward from the arrival perilune, drawn up to LOI-1 ignition
    t_start = t_peri - 3600.0 * float(hyperbola_hours)
    if not t_start < p1.t_ign_s:
        raise ValueError("hyperbola_hours must reach back before LOI-1 ignition")
    x_peri = np.asarray(arrival.state, float)
    t_back = np.linspace(p1.t_ign_s, t_start, 1500)
    if p1.t_ign_s < t_peri:
        tr = propagate(model, t_peri, x_peri, t_start, u=None, t_eval=t_back)
        t_h, x_h = tr.t[::-1], tr.x[:, ::-1]
    else:  # ignition at or after the arrival perilune
        tr = propagate(model, t_peri, x_peri, t_start, u=None,
                       t_eval=np.linspace(t_peri, t_start, 1500))
        fw = propagate(model, t_peri, x_peri, p1.t_ign_s, u=None,
                       t_eval=np.linspace(t_peri, p1.t_ign_s, 200)[1:])
        t_h = np.concatenate([tr.t[::-1], fw.t])
        x_h = np.column_stack([tr.x[:, ::-1], fw.x])
    arcs.append(_make_arc(basis, "hyperbola", 0, "arrival hyperbola", t_h, _rv_of_states(x_h)))
    # burns and coasts
    coasts_end = [s.problem.t_ign_s for s in sols[1:]] + [sols[-1].problem.t_end_s]
    rows = []
    for i, sol in enumerate(sols):
        prob = sol.problem
        loi = prob.loi
        hist = sol.history(n_burn=n_burn, n_coast=2)
        b = hist[hist.phase == "burn"]
        rb = b[["x_km", "y_km", "z_km"]].to_numpy().T
        arcs.append(_make_arc(basis, "burn", loi, f"LOI {loi} burn", b.t_s.to_numpy(), rb))
        coast = sol.flight[1]
        t_cut = float(b.t_s.iloc[-1])
        tc = _dense_grid(t_cut, coasts_end[i], n_coast)
        name = _ORBIT_NAMES.get(loi, f"orbit after LOI {loi}")
        period_txt = (f"{C.CAPTURE_PERIODS_S[loi - 1] / 3600:.3f} h" if loi < 3
                      else f"{C.CAPTURE_PERIODS_S[2] / 60:.3f} min")
        arcs.append(_make_arc(basis, "coast", loi, f"{name} ({period_txt})", tc,
                              _rv_of_states(coast.sol(tc))))
    last = sols[-1]
    if final_revolutions > 0 and len(sols) == 3:
        t0 = last.problem.t_end_s
        t1 = t0 + final_revolutions * C.CAPTURE_PERIODS_S[2]
        tf = np.linspace(t0, t1, max(int(600 * final_revolutions), 50))
        tr = propagate(last.problem.model, t0, last.end_state, t1, u=None, t_eval=tf)
        arcs.append(_make_arc(basis, "final", 3, "final orbit, one more revolution", tr.t,
                              _rv_of_states(tr.x)))
    hu = hyperbola_hours if uncaptured_hours is None else uncaptured_hours
    if hu and hu > 0:
        t1 = t_peri + 3600.0 * float(hu)
        tu = np.linspace(p1.t_ign_s, t1, 1500)
        tr = propagate(model, p1.t_ign_s, p1.x0, t1, u=None, t_eval=tu)
        arcs.append(_make_arc(basis, "uncaptured", 0, "arrival hyperbola without LOI 1",
                              tr.t, _rv_of_states(tr.x)))
    flown = [a for a in arcs if a.kind != "uncaptured"]
    t_all = np.concatenate([a.t_s for a in flown])
    r_all = np.concatenate([a.r_km for a in flown], axis=1)
    xy_all = np.concatenate([a.xy_LU for a in flown], axis=1)
    for sol in sols:
        prob = sol.problem
        burn = [a for a in arcs if a.kind == "burn" and a.loi == prob.loi][0]
        near = np.abs(t_all - prob.t_perilune_s) <= perilune_window_s
        rad = np.linalg.norm(r_all[:, near], axis=0)
        j = int(np.argmin(rad))
        t_p = float(t_all[near][j])
        ang_p = float(np.degrees(np.arctan2(xy_all[1, near][j], xy_all[0, near][j])))
        ang = burn.angle_deg
        rows.append({
            "loi": prob.loi, "ignition_s": float(burn.t_s[0]), "cutoff_s": float(burn.t_s[-1]),
            "burn_duration_min": float(burn.t_s[-1] - burn.t_s[0]) / 60.0,
            "ignition_from_nominal_perilune_min": (burn.t_s[0] - prob.t_perilune_s) / 60.0,
            "perilune_from_ignition_min": (t_p - burn.t_s[0]) / 60.0,
            "perilune_radius_km": float(rad[j]),
            "perilune_angle_deg": ang_p,
            "ignition_angle_deg": float(ang[0]), "cutoff_angle_deg": float(ang[-1]),
            "ignition_from_perilune_deg": float(_wrap180(ang[0] - ang_p)),
            "cutoff_from_perilune_deg": float(_wrap180(ang[-1] - ang_p)),
            "ignition_radius_km": float(burn.radius_km[0]),
            "cutoff_radius_km": float(burn.radius_km[-1]),
            "min_radius_km": float(burn.radius_km.min()),
        })
    burns = pd.DataFrame(rows)
    burns["arc_asymmetry_deg"] = burns.cutoff_from_perilune_deg + burns.ignition_from_perilune_deg
    return CaptureGeometry(basis, arcs, burns, float(hyperbola_hours))


def _moon(ax, radius=1.0, label=True):
    ax.add_patch(plt.Circle((0, 0), radius, color="0.85", zorder=0))
    if label:
        ax.text(0, 0, "Moon", ha="center", va="center", fontsize=9, color="0.3", zorder=1)


_PLANE_XLABEL = "x′: M-MME2000 equator, along the orbit's ascending node (LU)"
_PLANE_YLABEL = "z: M-MME2000 pole (LU)"


def plot_fig2_capture(geo: CaptureGeometry, figsize=None):
    """Draw Fig. 2: the whole capture sequence in the orbit plane, in LU.

    Parameters
    ----------
    geo : CaptureGeometry from :func:`capture_geometry`
    figsize : (width, height), inches (default: 7 in wide, height from the extent)

    Returns
    -------
    matplotlib.figure.Figure
    """
    flown = np.concatenate([a.xy_LU for a in geo.arcs if a.kind != "uncaptured"], axis=1)
    lo, hi = flown.min(axis=1) - 0.35, flown.max(axis=1) + 0.35
    if figsize is None:
        w = 7.0
        figsize = (w, float(np.clip((w - 0.9) * (hi[1] - lo[1]) / (hi[0] - lo[0]) + 0.8,
                                    4.0, 9.0)))
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    _moon(ax)
    col = CAPTURE_COLOURS
    for a in geo.select("uncaptured"):
        ax.plot(*a.xy_LU, color=col["hyperbola"], lw=0.9, ls=":", label=a.label)
    for a in geo.select("hyperbola"):
        ax.plot(*a.xy_LU, color=col["hyperbola"], lw=1.4, label=a.label)
        k = a.xy_LU.shape[1] // 3
        ax.annotate("", xy=a.xy_LU[:, k + 5], xytext=a.xy_LU[:, k],
                    arrowprops=dict(arrowstyle="-|>", color=col["hyperbola"], lw=1.4,
                                    mutation_scale=14))
    for a in geo.select("coast"):
        ax.plot(*a.xy_LU, color=col[f"coast{a.loi}"], lw=1.2, label=a.label)
    for a in geo.select("final"):
        ax.plot(*a.xy_LU, color=col["coast3"], lw=1.2)
    for i, a in enumerate(geo.select("burn")):
        ax.plot(*a.xy_LU, color=col["burn"], lw=3.2, solid_capstyle="butt",
                label="finite burn arcs (LOI 1, 2, 3)" if i == 0 else None, zorder=4)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel(_PLANE_XLABEL)
    ax.set_ylabel(_PLANE_YLABEL)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8.5, framealpha=0.9)
    return fig


def _burn_zoom_limits(geo, pad=0.25):
    xy = np.concatenate([a.xy_LU for a in geo.select("burn")], axis=1)
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    lo = np.minimum(lo, -0.05)  # keep part of the Moon in view
    span = (hi - lo).max()
    c = (lo + hi) / 2
    half = span * (0.5 + pad)
    return (c[0] - half, c[0] + half), (c[1] - half, c[1] + half)


def plot_fig3_burn_arcs(geo: CaptureGeometry, figsize=(7.0, 10.0)):
    """Draw Fig. 3: (a) zoom of Fig. 2 on the burn arcs; (b) their altitudes.

    Panel (b) plots the altitude of each perilune pass (km) against the polar angle in
    the orbit plane measured from that pass's perilune (deg), which separates the three
    arcs that overlap in (a).

    Parameters
    ----------
    geo : CaptureGeometry from :func:`capture_geometry`
    figsize : (width, height), inches

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = plt.figure(figsize=figsize, layout="constrained")
    gs = fig.add_gridspec(2, 1, height_ratios=(1.35, 1.0))
    ax = fig.add_subplot(gs[0])
    ax2 = fig.add_subplot(gs[1])
    col = CAPTURE_COLOURS
    _moon(ax, label=False)
    for a in geo.select("uncaptured"):
        ax.plot(*a.xy_LU, color=col["hyperbola"], lw=0.8, ls=":")
    for a in geo.select("hyperbola"):
        ax.plot(*a.xy_LU, color=col["hyperbola"], lw=1.0, label="arrival hyperbola")
    for a in geo.select("coast"):
        ax.plot(*a.xy_LU, color=col[f"coast{a.loi}"], lw=1.0, label=a.label)
    for a in geo.select("final"):
        ax.plot(*a.xy_LU, color=col["coast3"], lw=1.0)
    burns = geo.select("burn")
    widths = {1: 5.0, 2: 3.4, 3: 1.9}
    for a in burns:
        c = col.get(f"burn{a.loi}", col["burn"])
        ax.plot(*a.xy_LU, color=c, lw=widths.get(a.loi, 2.5), solid_capstyle="butt",
                label=f"LOI {a.loi} burn", zorder=4 + a.loi)
        ax.plot(*a.xy_LU[:, 0], "o", color=c, ms=5, mec="black", mew=0.6, zorder=8)
        ax.plot(*a.xy_LU[:, -1], "s", color=c, ms=5, mec="black", mew=0.6, zorder=8)
    # perilune direction of the first pass (the symmetry axis the paper refers to)
    row = geo.burns.iloc[0]
    th = math.radians(row.perilune_angle_deg)
    (x0, x1), (y0, y1) = _burn_zoom_limits(geo)
    ax.plot([0, 2 * math.cos(th)], [0, 2 * math.sin(th)], color="0.3", lw=0.9, ls="--",
            label="perilune direction (LOI 1 pass)")
    # labels at the ignition points: LOI 1 outside the arcs, LOI 2 and 3 inside them
    shift = {1: 0.12, 2: -0.16, 3: -0.32}
    for a in burns:
        p = a.xy_LU[:, 0]
        out = p / np.linalg.norm(p)
        ax.annotate(f"LOI {a.loi}", p, xytext=(p + shift.get(a.loi, 0.1) * out),
                    fontsize=10, color=col.get(f"burn{a.loi}"), fontweight="bold",
                    ha="center", va="center",
                    bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8),
                    arrowprops=dict(arrowstyle="-", color="0.4", lw=0.7))
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel(_PLANE_XLABEL)
    ax.set_ylabel(_PLANE_YLABEL)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8, framealpha=0.9)
    ax.set_title("(a) zoom on the burn arcs (● ignition, ■ cutoff)", fontsize=10, loc="left")

    # (b) altitude vs angle from each pass's perilune
    flown = [a for a in geo.arcs if a.kind in ("hyperbola", "coast", "burn", "final")]
    for _, row in geo.burns.iterrows():
        loi = int(row.loi)
        c = col.get(f"burn{loi}", col["burn"])
        t_lo = row.ignition_s - 40 * 60.0
        t_hi = row.cutoff_s + 40 * 60.0
        for a in flown:
            m = (a.t_s >= t_lo) & (a.t_s <= t_hi)
            if not m.any():
                continue
            ang = _wrap180(a.angle_deg[m] - row.perilune_angle_deg)
            alt = a.radius_km[m] - C.R_MOON
            if a.kind == "burn":
                ax2.plot(ang, alt, color=c, lw=3.0, solid_capstyle="butt", zorder=4,
                         label=f"LOI {loi} burn: {row.ignition_from_perilune_deg:+.1f}° to "
                               f"{row.cutoff_from_perilune_deg:+.1f}°")
            else:
                ax2.plot(ang, alt, color=c, lw=0.9, ls="--", alpha=0.8)
    ax2.axvline(0, color="0.3", lw=0.8, ls="--")
    ax2.set_xlim(-75, 75)
    top = max(row.ignition_radius_km for _, row in geo.burns.iterrows()) - C.R_MOON
    ax2.set_ylim(0, 1.6 * top)
    ax2.set_xlabel("angle in the orbit plane from the pass's perilune (deg)")
    ax2.set_ylabel("altitude (km)")
    ax2.grid(alpha=0.3)
    ax2.legend(loc="upper center", fontsize=8.5, framealpha=0.9)
    ax2.set_title("(b) altitude along each perilune pass (dashed: coasting)", fontsize=10,
                  loc="left")
    return fig


@dataclass
class Fig4Steering:
    """Data of Fig. 4: thrust angles and mass during one burn.

    Attributes
    ----------
    t_min : ndarray, shape (N,)
        Time from ignition, min.
    alpha_deg, beta_deg : ndarray, shape (N,)
        In-plane and out-of-plane thrust angles of Eq. (14), deg.
    m_kg : ndarray, shape (N,)
        Mass, kg.
    perilune_min : float
        Nominal perilune epoch of the pass, min from ignition.
    loi : int
    thrust_N, isp_s : float
    """

    t_min: np.ndarray
    alpha_deg: np.ndarray
    beta_deg: np.ndarray
    m_kg: np.ndarray
    perilune_min: float
    loi: int
    thrust_N: float
    isp_s: float

    @property
    def burn_duration_min(self) -> float:
        """Burn duration, min."""
        return float(self.t_min[-1] - self.t_min[0])

    def table(self):
        """The data as a DataFrame (CSV-ready, units in the column names)."""
        import pandas as pd

        return pd.DataFrame({"min_from_ignition": self.t_min, "alpha_deg": self.alpha_deg,
                             "beta_deg": self.beta_deg, "m_kg": self.m_kg})


def fig4_steering(solution, n: int = 241) -> Fig4Steering:
    """Thrust angles (Eq. (14)) and mass along the burn of a Solution (Fig. 4).

    Parameters
    ----------
    solution : Solution
    n : int
        Samples over the burn.

    Returns
    -------
    Fig4Steering
    """
    h = solution.history(n_burn=n, n_coast=2)
    b = h[h.phase == "burn"]
    prob = solution.problem
    return Fig4Steering(b.min_from_ignition.to_numpy(), b.alpha_deg.to_numpy(),
                        b.beta_deg.to_numpy(), b.m_kg.to_numpy(),
                        (prob.t_perilune_s - prob.t_ign_s) / 60.0, int(prob.loi),
                        float(prob.model.thrust_N), float(prob.model.isp_s))


def plot_fig4_steering(d: Fig4Steering, paper_alpha_deg=None, paper_mass_end_kg=None,
                       paper_duration_min: float | None = None, figsize=(7.0, 7.6)):
    """Draw Fig. 4: alpha (top), beta (middle) and mass (bottom) against time from ignition.

    Parameters
    ----------
    d : Fig4Steering from :func:`fig4_steering`
    paper_alpha_deg : (float, float), optional
        The paper's alpha at ignition and cutoff, drawn as reference marks.
    paper_mass_end_kg : float, optional
        The paper's mass at cutoff, drawn as a reference mark.
    paper_duration_min : float, optional
        The paper's burn duration, min: where its cutoff values are drawn (default ours).
    figsize : (width, height), inches

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axs = plt.subplots(3, 1, figsize=figsize, sharex=True, layout="constrained")
    t = d.t_min
    t_end = t[-1] if paper_duration_min is None else t[0] + paper_duration_min
    axs[0].plot(t, d.alpha_deg, color="tab:purple", lw=1.8, label="lunarcap")
    axs[0].axhline(180.0, color="0.6", lw=0.8, ls=":")
    if paper_alpha_deg is not None:
        axs[0].plot([t[0], t_end], paper_alpha_deg, "D", color="black", ms=6, mfc="none",
                    label="paper: start and end values (Sec. 3.3)")
    axs[0].set_ylabel("in-plane angle α (deg)")
    axs[0].legend(loc="upper left", fontsize=8.5)
    axs[1].plot(t, d.beta_deg, color="tab:orange", lw=1.8)
    lim = max(0.5, 1.3 * float(np.abs(d.beta_deg).max()))
    axs[1].set_ylim(-lim, lim)
    axs[1].axhline(0.0, color="0.6", lw=0.8, ls=":")
    axs[1].set_ylabel("out-of-plane angle β (deg)")
    axs[2].plot(t, d.m_kg, color="tab:blue", lw=1.8, label="lunarcap")
    if paper_mass_end_kg is not None:
        axs[2].plot([t_end], [paper_mass_end_kg], "D", color="black", ms=6, mfc="none",
                    label=f"paper: {paper_mass_end_kg:g} kg after LOI {d.loi} (Sec. 3.2.1)")
        axs[2].legend(loc="upper right", fontsize=8.5)
    axs[2].set_ylabel("mass (kg)")
    axs[2].set_xlabel(f"time from LOI {d.loi} ignition (min)")
    for ax in axs:
        ax.grid(alpha=0.3)
        if t[0] <= d.perilune_min <= t[-1]:
            ax.axvline(d.perilune_min, color="0.4", lw=0.9, ls="--")
    axs[0].text(d.perilune_min, 0.04, " nominal perilune", fontsize=8, va="bottom",
                ha="left", color="0.3", transform=axs[0].get_xaxis_transform())
    return fig


@dataclass
class Fig5Vectors:
    """Data of Fig. 5: thrust acceleration and velocity along one burn arc.

    Positions and vectors are projected on the drawing plane (rows e_x, e_y of
    ``basis``, M-MME2000).

    Attributes
    ----------
    t_min : ndarray, shape (N,)
        Time from ignition, min.
    xy_km : ndarray, shape (2, N)
        Projected position, km.
    v_xy_kmps : ndarray, shape (2, N)
        Projected velocity, km/s.
    a_xy_mps2 : ndarray, shape (2, N)
        Projected thrust acceleration, m/s^2.
    v_kmps, a_mps2 : ndarray, shape (3, N)
        The full vectors (M-MME2000).
    angle_deg : ndarray, shape (N,)
        Angle between the thrust acceleration and the velocity (3-D), deg.
    arrows : ndarray of int
        Indices of the samples drawn as arrows.
    basis : ndarray, shape (3, 3)
    loi : int
    """

    t_min: np.ndarray
    xy_km: np.ndarray
    v_xy_kmps: np.ndarray
    a_xy_mps2: np.ndarray
    v_kmps: np.ndarray
    a_mps2: np.ndarray
    angle_deg: np.ndarray
    arrows: np.ndarray
    basis: np.ndarray
    loi: int

    def table(self):
        """The arrows' data as a DataFrame (units in the column names)."""
        import pandas as pd

        i = self.arrows
        return pd.DataFrame({"min_from_ignition": self.t_min[i], "x_km": self.xy_km[0, i],
                             "y_km": self.xy_km[1, i], "vx_kmps": self.v_xy_kmps[0, i],
                             "vy_kmps": self.v_xy_kmps[1, i],
                             "ax_thrust_mps2": self.a_xy_mps2[0, i],
                             "ay_thrust_mps2": self.a_xy_mps2[1, i],
                             "angle_thrust_velocity_deg": self.angle_deg[i]})


def fig5_vectors(solution, basis, n: int = 241, n_arrows: int = 9) -> Fig5Vectors:
    """Thrust acceleration and velocity vectors along a burn, projected (Fig. 5).

    Parameters
    ----------
    solution : Solution
    basis : ndarray, shape (3, 3)
        Drawing plane (:func:`orbit_plane_basis`; ``CaptureGeometry.basis``).
    n : int
        Samples over the burn.
    n_arrows : int
        Arrows drawn, evenly spaced in time from ignition to cutoff.

    Returns
    -------
    Fig5Vectors
    """
    h = solution.history(n_burn=n, n_coast=2)
    b = h[h.phase == "burn"]
    r = b[["x_km", "y_km", "z_km"]].to_numpy().T
    v = b[["vx_kmps", "vy_kmps", "vz_kmps"]].to_numpy().T
    a = b[["ax_thrust_kmps2", "ay_thrust_kmps2", "az_thrust_kmps2"]].to_numpy().T * 1e3
    cosang = (v * a).sum(axis=0) / (np.linalg.norm(v, axis=0) * np.linalg.norm(a, axis=0))
    angle = np.degrees(np.arccos(np.clip(cosang, -1.0, 1.0)))
    basis = np.asarray(basis, float)
    arrows = np.unique(np.round(np.linspace(0, r.shape[1] - 1, n_arrows)).astype(int))
    return Fig5Vectors(b.min_from_ignition.to_numpy(), basis[:2] @ r, basis[:2] @ v,
                       basis[:2] @ a, v, a, angle, arrows, basis, int(solution.problem.loi))


def _nice(x: float) -> float:
    """1, 2 or 5 times a power of ten, at most ``x``."""
    e = 10.0 ** math.floor(math.log10(x))
    return max(m * e for m in (1, 2, 5) if m * e <= x)


def plot_fig5_vectors(d: Fig5Vectors, geo: CaptureGeometry | None = None, figsize=(7.0, 9.6),
                      arrow_fraction: float = 0.1):
    """Draw Fig. 5: thrust-acceleration and velocity arrows along a burn arc.

    (a) The arrows in the orbit plane (km); (b) the angle between them against time from
    ignition.

    Parameters
    ----------
    d : Fig5Vectors from :func:`fig5_vectors`
    geo : CaptureGeometry, optional
        Draws the neighbouring trajectory (hyperbola, first capture orbit) for context.
    figsize : (width, height), inches
    arrow_fraction : float
        Length of the longest arrow of each kind, as a fraction of the arc's extent.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = plt.figure(figsize=figsize, layout="constrained")
    gs = fig.add_gridspec(2, 1, height_ratios=(1.6, 0.7))
    ax = fig.add_subplot(gs[0])
    ax2 = fig.add_subplot(gs[1])
    col = CAPTURE_COLOURS
    xy = d.xy_km
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    extent = float((hi - lo).max())
    R = C.R_MOON
    ax.add_patch(plt.Circle((0, 0), R, color="0.85", zorder=0))
    if geo is not None:  # the trajectory up to 30 min before ignition and after cutoff
        t_ign = geo.select("burn", d.loi)[0].t_s[0]
        t_cut = geo.select("burn", d.loi)[0].t_s[-1]
        for a in geo.arcs:
            if a.kind == "burn":
                continue
            m = (a.t_s >= t_ign - 1800.0) & (a.t_s <= t_cut + 1800.0)
            if m.any() and a.kind in ("hyperbola", "coast"):
                c = col["hyperbola"] if a.kind == "hyperbola" else col[f"coast{a.loi}"]
                ax.plot(*(a.xy_LU[:, m] * C.LU_KM), color=c, lw=1.0, label=a.label)
    ax.plot(*xy, color="0.25", lw=1.2, label=f"LOI {d.loi} burn arc", zorder=5)
    i = d.arrows
    vmax = float(np.linalg.norm(d.v_xy_kmps[:, i], axis=0).max())
    amax = float(np.linalg.norm(d.a_xy_mps2[:, i], axis=0).max())
    L = arrow_fraction * extent
    v_scale = vmax / L    # km/s per km of arrow
    a_scale = amax / L    # m/s^2 per km of arrow
    qv = ax.quiver(xy[0, i], xy[1, i], d.v_xy_kmps[0, i], d.v_xy_kmps[1, i], angles="xy",
                   scale_units="xy", scale=v_scale, color="tab:blue", width=0.004, zorder=6)
    qa = ax.quiver(xy[0, i], xy[1, i], d.a_xy_mps2[0, i], d.a_xy_mps2[1, i], angles="xy",
                   scale_units="xy", scale=a_scale, color="tab:red", width=0.004, zorder=7)
    ax.plot(xy[0, i], xy[1, i], "o", color="black", ms=3, zorder=8)
    ax.annotate("ignition", xy[:, 0], xytext=(8, -2), textcoords="offset points", fontsize=9)
    ax.annotate("cutoff", xy[:, -1], xytext=(8, -2), textcoords="offset points", fontsize=9)
    v_ref = _nice(vmax)
    a_ref = _nice(amax)
    ax.quiverkey(qv, 0.04, 0.95, v_ref, f"velocity: arrow of {v_ref:g} km/s "
                 f"= {v_ref / v_scale:.0f} km", labelpos="E", coordinates="axes",
                 fontproperties={"size": 8.5})
    ax.quiverkey(qa, 0.04, 0.89, a_ref, f"thrust acceleration: arrow of {a_ref:g} m/s² "
                 f"= {a_ref / a_scale:.0f} km", labelpos="E", coordinates="axes",
                 fontproperties={"size": 8.5})
    pad = 0.3 * extent
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + 1.3 * pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x′: M-MME2000 equator, along the orbit's ascending node (km)")
    ax.set_ylabel("z: M-MME2000 pole (km)")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8, framealpha=0.9)
    ax.set_title(f"(a) LOI {d.loi}: velocity (blue) and thrust acceleration (red), projected",
                 fontsize=10, loc="left")
    ax2.plot(d.t_min, d.angle_deg, color="black", lw=1.6)
    ax2.plot(d.t_min[i], d.angle_deg[i], "o", color="black", ms=3)
    ax2.axhline(90.0, color="tab:red", lw=0.8, ls=":")
    ax2.text(d.t_min[0], 91.5, " 90°: above it the thrust slows the spacecraft", fontsize=8,
             color="tab:red", va="bottom")
    ax2.set_ylim(80, 182)
    ax2.set_xlabel(f"time from LOI {d.loi} ignition (min)")
    ax2.set_ylabel("angle thrust–velocity (deg)")
    ax2.grid(alpha=0.3)
    ax2.set_title("(b) angle between the thrust acceleration and the velocity (3-D)",
                  fontsize=10, loc="left")
    return fig


# =============================================================================== report
# Tables of the reproduction report: every number Song 2011 prints beside ours. Pure
# functions of DataFrames and dicts the notebook computes with lunarcap.runs.sweeps and
# lunarcap.runs.chain; nothing here solves or integrates.

#: Titles of the audit's groups of checks (:func:`lunarcap.paper.audit.audit_findings`).
AUDIT_CHECK_TITLES = {
    "a": "constants of Sec. 3.1",
    "b": "the 'difference %' of Tables 1-5 and B1",
    "c": "masses, propellant and burn durations vs the rocket equation",
    "d": "the fuel-mass sentences of Sec. 3.2",
    "e": "delta-V losses and their percentages",
    "f": "burn-duration totals",
    "g": "the period of the 100 km circular orbit",
    "h": "the perilune epochs vs the periods",
    "i": "Eq. (19) and its estimates",
    "j": "half the Eq. (19) duration vs the best ignition time",
    "k": "other checks (Fig. 4, two-body impulsive delta-Vs)",
}

_TABLE_QUANTITIES = (
    ("burn duration", "min", "paper_burn_duration_min", "burn_duration_min"),
    ("delta-V", "m/s", "paper_delta_v_mps", "delta_v_mps"),
    ("difference from impulsive", "%", "paper_loss_percent", "loss_percent"),
)


def short_where(where: str) -> str:
    """``"Sec. 3.2.1, para 2"`` from ``"Sec. 3.2.1, para 2 ('As shown in ...')"``."""
    return where.split(" ('", 1)[0].split(" (\"", 1)[0]


def paper_tables_long(sweeps: dict, impulsive_dv_mps=None):
    """Every number of the paper's Tables 1-5 and B1 beside ours, one row per number.

    Parameters
    ----------
    sweeps : dict
        ``{(thrust_N, loi): DataFrame}`` from :func:`lunarcap.runs.sweeps.sweep_table` with the
        paper's ignition offsets (columns ``paper_*`` beside ours; ``attrs`` ``thrust_N``,
        ``isp_s``).
    impulsive_dv_mps : sequence of 3 floats, optional
        Our impulsive delta-Vs of LOI 1-3 (m/s), set beside the impulsive rows the paper
        prints in every table.

    Returns
    -------
    pandas.DataFrame
        Columns ``source`` (Table 1 ... B1), ``thrust_N``, ``isp_s``, ``loi``,
        ``start_min``, ``quantity``, ``unit``, ``paper``, ``ours``, ``difference``
        (ours - paper, in ``unit``), ``paper_best`` (the paper marks the row best),
        ``ours_best`` (our smallest delta-V among the paper's offsets), ``verified``.
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    rows = []
    b1 = P.paper_table_b1()
    for (thrust, loi), df in sorted(sweeps.items()):
        src = P.paper_table(thrust, loi).attrs["source"]
        isp = df.attrs.get("isp_s", P.PAPER_ENGINES.get(int(thrust)))
        for r in df[~df.free_start].itertuples(index=False):
            for qty, unit, pcol, ocol in _TABLE_QUANTITIES:
                p, o = float(getattr(r, pcol)), float(getattr(r, ocol))
                if not np.isfinite(p):
                    continue
                rows.append({"source": src, "thrust_N": float(thrust), "isp_s": float(isp),
                             "loi": int(loi), "start_min": float(r.start_min), "quantity": qty,
                             "unit": unit, "paper": p, "ours": o, "difference": o - p,
                             "paper_best": bool(r.paper_best), "ours_best": bool(r.best),
                             "verified": bool(r.verified)})
        # Table B1: transcribed separately, compared with the same solution
        hit = b1[(b1.thrust_N == int(thrust)) & (b1.loi == int(loi))]
        for b in hit.itertuples(index=False):
            m = df[np.isclose(df.start_min, b.start_min) & ~df.free_start]
            if m.empty:
                continue
            r = m.iloc[0]
            for qty, unit, pval, ocol in (("burn duration", "min", b.burn_duration_min,
                                           "burn_duration_min"),
                                          ("delta-V", "m/s", b.delta_v_mps, "delta_v_mps"),
                                          ("difference from impulsive", "%", b.diff_percent,
                                           "loss_percent")):
                o = float(r[ocol])
                rows.append({"source": "Table B1", "thrust_N": float(thrust),
                             "isp_s": float(isp), "loi": int(loi),
                             "start_min": float(b.start_min), "quantity": qty, "unit": unit,
                             "paper": float(pval), "ours": o, "difference": o - float(pval),
                             "paper_best": True, "ours_best": bool(r["best"]),
                             "verified": bool(r["verified"])})
    if impulsive_dv_mps is not None:
        for loi, (p, o) in enumerate(zip(P.PAPER_IMPULSIVE_DV_MPS, impulsive_dv_mps), 1):
            rows.append({"source": "Tables 1-5, B1 (impulsive)", "thrust_N": np.nan,
                         "isp_s": np.nan, "loi": loi, "start_min": np.nan,
                         "quantity": "impulsive delta-V", "unit": "m/s", "paper": float(p),
                         "ours": float(o), "difference": float(o) - float(p),
                         "paper_best": False, "ours_best": False, "verified": True})
    return pd.DataFrame(rows)


def quote_equivalents(chains: dict, impulsive_final_mass_kg: dict | None = None,
                      best_starts: dict | None = None, fig4: Fig4Steering | None = None,
                      audit_values: dict | None = None) -> dict:
    """Our number equivalent to each number of the paper's prose, where one exists.

    Parameters
    ----------
    chains : dict
        ``{thrust_N: [summary_1, summary_2, summary_3]}``: :meth:`Solution.summary` of the
        best chain of each engine (the paper's best ignition offsets).
    impulsive_final_mass_kg : dict, optional
        ``{thrust_N: kg}``: mass after our impulsive sequence (same arrival mass and Isp).
    best_starts : dict, optional
        ``{(thrust_N, loi): min}``: our best ignition offset among the paper's.
    fig4 : Fig4Steering, optional
        The 150 N LOI-1 steering (:func:`fig4_steering`).
    audit_values : dict, optional
        ``{finding id: computed value}`` from :func:`lunarcap.paper.audit.audit_findings`
        (used for the two-body period of the 100 km orbit).

    Returns
    -------
    dict
        ``{quote name: (value, note)}`` in the quote's unit; names missing have no
        equivalent (or were not computed in this run).
    """
    from lunarcap.paper import printed as P
    out: dict = {}
    per = C.CAPTURE_PERIODS_S
    inp = "input (the paper's value)"
    for n in ("abstract_period_capture1_h", "period_capture1_about_h", "period_capture1_h",
              "period_capture1_about2_h"):
        out[n] = (per[0] / 3600.0, "input: the perilunes are 12.235 h apart")
    for n in ("abstract_period_capture2_h", "period_capture2_about_h", "period_capture2_h",
              "period_capture2_about2_h"):
        out[n] = (per[1] / 3600.0, "input: the perilunes are 3.525 h apart")
    t2b = (audit_values or {}).get("period/final")
    note = "input: the final coast lasts 117.848 min" + (
        f"; the two-body period of a 100 km circular orbit is {t2b:.3f} min"
        if t2b is not None else "")
    for n in ("period_final_about_min", "period_final_min"):
        out[n] = (per[2] / 60.0, note)
    out["mu_moon_km3s2"] = (C.MU_MOON, inp)
    out["mu_earth_km3s2"] = (C.MU_EARTH, inp)
    out["mu_sun_km3s2"] = (C.MU_SUN, "corrected: IAU 2009 / DE405 value (the printed one "
                                     "is ten times too small)")
    out["r_moon_km"] = (C.R_MOON, inp)
    out["lunar_unit_km"] = (C.LU_KM, inp)
    out["j2_moon"] = (C.J2_MOON, inp)
    out["arrival_mass_kg"] = (C.ARRIVAL_MASS_KG, inp)
    for j, (t, isp) in enumerate(C.PAPER_ENGINES, 1):
        out[f"engine{j}_thrust_N"] = (t, inp)
        out[f"engine{j}_isp_s"] = (isp, inp)
    for n in ("thrust_direction_bound_lower", "thrust_direction_bound_upper"):
        out[n] = (np.nan, "no equivalent number: the same bounds are used (lunarcap.optim.nlp), "
                          "with |u| = 1 imposed")

    def key(t):
        return f"{int(t)}N"

    totals_pct = {}
    m0 = C.ARRIVAL_MASS_KG
    imp_total = float(sum(P.PAPER_IMPULSIVE_DV_MPS))
    fuel_fin = {}
    for t, chain in chains.items():
        t = float(t)
        k = key(t)
        s = list(chain)
        if len(s) != 3:
            continue
        loss = [x["loss_mps"] for x in s]
        pct = [x["loss_percent"] for x in s]
        dur = [x["burn_duration_min"] for x in s]
        total_pct = 100.0 * sum(loss) / imp_total
        totals_pct[t] = total_pct
        mean_pct = float(np.mean(pct))
        fin = m0 - s[2]["m_end_kg"]
        fuel_fin[t] = fin
        pct_note = (f"total loss / total impulsive delta-V; the mean of our per-burn "
                    f"percentages (the paper's way) is {mean_pct:.2f} %")
        for n in (f"loss_total_{k}_mps", f"loss_total_{k}_mps_recalled"):
            out[n] = (float(sum(loss)), "sum of the three losses vs the paper's impulsive "
                                        "delta-Vs")
        for n in (f"loss_total_{k}_percent", f"loss_total_{k}_percent_recalled",
                  f"conclusion_loss_{k}_percent"):
            out[n] = (total_pct, pct_note)
        for n in (f"burn_total_{k}_min",):
            out[n] = (float(sum(dur)), "sum of the three burn durations")
        for n in (f"fuel_finite_{k}_kg", f"fuel_finite_{k}_about_kg"):
            out[n] = (fin, "arrival mass minus our mass after LOI 3")
        out[f"mass_final_{k}_kg"] = (s[2]["m_end_kg"], "mass after LOI 3")
        if impulsive_final_mass_kg and t in impulsive_final_mass_kg:
            imp = m0 - impulsive_final_mass_kg[t]
            out[f"fuel_impulsive_{k}_kg"] = (imp, "two-body impulsive sequence from the "
                                                  "arrival mass (rocket equation)")
            out[f"fuel_difference_{k}_kg"] = (fin - imp, "finite minus impulsive propellant")
            out[f"fuel_difference_{k}_percent"] = (100.0 * (fin - imp) / imp,
                                                   "100 (finite - impulsive) / impulsive")
        for n in (1, 2, 3):
            x = s[n - 1]
            out[f"loss_loi{n}_{k}_mps"] = (x["loss_mps"], "vs the paper's impulsive delta-V")
            out[f"loss_loi{n}_{k}_percent"] = (x["loss_percent"],
                                               "vs the paper's impulsive delta-V")
            out[f"loss_pct_loi{n}_{k}_summary"] = (x["loss_percent"],
                                                   "vs the paper's impulsive delta-V")
            for nm in (f"burn_loi{n}_{k}_min", f"burn_loi{n}_{k}_summary_min",
                       f"burn_loi{n}_{k}_about_min"):
                out[nm] = (x["burn_duration_min"], "burn duration")
            out[f"mass_after_loi{n}_{k}_kg"] = (x["m_end_kg"], f"mass after LOI {n}")
            out[f"fuel_loi{n}_{k}_about_kg"] = (x["fuel_kg"], f"propellant of LOI {n}")
            if x.get("eq19_duration_min") is not None:
                e19 = float(x["eq19_duration_min"])
                out[f"eq19_loi{n}_{k}_min"] = (e19, "Eq. (19) (corrected 19a) with the "
                                                    "paper's impulsive delta-V and our "
                                                    "ignition mass")
                out[f"eq19_half_loi{n}_{k}_min"] = (e19 / 2.0, "half of our Eq. (19) estimate")
        if t == 150.0:
            out["fuel_150N_recalled_kg"] = (fin, "arrival mass minus our mass after LOI 3")
            out["fig4_burn_loi1_150N_min"] = (dur[0], "LOI 1 burn duration")
            out["fig4_mass_end_kg"] = (s[2]["m_end_kg"],
                                       f"our mass after LOI 3; Fig. 4 shows LOI 1 only, "
                                       f"which ends at {s[0]['m_end_kg']:.3f} kg")
            alt = s[2]["rp_end_km"] - C.R_MOON
            for n in ("abstract_final_altitude_km", "final_altitude_km"):
                out[n] = (alt, "perilune altitude reached by LOI 3 (150 N), verified")
            for n in ("abstract_final_inclination_deg", "final_inclination_deg"):
                out[n] = (s[2]["inc_end_deg"], "inclination reached by LOI 3 (150 N)")
    if 150.0 in fuel_fin and 300.0 in fuel_fin:
        out["fuel_saving_300N_vs_150N_kg"] = (fuel_fin[150.0] - fuel_fin[300.0],
                                              "propellant of 150 N minus 300 N")
    if totals_pct:
        tmax = max(totals_pct, key=totals_pct.get)
        for n in ("abstract_max_loss_percent", "conclusion_max_loss_percent"):
            out[n] = (totals_pct[tmax], f"largest total loss ({tmax:g} N), total loss / total "
                                        "impulsive delta-V")
    for (t, loi), start in (best_starts or {}).items():
        name = f"best_start_loi{loi}_{key(t)}_min"
        if name in P.QUOTES:
            sign = -1.0 if P.QUOTES[name].value > 0 else 1.0  # printed as minutes before
            out[name] = (sign * float(start), "our best of the paper's ignition offsets")
    if fig4 is not None:
        out["fig4_alpha_start_deg"] = (float(fig4.alpha_deg[0]), "α at LOI-1 ignition")
        out["fig4_alpha_end_deg"] = (float(fig4.alpha_deg[-1]), "α at LOI-1 cutoff")
        out["fig4_beta_deg"] = (float(np.abs(fig4.beta_deg).max()),
                                "largest |β| during LOI 1")
        out["fig4_mass_start_kg"] = (float(fig4.m_kg[0]), "mass at LOI-1 ignition")
    return {k: v for k, v in out.items() if k in P.QUOTES}


def quotes_comparison(ours: dict):
    """Every number of the paper's prose (:data:`lunarcap.paper.printed.QUOTES`) beside ours.

    Parameters
    ----------
    ours : dict
        ``{quote name: (value, note)}`` from :func:`quote_equivalents`.

    Returns
    -------
    pandas.DataFrame
        Columns ``name``, ``where`` (section and paragraph), ``text`` (the printed words),
        ``printed`` (as printed), ``paper`` (value), ``unit``, ``ours``, ``difference``
        (ours - paper; NaN without an equivalent), ``note`` ("no equivalent" where none).
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    rows = []
    for q in P.QUOTES.values():
        val, note = ours.get(q.name, (np.nan, "no equivalent"))
        val = float(val)
        rows.append({"name": q.name, "where": short_where(q.where), "text": q.text,
                     "printed": q.printed, "paper": q.value, "unit": q.unit, "ours": val,
                     "difference": val - q.value if np.isfinite(val) else np.nan,
                     "note": note})
    return pd.DataFrame(rows)


def epochs_comparison(perilune_epochs_s):
    """The perilune epochs the paper prints (Sec. 3.2.1) beside our nominal ones.

    Parameters
    ----------
    perilune_epochs_s : sequence of float
        Our nominal perilune epochs, TDB s past J2000 (``Mission.perilune_epochs_s``).

    Returns
    -------
    pandas.DataFrame
        Columns ``perilune``, ``where``, ``paper`` (as printed), ``ours`` (TDB calendar),
        ``difference_s`` (ours - paper, s).
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar

    months = {"Jan": 1, "Feb": 2, "Mar": 3, "Apr": 4, "May": 5, "Jun": 6, "Jul": 7,
              "Aug": 8, "Sep": 9, "Oct": 10, "Nov": 11, "Dec": 12}
    rows = []
    for n, text in P.PAPER_EPOCHS_TDB.items():
        d, mon, rest = text.split("-", 2)
        y, hms = rest.split()[:2]
        t_p = seconds_from_calendar(f"{y}-{months[mon]:02d}-{int(d):02d} {hms} TDB")
        t_o = float(perilune_epochs_s[n - 1])
        rows.append({"perilune": n, "where": short_where(P.PAPER_EPOCHS_WHERE[n]),
                     "paper": text, "ours": calendar_from_seconds(t_o, decimals=0),
                     "difference_s": t_o - t_p})
    return pd.DataFrame(rows)


def _fmt_decimals(v: float, decimals: int, sign: bool = False) -> str:
    if not np.isfinite(v):
        return "—"
    if abs(v) >= 1e6:   # large numbers (gravitational parameters): 7 significant digits
        return f"{v:{'+' if sign else ''}.7g}"
    text = f"{v:{'+' if sign else ''},.{max(0, decimals)}f}"
    if sign and text[1:].replace("0", "").replace(".", "").replace(",", "") == "":
        text = text[1:]  # no "+0.00" / "-0.00"
    return text


def quotes_display(quotes, max_words: int = 70, extra_decimals: int = 1,
                   min_decimals: int = 3):
    """A compact, readable version of :func:`quotes_comparison` for the page.

    Parameters
    ----------
    quotes : DataFrame from :func:`quotes_comparison`
    max_words : int
        The printed words are cut to this many characters (with "…").
    extra_decimals, min_decimals : int
        Ours and the difference are shown with this many more decimals than printed, and
        at least ``min_decimals``.

    Returns
    -------
    pandas.DataFrame
        String columns ``words`` (where, as ``§3.2.1 ¶2`` for "Sec. 3.2.1, para 2", then
        the words), ``printed`` (with unit), ``ours`` and ``difference`` (ours - printed,
        same unit), ``note``.
    """
    import pandas as pd

    from lunarcap.paper import printed as P
    rows = []
    for r in quotes.itertuples(index=False):
        q = P.QUOTES[r.name]
        dec = max(q.decimals + extra_decimals, min_decimals)
        words = r.text if len(r.text) <= max_words else r.text[:max_words - 1].rstrip() + "…"
        unit = f" {r.unit}" if r.unit else ""
        where = r.where.replace("Sec. ", "§").replace(", para ", " ¶")
        rows.append({"words": f"{where}: {words}", "printed": f"{r.printed}{unit}",
                     "ours": _fmt_decimals(r.ours, dec),
                     "difference": _fmt_decimals(r.difference, dec, sign=True),
                     "note": r.note})
    return pd.DataFrame(rows)


def findings_display(findings):
    """A compact version of :func:`lunarcap.paper.audit.findings_table` for the page.

    Parameters
    ----------
    findings : DataFrame from :func:`lunarcap.paper.audit.findings_table`

    Returns
    -------
    pandas.DataFrame
        String columns ``finding`` (group letter and id, e.g. ``"a: sun-gm"``),
        ``printed`` and ``computed`` (6 significant digits, with the unit) and
        ``explanation`` (where the number is printed, then how it was checked).
    """
    import pandas as pd

    def num(v, unit):
        return f"{v:.6g}" + (f" {unit}" if unit else "")

    return pd.DataFrame({
        "finding": [f"{c}: {i}" for c, i in zip(findings.check, findings.id)],
        "printed": [num(v, u) for v, u in zip(findings.printed, findings.unit)],
        "computed": [num(v, u) for v, u in zip(findings.computed, findings.unit)],
        "explanation": [f"{short_where(w)}. {e}" for w, e in zip(findings["where"],
                                                                 findings.explanation)],
    })
