"""The page of published lunar captures (notebooks/real_missions.ipynb), beside ours.

The published figures of four captures (Chang'e-1, LRO, SELENE, KPLO) are data here
(:data:`PUBLISHED`, each row with the keys of its sources in :data:`SOURCES`), as are the
numbers taken from them for the comparisons. The notebook solves our free-ignition
capture chains for the LRO- and SELENE-class engines of the paper's Sec. 3.1 with the
public API (:func:`lunarcap.paper_plan` with every ignition free, then
:func:`lunarcap.solve`; cached); :func:`build` sets them beside the published figures,
flies our delta-Vs at the missions' masses and thrusts with Eq. (19)
(:func:`scaled_durations_min`), and sets KPLO's design beside the paper's capture.
"""

from __future__ import annotations

import re

import numpy as np
import pandas as pd

from lunarcap.capture.chain import arrival_for
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.physics.elements import orbit_summary
from lunarcap.physics.rocket import burn_duration_estimate_s, rocket_mass_after
from lunarcap.quantities import capture_name
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.page import Page

NOTEBOOK = "notebooks/real_missions.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 60, (
    Execution(
        "real_missions", "Beside published lunar captures",
        parameters=dict(engines=[[320.0, 200.0], [500.0, 300.0]],  # LRO-, SELENE-class
                        dynamics="full"),
        quick_parameters=dict(engines=[[320.0, 200.0]], dynamics="two-body"),
        outputs=table_files("real_missions", "published", "durations", "kplo")),
))

#: The engines of the paper's Sec. 3.1 ("about 320 N with Isp of 200 seconds", "about
#: 500 N, 300 s"): (thrust N, Isp s).
LRO_CLASS = (320.0, 200.0)
SELENE_CLASS = (500.0, 300.0)

# ---------------------------------------------------------------------- published numbers
#: LRO: launch mass, kg (S8); duration of its LOI burn, min (S7).
LRO_MASS_KG, LRO_LOI_MIN = 1916.0, 40.0
#: Chang'e-1: gross mass, kg, and its single orbit-manoeuvre engine, N (S1).
CE1_MASS_KG, CE1_THRUST_N = 2350.0, 490.0
#: Chang'e-1: start of braking to entry into orbit of LOI 1, 2, 3, min (S2-S5).
CE1_BURNS_MIN = (22.0, 14.0, 11.0)
#: Chang'e-1's specific impulse was not found: the SELENE-class one is assumed, s.
CE1_ISP_ASSUMED_S = 300.0
#: KPLO's design (S13, Table 2): impulsive delta-V of LOI 1, 2, 3, m/s.
KPLO_DV_MPS = (364.980, 250.534, 247.550)
#: KPLO's design (S13): perilune speed on arrival and after LOI 1, 2, 3, km/s.
KPLO_SPEED_KMPS = (2.497, 2.132, 1.881, 1.634)

#: Published figures, as printed in the sources (:data:`SOURCES`): mission, quantity,
#: published value (text, as printed), unit, source keys.
PUBLISHED = [
    # Chang'e-1 (CNSA), Nov 2007: 12 h -> 3.5 h -> 127 min circular at 200 km
    ("Chang'e-1", "spacecraft mass (gross)", "2,350", "kg", "S1"),
    ("Chang'e-1", "spacecraft mass", "2,300 (fuel nearly half)", "kg", "S6"),
    ("Chang'e-1", "orbit-manoeuvre engine", "490 (one engine)", "N", "S1"),
    ("Chang'e-1", "LOI 1 (5 Nov): braking start → in orbit", "11:15 → about 11:37 (22 min)",
     "Beijing time", "S2, S3"),
    ("Chang'e-1", "orbit after LOI 1", "12 h, about 200 (210) × 8,600", "km altitude",
     "S2, S4"),
    ("Chang'e-1", "LOI 2 (6 Nov): braking start → in orbit", "11:21 → about 11:35 (14 min)",
     "Beijing time", "S4"),
    ("Chang'e-1", "orbit after LOI 2", "3.5 h, 213 × 1,700", "km altitude", "S4"),
    ("Chang'e-1", "LOI 3 (7 Nov): braking start → in orbit", "08:24 → about 08:35 (11 min)",
     "Beijing time", "S5"),
    ("Chang'e-1", "orbit after LOI 3", "127 min, circular polar, 200", "km altitude", "S5"),
    # LRO (NASA), June 2009
    ("LRO", "launch mass / dry mass / fuel", "1,916 / 1,018 / 898", "kg", "S8"),
    ("LRO", "LOI burn (23 Jun 2009)", "40", "min", "S7"),
    ("LRO", "orbit after LOI", "220 × 3,100", "km altitude", "S7"),
    ("LRO", "LOI ΔV", "not found", "", "—"),
    # SELENE / Kaguya (JAXA), Oct 2007
    ("SELENE", "LOI 1 (4 Oct 2007, 06:20 JST): orbit", "101 × 11,741, period 16 h 42 min",
     "km altitude", "S9"),
    ("SELENE", "LOI 1 → nominal 100 km circular polar orbit", "4 Oct → 19 Oct 2007", "",
     "S11"),
    ("SELENE", "orbit after LOI 6 (18 Oct)", "80 × 123, period 1 h 58 min", "km altitude",
     "S10"),
    ("SELENE", "main orbiter mass", "2,914 (S12a) or 1,984.0 (S12b): sources disagree", "kg",
     "S12"),
    ("SELENE", "LOI burn durations and ΔV", "not found", "", "—"),
    # KPLO / Danuri (KARI)
    ("KPLO", "design: perilune speed on arrival", "2.497", "km/s", "S13"),
    ("KPLO", "design: LOI 1 / 2 / 3 impulsive ΔV", "364.980 / 250.534 / 247.550", "m/s",
     "S13"),
    ("KPLO", "design: perilune speed after LOI 1 / 2 / 3", "2.132 / 1.881 / 1.634", "km/s",
     "S13"),
    ("KPLO", "design: launch mass", "about 550", "kg", "S13"),
    ("KPLO", "LOI 1 (17 Dec 2022, 02:45 KST): orbit", "109 × 8,920, period 12.3 h",
     "km altitude", "S14"),
    ("KPLO", "LOI 1 burn, planned (press report)", "about 13", "min", "S17"),
    ("KPLO", "LOIs flown", "3 instead of the 5 planned", "", "S15, S16"),
    ("KPLO", "orbit after the last LOI (26 Dec)", "104.1 × 119.9", "km altitude", "S15"),
    ("KPLO", "fuel left after capture", "93 of 260", "kg", "S15"),
]

#: The sources (MyST): key -> reference, address and what was taken from it.
SOURCES = {
    "S1": "(a) China Aerospace Science and Technology Corporation (CASC, the builder), "
          "\"Chang'e 1\". <http://english.spacechina.com/n16421/n17215/n17269/n19037/"
          "c125365/content.html>. Based on the DFH-3 platform, weighs 2,350 kg; 200 km polar "
          "circular orbit. (b) China Space Report, \"Chang'e 1\" (mission page, a secondary "
          "source). <https://chinaspacereport.com/spaceflight/change1/>. A single 490 N "
          "orbit-manoeuvre thruster: the engine's thrust was not found in a CNSA or CASC "
          "source.",
    "S2": "Xinhua News Agency, \"China's first lunar probe enters moon's orbit\", 5 November "
          "2007, as published by china.org.cn. "
          "<http://china.org.cn/node_7040259/content_1230767.htm>. First braking started at "
          "11:15, entry into orbit at around 11:37; 12-hour orbit of about 200 × 8,600 km; "
          "final 127-minute circular orbit at 200 km.",
    "S3": "CCTV, \"Successful braking of Chang'e one: Breakthrough for China's space "
          "industry\", 6 November 2007. <http://www.cctv.com/english/20071106/101229.shtml>. "
          "\"entered the 12-hour lunar orbit after a 22-minute maneuver\".",
    "S4": "Xinhua News Agency, \"China's lunar probe moves closer to final orbit\", 6 November "
          "2007, as published by TwoCircles.net. "
          "<https://twocircles.net/2007nov06/chinas_lunar_probe_moves_closer_final_orbit.html>. "
          "Second braking started at 11:21, entry into the 3.5-hour orbit (213 × 1,700 km) at "
          "around 11:35; the 12-hour orbit was about 210 × 8,600 km.",
    "S5": "Xinhua News Agency, 7 November 2007, as published by china.org.cn. "
          "<http://english.china.org.cn/english/China/231127.htm>. Third braking started at "
          "08:24, entry into the 127-minute circular polar orbit at around 08:35; altitude "
          "200 km.",
    "S6": "Xinhua News Agency, 6 November 2007, as published by China Daily. "
          "<http://covid-19.chinadaily.com.cn/china/2007-11/06/content_6234339_2.htm>. Four "
          "orbital transfers, one correction and two brakings so far; \"the fuel that the "
          "2,300-kg Chang'e-1 carries accounts for nearly half of the satellite's total "
          "weight\".",
    "S7": "M. Robinson, \"LRO in lunar orbit!\", LROC news, Arizona State University, 23 June "
          "2009. <http://lroc.sese.asu.edu/news/147>. A 40-minute LOI burn completed at "
          "6:26:26 EDT; orbit 220 km × 3,100 km; four more small burns to a 30 × 216 km "
          "commissioning orbit.",
    "S8": "NASA Solar System Exploration, \"Lunar Reconnaissance Orbiter\" mission profile, "
          "citing the LRO/LCROSS launch press kit (NASA, June 2009). "
          "<http://solarsystem.nasa.gov/missions/profile.cfm?Sort=Target&Target=Moon&MCode=LRO"
          "&Display=ReadMore>. Launch mass 1,916 kg, dry mass 1,018 kg, fuel 898 kg.",
    "S9": "JAXA, press release (in Japanese) \"Getsu shūkai eisei 'Kaguya (SELENE)' no "
          "getsu shūkai kidō tōnyū manūba jisshi kekka ni tsuite\" (On the results of the "
          "lunar orbit insertion manoeuvre of the lunar orbiter KAGUYA (SELENE)), subtitle "
          "\"Getsu shūkai kidō e no tōnyū o kakunin\" (Insertion into lunar orbit "
          "confirmed), 5 October 2007. "
          "<https://www.jaxa.jp/press/2007/10/20071005_kaguya_j.html>. LOI1 at 06:20 JST on "
          "4 October 2007; apolune altitude 11,741 km, perilune altitude 101 km, period "
          "16 h 42 min.",
    "S10": "RBB Today (a Japanese news site; in Japanese), \"'Kaguya' kuritikaru fēzu "
           "shūryō! Tsuki teijō kansoku kidō e\" ('Kaguya' critical phase over! On to the "
           "regular lunar observation orbit), 21 October 2007. "
           "<https://s.rbbtoday.com/article/2007/10/21/45764.html>. LOI6 on 18 October from "
           "about 14:00, last firing ended about 19:00; orbit 80 × 123 km altitude, period "
           "1 h 58 min. A secondary report: these figures were not found in a JAXA source.",
    "S11": "M. Kato, S. Sasaki, Y. Takizawa and the Kaguya project team (JAXA), \"The Kaguya "
           "Mission Overview\", Space Science Reviews 154, 3–19 (2010), "
           "doi:10.1007/s11214-010-9678-3. <https://link.springer.com/article/10.1007/"
           "s11214-010-9678-3>. Abstract: inserted into a large elliptical lunar orbit on "
           "4 October 2007; after the apolune was lowered, the nominal 100 km circular polar "
           "observation orbit on 19 October.",
    "S12": "(a) Wikipedia, \"SELENE\", <https://en.wikipedia.org/wiki/SELENE>: main orbiter "
           "2,914 kg at launch. (b) NASA Solar System Exploration, \"KAGUYA: In Depth\", "
           "<https://solarsystem.nasa.gov/missions/kaguya/in-depth/>: spacecraft mass "
           "1,984.0 kg.",
    "S13": "Y.-J. Song, J. Bae, Y.-R. Kim, B.-Y. Kim (KARI), \"Early Phase Contingency "
           "Trajectory Design for the Failure of the First Lunar Orbit Insertion Maneuver: "
           "Direct Recovery Options\", Journal of Astronomy and Space Sciences 34(4), 331 (2017) "
           "{cite:p}`song2017`. "
           "<https://janss.kr/archive/view_article?pid=jass-34-331>; Table 2, \"Expected event "
           "sequences and associated values for the nominal LOA phase\", "
           "<http://www.janss.kr/download/download_excel?pid=jass-34-331&tid=T2>. KPLO launch "
           "mass approximately 550 kg.",
    "S14": "KBS World (German service), on the first LOI of Danuri, December 2022. "
           "<http://world.kbs.co.kr/service/news_view.htm?lang=g&Seq_Code=94205>. First LOI at "
           "about 02:45 on 17 December (KST); orbit 109 × 8,920 km altitude, period 12.3 h.",
    "S15": "Ministry of Science and ICT (MSIT), Korea, \"Danuri Successfully Enters Lunar "
           "Orbit\", December 2022. "
           "<https://www.msit.go.kr/eng/bbs/view.do?sCode=eng&mPid=2&mId=4&bbsSeqNo=42"
           "&nttSeqNo=765>. Third and last LOI on 26 December; orbit 104.1 × 119.9 km; 93 kg of "
           "fuel left of 260 kg.",
    "S16": "Korea JoongAng Daily, \"Korean lunar orbiter Danuri successfully enters target "
           "orbit\", 28 December 2022, citing MSIT and KARI. <https://koreajoongangdaily."
           "joins.com/2022/12/28/business/tech/Korea-Danuri-Lunar-orbiter/"
           "20221228105844332.html>. The target orbit reached through three LOIs instead of "
           "the five initially scheduled.",
    "S17": "SciMyst, \"South Korean spacecraft will fly into the Moon's orbit\" (citing KBS), "
           "December 2022. <https://scimyst.com/south-korean-spacecraft-will-fly-into-the-"
           "moons-orbit-124782>. Planned LOI 1: thrusters fired for 13 minutes, from 8,000 to "
           "7,500 km/h. A secondary press report; no KARI or MSIT statement of the burn's "
           "duration was found.",
}

#: The sources that are not primary ones (not the agency, the builder, a journal or a
#: press release): what they are. The source list marks each; a primary source for their
#: figures was searched for and not found.
NOT_PRIMARY = {
    "S1": "(b) is a secondary mission page",
    "S10": "a news site",
    "S12": "(a) is an encyclopaedia",
    "S14": "a broadcaster's news report",
    "S16": "a newspaper report",
    "S17": "a news site citing a broadcaster",
}

#: What was searched for and not found (the last entry of the source list).
NOT_FOUND = ("LRO's LOI ΔV and engine thrust; SELENE's LOI burn durations and ΔVs; "
             "Chang'e-1's specific impulse and mass at arrival; KPLO's thrust and mass at "
             "arrival. The engine figures \"about 320 N, 200 s\" (LRO) and \"about 500 N, "
             "300 s\" (SELENE) are the paper's (Sec. 3.1) and were not checked against "
             "another source.")


def published_table() -> pd.DataFrame:
    """:data:`PUBLISHED` as a DataFrame (mission, quantity, published, unit, source)."""
    return pd.DataFrame(PUBLISHED, columns=["mission", "quantity", "published", "unit",
                                            "source"])


def source_keys(text: str) -> list[str]:
    """The source keys cited in a text (``"S2, S4"`` -> ``["S2", "S4"]``)."""
    return re.findall(r"\bS\d+", text)


def sources_markdown() -> str:
    """The source list as a MyST definition list (keys in order, then what was not found).

    A source that is not a primary one (:data:`NOT_PRIMARY`) says so at its head.
    """
    items = [f"{k}\n: " + (f"*Not a primary source: {NOT_PRIMARY[k]}.* " if k in NOT_PRIMARY
                            else "") + v for k, v in SOURCES.items()]
    items.append(f"Not found\n: {NOT_FOUND}")
    return "\n\n".join(items)


def scaled_durations_min(delta_v_mps, m0_kg: float, thrust_N: float, isp_s: float) -> list:
    """Eq. (19) durations (min) of a chain of delta-Vs at another mass and thrust.

    The mass is carried from burn to burn by the rocket equation with the same Isp.
    """
    out, m = [], float(m0_kg)
    for dv in delta_v_mps:
        out.append(float(burn_duration_estimate_s(m, dv, thrust_N, isp_s)) / 60.0)
        m = float(rocket_mass_after(m, dv, isp_s))
    return out


def durations_table(chains: dict) -> pd.DataFrame:
    """Published burn durations beside ours (paper's spacecraft) and ours at the missions'.

    ``chains``: {(thrust N, Isp s): :func:`chain_of`}. LRO is compared with the
    LRO-class chain, Chang'e-1 with the SELENE-class chain (NaN where that engine is not
    given). Columns: mission, quantity, published_min, ours_engine,
    ours_paper_spacecraft_min, ours_at_mission_mass_min, at_mission_mass.
    """
    nan = float("nan")
    rows = []
    lro = chains.get(LRO_CLASS)
    lro_scaled = (scaled_durations_min(lro.delta_v_mps, LRO_MASS_KG, *LRO_CLASS)
                  if lro is not None else [nan])
    rows.append({"mission": "LRO", "quantity": "LOI 1 burn", "published_min": LRO_LOI_MIN,
                 "ours_engine": f"LRO-class, {LRO_CLASS[0]:g} N / {LRO_CLASS[1]:g} s",
                 "ours_paper_spacecraft_min": float(lro.burn_duration_min.iloc[0])
                 if lro is not None else nan,
                 "ours_at_mission_mass_min": lro_scaled[0],
                 "at_mission_mass": f"{LRO_MASS_KG:,.0f} kg (launch mass), "
                                    f"{LRO_CLASS[0]:g} N, {LRO_CLASS[1]:g} s"})
    sel = chains.get(SELENE_CLASS)
    ce1 = (scaled_durations_min(sel.delta_v_mps, CE1_MASS_KG, CE1_THRUST_N, CE1_ISP_ASSUMED_S)
           if sel is not None else [nan] * 3)
    for n in (1, 2, 3):
        rows.append({"mission": "Chang'e-1", "quantity": f"LOI {n} burn",
                     "published_min": CE1_BURNS_MIN[n - 1],
                     "ours_engine": f"SELENE-class, {SELENE_CLASS[0]:g} N / "
                                    f"{SELENE_CLASS[1]:g} s",
                     "ours_paper_spacecraft_min": float(sel.burn_duration_min.iloc[n - 1])
                     if sel is not None else nan,
                     "ours_at_mission_mass_min": ce1[n - 1],
                     "at_mission_mass": f"{CE1_MASS_KG:,.0f} kg (gross), {CE1_THRUST_N:g} N, "
                                        f"Isp {CE1_ISP_ASSUMED_S:g} s assumed"})
    return pd.DataFrame(rows)


def kplo_table(arrival_speed_kmps: float, chain: pd.DataFrame) -> pd.DataFrame:
    """KPLO's design capture (S13) beside the paper's and ours.

    Perilune speeds (km/s) on arrival and after each LOI, KPLO's and ours (the arrival
    state and the end states of our chain), ours - KPLO (m/s); impulsive delta-V of each
    LOI (m/s), KPLO's and the paper's, KPLO - paper (m/s).
    """
    nan = float("nan")
    ours = np.array([arrival_speed_kmps, *chain.v_end_kmps], dtype=float)
    return pd.DataFrame({
        "point": ["arrival perilune", "after LOI 1", "after LOI 2", "after LOI 3"],
        "kplo_speed_kmps": KPLO_SPEED_KMPS, "our_speed_kmps": ours,
        "speed_difference_mps": 1e3 * (ours - np.array(KPLO_SPEED_KMPS)),
        "kplo_delta_v_mps": [nan, *KPLO_DV_MPS],
        "paper_delta_v_mps": [nan, *paper.PAPER_IMPULSIVE_DV_MPS],
        "delta_v_difference_mps": [nan, *np.subtract(KPLO_DV_MPS,
                                                     paper.PAPER_IMPULSIVE_DV_MPS)]})


def solver_description() -> dict:
    """What the provenance block says about our numbers."""
    return {"our numbers": "free-ignition capture chains (as on the other-engines page), "
                           "cached",
            "scaling": "Eq. (19) with our finite-burn ΔV at the mission's mass and thrust"}


def prose_values(compare: pd.DataFrame, kplo: pd.DataFrame, m0_kg: float,
                 arrival_speed_kmps: float) -> dict:
    """The numbers the prose quotes, from :func:`durations_table` and :func:`kplo_table`."""
    out = {"lro_loi1_ours_min": float(compare.ours_paper_spacecraft_min.iloc[0]),
           "lro_loi1_scaled_min": float(compare.ours_at_mission_mass_min.iloc[0]),
           "lro_mass_ratio": LRO_MASS_KG / m0_kg}
    for n in (1, 2, 3):
        out[f"ce1_loi{n}_ours_min"] = float(compare.ours_paper_spacecraft_min.iloc[n])
        out[f"ce1_loi{n}_scaled_min"] = float(compare.ours_at_mission_mass_min.iloc[n])
        out[f"ce1_loi{n}_ratio"] = (CE1_BURNS_MIN[n - 1]
                                    / float(compare.ours_at_mission_mass_min.iloc[n]))
    after = kplo.speed_difference_mps.iloc[1:]
    out["kplo_arrival_faster_mps"] = -float(kplo.speed_difference_mps.iloc[0])
    out["kplo_max_abs_after_diff_mps"] = float(after.abs().max())
    out["kplo_loi1_dv_diff_mps"] = float(kplo.delta_v_difference_mps.iloc[1])
    out["kplo_total_dv_diff_mps"] = float(np.nansum(kplo.delta_v_difference_mps))
    out["our_arrival_speed_kmps"] = float(arrival_speed_kmps)
    return out


#: Published and computed durations within this factor of each other "agree in order of
#: magnitude" (the sources give the intervals to the minute; the masses are not known).
ORDER_FACTOR = 3.0


def ce1_verdict(ratios, why_missing: str = "") -> str:
    """What Chang'e-1's braking intervals say against our scaled durations, computed.

    ``ratios``: published interval over our duration at Chang'e-1's mass and thrust, for
    LOI 1, 2, 3 (NaN where not computed). The verdict follows the numbers: the order of
    magnitude agrees only if every ratio is within :data:`ORDER_FACTOR` of 1, and the
    launch-mass explanation is offered only when ours are all longer.

    >>> ce1_verdict([0.8, 0.7, 0.9]).split(" (")[0]
    'The order of magnitude agrees: the reported intervals are 0.70 to 0.90 of ours'
    >>> ce1_verdict([0.1, 0.7, 0.9]).split(":")[0]
    'The order of magnitude differs'
    """
    r = np.asarray(ratios, dtype=float)
    if not np.isfinite(r).any():
        return f"Not compared in this build ({why_missing or 'no duration computed'})."
    r = r[np.isfinite(r)]
    span = f"{r.min():.2f} to {r.max():.2f}" if r.min() != r.max() else f"{r.min():.2f}"
    if np.all((r > 1 / ORDER_FACTOR) & (r < ORDER_FACTOR)):
        head = (f"The order of magnitude agrees: the reported intervals are {span} of ours "
                f"(within a factor {ORDER_FACTOR:g}).")
    else:
        return (f"The order of magnitude differs: the reported intervals are {span} of ours, "
                f"beyond a factor {ORDER_FACTOR:g}, more than the unknown arrival mass and "
                "specific impulse can explain.")
    if np.all(r < 1):
        return head + (" Ours are longer, mainly because 2,350 kg is the launch mass: "
                       "Chang'e-1 made four orbital transfers of its own in Earth orbit "
                       "before the brakings, and its fuel was nearly half of its mass (S6), "
                       "so it arrived at the Moon lighter, by an amount not found.")
    if np.all(r > 1):
        return head + (" Ours are shorter although 2,350 kg is the launch mass (it arrived "
                       "lighter): a weaker engine or a larger ΔV than ours would explain it.")
    return head + (" Some of ours are longer and some shorter: beside the unknown arrival "
                   "mass, its own orbits and arrival speed shape each burn differently.")


def _add_published(page: Page, chains: dict, m0: float, dynamics: str) -> pd.DataFrame:
    """The published figures and the durations tables; returns the durations."""
    page.table(
        "published", published_table(),
        caption=("Published figures of four lunar captures, as printed in the sources "
                 f"S1–S{len(SOURCES)} (end of page); in brackets: from the reported start of "
                 "braking to the reported orbit entry. 'Not found': in no source consulted."),
        columns={"published": "published value", "unit": "unit", "source": "source"})
    compare = durations_table(chains)
    page.table(
        "durations", compare,
        caption=("Burn durations (min): published (LRO S7; Chang'e-1 S2–S5), ours on the "
                 f"paper's spacecraft ({m0:g} kg, free ignition, {dynamics} dynamics), and "
                 f"at the mission's mass by Eq. (19): LRO {LRO_MASS_KG:,.0f} kg, "
                 f"{LRO_CLASS[0]:g} N; Chang'e-1 {CE1_MASS_KG:,.0f} kg, {CE1_THRUST_N:g} N, "
                 f"Isp {CE1_ISP_ASSUMED_S:g} s (assumed: not found)."),
        columns={"published_min": "published (min)", "ours_engine": "our engine",
                 "ours_paper_spacecraft_min": "ours, paper's spacecraft (min)",
                 "ours_at_mission_mass_min": "ours at the mission's mass (min)",
                 "at_mission_mass": "mass and engine assumed"},
        floatfmt={"published_min": "g", "ours_paper_spacecraft_min": ".2f",
                  "ours_at_mission_mass_min": ".1f"},
        show_columns=["mission", "quantity", "published_min", "ours_engine",
                      "ours_paper_spacecraft_min", "ours_at_mission_mass_min"])
    return compare


def _add_kplo(page: Page, kplo: pd.DataFrame, engines, dynamics: str) -> None:
    page.table(
        "kplo", kplo,
        caption=("KPLO's design capture (S13, Table 2) beside the paper's: perilune speeds, "
                 f"KPLO's and ours ({engines[0][0]:g} N / {engines[0][1]:g} s, {dynamics} "
                 "dynamics), and each LOI's impulsive ΔV, KPLO's and the paper's "
                 "({cite:t}`song2009c`)."),
        columns={"point": "point", "kplo_speed_kmps": "speed, KPLO (km/s)",
                 "our_speed_kmps": "speed, ours (km/s)",
                 "speed_difference_mps": "ours − KPLO (m/s)",
                 "kplo_delta_v_mps": "impulsive ΔV, KPLO (m/s)",
                 "paper_delta_v_mps": "impulsive ΔV, paper (m/s)",
                 "delta_v_difference_mps": "KPLO − paper (m/s)"},
        floatfmt={"kplo_speed_kmps": ".3f", "our_speed_kmps": ".3f",
                  "speed_difference_mps": "+.1f", "kplo_delta_v_mps": ".3f",
                  "paper_delta_v_mps": ".3f", "delta_v_difference_mps": "+.3f"})


def _add_checks(page: Page, chains: dict, compare: pd.DataFrame, kplo: pd.DataFrame) -> None:
    after = kplo.speed_difference_mps.iloc[1:]
    page.expect("every burn of our chains passes the verification gate",
                all(bool(c.verified.all()) for c in chains.values()))
    page.expect("KPLO's capture orbits are ours: perilune speeds after each LOI within 5 m/s",
                bool(after.abs().max() < 5.0), f"{after.abs().max():.2f} m/s")
    page.expect("KPLO arrives faster than the paper's spacecraft (the prose)",
                page.values["kplo_arrival_faster_mps"] > 0,
                f"{page.values['kplo_arrival_faster_mps']:.2f} m/s")
    if SELENE_CLASS in chains:
        scaled = compare.ours_at_mission_mass_min.iloc[1:4].to_numpy()
        ratios = np.array(CE1_BURNS_MIN) / scaled
        page.expect("Chang'e-1: the scaled durations are the right order of magnitude "
                    "(published / scaled 0.5-1.5)", bool(np.all((ratios > 0.5) & (ratios < 1.5))),
                    str(np.round(ratios, 3)))
    if LRO_CLASS in chains:
        r = LRO_LOI_MIN / float(compare.ours_at_mission_mass_min.iloc[0])
        page.expect("LRO: published / scaled duration 0.5-2", 0.5 < r < 2.0, f"{r:.3f}")
        page.expect("LRO: the scaled duration is shorter than the 40 min burn (the prose)",
                    r > 1.0, f"{r:.3f}")


def chain_of(capture) -> pd.DataFrame:
    """One engine's solved chain as the rows the comparisons read, one per LOI.

    ``capture``: :func:`lunarcap.solve` of :func:`lunarcap.paper_plan` with that engine
    and every ignition free. Columns: loi, start_min, burn_duration_min, delta_v_mps,
    m_start_kg, m_end_kg, v_end_kmps (perilune speed after the burn, km/s), verified (the
    burn passed the re-propagation gate): the solutions' own numbers, unrounded.
    """
    cols = ("start_min", "burn_duration_min", "delta_v_mps", "m_start_kg", "m_end_kg",
            "v_end_kmps")
    return pd.DataFrame([{"loi": int(r["burn"]), **{c: r[c] for c in cols},
                          "verified": bool(r["verification_passed"])}
                         for r in capture.rows()])


def build(captures, output_name: str = "real_missions", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The page of published lunar captures beside ours (see the module docstring).

    Parameters
    ----------
    captures : list of lunarcap.CaptureResult
        One per engine, in the notebook's order: :func:`lunarcap.solve` of
        :func:`lunarcap.paper_plan` with that engine (thrust N, Isp s), every ignition
        free and the dynamics of the page. The LRO comparison needs the LRO-class engine
        (:data:`LRO_CLASS`), the Chang'e-1 comparison the SELENE-class one
        (:data:`SELENE_CLASS`): their rows are empty without it. KPLO is set beside the
        first (its orbits are every engine's).
    output_name, quick : the tables' prefix and whether it is a quick build.
    parameters : dict, optional
        The notebook's ``engines`` and ``dynamics``, shown in the page's provenance
        (default: read from the captures' plans).
    """
    plans = [c.plan for c in captures]
    engines = [(float(p.engine.thrust_N), float(p.engine.isp_s)) for p in plans]
    dynamics = str(plans[0].dynamics)
    params = ({k: [list(e) for e in v] if k == "engines" else v
               for k, v in parameters.items()} if parameters is not None
              else dict(engines=[list(e) for e in engines], dynamics=dynamics))
    page = Page(NOTEBOOK, params, output_name, quick, solver_description())
    chains = {e: chain_of(c) for e, c in zip(engines, captures)}
    plan = plans[0]   # the paper's arrival: every engine's
    arrival = arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole)
    arrival_speed = orbit_summary(arrival.state, C.MU_MOON)["v_kmps"]
    m0 = plan.arrival.mass_kg

    compare = _add_published(page, chains, m0, dynamics)
    kplo = kplo_table(arrival_speed, chains[engines[0]])  # any engine: the same targets
    _add_kplo(page, kplo, engines, dynamics)
    page.note("sources", sources_markdown())
    for name, v in prose_values(compare, kplo, m0, arrival_speed).items():
        page.value(name, v, why=f"the SELENE-class engine is not run in the "
                                f"{'quick book' if quick else 'this build'}"
                   if name.startswith("ce1_") else None)
    page.note("ce1_verdict", ce1_verdict(
        [page.values[f"ce1_loi{n}_ratio"] if isinstance(page.values[f"ce1_loi{n}_ratio"], float)
         else np.nan for n in (1, 2, 3)],
        "the SELENE-class engine is not run in the quick book" if quick else ""))
    _add_checks(page, chains, compare, kplo)
    page.data.update({"chains": chains, "captures": list(captures)})
    t = page.text
    page.headline(f"Our LRO-class LOI 1 (*{capture_name('free')}*, {dynamics} dynamics) lasts "
                  f"{t('lro_loi1_ours_min', '.1f', ' min')} on the paper's spacecraft and "
                  f"{t('lro_loi1_scaled_min', '.1f', ' min')} at LRO's launch mass, against "
                  f"LRO's {LRO_LOI_MIN:g} min burn.")
    page.capture("free", dynamics)
    return page
