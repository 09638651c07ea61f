"""Drawing of the book's figures: each function draws data computed by :mod:`.figdata`.

Nothing here computes a trajectory or solves anything (checked by an import-linter
contract: this module, and so every module it imports, imports neither the propagator nor
the optimiser); the data functions and their tests are in :mod:`lunarcap.report.figdata`.

The figures live in one module per family, re-exported here so that pages and notebooks
draw through ``figures.plot_...``:

* :mod:`.figstyle`: sizes, fonts, colours, the Moon, :func:`save_figure`;
* :mod:`.figures_capture`: the paper's Figs. 1-5 (RTN angles, the capture sequence);
* :mod:`.figures_studies`: sweeps, trade study, summary, verification, free ignition,
  steering laws, other engines, burn count, missed thrust, exported trajectory, the
  real Moon's evolution.
"""

from lunarcap.report.figstyle import (
    FIG_WIDTH_IN,
    HYPERBOLA_COLOUR,
    ISP_MARKERS,
    MIN_FONT_PT,
    burn_colour,
    coast_colour,
    draw_moon,
    legibility_problems,
    save_figure,
)
from lunarcap.report.figures_capture import (
    plot_fig1_geometry,
    plot_fig2_capture,
    plot_fig3_burn_arcs,
    plot_fig4_steering,
    plot_fig5_vectors,
)
from lunarcap.report.figures_studies import (
    plot_burn_count,
    plot_engine_loss,
    plot_evolution,
    plot_exported_trajectory,
    plot_free_ignition_rule,
    plot_mesh_convergence,
    plot_missed_penalty,
    plot_steering_penalty,
    plot_summary_loss,
    plot_sweep_dv,
    plot_trade_study_duration,
    plot_trade_study_loss,
)

__all__ = [
    "FIG_WIDTH_IN", "HYPERBOLA_COLOUR", "ISP_MARKERS", "MIN_FONT_PT", "burn_colour",
    "coast_colour", "draw_moon", "legibility_problems", "save_figure",
    "plot_fig1_geometry", "plot_fig2_capture", "plot_fig3_burn_arcs", "plot_fig4_steering",
    "plot_fig5_vectors",
    "plot_burn_count", "plot_engine_loss", "plot_evolution", "plot_exported_trajectory",
    "plot_free_ignition_rule", "plot_mesh_convergence", "plot_missed_penalty",
    "plot_steering_penalty", "plot_summary_loss", "plot_sweep_dv", "plot_trade_study_duration",
    "plot_trade_study_loss",
]
