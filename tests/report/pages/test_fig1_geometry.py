"""The Fig. 1 page (lunarcap.report.pages.fig1_geometry): geometry only, no solver."""

import math

import numpy as np
import pytest

from lunarcap.report.pages import fig1_geometry


@pytest.fixture(scope="module")
def page():
    return fig1_geometry.build(55.0, 30.0, -40.0, 12.235, "t_fig1", True)


def test_rtn_triad_is_orthonormal_and_u_has_the_drawn_angles(page):
    t = page.items["vectors"].df.set_index("vector")
    rtn = t.loc[["i_r", "i_t", "i_n"], ["x", "y", "z"]].to_numpy()
    np.testing.assert_allclose(rtn @ rtn.T, np.eye(3), atol=1e-12)
    u = t.loc["u", ["x", "y", "z"]].to_numpy(float)
    assert np.linalg.norm(u) == pytest.approx(1.0)
    # Eq. (14): beta from the normal component, alpha from the in-plane ones
    assert u @ rtn[2] == pytest.approx(math.sin(math.radians(30.0)))
    assert math.degrees(math.atan2(u @ rtn[0], u @ rtn[1])) == pytest.approx(55.0)
    # the position is radial: r / |r| = i_r, in LU beyond the lunar surface
    r = t.loc["r (LU)", ["x", "y", "z"]].to_numpy(float)
    np.testing.assert_allclose(r / np.linalg.norm(r), rtn[0], atol=1e-12)
    assert np.linalg.norm(r) > 1.0


def test_values_checks_and_caption(page):
    assert page.values["alpha_deg"] == pytest.approx(55.0)
    assert page.values["beta_deg"] == pytest.approx(30.0)
    # before perilune the spacecraft descends: negative flight-path angle
    assert page.values["gamma_deg"] < 0
    assert "period 12.235 h" in page.items["rtn"].caption
    assert page.items["rtn"].paper == "Fig. 1" and page.items["vectors"].paper is None
    assert page.parameters == dict(alpha_deg=55.0, beta_deg=30.0, true_anomaly_deg=-40.0,
                                   period_h=12.235)
    page.check()


def test_angle_beyond_180_and_perilune_position():
    p = fig1_geometry.build(215.0, -5.0, 0.0, 3.525, "t_fig1b", True)
    p.check()  # Eq. (14) gives back 215 deg (four-quadrant) and -5 deg
    assert p.values["alpha_deg"] == pytest.approx(215.0)
    assert p.values["gamma_deg"] == pytest.approx(0.0, abs=1e-9)  # v along i_t at perilune
