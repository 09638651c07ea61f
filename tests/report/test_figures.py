"""The data behind the book's figures and tables (not their pixels)."""

import math

import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import pytest

from lunarcap.mission.scenario import paper_engines, paper_scenario
from lunarcap.paper.audit import AUDIT_CHECK_TITLES
from lunarcap.physics import constants as C
from lunarcap.physics.frames import thrust_angles_deg, thrust_direction_rtn
from lunarcap.report import display, figdata, figures, reproduction
from lunarcap.report.figures import capture_sequence as sequence_figures
from lunarcap.report.figures import fig1_geometry as fig1_figures
from lunarcap.report.pages import capture_sequence as sequence_page
from lunarcap.report.pages import fig1_geometry as fig1_page
from lunarcap.repro import paths


def _unit(rng, n):
    u = rng.normal(size=(3, n))
    return u / np.linalg.norm(u, axis=0)


# ------------------------------------------------------------------ Eq. (14)
def test_eq14_on_random_directions():
    rng = np.random.default_rng(14)
    u = _unit(rng, 500)
    alpha, beta = thrust_angles_deg(u)
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
    a, b = thrust_angles_deg(u)
    if alpha is not None:
        assert float(a) == pytest.approx(alpha, abs=1e-12)
    assert float(b) == pytest.approx(beta, abs=1e-12)


def test_thrust_direction_inverts_eq14():
    rng = np.random.default_rng(1)
    for a, b in zip(rng.uniform(0, 360, 200), rng.uniform(-89.9, 89.9, 200)):
        u = thrust_direction_rtn(a, b)
        assert np.linalg.norm(u) == pytest.approx(1.0, abs=1e-14)
        aa, bb = thrust_angles_deg(u)
        assert float(aa) == pytest.approx(a, abs=1e-9) and float(bb) == pytest.approx(b, abs=1e-9)


def test_eq14_agrees_with_the_solution_module():
    sol = pytest.importorskip("lunarcap.optim.solution")
    if not hasattr(sol, "thrust_angles_deg"):
        pytest.skip("lunarcap.optim.solution has no thrust_angles_deg")
    u = _unit(np.random.default_rng(3), 100)
    for ours, theirs in zip(thrust_angles_deg(u), sol.thrust_angles_deg(u)):
        np.testing.assert_allclose(ours, theirs, atol=1e-12)


# ------------------------------------------------------------------ Fig. 1
@pytest.mark.parametrize("alpha, beta, nu", [(55.0, 30.0, -40.0), (180.0, 0.0, 0.0),
                                             (137.5, -10.0, 25.0), (300.0, 80.0, 170.0)])
def test_fig1_geometry_is_consistent_with_eq14(alpha, beta, nu):
    g = fig1_page.fig1_geometry(alpha_deg=alpha, beta_deg=beta, true_anomaly_deg=nu)
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
    g0 = fig1_page.fig1_geometry(true_anomaly_deg=0.0)
    assert g0.flight_path_angle_deg == pytest.approx(0.0, abs=1e-9)      # v along i_t
    r = np.linalg.norm(g0.orbit_LU, axis=0) * C.LU_KM
    assert r.min() == pytest.approx(C.R_MOON + 100.0, rel=1e-9)          # 100 km perilune
    g = fig1_page.fig1_geometry(true_anomaly_deg=-40.0)
    assert g.flight_path_angle_deg < 0                                   # approaching perilune
    assert g.v_hat @ g.rtn[1] == pytest.approx(math.cos(math.radians(g.flight_path_angle_deg)))


def test_fig1_accepts_a_direction_and_rejects_bad_ones():
    g = fig1_page.fig1_geometry(u_rtn=[0.0, -2.0, 0.0])
    assert g.alpha_deg == pytest.approx(180.0) and g.beta_deg == pytest.approx(0.0)
    for bad in ([0, 0, 0], [1, np.nan, 0], [1, 0]):
        with pytest.raises(ValueError):
            fig1_page.fig1_geometry(u_rtn=bad)


def test_fig1_vectors_table():
    t = fig1_page.fig1_geometry().vectors_table()
    assert list(t.columns) == ["vector", "x", "y", "z"] and len(t) == 7
    assert t[["x", "y", "z"]].notna().all().all()


def test_plot_fig1_draws_both_panels():
    fig = fig1_figures.plot_fig1_geometry(fig1_page.fig1_geometry())
    assert len(fig.axes) == 2
    assert fig.axes[0].get_xlabel().endswith("(LU)") and fig.axes[0].get_ylabel() == "y (LU)"
    plt.close(fig)


# ------------------------------------------------------------------ tables and files
def test_markdown_table_formatting():
    df = pd.DataFrame({"name": ["a|b", "c"], "v": [-0.0004, np.inf], "w": [np.nan, 2.0]})
    md = display.markdown_table(df, {"v": "+.2f", "w": ".1f"}).splitlines()
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
    md = display.show_table(df, "t1", "Caption (m/s).", "notebooks/x.ipynb", {"a": 1},
                          labels={"dv_mps": "ΔV (m/s)"}, display=False)
    assert (gen / "tables" / "t1.csv").read_text() == "dv_mps\n1.23456\n"
    assert ":::{table} Caption (m/s)." in md and ":name: tbl-t1" in md
    assert "| ΔV (m/s) |" in md and "| 1.235 |" in md
    assert "{download}`t1.csv <tables/t1.csv>`" in md and "`notebooks/x.ipynb` with a=1" in md
    fig = fig1_figures.plot_fig1_geometry(fig1_page.fig1_geometry())
    md = display.show_figure(fig, "f1", "A caption (deg).", "notebooks/x.ipynb", display=False)
    for ext in ("png", "svg"):
        assert (gen / "figures" / f"f1.{ext}").stat().st_size > 1000
    assert ":::{figure} figures/f1.png" in md and ":name: fig-f1" in md
    assert not [p for p in (gen / "figures").iterdir() if ".tmp" in p.name]


def test_paper_tables_and_figures_carry_the_papers_number_and_no_book_number(tmp_path,
                                                                            monkeypatch):
    # one that regenerates the paper's has the paper's number at the head of its caption,
    # no label and the class that lunarcap.bookbuild.sphinx_ext keeps from being numbered
    # (the quick book's test_caption_numbers_never_read_like_the_papers checks the HTML)
    gen = tmp_path / "generated"
    monkeypatch.setattr(paths, "GENERATED", gen)
    monkeypatch.setattr(paths, "TABLES", gen / "tables")
    monkeypatch.setattr(paths, "FIGURES", gen / "figures")
    df = pd.DataFrame({"dv_mps": [1.0]})
    md = display.show_table(df, "t2", "Delta-V (m/s).", "notebooks/x.ipynb", display=False,
                            paper="Table 1")
    assert md.startswith(":::{table} **Song et al. (2011) Table 1.** Delta-V (m/s).\n")
    assert ":name:" not in md and "\n:class: lc-paper\n" in md
    fig = fig1_figures.plot_fig1_geometry(fig1_page.fig1_geometry())
    md = display.show_figure(fig, "f2", "Geometry.", "notebooks/x.ipynb", display=False,
                             paper="Fig. 1")
    assert "\n\n**Song et al. (2011) Fig. 1.** Geometry. " in md and ":name:" not in md
    assert "\n:figclass: lc-paper\n" in md
    from lunarcap.bookbuild import sphinx_ext

    assert sphinx_ext.PAPER_CLASS == display.PAPER_CLASS == "lc-paper"


# ------------------------------------------------------------------ Figs. 2-5: capture sequence
def test_orbit_plane_basis_is_right_handed_and_follows_the_pole():
    rng = np.random.default_rng(2)
    for _ in range(50):
        r, v = rng.normal(size=3) * 2000, rng.normal(size=3)
        b = figdata.orbit_plane_basis(r, v)
        np.testing.assert_allclose(b @ b.T, np.eye(3), atol=1e-12)
        np.testing.assert_allclose(np.cross(b[0], b[1]), b[2], atol=1e-12)
        h = np.cross(r, v)
        np.testing.assert_allclose(b[2], h / np.linalg.norm(h), atol=1e-12)
        assert abs(b[:2] @ h).max() < 1e-9 * np.linalg.norm(h)   # e_x, e_y in the plane
        assert b[0][2] == pytest.approx(0.0, abs=1e-12)          # e_x on the equator
    # a polar orbit: e_y is the M-MME2000 z axis and the orbit turns counter-clockwise
    b = figdata.orbit_plane_basis([1838.2, 0, 0], [0.2, 0, 1.6])
    np.testing.assert_allclose(b[1], [0, 0, 1], atol=1e-12)
    # equatorial orbit: falls back on the direction of r
    b = figdata.orbit_plane_basis([1838.2, 0, 0], [0, 1.6, 0])
    np.testing.assert_allclose(b[1], [1, 0, 0], atol=1e-12)
    with pytest.raises(ValueError):
        figdata.orbit_plane_basis([1, 0, 0], [2, 0, 0])


@pytest.fixture(scope="module")
def capture():
    """The paper's 150 N plan (-10, -6, -5 min): solved once, then from the disk cache."""
    from lunarcap.capture.chain import arrival_for, solve_plan
    from lunarcap.mission.plan import load_plan

    plan = load_plan("song2011-150N")
    sols = solve_plan(plan)
    return sols, plan, figdata.capture_geometry(sols, arrival_for(plan.arrival))


@pytest.mark.slow
def test_capture_geometry_burn_arcs_lie_near_the_100km_perilune(capture):
    sols, plan, geo = capture
    rp = C.R_MOON + paper_scenario().perilune_altitude_km
    burns = geo.select("burn")
    assert [a.burn for a in burns] == [1, 2, 3]
    assert geo.max_out_of_plane_km < 10.0           # the chain stays in the arrival plane
    for a in burns:
        r = a.radius_km
        r_proj = np.linalg.norm(a.xy_LU, axis=0) * C.LU_KM
        np.testing.assert_allclose(r_proj, r, atol=0.05)     # projection keeps radii
        assert abs(r.min() - rp) < 2.0, (a.burn, r.min())      # perilune at 100 km +- 2 km
        assert (r >= rp - 2.0).all() and r.max() < rp + 400.0
    # ignition before and cutoff after each pass's perilune, both within 60 deg of it
    t = geo.burns
    assert (t.ignition_from_perilune_deg < 0).all() and (t.cutoff_from_perilune_deg > 0).all()
    assert (t.ignition_from_perilune_deg > -60).all() and (t.cutoff_from_perilune_deg < 60).all()
    np.testing.assert_allclose(t.burn_duration_min,
                               [s.summary()["burn_duration_min"] for s in sols], atol=1e-6)
    np.testing.assert_allclose(t.perilune_radius_km, rp, atol=2.0)


@pytest.mark.slow
def test_capture_geometry_arcs_join_up(capture):
    sols, plan, geo = capture
    hyp = geo.select("hyperbola")[0]
    burns, coasts = geo.select("burn"), geo.select("coast")
    assert hyp.t_s[0] < hyp.t_s[-1] == pytest.approx(sols[0].problem.t_ign_s)
    assert (np.diff(hyp.t_s) > 0).all()
    assert hyp.t_s[-1] - hyp.t_s[0] == pytest.approx(
        geo.hyperbola_hours * 3600 - 60 * 10.0, abs=1e-6)
    np.testing.assert_allclose(hyp.r_km[:, -1], burns[0].r_km[:, 0], atol=1e-3)
    for n in range(3):
        np.testing.assert_allclose(burns[n].r_km[:, -1], coasts[n].r_km[:, 0], atol=1e-3)
        if n < 2:   # each coast ends where the next burn ignites (km)
            np.testing.assert_allclose(coasts[n].r_km[:, -1], burns[n + 1].r_km[:, 0],
                                       atol=1e-2)
            assert coasts[n].t_s[-1] == pytest.approx(sols[n + 1].problem.t_ign_s)
    final = geo.select("final")[0]
    rp_km = C.R_MOON + paper_scenario().perilune_altitude_km
    np.testing.assert_allclose(final.radius_km, rp_km, atol=25.0)
    # the hyperbola without LOI 1 leaves the Moon; the captured path does not
    assert geo.select("uncaptured")[0].radius_km[-1] > 3 * C.R_MOON
    assert coasts[0].radius_km.max() < 8 * C.R_MOON


@pytest.mark.slow
def test_fig4_steering_data(capture):
    sols = capture[0]
    d = figdata.fig4_steering(sols[0])
    s = sols[0].summary()
    assert d.m_kg[0] == pytest.approx(s["m_start_kg"], abs=1e-9)
    assert d.m_kg[-1] == pytest.approx(s["m_end_kg"], abs=1e-6)
    assert (np.diff(d.m_kg) < 0).all()                        # mass decreases throughout
    assert d.t_min[0] == pytest.approx(0.0, abs=1e-9)
    assert d.burn_duration_min == pytest.approx(s["burn_duration_min"], abs=1e-9)
    assert d.perilune_min == pytest.approx(10.0)
    # Sec. 3.3: alpha from about 137.5 to 215.3 deg through 180, beta almost 0
    assert abs(d.alpha_deg[0] - 137.5) < 3 and abs(d.alpha_deg[-1] - 215.3) < 3
    assert np.abs(d.beta_deg).max() < 0.5
    assert list(d.table().columns) == ["min_from_ignition", "alpha_deg", "beta_deg", "m_kg"]


@pytest.mark.slow
def test_fig5_thrust_opposes_velocity_through_the_burn(capture):
    sols, plan, geo = capture
    d = sequence_page.fig5_vectors(sols[0], geo.basis)
    assert (d.angle_deg > 90).all()                           # "tend to de-accelerate"
    # the projected vectors keep the angle (the motion is nearly planar)
    cos2d = (d.v_xy_kmps * d.a_xy_mps2).sum(0) / (np.linalg.norm(d.v_xy_kmps, axis=0)
                                                   * np.linalg.norm(d.a_xy_mps2, axis=0))
    assert (cos2d < 0).all()
    # thrust acceleration T/m, m/s^2, grows as the mass falls
    acc = np.linalg.norm(d.a_mps2, axis=0)
    h = figdata.fig4_steering(sols[0])
    np.testing.assert_allclose(acc, 150.0 / h.m_kg, rtol=1e-9)
    assert d.arrows[0] == 0 and d.arrows[-1] == d.t_min.size - 1
    assert len(d.table()) == d.arrows.size


@pytest.mark.slow
def test_capture_figures_draw(capture):
    sols, plan, geo = capture
    figs = [(figures.plot_fig2_capture(geo), 1),
            (sequence_figures.plot_fig3_burn_arcs(geo), 2),
            (sequence_figures.plot_fig4_steering(figdata.fig4_steering(sols[0]), (137.5, 215.3),
                                                 434.471, 19.51), 3),
            (sequence_figures.plot_fig5_vectors(sequence_page.fig5_vectors(sols[0], geo.basis),
                                                geo), 2)]
    for fig, n_axes in figs:
        assert len(fig.axes) == n_axes
        for ax in fig.axes:   # units on every axis (shared x axes: on the bottom one)
            assert "(" in ax.get_ylabel()
            assert "(" in ax.get_xlabel() or ax is not fig.axes[-1] and not ax.get_xlabel()
        assert "(" in fig.axes[-1].get_xlabel()
        assert figures.legibility_problems(fig) == []
        plt.close(fig)
    # Fig. 5 (a): the arrows stand out from every orbit and arc drawn under them (the
    # velocity arrows were blue on the blue capture orbit)
    ax = figs[3][0].axes[0]
    from matplotlib.colors import to_hex
    from matplotlib.quiver import Quiver

    lines = {to_hex(ln.get_color()) for ln in ax.get_lines() if ln.get_linestyle() != "None"}
    arrows = [to_hex(q.get_facecolor()[0]) for q in ax.get_children() if isinstance(q, Quiver)]
    assert len(arrows) == 2 and not set(arrows) & lines, (arrows, lines)


# ------------------------------------------------------------------ reproduction report
def _fake_sweep(thrust, loi, isp):
    from lunarcap.paper import printed as paper
    p = paper.paper_table(thrust, loi)
    df = pd.DataFrame({
        "start_min": p.start_min.astype(float), "free_start": False,
        "paper_burn_duration_min": p.burn_duration_min, "burn_duration_min":
            p.burn_duration_min + 0.01, "paper_delta_v_mps": p.delta_v_mps,
        "delta_v_mps": p.delta_v_mps - 0.5, "paper_delta_v_loss_percent": p.diff_percent,
        "loss_vs_paper_impulse_percent": p.diff_percent + 0.1, "paper_best": p.best,
        "verified": True})
    df["best"] = df.delta_v_mps == df.delta_v_mps.min()
    df.attrs.update(thrust_N=float(thrust), isp_s=isp, loi=loi)
    return df


def test_paper_tables_long_has_every_printed_number():
    from lunarcap.paper import printed as paper
    sweeps = {(150.0, n): _fake_sweep(150, n, 200.0) for n in (1, 2, 3)}
    t = reproduction.paper_tables_long(sweeps, impulsive_dv_mps=[353.272, 254.0, 245.5])
    n_rows = sum(len(paper.paper_table(150, n)) for n in (1, 2, 3))
    assert (t.source != "Table B1").sum() == 3 * n_rows + 3
    assert (t.source == "Table B1").sum() == 9 and t[t.source == "Table B1"].paper_best.all()
    np.testing.assert_allclose(t.difference, t.ours - t.paper)
    dv = t[(t.quantity == "delta-V")]
    np.testing.assert_allclose(dv.difference, -0.5, atol=1e-9)
    imp = t[t.quantity == reproduction.IMPULSE_ROW_TWO_BODY]
    np.testing.assert_allclose(imp.difference, [0.0, 254.0 - 254.034, 245.5 - 245.363],
                               atol=1e-9)
    assert set(t.unit) == {"min", "m/s", "%"}
    assert t[t.source == "Table 1"].start_min.nunique() == 6


def _fake_chain(thrust, isp):
    from lunarcap.paper import printed as paper
    out, m = [], paper_scenario().mass_kg
    for n in (1, 2, 3):
        b = paper.paper_best(thrust, n)
        imp = paper.PAPER_IMPULSIVE_DV_MPS[n - 1]
        m_end = m * math.exp(-b["delta_v_mps"] / (C.G0_MPS2 * isp))
        out.append({"loss_vs_paper_impulse_mps": b["delta_v_mps"] - imp,
                    "loss_vs_paper_impulse_percent": 100 * (b["delta_v_mps"] - imp) / imp,
                    "burn_duration_min": b["burn_duration_min"], "m_start_kg": m,
                    "m_end_kg": m_end, "fuel_kg": m - m_end, "eq19_duration_min": 10.0 * n,
                    "rp_end_km": C.R_MOON + 100.0, "inc_end_deg": 90.0})
        m = m_end
    return out


def test_quote_equivalents_and_comparison():
    from lunarcap.paper import printed as paper
    chains = {t: _fake_chain(t, isp) for t, isp in tuple(paper_engines().items())}
    ours = reproduction.quote_equivalents(
        chains, impulsive_final_mass_kg={t: 340.0 for t, _ in tuple(paper_engines().items())},
        best_starts={(150.0, 1): -10.0, (150.0, 2): -6.0, (150.0, 3): -5.0},
        audit_values={"period/final": 117.868})
    assert set(ours) <= set(paper.QUOTES)
    q = reproduction.quotes_comparison(ours)
    assert len(q) == len(paper.QUOTES) and q.name.is_unique
    by = q.set_index("name")
    # signs of the ignition offsets follow the printed convention ("10" minutes before)
    assert by.loc["best_start_loi1_150N_min", "ours"] == 10.0
    assert by.loc["best_start_loi2_150N_min", "ours"] == -6.0
    # totals: the sum of Table B1's losses (20.273 m/s), and a percentage of the total
    assert by.loc["loss_total_150N_mps", "ours"] == pytest.approx(20.273, abs=1e-9)
    assert by.loc["loss_total_150N_percent", "ours"] == pytest.approx(2.3776, abs=1e-4)
    assert by.loc["burn_total_150N_min", "ours"] == pytest.approx(41.02, abs=1e-9)
    assert by.loc["fuel_finite_150N_kg", "ours"] == pytest.approx(
        paper_scenario().mass_kg - chains[150.0][2]["m_end_kg"])
    assert by.loc["fuel_impulsive_150N_kg", "ours"] == pytest.approx(paper_scenario().mass_kg - 340)
    assert by.loc["eq19_half_loi3_150N_min", "ours"] == pytest.approx(15.0)
    assert "117.868" in by.loc["period_final_min", "note"]
    assert by.loc["mu_sun_km3s2", "ours"] == C.MU_SUN
    # no equivalent: NaN and said so
    none = q[q.ours.isna()]
    assert (none.note.str.contains("no equivalent")).all() and none.difference.isna().all()
    assert {"lro_thrust_N", "kick_motor_dry_mass_kg"} <= set(none.name)
    assert "fig4_alpha_start_deg" in set(none.name)            # no Fig. 4 data given
    np.testing.assert_allclose(q.difference.dropna(), (q.ours - q.paper).dropna())


def test_epochs_comparison():
    from lunarcap.physics.epochs import seconds_from_calendar

    t0 = seconds_from_calendar(paper_scenario().epoch_tdb)
    ep = np.cumsum([t0, *paper_scenario().capture_periods_s])
    t = reproduction.epochs_comparison(ep)
    assert list(t.perilune) == [1, 2, 3]
    np.testing.assert_allclose(t.difference_s, [0.0, -1.0, -3.0], atol=1e-6)
    assert t.ours.iloc[0] == "2017-02-20 03:41:26 TDB"


def test_short_where_and_check_titles():
    assert reproduction.short_where("Sec. 3.2.1, para 2 ('As shown in Table 1...')") == \
        "Sec. 3.2.1, para 2"
    from lunarcap.paper import audit
    assert set(audit.findings_table().check) <= set(AUDIT_CHECK_TITLES)


def test_quotes_display_is_compact_and_keeps_every_row():
    chains = {t: _fake_chain(t, isp) for t, isp in tuple(paper_engines().items())}
    q = reproduction.quotes_comparison(reproduction.quote_equivalents(chains))
    d = reproduction.quotes_display(q, max_words=40)
    assert len(d) == len(q) and list(d.columns) == ["words", "printed", "ours",
                                                    "difference", "note"]
    assert (d.words.str.split(": ", n=1).str[1].str.len() <= 40).all()
    row = d[q.name == "loss_total_150N_mps"].iloc[0]
    assert row.printed == "20.20 m/s" and row.ours == "20.273" and row.difference == "+0.073"
    assert d[q.name == "abstract_period_capture1_h"].ours.iloc[0] == "12.235"
    assert row["words"].startswith("§3.2.1 ¶")
    none = d[q.ours.isna()]
    assert (none.ours == "—").all() and (none.difference == "—").all()
    # gravitational parameters: grouped digits, one decimal, no exponent
    sun = d[q.name == "mu_sun_km3s2"].iloc[0]
    assert sun.ours == "132,712,440,018.0" and sun.difference == "+119,441,195,810.4"
    assert sun.printed == "13,271,244,207.6 km³/s²"


def test_findings_display():
    from lunarcap.paper import audit
    t = audit.findings_table(only_inconsistent=True)
    d = reproduction.findings_display(t)
    assert len(d) == len(t) and list(d.columns) == ["finding", "printed", "computed",
                                                    "explanation"]
    row = d[t.id == "sun-gm"].iloc[0]
    assert row.finding == "a: sun-gm" and row.printed == "13,271,244,207.6 km³/s²"
    assert row.computed == "132,712,440,018.0 km³/s²"
    assert row.explanation.startswith("Sec. 3.1, para 1. ")
