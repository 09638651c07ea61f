"""Drawing of the book's figures: each function draws data computed by :mod:`.figdata`.

Nothing here computes a trajectory or solves anything (checked by an import-linter
contract: this module imports neither the propagator nor the optimiser); the data
functions and their tests are in :mod:`lunarcap.report.figdata`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import matplotlib
import matplotlib.pyplot as plt
import numpy as np

from lunarcap.physics import constants as C
from lunarcap.repro import paths

if TYPE_CHECKING:  # data types, for annotations only
    from lunarcap.report.figdata import CaptureGeometry, Fig1Geometry, Fig4Steering, Fig5Vectors

# Reproducible SVG output (no random ids, no date).
matplotlib.rcParams["svg.hashsalt"] = "lunarcap"

#: Width of every figure, inches: the book's text column at 1280 and 1024 px is about 700
#: CSS px, so a figure of this width (96 CSS px per inch) is shown at about its natural
#: size and a font of :data:`MIN_FONT_PT` reads at 9 px or more (``make screenshots``
#: fails on a figure shown below 80 % of its natural width).
FIG_WIDTH_IN = 6.8
#: Smallest font of any figure text, pt (tests/report/test_figures.py checks every text).
MIN_FONT_PT = 9.0
matplotlib.rcParams.update({"font.size": 10, "axes.titlesize": 10, "axes.labelsize": 10,
                            "xtick.labelsize": 9, "ytick.labelsize": 9,
                            "legend.fontsize": 9, "figure.titlesize": 11})

#: One marker per specific impulse (with one colour each), so curves differ in grey too.
ISP_MARKERS = ("o", "s", "^", "D", "v", "P")


# =============================================================================== Fig. 1
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


# =============================================================================== Figs. 2-5
#: Colours of the capture-sequence figures: one per orbit, one per burn (cycled).
_COAST_COLOURS = ("tab:blue", "tab:green", "tab:purple", "tab:olive", "tab:cyan", "tab:pink")
_BURN_COLOURS = ("#d62728", "#ff7f0e", "#8c2d04", "#e377c2", "#7f7f7f", "#bcbd22")
HYPERBOLA_COLOUR = "0.35"


def coast_colour(burn: int) -> str:
    """Colour of the orbit reached by burn ``burn`` (1-based)."""
    return _COAST_COLOURS[(burn - 1) % len(_COAST_COLOURS)]


def burn_colour(burn: int) -> str:
    """Colour of burn ``burn`` (1-based)."""
    return _BURN_COLOURS[(burn - 1) % len(_BURN_COLOURS)]


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
    hyp = HYPERBOLA_COLOUR
    for a in geo.select("uncaptured"):
        ax.plot(*a.xy_LU, color=hyp, lw=0.9, ls=":", label=a.label)
    for a in geo.select("hyperbola"):
        ax.plot(*a.xy_LU, color=hyp, lw=1.4, label=a.label)
        k = a.xy_LU.shape[1] // 3
        ax.annotate("", xy=a.xy_LU[:, k + 5], xytext=a.xy_LU[:, k],
                    arrowprops=dict(arrowstyle="-|>", color=hyp, lw=1.4, mutation_scale=14))
    for a in geo.select("coast"):
        ax.plot(*a.xy_LU, color=coast_colour(a.burn), lw=1.2, label=a.label)
    for a in geo.select("final"):
        ax.plot(*a.xy_LU, color=coast_colour(a.burn), lw=1.2)
    burns = geo.select("burn")
    for i, a in enumerate(burns):
        ax.plot(*a.xy_LU, color=burn_colour(1), lw=3.2, solid_capstyle="butt",
                label=f"finite burn arcs (burns 1 to {len(burns)})" if i == 0 else None,
                zorder=4)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.set_xlabel(_PLANE_XLABEL)
    ax.set_ylabel(_PLANE_YLABEL)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=9.5, framealpha=0.9)
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
    _moon(ax, label=False)
    for a in geo.select("uncaptured"):
        ax.plot(*a.xy_LU, color=HYPERBOLA_COLOUR, lw=0.8, ls=":")
    for a in geo.select("hyperbola"):
        ax.plot(*a.xy_LU, color=HYPERBOLA_COLOUR, lw=1.0, label="arrival hyperbola")
    for a in geo.select("coast"):
        ax.plot(*a.xy_LU, color=coast_colour(a.burn), lw=1.0, label=a.label)
    for a in geo.select("final"):
        ax.plot(*a.xy_LU, color=coast_colour(a.burn), lw=1.0)
    burns = geo.select("burn")
    for a in burns:
        c = burn_colour(a.burn)
        ax.plot(*a.xy_LU, color=c, lw=max(5.0 - 1.55 * (a.burn - 1), 1.2),
                solid_capstyle="butt", label=f"burn {a.burn}", zorder=4 + a.burn)
        ax.plot(*a.xy_LU[:, 0], "o", color=c, ms=5, mec="black", mew=0.6, zorder=8)
        ax.plot(*a.xy_LU[:, -1], "s", color=c, ms=5, mec="black", mew=0.6, zorder=8)
    # perilune direction of the first pass (the symmetry axis the paper refers to)
    row = geo.burns.iloc[0]
    th = math.radians(row.perilune_angle_deg)
    (x0, x1), (y0, y1) = _burn_zoom_limits(geo)
    ax.plot([0, 2 * math.cos(th)], [0, 2 * math.sin(th)], color="0.3", lw=0.9, ls="--",
            label="perilune direction (first pass)")
    # labels at the ignition points: the first outside the arcs, the others inside them
    for a in burns:
        p = a.xy_LU[:, 0]
        out = p / np.linalg.norm(p)
        shift = 0.12 if a.burn == 1 else -0.16 * (a.burn - 1)
        ax.annotate(f"burn {a.burn}", p, xytext=(p + shift * out),
                    fontsize=10, color=burn_colour(a.burn), fontweight="bold",
                    ha="center", va="center",
                    bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.8),
                    arrowprops=dict(arrowstyle="-", color="0.4", lw=0.7))
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.set_xlabel(_PLANE_XLABEL)
    ax.set_ylabel(_PLANE_YLABEL)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=9, framealpha=0.9)
    ax.set_title("(a) zoom on the burn arcs (● ignition, ■ cutoff)", fontsize=10, loc="left")

    # (b) altitude vs angle from each pass's perilune (data: CaptureGeometry.pass_profiles)
    rows = {int(r.burn): r for _, r in geo.burns.iterrows()}
    for prof in geo.pass_profiles():
        k, row = prof["burn"], rows[prof["burn"]]
        c = burn_colour(k)
        if prof["kind"] == "burn":
            ax2.plot(prof["angle_deg"], prof["altitude_km"], color=c, lw=3.0,
                     solid_capstyle="butt", zorder=4,
                     label=f"burn {k}: {row.ignition_from_perilune_deg:+.1f}° to "
                           f"{row.cutoff_from_perilune_deg:+.1f}°")
        else:
            ax2.plot(prof["angle_deg"], prof["altitude_km"], color=c, lw=0.9, ls="--",
                     alpha=0.8)
    ax2.axvline(0, color="0.3", lw=0.8, ls="--")
    ax2.set_xlim(-75, 75)
    top = max(row.ignition_radius_km for _, row in geo.burns.iterrows()) - C.R_MOON
    ax2.set_ylim(0, 1.6 * top)
    ax2.set_xlabel("angle in the orbit plane from the pass's perilune (deg)")
    ax2.set_ylabel("altitude (km)")
    ax2.grid(alpha=0.3)
    ax2.legend(loc="upper center", fontsize=9.5, framealpha=0.9)
    ax2.set_title("(b) altitude along each perilune pass (dashed: coasting)", fontsize=10,
                  loc="left")
    return fig


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
    axs[0].legend(loc="upper left", fontsize=9.5)
    axs[1].plot(t, d.beta_deg, color="tab:orange", lw=1.8)
    lim = max(0.5, 1.3 * float(np.abs(d.beta_deg).max()))
    axs[1].set_ylim(-lim, lim)
    axs[1].axhline(0.0, color="0.6", lw=0.8, ls=":")
    axs[1].set_ylabel("out-of-plane angle β (deg)")
    axs[2].plot(t, d.m_kg, color="tab:blue", lw=1.8, label="lunarcap")
    if paper_mass_end_kg is not None:
        axs[2].plot([t_end], [paper_mass_end_kg], "D", color="black", ms=6, mfc="none",
                    label=f"paper: {paper_mass_end_kg:g} kg after burn {d.burn} (Sec. 3.2.1)")
        axs[2].legend(loc="upper right", fontsize=9.5)
    axs[2].set_ylabel("mass (kg)")
    axs[2].set_xlabel(f"time from burn {d.burn} ignition (min)")
    for ax in axs:
        ax.grid(alpha=0.3)
        if t[0] <= d.perilune_min <= t[-1]:
            ax.axvline(d.perilune_min, color="0.4", lw=0.9, ls="--")
    axs[0].text(d.perilune_min, 0.04, " nominal perilune", fontsize=9, va="bottom",
                ha="left", color="0.3", transform=axs[0].get_xaxis_transform())
    return fig


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
    xy = d.xy_km
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    extent = float((hi - lo).max())
    R = C.R_MOON
    ax.add_patch(plt.Circle((0, 0), R, color="0.85", zorder=0))
    if geo is not None:  # the trajectory up to 30 min before ignition and after cutoff
        t_ign = geo.select("burn", d.burn)[0].t_s[0]
        t_cut = geo.select("burn", d.burn)[0].t_s[-1]
        for a in geo.arcs:
            if a.kind == "burn":
                continue
            m = (a.t_s >= t_ign - 1800.0) & (a.t_s <= t_cut + 1800.0)
            if m.any() and a.kind in ("hyperbola", "coast"):
                c = HYPERBOLA_COLOUR if a.kind == "hyperbola" else coast_colour(a.burn)
                ax.plot(*(a.xy_LU[:, m] * C.LU_KM), color=c, lw=1.0, label=a.label)
    ax.plot(*xy, color="0.25", lw=1.2, label=f"burn {d.burn} arc", zorder=5)
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
    ax.legend(loc="lower right", fontsize=9, framealpha=0.9)
    ax.set_title(f"(a) burn {d.burn}: velocity (blue) and thrust acceleration (red), projected",
                 fontsize=10, loc="left")
    ax2.plot(d.t_min, d.angle_deg, color="black", lw=1.6)
    ax2.plot(d.t_min[i], d.angle_deg[i], "o", color="black", ms=3)
    ax2.axhline(90.0, color="tab:red", lw=0.8, ls=":")
    ax2.text(d.t_min[0], 91.5, " 90°: above it the thrust slows the spacecraft", fontsize=9,
             color="tab:red", va="bottom")
    ax2.set_ylim(80, 182)
    ax2.set_xlabel(f"time from burn {d.burn} ignition (min)")
    ax2.set_ylabel("angle thrust–velocity (deg)")
    ax2.grid(alpha=0.3)
    ax2.set_title("(b) angle between the thrust acceleration and the velocity (3-D)",
                  fontsize=10, loc="left")
    return fig


# =============================================================================== Tables 1-5
def plot_sweep_dv(sweep, printed=None, printed_label: str = "paper"):
    """Delta-V (m/s) against ignition offset (min) of one ignition sweep.

    Parameters
    ----------
    sweep : DataFrame from :func:`lunarcap.runs.sweeps.sweep_table` (``start_min``,
        ``delta_v_mps``, ``best``, ``eq19_duration_min``; ``attrs["impulsive_delta_v_mps"]``)
    printed : DataFrame of the paper's rows (``start_min``, ``delta_v_mps``), optional
    printed_label : legend text of the paper's rows

    Returns
    -------
    matplotlib.figure.Figure
    """
    imp = sweep.attrs["impulsive_delta_v_mps"]
    eq19_min = float(sweep.eq19_duration_min.iloc[0])
    fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
    order = sweep.sort_values("start_min")
    ax.plot(order.start_min, order.delta_v_mps, "o-", color="C0", label="lunarcap")
    if printed is not None:
        ax.plot(printed.start_min, printed.delta_v_mps, "s", mfc="none", mec="C1", ms=8,
                label=printed_label)
    b = sweep[sweep.best].iloc[0]
    ax.plot(b.start_min, b.delta_v_mps, "*", color="C0", ms=14, label="our best")
    ax.axhline(imp, color="0.4", ls=":", lw=1, label=f"impulsive, paper ({imp:.3f} m/s)")
    ax.axvline(-eq19_min / 2, color="C2", ls="--", lw=1,
               label=f"−½ Eq. (19) duration ({-eq19_min / 2:.2f} min)")
    ax.set_xlabel("ignition, min from the nominal perilune")
    ax.set_ylabel("ΔV (m/s)")
    ax.grid(alpha=0.3)
    fig.legend(loc="outside lower center", ncols=2, fontsize=9, frameon=False)
    return fig


# =============================================================================== trade study
def _trade_axes(ax, newton_per_ratio: float):
    """Log thrust-to-weight axis with the thrust (N) on a secondary top axis."""
    ax.set_xscale("log")
    top = ax.secondary_xaxis("top", functions=(lambda r: np.asarray(r) * newton_per_ratio,
                                               lambda t: np.asarray(t) / newton_per_ratio))
    top.set_xlabel("thrust (N)", fontsize=9)
    top.tick_params(labelsize=9)
    ax.grid(alpha=0.3, which="both")


def _isp_colours(isp_s) -> dict:
    cycle = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return {float(isp): cycle[k % len(cycle)] for k, isp in enumerate(isp_s)}


def plot_trade_study_loss(ok, theory, paper, isp_s, part_titles: dict,
                          newton_per_ratio: float, ylim=(0.01, 40.0)):
    """Loss (% of the impulsive delta-V, log) against thrust-to-weight, one panel per part.

    Parameters
    ----------
    ok : DataFrame of the study's verified rows (``part``, ``isp_s``, ``thrust_to_weight``,
        ``objective_loss_percent``); rows with a loss <= 0 are not drawn (log axis)
    theory : DataFrame of Robbins' estimate on a dense grid (``analytic_loss_percent``), only where
    it
        is to be drawn
    paper : DataFrame of the paper's engines (``thrust_N``, ``isp_s``, ``thrust_to_weight``,
        ``part``, ``paper_delta_v_loss_percent``), drawn as stars
    isp_s : the specific impulses (s), one colour each
    part_titles : ``{part: panel title}``, in panel order (four panels, 2 x 2)
    newton_per_ratio : thrust (N) of a thrust-to-weight ratio of 1 (top axis)
    ylim : loss axis limits, %

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = _isp_colours(isp_s)
    fig, axes = plt.subplots(2, 2, figsize=(FIG_WIDTH_IN, 8.2), layout="constrained",
                             sharex=True)
    for ax, part in zip(axes.flat, part_titles):
        for k, isp in enumerate(isp_s):
            d = ok[(ok.part == part) & (ok.isp_s == isp) & (ok.objective_loss_percent > 0)]
            d = d.sort_values("thrust_to_weight")
            ax.plot(d.thrust_to_weight, d.objective_loss_percent, "-", marker=ISP_MARKERS[k % 6],
                    ms=4,
                    lw=1.4, color=colours[float(isp)], label=f"optimal, Isp {isp:g} s")
            th = theory[(theory.part == part) & (theory.isp_s == isp)]
            ax.plot(th.thrust_to_weight, th.analytic_loss_percent, ls=(0, (5, 2)),
                    color=colours[float(isp)], lw=1.6, label=f"Robbins (1966), Isp {isp:g} s")
        for r in paper[paper.part == part].itertuples(index=False):
            ax.plot(r.thrust_to_weight, r.paper_delta_v_loss_percent, marker="*", ms=13, ls="none",
                    color=colours.get(float(r.isp_s), "black"), mec="black", mew=0.7)
            ax.annotate(f"{r.thrust_N:g} N / {r.isp_s:g} s",
                        (r.thrust_to_weight, r.paper_delta_v_loss_percent), xytext=(6, 3),
                        textcoords="offset points", fontsize=9)
        _trade_axes(ax, newton_per_ratio)
        ax.set_yscale("log")
        ax.set_ylim(*ylim)
        ax.set_title(part_titles[part], fontsize=10)
        ax.set_ylabel("loss (% of the impulsive ΔV)")
    for ax in axes[1]:
        ax.set_xlabel("thrust-to-weight ratio T / (m₀ g₀)")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    handles.append(plt.Line2D([], [], marker="*", ms=11, ls="none", color="0.6", mec="black"))
    labels.append("paper, Table B1 (colour: its Isp)")
    fig.legend(handles, labels, loc="outside lower center", ncol=2, fontsize=9)
    return fig


def plot_trade_study_duration(ok, isp_s, part_titles: dict, newton_per_ratio: float):
    """Optimal burn duration and ignition offset, each over the Eq. (19) duration.

    Parameters
    ----------
    ok : DataFrame of the study's verified LOI rows (``part``, ``isp_s``,
        ``thrust_to_weight``, ``burn_duration_min``, ``start_min``, ``eq19_duration_min``)
    isp_s : the specific impulses (s), one colour each
    part_titles : ``{part: column title}`` of the burns (three columns)
    newton_per_ratio : thrust (N) of a thrust-to-weight ratio of 1 (top axis)

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = _isp_colours(isp_s)
    parts = list(part_titles)
    fig, axes = plt.subplots(len(parts), 2, figsize=(FIG_WIDTH_IN, 2.6 * len(parts) + 0.8),
                             layout="constrained", sharex=True, squeeze=False)
    for i, part in enumerate(parts):
        for k, isp in enumerate(isp_s):
            d = ok[(ok.part == part) & (ok.isp_s == isp)].sort_values("thrust_to_weight")
            style = dict(marker=ISP_MARKERS[k % 6], ms=4, lw=1.4, color=colours[float(isp)],
                         label=f"Isp {isp:g} s")
            axes[i, 0].plot(d.thrust_to_weight, d.burn_duration_min / d.eq19_duration_min,
                            **style)
            axes[i, 1].plot(d.thrust_to_weight, d.start_min / d.eq19_duration_min, **style)
        axes[i, 0].axhline(1.0, color="0.4", ls="--", lw=1, label="Eq. (19)")
        axes[i, 1].axhline(-0.5, color="0.4", ls="--", lw=1, label="−½ Eq. (19) (the rule)")
        axes[i, 0].set_title(f"{part_titles[part]}: duration", fontsize=10)
        axes[i, 1].set_title(f"{part_titles[part]}: ignition", fontsize=10)
        axes[i, 0].set_ylabel("optimal / Eq. (19)")
        axes[i, 1].set_ylabel("offset / Eq. (19) duration")
        for ax in axes[i]:
            _trade_axes(ax, newton_per_ratio)
    for ax in axes[-1]:
        ax.set_xlabel("T / (m₀ g₀)")
    axes[0, 0].legend(fontsize=9)
    axes[0, 1].legend(fontsize=9)
    return fig


# ======================================================== summary and verification pages
def plot_summary_loss(chains: dict):
    """Delta-V loss per LOI of each engine's best chain: the paper's and ours, two ways.

    Parameters
    ----------
    chains : {engine label: DataFrame} from :func:`lunarcap.runs.sweeps.sequence_table`
        (``loi``, ``paper_delta_v_mps``, ``paper_impulsive_delta_v_mps``,
        ``loss_vs_paper_impulse_mps``,
        ``delta_v_loss_mps``), one bar group per LOI, one panel per engine.

    Returns
    -------
    matplotlib.figure.Figure
    """
    n = len(chains)
    fig, axes = plt.subplots(1, n, figsize=(FIG_WIDTH_IN, 4.0), sharey=True,
                             layout="constrained", squeeze=False)
    w = 0.27
    for ax, (name, s) in zip(axes[0], chains.items()):
        x = np.arange(len(s))
        ax.bar(x - w, s.paper_delta_v_mps - s.paper_impulsive_delta_v_mps, w, color="C1",
               label="paper (Table B1)")
        ax.bar(x, s.loss_vs_paper_impulse_mps, w, color="C0",
               label="ours vs the paper's impulsive ΔV")
        ax.bar(x + w, s.delta_v_loss_mps, w, color="C2", label="ours vs our impulsive ΔV")
        ax.set_xticks(x, [f"LOI {k}" for k in s.loi])
        ax.set_title(name, fontsize=10)
        ax.grid(axis="y", alpha=0.3)
    axes[0][0].set_ylabel("ΔV loss (m/s)")
    fig.legend(*axes[0][0].get_legend_handles_labels(), loc="outside lower center",
               ncols=1, fontsize=9, frameon=False)
    return fig


def plot_mesh_convergence(mesh, tol_dv_mps: float, default_points: int):
    """Delta-V change from the finest mesh against the number of collocation points.

    Parameters
    ----------
    mesh : DataFrame with ``case``, ``collocation_points``, ``delta_v_change_vs_finest_mps``
        and ``accepted`` (bool: passed the gate), one row per case and mesh; the finest
        mesh of each case (change exactly 0) is the reference and is not drawn
    tol_dv_mps : the delta-V gate (m/s), drawn dotted
    default_points : collocation points of the default mesh, drawn dashed

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, ax = plt.subplots(figsize=(6.4, 4.6), layout="constrained")
    for k, (case, g) in enumerate(mesh.groupby("case", sort=False)):
        g = g[g.delta_v_change_vs_finest_mps != 0]
        y = g.delta_v_change_vs_finest_mps.abs().clip(lower=1e-12)
        ok = g.accepted.astype(bool)
        ax.plot(g.collocation_points, y, "-", color=f"C{k}", lw=1)
        if ok.any():
            ax.plot(g.collocation_points[ok], y[ok], "o", color=f"C{k}",
                    label=f"{case}, accepted")
        if (~ok).any():
            ax.plot(g.collocation_points[~ok], y[~ok], "x", color=f"C{k}", ms=8,
                    label=f"{case}, rejected by the gate")
    ax.axhline(tol_dv_mps, color="0.4", ls=":", lw=1, label="ΔV gate (m/s)")
    ax.axvline(default_points, color="0.4", ls="--", lw=1, label="default mesh")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xticks([20, 30, 50, 100, 200, 300], ["20", "30", "50", "100", "200", "300"])
    ax.set_xticks([], minor=True)
    ax.set_xlabel("collocation points")
    ax.set_ylabel("|ΔV − ΔV on the finest mesh| (m/s)")
    ax.grid(alpha=0.3, which="both")
    fig.legend(loc="outside lower center", ncols=2, fontsize=9, frameon=False)
    return fig


# ======================================================== free-ignition page
def plot_free_ignition_rule(rule):
    """Optimal ignition against the Eq. (19)/2 rule (top) and the residual (bottom).

    Parameters
    ----------
    rule : DataFrame from :func:`lunarcap.report.pages.free_ignition.rule_table`
        (``engine``, ``burn``, ``rule_start_min``, ``free_start_min``, ``grid_start_min``,
        ``eq19_duration_min``, ``start_minus_rule_min``; min).

    Returns
    -------
    matplotlib.figure.Figure
    """
    marks = {1: "o", 2: "s", 3: "^"}
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 7.6), layout="constrained")
    for k, engine in enumerate(dict.fromkeys(rule.engine)):
        for r in rule[rule.engine == engine].itertuples():
            m = marks.get(int(r.burn), "D")
            ax.plot(r.rule_start_min, r.free_start_min, m, color=f"C{k}", ms=7)
            if np.isfinite(r.grid_start_min):
                ax.plot(r.rule_start_min, r.grid_start_min, m, color=f"C{k}", ms=9,
                        mfc="none", alpha=0.7)
            bx.plot(r.eq19_duration_min, r.start_minus_rule_min, m, color=f"C{k}", ms=7)
        ax.plot([], [], "-", color=f"C{k}", lw=6, label=engine)
    lo = np.nanmin([rule.rule_start_min.min(), rule.free_start_min.min(),
                    rule.grid_start_min.min()]) - 0.7
    ax.plot([lo, 0], [lo, 0], "k--", lw=0.8, label="optimal = −Eq. (19)/2")
    for n in sorted(set(int(b) for b in rule.burn)):
        ax.plot([], [], marks.get(n, "D"), color="0.4", label=f"burn {n}")
    ax.plot([], [], "o", color="0.4", mfc="none", label="best grid point")
    ax.set_xlabel("rule start, −Eq. (19) duration / 2 (min)")
    ax.set_ylabel("ignition (min from the nominal perilune)")
    ax.set_title("filled: free optimum; open: paper's best grid point", fontsize=9)
    ax.legend(fontsize=9.5, loc="upper left")
    ax.grid(alpha=0.3)
    bx.axhline(0, color="k", lw=0.8)
    bx.set_xlabel("Eq. (19) duration (min)")
    bx.set_ylabel("optimal start − rule start (min)")
    bx.set_title("negative: the optimum ignites earlier than the rule", fontsize=9)
    bx.grid(alpha=0.3)
    return fig


# =============================================================================== steering laws
def plot_steering_penalty(steer, engines: list, laws=("inertial", "antivelocity")):
    """Delta-V and J penalties of simple steering laws per LOI, one column per engine.

    Parameters
    ----------
    steer : DataFrame of :func:`lunarcap.runs.sweeps.steering_table` rows of every engine
        (``engine``, ``loi``, ``steering``, ``delta_v_penalty_mps``,
        ``objective_penalty_mps``, ``rp_miss_km``)
    engines : engine labels (the ``engine`` column), one column of panels each, in order
    laws : the laws drawn (bars side by side per LOI); an antivelocity bar whose perilune
        radius is missed is labelled with the miss (km)

    Returns
    -------
    matplotlib.figure.Figure
    """
    colours = {"inertial": "C0", "antivelocity": "C3"}
    n = len(engines)
    fig, axes = plt.subplots(2, n, figsize=(FIG_WIDTH_IN, 6.0), sharex=True, squeeze=False,
                             layout="constrained")
    w = 0.72 / len(laws)
    for j, eng in enumerate(engines):
        sel = steer[steer.engine == eng]
        for k, law in enumerate(laws):
            s = sel[sel.steering == law].sort_values("loi")
            off = (k - (len(laws) - 1) / 2) * w
            c = colours.get(law, f"C{k + 4}")
            axes[0][j].bar(s.loi + off, s.delta_v_penalty_mps, w, color=c, label=law)
            axes[1][j].bar(s.loi + off, s.objective_penalty_mps, w, color=c, label=law)
            if law == "antivelocity":
                for r in s.itertuples():
                    if r.rp_miss_km:
                        axes[1][j].annotate(f"rp {r.rp_miss_km:+.1f} km",
                                            (r.loi + off, r.objective_penalty_mps),
                                            xytext=(0, 2), textcoords="offset points",
                                            ha="center", va="bottom", fontsize=9,
                                            rotation=90)
        axes[0][j].set_title(eng, fontsize=10)
        for ax in axes[:, j]:
            ax.axhline(0, color="k", lw=0.6)
            ax.grid(axis="y", alpha=0.3)
            ax.margins(y=0.15)
        x = np.arange(1, 4)
        axes[1][j].set_xticks(x, [f"LOI {i}" for i in x])
    axes[0][0].set_ylabel("ΔV penalty (m/s)")
    axes[1][0].set_ylabel("J penalty (m/s)")
    axes[0][-1].legend(fontsize=9)
    return fig


# =============================================================================== other engines
def plot_engine_loss(totals, loss_column: str, loss_label: str):
    """Total loss and propellant of the capture against thrust, one marker per engine.

    Parameters
    ----------
    totals : DataFrame, one row per engine (``thrust_N``, ``isp_s``, ``origin``: a name for
        an engine cited by the paper, "paper's engine" for the paper's own,
        ``total_fuel_kg`` and ``loss_column``)
    loss_column : column of the loss drawn (m/s)
    loss_label : y-axis label of the loss, naming its impulsive reference

    Returns
    -------
    matplotlib.figure.Figure
    """
    isp_colours = {200.0: "C0", 250.0: "C1", 300.0: "C2"}
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.6), sharex=True,
                                 layout="constrained")
    for r in totals.sort_values("thrust_N").itertuples():
        c = isp_colours.get(float(r.isp_s), "C7")
        cited = r.origin != "paper's engine"
        for a, y in ((ax, getattr(r, loss_column)), (bx, r.total_fuel_kg)):
            a.plot(r.thrust_N, y, "D" if cited else "o", color=c, ms=8,
                   mfc=c if cited else "white", mew=2)
            a.annotate(r.origin if cited else f"{r.thrust_N:g} N", (r.thrust_N, y),
                       xytext=(6, 4), textcoords="offset points", fontsize=9)
    for isp, c in isp_colours.items():
        if isp in set(totals.isp_s.astype(float)):
            ax.plot([], [], "s", color=c, label=f"Isp {isp:g} s")
    ax.plot([], [], "o", color="0.4", mfc="white", mew=2, label="paper's engines")
    ax.plot([], [], "D", color="0.4", label="cited in Sec. 3.1")
    ax.set_ylabel(loss_label)
    ax.legend(fontsize=9)
    bx.set_xlabel("thrust (N)")
    bx.set_ylabel("propellant, LOI 1–3 (kg)")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.margins(x=0.2, y=0.12)
    return fig


# =============================================================================== burn count
def plot_burn_count(counts):
    """Total loss and time to the final orbit against the number of burns, one line per plan.

    Parameters
    ----------
    counts : DataFrame, one row per (plan, count) with ``label``, ``n_burns``, ``status``,
        ``total_delta_v_loss_mps`` and ``time_to_final_orbit_h`` (rows not "ok" are drawn as an
        open marker on the axis: no capture with that count)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(FIG_WIDTH_IN, 6.4), sharex=True,
                                 layout="constrained")
    for j, (label, g) in enumerate(counts.groupby("label", sort=False)):
        g = g.sort_values("n_burns")
        ok = g[g.status == "ok"]
        c = f"C{j}"
        m = ISP_MARKERS[j % len(ISP_MARKERS)]
        ax.plot(ok.n_burns, ok.total_delta_v_loss_mps, "-", marker=m, color=c, label=label)
        bx.plot(ok.n_burns, ok.time_to_final_orbit_h, "-", marker=m, color=c, label=label)
        bad = g[g.status != "ok"]
        for a in (ax, bx):
            a.plot(bad.n_burns, np.zeros(len(bad)), "x", color=c, ms=9, mew=2)
    ax.set_ylabel("total loss vs impulsive limit (m/s)")
    bx.set_ylabel("arrival perilune → end of last burn (h)")
    bx.set_xlabel("number of burns")
    for a in (ax, bx):
        a.grid(alpha=0.3)
        a.set_xticks(sorted(set(counts.n_burns.astype(int))))
    ax.plot([], [], "x", color="0.4", mew=2, label="no plan (infeasible or failed)")
    ax.legend(fontsize=9)
    return fig


# =============================================================================== missed thrust
def plot_missed_penalty(cases):
    """Penalty map of a missed burn: fraction flown × delay, the penalty written in each cell.

    Parameters
    ----------
    cases : DataFrame, one row per case with ``fraction``, ``delay_min``, ``status``,
        ``penalty_mps`` and ``cutoff_orbit`` (cells without a recovery are grey, marked
        "none"; an "esc." under the number marks a cut-off on a hyperbola)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fr = sorted(set(cases.fraction.astype(float)))
    de = sorted(set(cases.delay_min.astype(float)))
    grid = np.full((len(fr), len(de)), np.nan)
    fig, ax = plt.subplots(figsize=(7.2, 0.8 + 0.75 * len(fr)), layout="constrained")
    for r in cases.itertuples():
        i, j = fr.index(float(r.fraction)), de.index(float(r.delay_min))
        if r.status == "recovered":
            grid[i, j] = max(float(r.penalty_mps), 0.0)
    vmax = max(np.nanmax(grid), 1.0) if np.isfinite(grid).any() else 1.0
    shown = np.ma.masked_invalid(np.log10(grid + 1.0))
    im = ax.imshow(shown, cmap="viridis_r", vmin=0, vmax=np.log10(vmax + 1.0), aspect="auto",
                   origin="lower")
    ax.set_facecolor("0.85")
    for r in cases.itertuples():
        i, j = fr.index(float(r.fraction)), de.index(float(r.delay_min))
        txt = (("0" if abs(r.penalty_mps) < 0.005 else  # no "-0.0" for a null penalty
                f"{r.penalty_mps:.2f}" if abs(r.penalty_mps) < 1 else f"{r.penalty_mps:.1f}")
               if r.status == "recovered" else "none")
        if r.cutoff_orbit == "escape":
            txt += "\nesc."
        ax.text(j, i, txt, ha="center", va="center", fontsize=9,
                color="k" if r.status != "recovered" or grid[i, j] < vmax / 3 else "w")
    ax.set_xticks(range(len(de)), [f"{d:g}" for d in de])
    ax.set_yticks(range(len(fr)), [f"{f:g}" for f in fr])
    ax.set_xlabel("delay before the recovery (min)")
    ax.set_ylabel("fraction of the burn flown")
    cb = fig.colorbar(im, ax=ax)
    ticks = [t for t in (0, 1, 10, 100, 1000) if t <= vmax]
    cb.set_ticks([np.log10(t + 1.0) for t in ticks], labels=[f"{t:g}" for t in ticks])
    cb.set_label("penalty (m/s)")
    return fig


# =============================================================================== exchange
def plot_exported_trajectory(arcs, r_moon_km: float):
    """The exported trajectory, as read back from the OEM, in two ICRF projections.

    Parameters
    ----------
    arcs : list of (name, xyz (3, N) km ICRF, is_burn)
    r_moon_km : the Moon's radius, km (the grey disc)

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig, axes = plt.subplots(1, 2, figsize=(FIG_WIDTH_IN, 3.8), layout="constrained")
    burn_labelled = False
    for (i, j), ax in zip(((0, 1), (0, 2)), axes):
        _moon(ax, r_moon_km, label=False)
        k = 0
        for name, xyz, is_burn in arcs:
            if is_burn:
                ax.plot(xyz[i], xyz[j], color=burn_colour(1), lw=3.0, zorder=4,
                        solid_capstyle="butt",
                        label=None if burn_labelled or ax is axes[1] else "burns")
                burn_labelled = True
            else:
                ax.plot(xyz[i], xyz[j], color=HYPERBOLA_COLOUR if name == "approach"
                        else coast_colour(k), lw=1.1,
                        label=name if ax is axes[0] else None)
                k += name != "approach"
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel(f"{'xyz'[i]} ICRF (km)")
        ax.set_ylabel(f"{'xyz'[j]} ICRF (km)")
    fig.legend(loc="outside lower center", ncols=6, fontsize=8.5)
    return fig
