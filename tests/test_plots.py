"""The data behind the book's figures and tables (not their pixels)."""

import math

import numpy as np
import pandas as pd
import pytest

from lunarcap import constants as C
from lunarcap import paths, plots


def _unit(rng, n):
    u = rng.normal(size=(3, n))
    return u / np.linalg.norm(u, axis=0)


# ------------------------------------------------------------------ Eq. (14)
def test_eq14_on_random_directions():
    rng = np.random.default_rng(14)
    u = _unit(rng, 500)
    alpha, beta = plots.thrust_angles_deg(u)
    np.testing.assert_allclose(alpha, np.degrees(np.arctan2(u[0], u[1])) % 360, atol=1e-12)
    np.testing.assert_allclose(beta, np.degrees(np.arcsin(u[2])), atol=1e-12)
    assert ((alpha >= 0) & (alpha < 360)).all() and (np.abs(beta) <= 90).all()


@pytest.mark.parametrize("u, alpha, beta", [
    ((0, 1, 0), 0.0, 0.0),      # along i_t
    ((1, 0, 0), 90.0, 0.0),     # along i_r
    ((0, -1, 0), 180.0, 0.0),   # braking
    ((-1, 0, 0), 270.0, 0.0),
    ((0, 0, 1), None, 90.0),    # along i_n: alpha undefined
    ((0, 1, 1), 0.0, 45.0),     # not normalised: beta from u_n / |u|
])
def test_eq14_special_directions(u, alpha, beta):
    a, b = plots.thrust_angles_deg(u)
    if alpha is not None:
        assert float(a) == pytest.approx(alpha, abs=1e-12)
    assert float(b) == pytest.approx(beta, abs=1e-12)


def test_thrust_direction_inverts_eq14():
    rng = np.random.default_rng(1)
    for a, b in zip(rng.uniform(0, 360, 200), rng.uniform(-89.9, 89.9, 200)):
        u = plots.thrust_direction_rtn(a, b)
        assert np.linalg.norm(u) == pytest.approx(1.0, abs=1e-14)
        aa, bb = plots.thrust_angles_deg(u)
        assert float(aa) == pytest.approx(a, abs=1e-9) and float(bb) == pytest.approx(b, abs=1e-9)


def test_eq14_agrees_with_the_solution_module():
    sol = pytest.importorskip("lunarcap.solution")
    if not hasattr(sol, "thrust_angles_deg"):
        pytest.skip("lunarcap.solution has no thrust_angles_deg")
    u = _unit(np.random.default_rng(3), 100)
    for ours, theirs in zip(plots.thrust_angles_deg(u), sol.thrust_angles_deg(u)):
        np.testing.assert_allclose(ours, theirs, atol=1e-12)


# ------------------------------------------------------------------ Fig. 1
@pytest.mark.parametrize("alpha, beta, nu", [(55.0, 30.0, -40.0), (180.0, 0.0, 0.0),
                                             (137.5, -10.0, 25.0), (300.0, 80.0, 170.0)])
def test_fig1_geometry_is_consistent_with_eq14(alpha, beta, nu):
    g = plots.fig1_geometry(alpha_deg=alpha, beta_deg=beta, true_anomaly_deg=nu)
    assert g.alpha_deg == pytest.approx(alpha % 360, abs=1e-9)
    assert g.beta_deg == pytest.approx(beta, abs=1e-9)
    q = g.rtn
    np.testing.assert_allclose(q @ q.T, np.eye(3), atol=1e-12)            # orthonormal
    np.testing.assert_allclose(np.cross(q[0], q[1]), q[2], atol=1e-12)    # right-handed
    np.testing.assert_allclose(q @ g.u, g.u_rtn, atol=1e-12)              # u in RTN
    np.testing.assert_allclose(q[0], g.r_LU / np.linalg.norm(g.r_LU), atol=1e-12)
    np.testing.assert_allclose(q[2], [0, 0, 1], atol=1e-12)               # orbit in x-y
    assert g.u_plane @ q[2] == pytest.approx(0, abs=1e-12)
    assert np.linalg.norm(g.u_plane) == pytest.approx(1, abs=1e-12)
    # the alpha arc runs in the orbit plane from i_t to the projection of u
    np.testing.assert_allclose(g.alpha_arc[:, 0], q[1], atol=1e-12)
    np.testing.assert_allclose(g.alpha_arc[:, -1], g.u_plane, atol=1e-9)
    assert np.abs(q[2] @ g.alpha_arc).max() < 1e-12
    # the beta arc runs from the projection to u
    np.testing.assert_allclose(g.beta_arc[:, 0], g.u_plane, atol=1e-12)
    np.testing.assert_allclose(g.beta_arc[:, -1], g.u, atol=1e-9)
    for arc in (g.alpha_arc, g.beta_arc):
        np.testing.assert_allclose(np.linalg.norm(arc, axis=0), 1.0, atol=1e-12)


def test_fig1_orbit_and_flight_path_angle():
    g0 = plots.fig1_geometry(true_anomaly_deg=0.0)
    assert g0.flight_path_angle_deg == pytest.approx(0.0, abs=1e-9)      # v along i_t
    r = np.linalg.norm(g0.orbit_LU, axis=0) * C.LU_KM
    assert r.min() == pytest.approx(C.R_MOON + 100.0, rel=1e-9)          # 100 km perilune
    g = plots.fig1_geometry(true_anomaly_deg=-40.0)
    assert g.flight_path_angle_deg < 0                                   # approaching perilune
    assert g.v_hat @ g.rtn[1] == pytest.approx(math.cos(math.radians(g.flight_path_angle_deg)))


def test_fig1_accepts_a_direction_and_rejects_bad_ones():
    g = plots.fig1_geometry(u_rtn=[0.0, -2.0, 0.0])
    assert g.alpha_deg == pytest.approx(180.0) and g.beta_deg == pytest.approx(0.0)
    for bad in ([0, 0, 0], [1, np.nan, 0], [1, 0]):
        with pytest.raises(ValueError):
            plots.fig1_geometry(u_rtn=bad)


def test_fig1_vectors_table():
    t = plots.fig1_geometry().vectors_table()
    assert list(t.columns) == ["vector", "x", "y", "z"] and len(t) == 7
    assert t[["x", "y", "z"]].notna().all().all()


def test_plot_fig1_draws_both_panels():
    fig = plots.plot_fig1_geometry(plots.fig1_geometry())
    assert len(fig.axes) == 2
    assert fig.axes[0].get_xlabel().endswith("(LU)") and fig.axes[0].get_ylabel() == "y (LU)"
    plots.plt.close(fig)


# ------------------------------------------------------------------ tables and files
def test_markdown_table_formatting():
    df = pd.DataFrame({"name": ["a|b", "c"], "v": [-0.0004, np.inf], "w": [np.nan, 2.0]})
    md = plots.markdown_table(df, {"v": "+.2f", "w": ".1f"}).splitlines()
    assert md[0] == "| name | v | w |"
    assert md[1] == "|:---|---:|---:|"
    assert md[2] == "| a\\|b | 0.00 | — |"          # no "-0.00", NaN as a dash
    assert md[3] == "| c | ∞ | 2.0 |"


def test_show_table_and_figure_write_files(tmp_path, monkeypatch):
    gen = tmp_path / "generated"
    monkeypatch.setattr(paths, "GENERATED", gen)
    monkeypatch.setattr(paths, "TABLES", gen / "tables")
    monkeypatch.setattr(paths, "FIGURES", gen / "figures")
    df = pd.DataFrame({"dv_mps": [1.23456]})
    md = plots.show_table(df, "t1", "Caption (m/s).", "notebooks/x.ipynb", {"a": 1},
                          labels={"dv_mps": "ΔV (m/s)"}, display=False)
    assert (gen / "tables" / "t1.csv").read_text() == "dv_mps\n1.23456\n"
    assert ":::{table} Caption (m/s)." in md and ":name: tbl-t1" in md
    assert "| ΔV (m/s) |" in md and "| 1.235 |" in md
    assert "{download}`t1.csv <tables/t1.csv>`" in md and "`notebooks/x.ipynb` with a=1" in md
    fig = plots.plot_fig1_geometry(plots.fig1_geometry())
    md = plots.show_figure(fig, "f1", "A caption (deg).", "notebooks/x.ipynb", display=False)
    for ext in ("png", "svg"):
        assert (gen / "figures" / f"f1.{ext}").stat().st_size > 1000
    assert ":::{figure} figures/f1.png" in md and ":name: fig-f1" in md
    assert not [p for p in (gen / "figures").iterdir() if ".tmp" in p.name]
