"""The drawing of Fig. 1 (page :mod:`lunarcap.report.pages.fig1_geometry`): the RTN angles.

It draws the data the page computes (:class:`~lunarcap.report.pages.fig1_geometry.Fig1Geometry`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.report.figstyle import ALPHA_COLOUR, BETA_COLOUR, RTN_COLOURS

if TYPE_CHECKING:  # data types, for annotations only
    from lunarcap.report.pages.fig1_geometry import Fig1Geometry


def _text_align(vec) -> dict:
    """Horizontal/vertical alignment that puts a label beyond the tip of a 2-D arrow."""
    ha = "left" if vec[0] > 0.35 else ("right" if vec[0] < -0.35 else "center")
    va = "bottom" if vec[1] > 0.35 else ("top" if vec[1] < -0.35 else "center")
    return {"ha": ha, "va": va}


_FIG1_COLOURS = {**RTN_COLOURS, "u": "black", "v": "0.45"}


def _fig1_plane(ax, geo: Fig1Geometry) -> None:
    """Fig. 1 (a): the orbit plane with i_r, i_t, v, the projected u and alpha."""
    col = _FIG1_COLOURS
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
    ax.plot(rx + arc[0], ry + arc[1], color=ALPHA_COLOUR, lw=1.2)
    mid = geo.alpha_arc[:, geo.alpha_arc.shape[1] // 2]
    ax.text(rx + 0.55 * s * mid[0], ry + 0.55 * s * mid[1], r"$\alpha$", color=ALPHA_COLOUR,
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


def _fig1_triad(ax3, geo: Fig1Geometry) -> None:
    """Fig. 1 (b): the RTN triad, u and its angles, in the triad's own axes."""
    col = _FIG1_COLOURS

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
    ax3.plot(*aa, color=ALPHA_COLOUR, lw=1.4)
    ax3.plot(*ba, color=BETA_COLOUR, lw=1.4)
    am = aa[:, aa.shape[1] // 2] * 1.3
    bm = ba[:, ba.shape[1] // 2] * 1.15
    ax3.text(*am, r"$\alpha$", color=ALPHA_COLOUR, fontsize=13)
    ax3.text(*bm, r"$\beta$", color=BETA_COLOUR, fontsize=13)
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
    _fig1_plane(ax, geo)
    _fig1_triad(ax3, geo)
    return fig
