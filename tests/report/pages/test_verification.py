"""The verification page (lunarcap.report.pages.verification), two cases in two-body."""

import numpy as np
import pytest

import lunarcap
from lunarcap.capture.chain import paper_case
from lunarcap.optim import verify
from lunarcap.report.pages import verification

pytestmark = pytest.mark.slow

CASES = [[450.0, 300.0, 1, -3.0, []], [450.0, 300.0, 2, -2.0, [-3.0]]]


def _burns(cases, dynamics="two-body"):
    """Each case solved as the notebook solves it (lunarcap.solve_burn of lunarcap.paper_plan)."""
    return [lunarcap.solve_burn(lunarcap.paper_plan(t, i, dynamics=dynamics), n, start=s,
                                previous_starts=p, impulsive=False)
            for t, i, n, s, p in verification.cases_of(cases)]


@pytest.fixture(scope="module")
def page():
    chains = [lunarcap.solve(lunarcap.paper_plan(450.0, 300.0, dynamics="two-body"))]
    return verification.build(_burns(CASES), chains, CASES[:1], [[3, 6, 4], [8, 16, 5]],
                              "t_ver", True, dict(cases=CASES, dynamics="two-body"))


def test_the_public_solves_are_the_paper_cases_cached_solves():
    """lunarcap.solve_burn of lunarcap.paper_plan reaches the internal paper_case's solve
    (the same plan key, so the same cached solution and verification)."""
    for b, (t, i, n, s, p) in zip(_burns(CASES), verification.cases_of(CASES)):
        assert verification.case_of(b) == (t, i, n, s, p)
        sol = paper_case(t, i, n, s, p, "two-body")
        assert b.solution.summary() == sol.summary()


def test_every_case_passes_the_gate_with_margin(page):
    ver = page.items["cases"].df
    assert list(ver.case) == ["450 N, LOI 1, -3 min, B1", "450 N, LOI 2, -2 min, B1"]
    assert (ver.passed == "passed").all()
    assert (ver.final_position_diff_m.abs() < verify.TOL_POSITION_M).all()
    assert (ver.end_speed_diff_mps.abs() < verify.TOL_SPEED_MPS).all()
    assert (ver.objective_diff_mps.abs() < verify.TOL_DV_MPS).all()
    assert (ver.rp_error_m.abs() < verify.TOL_RP_M).all()
    assert (ver.gamma_error_deg.abs() < verify.TOL_ANGLE_DEG).all()
    assert ver.ra_error_m.isna().all()  # no circular target before LOI 3
    assert len(page.items["cases"].show_columns) <= 7
    assert "t_ver_cases_full.csv" in page.items["cases"].caption


def test_gate_table_is_the_worst_of_each_column(page):
    ver, gate = page.items["cases_full"].df, page.items["gate"].df.set_index("quantity")
    r = gate.loc["|r_p − target|"]
    assert r.worst == pytest.approx(ver.rp_error_m.abs().max())
    assert r.gate_over_worst == pytest.approx(verify.TOL_RP_M / r.worst)
    gated = gate[gate.gate.notna() & gate.worst.notna()]
    assert (gated.worst < gated.gate).all()


def test_impulsive_limit_is_the_richardson_extrapolation(page):
    imp = page.items["impulsive"].df
    np.testing.assert_allclose(imp.delta_v_mps,
                               (4 * imp.delta_v_short_mps - imp.delta_v_long_mps) / 3)
    np.testing.assert_allclose(imp.burn_short_s, imp.burn_long_s / 2, rtol=1e-6)
    assert (imp.burn_long_s > 3.0).all() and (imp.burn_long_s < 5.0).all()
    # a burn of seconds is nearly an impulse: the extrapolation is far below the gate
    assert (imp.extrapolation_mps.abs() < 0.1 * verify.TOL_DV_MPS).all()
    assert (imp.verified == "passed").all()
    # and any finite burn of the engine needs more
    fin = page.data["cases"].set_index("loi").delta_v_mps
    assert (imp.set_index("loi").delta_v_mps < fin).all()


def test_provenance_and_cases_follow_the_notebooks_solves(page):
    assert page.parameters == {"cases": CASES, "dynamics": "two-body"}
    assert list(page.items["impulsive"].df.loi) == [1, 2]   # the LOIs of the cases only


def test_mesh_table(page):
    m = page.items["mesh_full"].df
    assert list(m.collocation_points) == [36, 120]
    assert m.delta_v_change_vs_finest_mps.iloc[-1] == 0.0
    np.testing.assert_allclose(m.delta_v_change_vs_finest_mps,
                               m.delta_v_mps - m.delta_v_mps.iloc[-1])
    assert m.mesh.iloc[-1] == "8×16 LGR-5 (default)"
    assert ((m.accepted == "passed") == (m.outside_gate == "")).all()  # a reason per rejection
    v = page.values
    assert v["default_points"] == 120 and v["n_mesh_solves"] == 2
    assert v["n_cases"] == 2 and v["n_passed"] == 2
    page.check()


def test_fixed_point_has_no_exponent_and_no_negative_zero():
    fp = verification.fixed_point
    assert fp(3.0e-9) == "0.0000000030" and fp(2.47) == "2.5" and fp(33699.2) == "34,000"
    assert fp(-2.1e5, sign=True) == "-210,000" and fp(3.3e-4, sign=True) == "+0.00033"
    assert fp(-0.0, sign=True) == "0" and fp(float("nan")) == "—"
    for v in (1.234e-12, -9.99e-6, 0.0996, 12345.6):
        text = fp(v)
        assert "e" not in text and float(text.replace(",", "")) == pytest.approx(v, rel=0.05)


def test_shown_gate_and_mesh_tables_are_fixed_point(page):
    from lunarcap.report.display import markdown_table
    for key in ("gate", "mesh"):
        item = page.items[key]
        df = item.df[item.show_columns] if item.show_columns else item.df
        text = markdown_table(df, item.floatfmt)
        assert "e-0" not in text and "e+0" not in text and "-0 " not in text, key
