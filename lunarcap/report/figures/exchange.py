"""Figures of the exchange page: the exported trajectory in the orbit plane.

Drawn from data that :mod:`lunarcap.report.pages.exchange` computes; nothing here computes
a trajectory.
"""

from __future__ import annotations

import matplotlib.pyplot as plt

from lunarcap.report.figstyle import (
    FIG_WIDTH_IN,
    HYPERBOLA_COLOUR,
    burn_colour,
    coast_colour,
    colour_name,
    draw_moon,
)


def burn_colour_words(n_burns: int) -> str:
    """The burns' colours in the words of the caption, from the palette the figure uses.

    Caption and figure agree by construction: burn n is drawn in ``burn_colour(n)``.

    >>> burn_colour_words(3)
    'burns 1, 2 and 3 in red, orange and brown'
    >>> burn_colour_words(1)
    'the burn in red'
    """
    words = [colour_name(burn_colour(n)) for n in range(1, n_burns + 1)]
    if n_burns == 1:
        return f"the burn in {words[0]}"

    def both(xs):
        return ", ".join(xs[:-1]) + " and " + xs[-1]

    return f"burns {both([str(n) for n in range(1, n_burns + 1)])} in {both(words)}"


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
    n_burns = sum(bool(is_burn) for _, _, is_burn in arcs)
    for (i, j), ax in zip(((0, 1), (0, 2)), axes):
        draw_moon(ax, r_moon_km, label=False)
        for name, xyz, is_burn in arcs:
            # "burn n" and "coast n" (the orbit burn n reached) by n; the final orbit is
            # the last burn's
            n = n_burns if name == "final orbit" else int(name.split()[-1]) \
                if name.split()[-1].isdigit() else 0
            label = name if ax is axes[0] else None
            if is_burn:
                ax.plot(xyz[i], xyz[j], color=burn_colour(n), lw=3.0, zorder=4,
                        solid_capstyle="butt", label=label)
            else:
                ax.plot(xyz[i], xyz[j], color=coast_colour(n) if n else HYPERBOLA_COLOUR,
                        lw=1.1, label=label)
        ax.set_aspect("equal")
        ax.grid(alpha=0.3)
        ax.set_xlabel(f"{'xyz'[i]} ICRF (km)")
        ax.set_ylabel(f"{'xyz'[j]} ICRF (km)")
    fig.legend(loc="outside lower center", ncols=4)
    return fig
