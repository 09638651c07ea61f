"""One palette for the book, and figures whose key reads as easily as their axes.

Every colour of a figure comes from lunarcap.report.figstyle (one colour per orbit, burn
and engine on every page), and a figure whose legend is smaller than its axis text is
refused when it is saved for the book.
"""

import re
from pathlib import Path

import matplotlib
import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.colors import to_hex

from lunarcap.report import figstyle as S
from lunarcap.report.figures.exchange import plot_exported_trajectory

matplotlib.use("Agg")

REPORT = Path(S.__file__).parent
#: A colour literal: matplotlib's cycle ("C0", f"C{k}"), a named tableau colour, a hex code.
COLOUR_LITERAL = re.compile(r"""["'](C\d|tab:[a-z]+|#[0-9a-fA-F]{6})["']|f["']C\{""")


def _modules():
    return sorted([*REPORT.glob("figures*.py"), *(REPORT / "pages").glob("*.py")])


@pytest.mark.parametrize("path", _modules(), ids=lambda p: p.name)
def test_figure_and_page_modules_take_every_colour_from_the_palette(path):
    found = [ln.strip() for ln in path.read_text(encoding="utf-8").splitlines()
             if COLOUR_LITERAL.search(ln)]
    assert not found, f"{path.name}: colours not from figstyle: {found[:3]}"


def test_the_colour_literal_pattern_catches_what_it_must():
    for line in ('color="C0"', "color=f\"C{k}\"", "c='tab:blue'", 'mec="#1f77b4"'):
        assert COLOUR_LITERAL.search(line), line
    assert not COLOUR_LITERAL.search('color=coast_colour(1), ls="--", lw=0.8, color="0.4"')


def test_paper_engines_have_one_colour_whatever_names_them():
    for thrust, isp in ((150, 200), (300, 250), (450, 300)):
        c = S.engine_colour(thrust, isp)
        assert c == S.isp_colour(isp) == S.label_colour(f"song2011-{thrust}N") \
            == S.label_colour(f"{thrust} N / {isp} s") == S.engine_colour(thrust)
    colours = {S.engine_colour(t, i) for t, i in S.ENGINE_COLOURS}
    assert len(colours) == len(S.ENGINE_COLOURS)
    # an orbit and a burn never share a colour with the orbit or burn of the same number
    for n in range(1, 4):
        assert S.coast_colour(n) != S.burn_colour(n)
        assert S.colour_name(S.coast_colour(n)) != S.coast_colour(n)   # captions name it


def _arcs():
    t = np.linspace(0, 2 * np.pi, 50)
    ring = np.vstack([2000 * np.cos(t), 2000 * np.sin(t), 0 * t])
    names = ["approach", "burn 1", "coast 1", "burn 2", "coast 2", "burn 3", "final orbit"]
    return [(n, ring * (1 + 0.1 * k), n.startswith("burn")) for k, n in enumerate(names)]


def test_exported_trajectory_colours_each_orbit_and_burn_as_every_other_figure():
    fig = plot_exported_trajectory(_arcs(), 1738.2)
    colour = {ln.get_label(): to_hex(ln.get_color()) for ln in fig.axes[0].get_lines()}
    assert colour["coast 1"] == to_hex(S.coast_colour(1))      # the 12.235 h orbit: blue
    assert colour["coast 2"] == to_hex(S.coast_colour(2))
    assert colour["final orbit"] == to_hex(S.coast_colour(3))  # reached by burn 3
    assert colour["burn 2"] == to_hex(S.burn_colour(2))
    assert colour["approach"] == to_hex(S.HYPERBOLA_COLOUR)
    plt.close(fig)


def test_a_legend_smaller_than_the_axis_text_is_refused(tmp_path, monkeypatch):
    from lunarcap.repro import paths

    monkeypatch.setattr(paths, "FIGURES", tmp_path)
    fig, ax = plt.subplots(figsize=(S.FIG_WIDTH_IN, 3))
    ax.plot([0, 1], [0, 1], label="a curve")
    ax.set_xlabel("x (km)")
    ax.legend()                       # the book's default: as large as the axis labels
    assert S.legibility_problems(fig) == []
    ax.legend(fontsize=8)             # the dispersions page's legend before this change
    problems = S.legibility_problems(fig)
    assert any("legend" in p for p in problems) and any("below 9" in p for p in problems)
    with pytest.raises(ValueError, match="hard to read"):
        S.save_figure(fig, "small_legend")
    plt.close(fig)
