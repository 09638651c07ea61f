"""The impulsive-baseline page (notebooks/impulsive_baseline.ipynb): the two-body chain, Eq. (19).

The notebook computes the paper's impulsive capture chain in the two-body model with the
public API (:meth:`lunarcap.CapturePlan.impulsive` of :func:`lunarcap.paper_plan`, its
arrival mass and perilune altitude set: tangential perilune impulses, vis-viva speeds,
the arrival v_inf reconstructed from the paper's LOI-1 delta-V, the same chain as
:func:`lunarcap.mission.impulsive.impulsive_sequence`); :func:`build` sets it beside the
impulsive delta-Vs the paper prints, with the burn-duration estimate of Eq. (19)
evaluated with the masses :func:`eq19_masses` names:

* ``"paper"``: the masses the paper prints for its *finite-burn* chain (150 N / 200 s
  only: 524.895 kg at arrival, 434.471 kg after LOI 1, 381.005 kg after LOI 2);
* ``"impulsive"``: the masses of the impulsive chain itself (rocket equation).

The note ``eq19_masses_note`` says, from the numbers, which masses reproduce the paper's
printed estimates (18.82, 11.50 and 9.76 min) and why.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.mission.impulsive import impulsive_sequence
from lunarcap.mission.scenario import paper_engine_pairs, paper_scenario
from lunarcap.paper import audit
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.physics.rocket import burn_duration_estimate_s
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.labels import period_text
from lunarcap.report.page import Page

#: The paper's engine whose Eq. (19) estimates and masses it prints (N, s; its first
#: packaged plan's).
PAPER_ENGINE = paper_engine_pairs()[0]

NOTEBOOK = "notebooks/impulsive_baseline.ipynb"
BOOK = BookPage(NOTEBOOK, "Results", 20, (
    Execution(
        "impulsive_baseline", "Impulsive baseline: 150 N, Isp 200 s",
        parameters=dict(thrust_N=150.0, isp_s=200.0, mass_kg=524.895, altitude_km=100.0,
                        eq19_masses="paper"),
        outputs=table_files("impulsive_baseline", "delta_v", "eq19")),
))

#: The finite-burn masses the paper prints (Sec. 3.2.1, 150 N / 200 s): at arrival, after
#: LOI 1 and after LOI 2, i.e. at the ignition of LOI 1, 2 and 3.
PAPER_MASS_QUOTES = ("arrival_mass_kg", "mass_after_loi1_150N_kg", "mass_after_loi2_150N_kg")

#: Our Eq. (19) estimates must round to the paper's within this (min) with its masses.
EQ19_TOLERANCE_MIN = 0.05


def paper_eq19(thrust_N: float, isp_s: float):
    """The paper's Eq. (19) estimates (min) and finite-chain masses (kg), or NaNs and None.

    The paper prints both for its 150 N / 200 s engine only (Sec. 3.2.1).
    """
    if (float(thrust_N), float(isp_s)) != PAPER_ENGINE:
        return [np.nan] * 3, None
    return ([paper.quote(f"eq19_loi{n}_150N_min").value for n in (1, 2, 3)],
            [paper.quote(q).value for q in PAPER_MASS_QUOTES])


def _masses_note(burns, chain, thrust_N, isp_s, printed_min) -> str:
    """Which masses reproduce the paper's Eq. (19) estimates, from the numbers."""
    fin = [paper.quote(q).value for q in PAPER_MASS_QUOTES]
    imp = [b.m_before_kg for b in chain]
    dv = [b.delta_v_mps for b in burns]
    t_fin = [b.eq19_duration_min for b in impulsive_sequence(
        thrust_N, isp_s, fin[0], eq19_masses_kg=fin)]
    t_imp = [b.eq19_duration_min for b in chain]
    # Eq. (19) is proportional to m0: the mass the printed LOI-1 estimate implies
    m0_implied = fin[0] * printed_min[0] / t_fin[0]
    arr = {f.id: f for f in audit.audit_findings()}["mass/arrival-implied"]
    t_arr = t_fin[0] * arr.computed / fin[0]
    t_pdv = [burn_duration_estimate_s(fin[n], paper.PAPER_IMPULSIVE_DV_MPS[n], thrust_N, isp_s) / 60
             for n in (1, 2)]
    return (
        f"**Which masses reproduce the paper's estimates.** Eq. (19) is proportional to the "
        f"mass at ignition $m_0$. The paper's finite-burn chain (Sec. 3.2.1) has "
        f"{fin[0]:.3f}, {fin[1]:.3f} and {fin[2]:.3f} kg at the three ignitions; the "
        f"impulsive chain above has {imp[0]:.3f}, {imp[1]:.3f} and {imp[2]:.3f} kg, "
        f"{imp[1] - fin[1]:.3f} and {imp[2] - fin[2]:.3f} kg more at LOI 2 and LOI 3, "
        f"because impulses spend less propellant than finite burns. With the finite-chain "
        f"masses Eq. (19) gives {t_fin[1]:.2f} and {t_fin[2]:.2f} min for LOI 2 and LOI 3 "
        f"(the paper prints {printed_min[1]:.2f} and {printed_min[2]:.2f} min; with the "
        f"paper's impulsive delta-Vs instead of our {dv[1]:.3f} and {dv[2]:.3f} m/s: "
        f"{t_pdv[0]:.2f} and {t_pdv[1]:.2f} min); with the impulsive-chain masses "
        f"{t_imp[1]:.2f} and {t_imp[2]:.2f} min, {t_imp[1] - printed_min[1]:.2f} and "
        f"{t_imp[2] - printed_min[2]:.2f} min more than printed. The paper therefore "
        f"evaluated Eq. (19) for each burn with the mass its finite-burn chain had at that "
        f"ignition. LOI 1 starts from the arrival mass in both chains: from the stated "
        f"{fin[0]:.3f} kg Eq. (19) gives {t_fin[0]:.2f} min, "
        f"{t_fin[0] - printed_min[0]:.2f} min above the printed {printed_min[0]:.2f} min, "
        f"which implies $m_0$ = {m0_implied:.2f} kg. The paper's printed masses imply an "
        f"arrival mass of {arr.computed:.3f} kg (the {{doc}}`reproduction report "
        f"<reproduction_report>`, finding `{arr.id}`), from which Eq. (19) gives "
        f"{t_arr:.2f} min: the paper's results were computed from a slightly smaller "
        f"arrival mass than the one it states.")


def delta_v_table(burns, rp_km: float) -> pd.DataFrame:
    """One row per impulse: orbits before and after, ΔV beside the paper's, mass after."""
    dv = np.array([b.delta_v_mps for b in burns])
    circle_kmps = float(np.sqrt(C.MU_MOON / rp_km))  # speed on the circle at the perilune
    paper_dv = np.array(paper.PAPER_IMPULSIVE_DV_MPS)
    return pd.DataFrame({
        "loi": [b.burn for b in burns],
        "from_orbit": [period_text(b.period_before_h) for b in burns],
        "to_orbit": [("circle, " if np.isclose(b.v_after_kmps, circle_kmps) else "")
                     + period_text(b.period_after_h) for b in burns],
        "delta_v_mps": dv, "paper_delta_v_mps": paper_dv, "difference_mps": dv - paper_dv,
        "m_after_kg": [b.m_after_kg for b in burns]})


def eq19_table(burns, masses, printed_min) -> pd.DataFrame:
    """Eq. (19) durations from the impulses, with the given masses (None: the chain's)."""
    t19 = np.array([b.eq19_duration_min for b in burns])
    return pd.DataFrame({
        "loi": [b.burn for b in burns], "delta_v_mps": [b.delta_v_mps for b in burns],
        "m0_kg": [b.m_before_kg for b in burns] if masses is None else masses,
        "duration_min": t19, "paper_duration_min": printed_min,
        "difference_min": t19 - np.array(printed_min)})


def prose_values(burns, v_inf: float, rp_km: float, printed_min) -> dict:
    """Numbers quoted in the prose here and on other pages (book/model.md, book/index.md)."""
    dv = np.array([b.delta_v_mps for b in burns])
    t19 = np.array([b.eq19_duration_min for b in burns])
    paper_dv = np.array(paper.PAPER_IMPULSIVE_DV_MPS)
    out = {"v_inf_kmps": float(v_inf), "rp_km": float(rp_km)}
    for n in (1, 2, 3):
        out[f"dv_loi{n}_mps"] = float(dv[n - 1])
        out[f"paper_dv_loi{n}_mps"] = float(paper_dv[n - 1])
        out[f"dv_diff_loi{n}_mps"] = float(dv[n - 1] - paper_dv[n - 1])
        out[f"eq19_loi{n}_min"] = float(t19[n - 1])
        out[f"paper_eq19_loi{n}_min"] = float(printed_min[n - 1])
    for n, q in enumerate(PAPER_MASS_QUOTES, start=1):  # m0 of eq19_masses="paper"
        out[f"paper_m0_loi{n}_kg"] = float(paper.quote(q).value)
    out["dv_total_mps"] = float(dv.sum())
    out["paper_dv_total_mps"] = float(paper_dv.sum())
    out["mass_final_kg"] = float(burns[-1].m_after_kg)
    return out


def _add_checks(page: Page, burns, printed_min, altitude_km: float, eq19_paper: bool) -> None:
    """Headline checks: the book build fails if the reproduction drifts."""
    dv = np.array([b.delta_v_mps for b in burns])
    t19 = np.array([b.eq19_duration_min for b in burns])
    paper_dv = np.array(paper.PAPER_IMPULSIVE_DV_MPS)
    if altitude_km == paper_scenario().perilune_altitude_km:
        page.expect("LOI 1 is the paper's 353.272 m/s (by construction)",
                    abs(dv[0] - paper_dv[0]) < 1e-3, f"{dv[0]:.4f} m/s")
        for n in (2, 3):
            page.expect(f"LOI {n} within 0.25 m/s of the paper",
                        abs(dv[n - 1] - paper_dv[n - 1]) < 0.25,
                        f"{dv[n - 1] - paper_dv[n - 1]:+.3f} m/s")
    if eq19_paper:
        for n in (1, 2, 3):
            page.expect(f"Eq. (19) LOI {n} within {EQ19_TOLERANCE_MIN} min of the paper's",
                        abs(t19[n - 1] - printed_min[n - 1]) < EQ19_TOLERANCE_MIN,
                        f"{t19[n - 1]:.3f} vs {printed_min[n - 1]:.2f} min")


def _engine_and_orbit(capture) -> tuple:
    """The plan's thrust (N), Isp (s), arrival mass (kg) and perilune altitude (km)."""
    return (capture.engine.thrust_N, capture.engine.isp_s, capture.arrival.mass_kg,
            capture.arrival.perilune_altitude_km)


def _add_tables(page: Page, capture, burns, masses, printed_min) -> None:
    """The chain's delta-Vs beside the paper's, and its Eq. (19) durations beside the paper's."""
    thrust_N, isp_s, mass_kg, altitude_km = _engine_and_orbit(capture)
    rp_km = capture.perilune_radius_km
    page.table(
        "delta_v", delta_v_table(burns, rp_km),
        caption=(f"Impulsive capture sequence, two-body, perilune altitude {altitude_km:g} km, "
                 f"{mass_kg:g} kg at arrival, Isp {isp_s:g} s, beside the paper's values "
                 "(Tables 1-5). Orbits by their periods; mass after each impulse (rocket "
                 "equation)."),
        columns={"delta_v_mps": "ΔV, ours (m/s)", "difference_mps": "ours − paper (m/s)"},
        floatfmt={"delta_v_mps": ".3f", "paper_delta_v_mps": ".3f", "difference_mps": "+.3f",
                  "m_after_kg": ".3f"})
    page.table(
        "eq19", eq19_table(burns, masses, printed_min),
        caption=(f"Eq. (19) burn durations, {thrust_N:g} N / {isp_s:g} s, from the impulses "
                 "above, m₀ the mass at ignition "
                 + ("of the paper's finite-burn chain (Sec. 3.2.1)"
                    if masses is not None else "of the impulsive chain")
                 + ", beside the paper's (Sec. 3.2.1, 150 N only)."),
        columns={"duration_min": "duration, ours (min)",
                 "paper_duration_min": "duration, paper (min)",
                 "difference_min": "ours − paper (min)"},
        floatfmt={"delta_v_mps": ".3f", "m0_kg": ".3f", "duration_min": ".2f",
                  "paper_duration_min": ".2f", "difference_min": "+.2f"})


def _add_masses_note(page: Page, capture, burns, chain, printed_min) -> bool:
    """The note on which masses reproduce the paper's Eq. (19); True for the paper's case."""
    paper = paper_scenario()
    thrust_N, isp_s, mass_kg, altitude_km = _engine_and_orbit(capture)
    paper_case = ((float(thrust_N), float(isp_s)) == PAPER_ENGINE
                  and mass_kg == paper.mass_kg
                  and altitude_km == paper.perilune_altitude_km)
    page.note("eq19_masses_note",
              _masses_note(burns, chain, thrust_N, isp_s, printed_min) if paper_case else
              "The paper prints its Eq. (19) estimates and its finite-burn masses only for "
              f"its 150 N / 200 s engine from {paper.mass_kg:g} kg with "
              f"{paper.perilune_altitude_km:g} km perilunes: there is nothing to compare with "
              "here.")
    return paper_case


def eq19_masses(eq19_masses: str = "paper", thrust_N: float = PAPER_ENGINE[0],
                isp_s: float = PAPER_ENGINE[1]) -> list | None:
    """The masses at ignition (kg) the page's Eq. (19) takes, by name; None: the chain's.

    ``"paper"``: those the paper prints for its finite-burn chain (Sec. 3.2.1; 150 N /
    200 s only: ValueError for another engine); ``"impulsive"``: None, the masses of the
    impulsive chain itself (:meth:`lunarcap.CapturePlan.impulsive`'s default).

    >>> eq19_masses("paper")
    [524.895, 434.471, 381.005]
    >>> eq19_masses("impulsive", 300.0, 250.0) is None
    True
    """
    if eq19_masses not in ("paper", "impulsive"):
        raise ValueError(f"eq19_masses must be 'paper' or 'impulsive', got {eq19_masses!r}")
    paper_masses = paper_eq19(thrust_N, isp_s)[1]
    if eq19_masses == "paper" and paper_masses is None:
        raise ValueError("eq19_masses='paper': the paper prints its finite-burn masses only "
                         "for 150 N / 200 s; use eq19_masses='impulsive'")
    return paper_masses if eq19_masses == "paper" else None


def build(capture, chain, burns, masses=None, output_name: str = "impulsive_baseline",
          quick: bool = False, parameters: dict | None = None) -> Page:
    """The page of the impulsive baseline computed in the notebook (see the module docstring).

    Parameters
    ----------
    capture : lunarcap.CapturePlan
        The paper's plan (:func:`lunarcap.paper_plan`) with the arrival mass (kg) and
        perilune altitude (km) asked; the engine's thrust enters Eq. (19) only.
    chain : list of ImpulsiveBurn
        ``capture.impulsive()``: the impulsive chain, Eq. (19) with its own masses.
    burns : list of ImpulsiveBurn
        ``capture.impulsive(eq19_masses_kg=masses)``: the same chain, Eq. (19) with
        ``masses``.
    masses : list of float, optional
        The masses at ignition (kg) of ``burns``' Eq. (19) (:func:`eq19_masses`); None:
        the chain's.
    output_name, quick : the page's output name and whether it is a quick build (recorded
        in the provenance only: nothing here is coarsened).
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance.
    """
    thrust_N, isp_s, _, altitude_km = _engine_and_orbit(capture)
    printed_min = paper_eq19(thrust_N, isp_s)[0]
    page = Page(NOTEBOOK, dict(parameters or {}), output_name, quick)
    _add_tables(page, capture, burns, masses, printed_min)
    for name, v in prose_values(burns, capture.arrival.v_inf_kmps, capture.perilune_radius_km,
                                printed_min).items():
        page.value(name, v)
    paper_case = _add_masses_note(page, capture, burns, chain, printed_min)
    _add_checks(page, burns, printed_min, altitude_km, paper_case and masses is not None)
    page.data["burns"] = burns
    t = page.text
    page.headline(f"Two-body tangential impulses differ from the paper's impulsive LOI 2 and "
                  f"LOI 3 by {t('dv_diff_loi2_mps', '+.3f')} and "
                  f"{t('dv_diff_loi3_mps', '+.3f', ' m/s')} (ours − paper; LOI 1 agrees by "
                  f"construction: the arrival speed is taken from it).")
    return page
