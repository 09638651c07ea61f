"""The computing parts of the impulsive-baseline page (two-body, analytic: fast)."""

import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.report.pages import impulsive_baseline as ib


@pytest.fixture(scope="module")
def burns():
    paper = paper_scenario()
    return ib.impulsive_sequence(150.0, 200.0, paper.mass_kg, paper.perilune_altitude_km)


def test_delta_v_table_beside_the_paper(burns):
    t = ib.delta_v_table(burns, C.R_MOON + paper_scenario().perilune_altitude_km)
    assert t.difference_mps.tolist() == pytest.approx(
        [b.delta_v_mps - p for b, p in zip(burns, paper.PAPER_IMPULSIVE_DV_MPS)])
    assert [s.startswith("circle, ") for s in t.to_orbit] == [False, False, True]
    assert t.m_after_kg.iloc[-1] == pytest.approx(burns[-1].m_after_kg)


def test_eq19_table_uses_the_given_masses(burns):
    t = ib.eq19_table(burns, [500.0, 400.0, 350.0], [20.0, 10.0, 9.0])
    assert t.m0_kg.tolist() == [500.0, 400.0, 350.0]
    t = ib.eq19_table(burns, None, [20.0, 10.0, 9.0])
    assert t.m0_kg.tolist() == pytest.approx([b.m_before_kg for b in burns])
    assert t.difference_min.tolist() == pytest.approx(
        [b.eq19_duration_min - p for b, p in zip(burns, [20.0, 10.0, 9.0])])


def test_prose_values_totals(burns):
    v = ib.prose_values(burns, 0.8, 1838.2, [20.0, 10.0, 9.0])
    assert v["dv_total_mps"] == pytest.approx(sum(b.delta_v_mps for b in burns))
    assert v["dv_diff_loi2_mps"] == pytest.approx(burns[1].delta_v_mps
                                                  - paper.PAPER_IMPULSIVE_DV_MPS[1])
    assert v["paper_eq19_loi3_min"] == 9.0
