"""The burn-count figure: a count without a capture is not drawn as a value."""

import matplotlib
import numpy as np
import pandas as pd

from lunarcap.report import figures as F
from lunarcap.report.figures import burn_count

matplotlib.use("Agg")

LABELS = ("song2011-150N (150 N / 200 s, 524.895 kg)", "lro-like-5burn (320 N / 200 s, 1916 kg)")


def _counts():
    """Two plans, N = 1..3; the LRO-like plan infeasible in one burn, its N = 3 failed."""
    status = {(LABELS[1], 1): "infeasible", (LABELS[1], 3): "failed"}
    return pd.DataFrame([dict(label=lab, n_burns=n, status=status.get((lab, n), "ok"),
                              total_delta_v_loss_mps=np.nan if (lab, n) in status else 90.0 / n,
                              time_to_final_orbit_h=np.nan if (lab, n) in status else 8.0 * n)
                         for lab in LABELS for n in (1, 2, 3)])


def test_a_count_without_a_capture_is_marked_apart_not_drawn_as_a_value():
    """The book drew the LRO-like plan's infeasible single burn as a cross at a loss of 0,
    which reads as a free capture; it is now a mark in a strip without a value axis."""
    fig = burn_count.plot_burn_count(_counts())
    strip, loss, time = fig.axes
    for ax in (loss, time):                 # the value panels hold the captures only
        points = {(ln.get_color(), x) for ln in ax.get_lines()
                  for x in np.atleast_1d(ln.get_xdata())}
        lro = {x for c, x in points if c == strip.get_lines()[0].get_color()}
        assert lro == {2}, lro
    marks = {(float(ln.get_xdata()[0]), float(ln.get_ydata()[0]), ln.get_marker())
             for ln in strip.get_lines()}
    assert marks == {(1.0, 0.0, "x"), (3.0, 0.0, "$!$")}
    assert [t.get_text() for t in strip.get_yticklabels()] == ["lro-like-5burn"]
    assert "×: infeasible" in strip.get_title() and "!: failed" in strip.get_title()
    assert F.legibility_problems(fig) == []


def test_without_a_missing_count_there_is_no_strip():
    ok = _counts().assign(status="ok", total_delta_v_loss_mps=5.0, time_to_final_orbit_h=1.0)
    assert len(burn_count.plot_burn_count(ok).axes) == 2
