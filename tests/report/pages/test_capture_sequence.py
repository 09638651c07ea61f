"""The capture-sequence page (lunarcap.report.pages.capture_sequence), built in two-body."""

import numpy as np
import pandas as pd
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.report.labels import label
from lunarcap.report.pages import capture_sequence
from lunarcap.repro import paths

pytestmark = pytest.mark.slow

T_N, ISP_S = 150.0, 200.0


@pytest.fixture(scope="module")
def page():
    # as the notebook computes it: the paper's plan solved with the public API
    import lunarcap

    result = lunarcap.solve(lunarcap.paper_plan(T_N, ISP_S, starts=[-10.0, -6.0, -5.0],
                                                dynamics="two-body"), impulsive=False)
    return capture_sequence.build(result, result.plot(), "t_capture", True)


def test_burns_follow_the_rocket_equation_from_the_arrival_mass(page):
    df = page.items["burns"].df
    assert list(df.burn) == [1, 2, 3] and (df.verified == "passed").all()
    ve = C.G0_MPS2 * ISP_S
    m0 = np.r_[paper_scenario().mass_kg, df.m_end_kg.to_numpy()[:-1]]
    # mass after each burn: m0 exp(-dV / (g0 Isp)), each burn starting with the last's mass
    np.testing.assert_allclose(df.m_end_kg, m0 * np.exp(-df.delta_v_mps / ve), rtol=1e-6)
    # constant thrust: the propellant burnt is T t / (g0 Isp)
    np.testing.assert_allclose(df.burn_duration_min * 60 * T_N / ve, m0 - df.m_end_kg,
                               rtol=1e-6)


def test_burns_beside_table_b1_and_straddling_their_perilunes(page):
    df = page.items["burns"].df
    b1 = [paper.paper_best(150, n)["burn_duration_min"] for n in (1, 2, 3)]
    np.testing.assert_allclose(df.paper_burn_duration_min, b1)
    # two-body durations within 0.1 min of the paper's (full dynamics, 0.01 min printed)
    assert (abs(df.burn_duration_min - df.paper_burn_duration_min) < 0.1).all()
    assert (df.ignition_from_perilune_deg < 0).all() and (df.cutoff_from_perilune_deg > 0).all()
    assert ((df.perilune_from_ignition_min > 0)
            & (df.perilune_from_ignition_min < df.burn_duration_min)).all()
    v = page.values
    assert v["total_burn_min"] == pytest.approx(df.burn_duration_min.sum())
    assert v["mass_final_kg"] == pytest.approx(df.m_end_kg.iloc[-1])
    assert v["mass_end_burn1_kg"] == pytest.approx(df.m_end_kg.iloc[0], abs=1e-6)
    assert v["out_of_plane_km"] < 1e-3  # two-body: the orbit plane does not move


def test_figure_data_and_checks(page, tmp_path, monkeypatch):
    d4, d5 = page.data["fig4"], page.data["fig5"]
    assert np.all(np.diff(d4.alpha_deg) > 0) and abs(d4.alpha_deg[0] - 137.5) < 3.0
    assert (d5.angle_deg > 90.0).all()  # the thrust slows the spacecraft throughout
    assert page.values["angle_min_deg"] == min(d5.angle_deg[0], d5.angle_deg[-1])
    page.check()
    # showing a figure writes its data next to the tables, as the caption links it
    for name in ("GENERATED", "TABLES", "FIGURES"):
        monkeypatch.setattr(paths, name, tmp_path / name.lower())
    page.show("fig4", display=False)
    csv = pd.read_csv(paths.table_path("t_capture_fig4"))
    np.testing.assert_allclose(csv.alpha_deg, d4.alpha_deg)
    assert "t_capture_fig4.csv" in page.items["fig4"].caption
    # the paper's case (150 N / 200 s at its best offsets): Figs. 2-5 carry its numbers
    assert [page.items[f"fig{k}"].paper for k in (2, 3, 4, 5)] == [
        "Fig. 2", "Fig. 3", "Fig. 4", "Fig. 5"]
    assert page.items["burns"].paper is None
    assert paths.figure_path("t_capture_fig4", "svg").is_file()


def test_every_shown_column_has_a_label_with_its_unit(page):
    t = page.items["burns"]
    for c in t.show_columns:
        lab = (t.columns or {}).get(c, label(c))
        assert ("(" in lab) == c.endswith(("_mps", "_min", "_deg", "_kg")), (c, lab)
    assert len(t.show_columns) <= 8
