"""Figures and tables for the book: data functions, drawing functions and display helpers.

Each figure has a *data* function returning plain arrays (tested) and a *drawing*
function that only draws them (not tested pixel by pixel). The display helpers
write a table (CSV) or figure (PNG + SVG) below ``book/generated/`` through
:mod:`lunarcap.paths` and show it in the notebook as a numbered MyST ``table`` or
``figure`` with a caption and a note naming the notebook and parameters that made it.

This module is presentation only: no physics is defined here (the RTN frame comes
from :func:`lunarcap.frames.rtn_basis`, orbits from :mod:`lunarcap.elements`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import matplotlib
import matplotlib.pyplot as plt
import numpy as np

from . import constants as C
from . import paths
from .elements import rv_from_coe, semi_major_axis_from_period
from .frames import rtn_basis, thrust_angles_deg, thrust_direction_rtn  # noqa: F401
from .provenance import source_note

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
        Rows i_r, i_t, i_n in the drawing frame (Eq. A5, :func:`lunarcap.frames.rtn_basis`).
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
        named under the table (:func:`lunarcap.provenance.source_note`).
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
    notebook, parameters : named in the caption (:func:`lunarcap.provenance.source_note`).
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
