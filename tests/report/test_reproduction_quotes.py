"""quote_equivalents (lunarcap.report.reproduction) on hand-made chains."""

import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper import printed as P
from lunarcap.physics import constants as C
from lunarcap.report import reproduction as rep


def _chain(thrust_N, losses, m_end_kg):
    rows = []
    for n, (loss, m) in enumerate(zip(losses, m_end_kg), start=1):
        imp = P.PAPER_IMPULSIVE_DV_MPS[n - 1]
        rows.append({"burn": n, "thrust_N": thrust_N, "loss_vs_paper_impulse_mps": loss,
                     "loss_vs_paper_impulse_percent": 100 * loss / imp,
                     "burn_duration_min": 20.0 / n * 150.0 / thrust_N,
                     "m_end_kg": m, "fuel_kg": 50.0, "eq19_duration_min": 18.0 / n,
                     "rp_end_km": C.R_MOON + 100.001, "inc_end_deg": 90.0})
    return rows


def test_totals_per_engine_and_across_engines():
    chains = {150.0: _chain(150.0, [12.0, 5.0, 3.0], [450.0, 380.0, 340.0]),
              300.0: _chain(300.0, [3.0, 1.0, 0.5], [455.0, 390.0, 370.0])}
    q = rep.quote_equivalents(chains, best_starts={(150.0, 1): -10.0})
    imp_total = sum(P.PAPER_IMPULSIVE_DV_MPS)
    assert q["loss_total_150N_mps"][0] == pytest.approx(20.0)
    assert q["loss_total_300N_percent"][0] == pytest.approx(100 * 4.5 / imp_total)
    assert q["fuel_finite_150N_kg"][0] == pytest.approx(paper_scenario().mass_kg - 340.0)
    assert q["fuel_saving_300N_vs_150N_kg"][0] == pytest.approx(30.0)
    assert q["abstract_max_loss_percent"][0] == pytest.approx(100 * 20.0 / imp_total)
    assert q["fig4_burn_loi1_150N_min"][0] == 20.0
    assert q["eq19_loi1_150N_min"][0] == 18.0
    assert q["final_altitude_km"][0] == pytest.approx(100.001)
    assert q["best_start_loi1_150N_min"][0] == 10.0      # printed as minutes before
    assert q["mu_sun_km3s2"][0] == C.MU_SUN
    assert set(q) <= set(P.QUOTES)
