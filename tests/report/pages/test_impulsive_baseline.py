"""The impulsive-baseline page (lunarcap.report.pages.impulsive_baseline): closed forms only."""

import numpy as np
import pytest

from lunarcap.mission.plan import paper_plan
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.report.pages import impulsive_baseline

PRINTED_EQ19_MIN = [18.82, 11.50, 9.76]         # Sec. 3.2.1
PRINTED_MASSES_KG = [524.895, 434.471, 381.005]  # arrival, after LOI 1, after LOI 2


def _page(thrust_N=150.0, isp_s=200.0, mass_kg=524.895, altitude_km=100.0,
          eq19_masses="paper", output_name="t_imp"):
    """The page as the notebook computes it: the plan's impulsive chain (public API)."""
    import lunarcap

    plan = lunarcap.paper_plan(thrust_N, isp_s).to_dict()
    plan["arrival"]["perilune_altitude_km"] = altitude_km
    capture = lunarcap.load_plan(plan, mass_kg=mass_kg)
    masses = impulsive_baseline.eq19_masses(eq19_masses, thrust_N, isp_s)
    return impulsive_baseline.build(capture, capture.impulsive(),
                                    capture.impulsive(eq19_masses_kg=masses), masses,
                                    output_name, True)


@pytest.fixture(scope="module")
def page():
    return _page()


def test_the_public_chain_is_the_papers_impulsive_sequence():
    """The plan's chain (lunarcap's public API) is impulsive_sequence's, bit for bit."""
    import lunarcap
    from lunarcap.mission.impulsive import impulsive_sequence

    masses = impulsive_baseline.eq19_masses("paper")
    for altitude_km, mass_kg in ((100.0, 524.895), (150.0, 600.0)):
        plan = lunarcap.paper_plan(150.0, 200.0).to_dict()
        plan["arrival"]["perilune_altitude_km"] = altitude_km
        capture = lunarcap.load_plan(plan, mass_kg=mass_kg)
        assert capture.impulsive() == impulsive_sequence(150.0, 200.0, mass_kg, altitude_km)
        assert capture.impulsive(eq19_masses_kg=masses) == impulsive_sequence(
            150.0, 200.0, mass_kg, altitude_km, eq19_masses_kg=masses)


def _eq19_min(m0, dv, thrust, isp):
    ve = C.G0_MPS2 * isp
    return m0 * (1 - np.exp(-dv / ve)) * ve / thrust / 60


def test_delta_v_table_against_the_paper_and_the_plan(page):
    df = page.items["delta_v"].df
    np.testing.assert_allclose(df.paper_delta_v_mps, paper.PAPER_IMPULSIVE_DV_MPS)
    np.testing.assert_allclose(df.difference_mps, df.delta_v_mps - df.paper_delta_v_mps)
    assert df.delta_v_mps[0] == pytest.approx(353.272, abs=1e-9)  # by construction
    assert (df.difference_mps[1:].abs() < 0.25).all()             # genuine checks
    # the masses follow the rocket equation from the arrival mass
    m = 524.895 * np.exp(-np.cumsum(df.delta_v_mps) / (C.G0_MPS2 * 200.0))
    np.testing.assert_allclose(df.m_after_kg, m)
    # the same chain as the paper's capture plan
    plan = paper_plan(150.0, 200.0).impulsive()
    np.testing.assert_allclose(df.delta_v_mps, [b.delta_v_mps for b in plan])
    assert list(df.from_orbit) == ["hyperbola", "12.235 h", "3.525 h"]
    # the final orbit in minutes, as the paper writes it: 2 pi sqrt(r^3 / mu) at 1838.2 km
    final_min = 2 * np.pi * np.sqrt((C.R_MOON + 100.0) ** 3 / C.MU_MOON) / 60
    assert list(df.to_orbit) == ["12.235 h", "3.525 h", f"circle, {final_min:.1f} min"]
    assert list(df.to_orbit)[-1] == "circle, 117.9 min"


def test_eq19_with_the_papers_finite_chain_masses_reproduces_its_estimates(page):
    df = page.items["eq19"].df
    np.testing.assert_allclose(df.m0_kg, PRINTED_MASSES_KG)
    np.testing.assert_allclose(df.duration_min,
                               _eq19_min(df.m0_kg, df.delta_v_mps, 150.0, 200.0))
    np.testing.assert_allclose(df.paper_duration_min, PRINTED_EQ19_MIN)
    assert (df.difference_min.abs() < 0.05).all()
    assert df.difference_min[0] == pytest.approx(0.034, abs=1e-3)  # 524.895 vs 523.94 kg
    page.check()


def test_impulsive_chain_masses_miss_loi2_and_loi3_and_the_note_says_why(page):
    p = _page(eq19_masses="impulsive", output_name="t_imp2")
    df = p.items["eq19"].df
    burns = paper_plan(150.0, 200.0).impulsive()
    np.testing.assert_allclose(df.m0_kg, [b.m_before_kg for b in burns])
    # heavier at LOI 2 and 3 (impulses spend less): 0.10 min longer than printed
    assert (df.m0_kg[1:].to_numpy() > np.array(PRINTED_MASSES_KG[1:])).all()
    assert (df.difference_min[1:] > 0.09).all()
    p.check()  # the paper-mass checks are not asserted here, the delta-Vs are
    note = page.notes["eq19_masses_note"]
    assert "11.60 and 9.86 min" in note and "523.94 kg" in note and "523.982 kg" in note


def test_other_engines():
    with pytest.raises(ValueError, match="only for 150 N"):
        impulsive_baseline.eq19_masses("paper", 300.0, 250.0)
    with pytest.raises(ValueError, match="'paper' or 'impulsive'"):
        impulsive_baseline.eq19_masses("finite")
    p = _page(300.0, 250.0, eq19_masses="impulsive", output_name="t_imp3")
    assert p.items["eq19"].df.paper_duration_min.isna().all()
    assert "nothing to compare" in p.notes["eq19_masses_note"]
    # Eq. (19) from the arrival mass with this engine's thrust and Isp
    assert p.values["eq19_loi1_min"] == pytest.approx(_eq19_min(524.895, 353.272, 300.0, 250.0))
    p.check()


def test_glued_paper_masses_are_the_printed_ones(page):
    # the rerun page quotes them to explain eq19_masses="paper"
    got = [page.values[f"paper_m0_loi{n}_kg"] for n in (1, 2, 3)]
    np.testing.assert_allclose(got, PRINTED_MASSES_KG)
    np.testing.assert_allclose(page.items["eq19"].df.m0_kg, got)
