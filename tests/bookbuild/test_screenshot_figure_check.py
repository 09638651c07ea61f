"""The figure check of `make screenshots`, without Chromium: a figure's natural width comes
from its PNG's pixels and recorded resolution, and a page whose figure is shown below
MIN_FIGURE_SCALE of it fails."""

import matplotlib
import matplotlib.pyplot as plt
import pytest

from lunarcap.bookbuild import screenshots as S

matplotlib.use("Agg")


def _png(tmp_path, width_in, dpi=150):
    fig = plt.figure(figsize=(width_in, 2))
    path = tmp_path / "_images" / f"f{width_in}.png"
    path.parent.mkdir(exist_ok=True)
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path, int(round(width_in * dpi))


def test_png_dpi_reads_the_resolution_matplotlib_records(tmp_path):
    path, _ = _png(tmp_path, 3.0, dpi=150)
    assert S.png_dpi(path) == pytest.approx(150, abs=0.1)
    assert S.png_dpi(tmp_path / "absent.png") is None


@pytest.mark.parametrize("width_in,fails", [(10.0, True), (6.8, False)])
def test_a_wide_figure_in_a_700_px_column_fails_the_page(tmp_path, width_in, fails):
    path, natural = _png(tmp_path, width_in)
    images = [{"label": "figure 1: x", "src": "http://127.0.0.1:1/_images/" + path.name,
               "naturalWidth": natural, "shownWidth": 700}]
    figs = S.figure_reports(images, "http://127.0.0.1:1/", tmp_path)
    assert figs[0]["scale"] == pytest.approx(700 / (width_in * 96), rel=1e-3)
    rep = S.PageReport("generated/trade_study", 1280, figures=figs)
    assert rep.ok is not fails
    assert ("FAIL" if fails else "ok") in rep.lines()[0]
    assert "figures 1 (smallest" in rep.lines()[0]
    assert (len(rep.lines()) > 1) is fails   # the shrunk figure is named
