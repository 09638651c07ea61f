"""The drawing of Figs. 3-5 (page :mod:`lunarcap.report.pages.capture_sequence`).

The burn arcs and their altitudes (Fig. 3), the steering angles and mass (Fig. 4), and
the thrust acceleration against the velocity (Fig. 5), from the data the page computes.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import matplotlib.pyplot as plt
import numpy as np

from lunarcap.physics import constants as C
from lunarcap.report.figstyle import (
    ALPHA_COLOUR,
    BETA_COLOUR,
    HYPERBOLA_COLOUR,
    MASS_COLOUR,
    VELOCITY_COLOUR,
    burn_colour,
    coast_colour,
    colour_name,
    draw_moon,
)
from lunarcap.report.figures.capture import PLANE_XLABEL, PLANE_YLABEL

if TYPE_CHECKING:  # data types, for annotations only
    from lunarcap.report.figdata import CaptureGeometry, Fig4Steering
    from lunarcap.report.pages.capture_sequence import Fig5Vectors


def _burn_zoom_limits(geo, pad=0.25):
    xy = np.concatenate([a.xy_LU for a in geo.select("burn")], axis=1)
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    lo = np.minimum(lo, -0.05)  # keep part of the Moon in view
    span = (hi - lo).max()
    c = (lo + hi) / 2
    half = span * (0.5 + pad)
    return (c[0] - half, c[0] + half), (c[1] - half, c[1] + half)


def _fig3_zoom(ax, geo: CaptureGeometry) -> None:
    """Fig. 3 (a): Fig. 2 zoomed on the burn arcs, ignition and cutoff marked."""
    draw_moon(ax, label=False)
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
    ax.set_xlabel(PLANE_XLABEL)
    ax.set_ylabel(PLANE_YLABEL)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", framealpha=0.9)
    ax.set_title("(a) zoom on the burn arcs (● ignition, ■ cutoff)", fontsize=10, loc="left")


def _fig3_altitudes(ax2, geo: CaptureGeometry) -> None:
    """Fig. 3 (b): altitude against the angle from each pass's perilune (pass_profiles)."""
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
    ax2.legend(loc="upper center", framealpha=0.9)
    ax2.set_title("(b) altitude along each perilune pass (dashed: coasting)", fontsize=10,
                  loc="left")


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
    _fig3_zoom(ax, geo)
    _fig3_altitudes(ax2, geo)
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
    axs[0].plot(t, d.alpha_deg, color=ALPHA_COLOUR, lw=1.8, label="lunarcap")
    axs[0].axhline(180.0, color="0.6", lw=0.8, ls=":")
    if paper_alpha_deg is not None:
        axs[0].plot([t[0], t_end], paper_alpha_deg, "D", color="black", ms=6, mfc="none",
                    label="paper: start and end values (Sec. 3.3)")
    axs[0].set_ylabel("in-plane angle α (deg)")
    axs[0].legend(loc="upper left")
    axs[1].plot(t, d.beta_deg, color=BETA_COLOUR, lw=1.8)
    lim = max(0.5, 1.3 * float(np.abs(d.beta_deg).max()))
    axs[1].set_ylim(-lim, lim)
    axs[1].axhline(0.0, color="0.6", lw=0.8, ls=":")
    axs[1].set_ylabel("out-of-plane angle β (deg)")
    axs[2].plot(t, d.m_kg, color=MASS_COLOUR, lw=1.8, label="lunarcap")
    if paper_mass_end_kg is not None:
        axs[2].plot([t_end], [paper_mass_end_kg], "D", color="black", ms=6, mfc="none",
                    label=f"paper: {paper_mass_end_kg:g} kg after burn {d.burn} (Sec. 3.2.1)")
        axs[2].legend(loc="upper right")
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


def _fig5_context(ax, d: Fig5Vectors, geo: CaptureGeometry) -> None:
    """The trajectory up to 30 min before ignition and after cutoff (Fig. 5 (a))."""
    t_ign = geo.select("burn", d.burn)[0].t_s[0]
    t_cut = geo.select("burn", d.burn)[0].t_s[-1]
    for a in geo.arcs:
        if a.kind == "burn":
            continue
        m = (a.t_s >= t_ign - 1800.0) & (a.t_s <= t_cut + 1800.0)
        if m.any() and a.kind in ("hyperbola", "coast"):
            c = HYPERBOLA_COLOUR if a.kind == "hyperbola" else coast_colour(a.burn)
            ax.plot(*(a.xy_LU[:, m] * C.LU_KM), color=c, lw=1.0, label=a.label)


def _fig5_arrows(ax, d: Fig5Vectors, geo: CaptureGeometry | None,
                 arrow_fraction: float) -> None:
    """Fig. 5 (a): velocity and thrust-acceleration arrows along the arc, each to its scale."""
    xy = d.xy_km
    lo, hi = xy.min(axis=1), xy.max(axis=1)
    extent = float((hi - lo).max())
    ax.add_patch(plt.Circle((0, 0), C.R_MOON, color="0.85", zorder=0))
    if geo is not None:
        _fig5_context(ax, d, geo)
    ax.plot(*xy, color="0.6", lw=1.0, label=f"burn {d.burn} arc", zorder=5)
    i = d.arrows
    vmax = float(np.linalg.norm(d.v_xy_kmps[:, i], axis=0).max())
    amax = float(np.linalg.norm(d.a_xy_mps2[:, i], axis=0).max())
    L = arrow_fraction * extent
    v_scale = vmax / L    # km/s per km of arrow
    a_scale = amax / L    # m/s^2 per km of arrow
    qv = ax.quiver(xy[0, i], xy[1, i], d.v_xy_kmps[0, i], d.v_xy_kmps[1, i], angles="xy",
                   scale_units="xy", scale=v_scale, color=VELOCITY_COLOUR, width=0.006, zorder=6)
    qa = ax.quiver(xy[0, i], xy[1, i], d.a_xy_mps2[0, i], d.a_xy_mps2[1, i], angles="xy",
                   scale_units="xy", scale=a_scale, color=burn_colour(d.burn), width=0.006,
                   zorder=7)
    ax.plot(xy[0, i], xy[1, i], "o", color="black", ms=3, zorder=8)
    ax.annotate("ignition", xy[:, 0], xytext=(8, -2), textcoords="offset points", fontsize=9)
    ax.annotate("cutoff", xy[:, -1], xytext=(8, -2), textcoords="offset points", fontsize=9)
    v_ref = _nice(vmax)
    a_ref = _nice(amax)
    ax.quiverkey(qv, 0.04, 0.95, v_ref, f"velocity: arrow of {v_ref:g} km/s "
                 f"= {v_ref / v_scale:.0f} km", labelpos="E", coordinates="axes",
                 fontproperties={"size": 10})
    ax.quiverkey(qa, 0.04, 0.89, a_ref, f"thrust acceleration: arrow of {a_ref:g} m/s² "
                 f"= {a_ref / a_scale:.0f} km", labelpos="E", coordinates="axes",
                 fontproperties={"size": 10})
    pad = 0.3 * extent
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + 1.3 * pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x′: M-MME2000 equator, along the orbit's ascending node (km)")
    ax.set_ylabel("z: M-MME2000 pole (km)")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", framealpha=0.9)
    ax.set_title(f"(a) burn {d.burn}: velocity ({colour_name(VELOCITY_COLOUR)}) and thrust "
                 f"acceleration ({colour_name(burn_colour(d.burn))}), projected",
                 fontsize=10, loc="left")


def _fig5_angle(ax2, d: Fig5Vectors) -> None:
    """Fig. 5 (b): the angle between thrust acceleration and velocity against time."""
    i = d.arrows
    ax2.plot(d.t_min, d.angle_deg, color="black", lw=1.6)
    ax2.plot(d.t_min[i], d.angle_deg[i], "o", color="black", ms=3)
    ax2.axhline(90.0, color=burn_colour(d.burn), lw=0.8, ls=":")
    ax2.text(d.t_min[0], 91.5, " 90°: above it the thrust slows the spacecraft", fontsize=9,
             color=burn_colour(d.burn), va="bottom")
    ax2.set_ylim(80, 182)
    ax2.set_xlabel(f"time from burn {d.burn} ignition (min)")
    ax2.set_ylabel("angle thrust–velocity (deg)")
    ax2.grid(alpha=0.3)
    ax2.set_title("(b) angle between the thrust acceleration and the velocity (3-D)",
                  fontsize=10, loc="left")


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
    _fig5_arrows(ax, d, geo, arrow_fraction)
    _fig5_angle(ax2, d)
    return fig
