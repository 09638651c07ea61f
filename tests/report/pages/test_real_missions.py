"""The page of published lunar captures (lunarcap.report.pages.real_missions).

The published figures and their sources are data: checked without solving. The page
itself is built in two-body dynamics with the LRO-class engine only, solved as the notebook
solves it (lunarcap.solve of lunarcap.paper_plan, every ignition free; slow).
"""

import math

import numpy as np
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper.printed import PAPER_IMPULSIVE_DV_MPS
from lunarcap.physics import constants as C
from lunarcap.physics.rocket import burn_duration_estimate_s
from lunarcap.report.labels import label
from lunarcap.report.pages import real_missions as rm


# ------------------------------------------------------------------ the published data
def test_every_published_figure_cites_a_listed_source_and_every_source_is_cited():
    df = rm.published_table()
    cited = set()
    for r in df.itertuples():
        keys = rm.source_keys(r.source)
        assert keys or (r.source == "—" and r.published == "not found"), r
        cited |= set(keys)
    assert cited == set(rm.SOURCES)
    assert list(rm.SOURCES) == [f"S{k}" for k in range(1, len(rm.SOURCES) + 1)]
    md = rm.sources_markdown()
    for k in rm.SOURCES:
        assert f"\n{k}\n: " in "\n" + md
    assert md.endswith(rm.NOT_FOUND)


def test_numbers_used_in_the_comparisons_are_the_published_ones():
    text = {(r.mission, r.quantity): r.published for r in rm.published_table().itertuples()}
    for n, minutes in enumerate(rm.CE1_BURNS_MIN, start=1):
        key = next(k for k in text if k[0] == "Chang'e-1" and k[1].startswith(f"LOI {n} ("))
        assert f"({minutes:g} min)" in text[key]
    assert text[("Chang'e-1", "spacecraft mass (gross)")] == f"{rm.CE1_MASS_KG:,.0f}"
    assert text[("Chang'e-1", "orbit-manoeuvre engine")].startswith(f"{rm.CE1_THRUST_N:g} ")
    assert text[("LRO", "LOI burn (23 Jun 2009)")] == f"{rm.LRO_LOI_MIN:g}"
    assert text[("LRO", "launch mass / dry mass / fuel")].startswith(f"{rm.LRO_MASS_KG:,.0f} ")
    assert text[("KPLO", "design: LOI 1 / 2 / 3 impulsive ΔV")] == \
        " / ".join(f"{v:.3f}" for v in rm.KPLO_DV_MPS)
    speeds = [float(text[("KPLO", "design: perilune speed on arrival")])]
    speeds += [float(v) for v in text[("KPLO", "design: perilune speed after LOI 1 / 2 / 3")]
               .split(" / ")]
    assert tuple(speeds) == rm.KPLO_SPEED_KMPS


def test_durations_at_the_mission_mass_follow_eq19_and_the_rocket_equation():
    dv = (350.0, 250.0, 240.0)
    out = rm.scaled_durations_min(dv, 2350.0, 490.0, 300.0)
    m = 2350.0
    for d, t in zip(dv, out):
        # Eq. (19): m0 [1 - exp(-dV/(g0 Isp))] g0 Isp / T
        expect = m * (1 - math.exp(-d / (C.G0_MPS2 * 300.0))) * C.G0_MPS2 * 300.0 / 490.0 / 60
        assert t == pytest.approx(expect)
        assert t == pytest.approx(burn_duration_estimate_s(m, d, 490.0, 300.0) / 60)
        m *= math.exp(-d / (C.G0_MPS2 * 300.0))
    # a heavier spacecraft burns longer, a stronger engine shorter
    assert rm.scaled_durations_min(dv, 2000.0, 490.0, 300.0)[0] < out[0]
    assert rm.scaled_durations_min(dv, 2350.0, 600.0, 300.0)[0] < out[0]


# ------------------------------------------------------------------ the page (solves)
@pytest.fixture(scope="module")
def page():
    """The page as the notebook builds it: the LRO-class chain solved by the public API."""
    import lunarcap

    capture = lunarcap.solve(lunarcap.paper_plan(*rm.LRO_CLASS, starts=["free"] * 3,
                                                 dynamics="two-body"), impulsive=False)
    return rm.build([capture], "t_real_missions", True,
                    dict(engines=[list(rm.LRO_CLASS)], dynamics="two-body"))


@pytest.mark.slow
def test_the_public_route_reaches_the_cached_chain_the_page_read_before(page):
    # the notebook's lunarcap.solve(lunarcap.paper_plan(..., starts=["free"] * 3)) and the
    # study's sequence_table solve the same plan keys: the same solutions, bit for bit
    from lunarcap.studies.sweeps import sequence_table

    ref = sequence_table(*rm.LRO_CLASS, ("free",) * 3, "two-body", with_impulsive_model=False)
    ours = page.data["chains"][rm.LRO_CLASS]
    for c in ("start_min", "burn_duration_min", "delta_v_mps", "m_start_kg", "m_end_kg",
              "v_end_kmps", "verified"):
        assert list(ours[c]) == list(ref[c]), c
    # without the notebook's parameters, the provenance reads them from the plans
    bare = rm.build(page.data["captures"], "t_real_missions", True)
    assert bare.parameters == page.parameters == {"engines": [[320.0, 200.0]],
                                                  "dynamics": "two-body"}


@pytest.mark.slow
def test_durations_table(page):
    df = page.items["durations"].df
    assert list(df.mission) == ["LRO", "Chang'e-1", "Chang'e-1", "Chang'e-1"]
    lro = df.iloc[0]
    chain = page.data["chains"][rm.LRO_CLASS]
    assert lro.ours_paper_spacecraft_min == chain.burn_duration_min.iloc[0]
    # our LOI 1 at LRO's launch mass lasts longer in proportion (to first order) to the mass
    ratio = lro.ours_at_mission_mass_min / lro.ours_paper_spacecraft_min
    assert 0.8 * rm.LRO_MASS_KG / paper_scenario().mass_kg < ratio < 1.2 * rm.LRO_MASS_KG / \
        paper_scenario().mass_kg
    assert df.iloc[1:].ours_at_mission_mass_min.isna().all()  # no SELENE-class engine given
    page.check()


@pytest.mark.slow
def test_kplo_table(page):
    k = page.items["kplo"].df
    np.testing.assert_allclose(k.speed_difference_mps,
                               1e3 * (k.our_speed_kmps - k.kplo_speed_kmps))
    np.testing.assert_allclose(k.paper_delta_v_mps.iloc[1:], PAPER_IMPULSIVE_DV_MPS)
    np.testing.assert_allclose(k.delta_v_difference_mps.iloc[1:],
                               np.subtract(rm.KPLO_DV_MPS, PAPER_IMPULSIVE_DV_MPS))
    # two-body: the speed after LOI 3 is the circular speed at 100 km altitude, and after
    # LOI 1 the perilune speed of a 12.235 h orbit with that perilune (vis-viva)
    rp = C.R_MOON + 100.0
    assert k.our_speed_kmps.iloc[3] == pytest.approx(math.sqrt(C.MU_MOON / rp), abs=1e-4)
    a = (C.MU_MOON * (12.235 * 3600 / (2 * math.pi)) ** 2) ** (1 / 3)
    assert k.our_speed_kmps.iloc[1] == pytest.approx(
        math.sqrt(C.MU_MOON * (2 / rp - 1 / a)), abs=1e-3)
    # arrival on a hyperbola: faster than escape at the perilune
    assert k.our_speed_kmps.iloc[0] > math.sqrt(2 * C.MU_MOON / rp)
    assert page.values["kplo_arrival_faster_mps"] == pytest.approx(
        1e3 * (rm.KPLO_SPEED_KMPS[0] - k.our_speed_kmps.iloc[0]))


@pytest.mark.slow
def test_every_shown_column_has_a_label_with_its_unit(page):
    for key in ("published", "durations", "kplo"):
        item = page.items[key]
        shown = item.show_columns or list(item.df.columns)
        assert len(shown) <= 7, key
        for c in shown:
            lab = (item.columns or {}).get(c, label(c))
            if c.endswith(("_mps", "_kmps", "_min")):
                assert "(" in lab, (key, c, lab)


def test_sources_render_without_a_cjk_font():
    # titles in Japanese (or Chinese, Korean) render as boxes without a CJK font: each such
    # source is given romanised, with an English translation, and says its language
    md = rm.sources_markdown()
    cjk = [ch for ch in md if 0x2E80 <= ord(ch) <= 0x9FFF or 0xAC00 <= ord(ch) <= 0xD7AF
           or 0xFF00 <= ord(ch) <= 0xFFEF]
    assert not cjk, "".join(cjk)
    for k in ("S9", "S10"):
        assert "in Japanese" in rm.SOURCES[k] and "Kaguya" in rm.SOURCES[k], k
    assert "On the results of the lunar orbit insertion manoeuvre" in rm.SOURCES["S9"]
