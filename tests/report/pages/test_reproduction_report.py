"""The reproduction report (lunarcap.report.pages.reproduction_report), built in two-body.

Two-body dynamics and one engine in part (a): the identities between the columns, the
paper's printed values, the audit and the epochs are checked, not the agreement with the
paper (which needs the full dynamics, asserted by the page's own checks in the book).
"""

import numpy as np
import pandas as pd
import pytest

import lunarcap
from lunarcap.mission.plan import paper_plan
from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper import audit
from lunarcap.paper import printed as paper
from lunarcap.physics import constants as C
from lunarcap.report import reproduction
from lunarcap.report.pages import reproduction_report

pytestmark = pytest.mark.slow


def _burns(engines, dynamics="two-body"):
    """Part (a)'s solves as the notebook makes them (lunarcap.solve_burn per printed offset)."""
    rr = reproduction_report
    return {(t, loi): [lunarcap.solve_burn(lunarcap.paper_plan(t, i, dynamics=dynamics), loi,
                                           start=s, impulsive=False)
                       for s in rr.paper_starts(t, loi)]
            for t, i in engines for loi in (1, 2, 3)}


@pytest.fixture(scope="module")
def page():
    captures = [lunarcap.solve(lunarcap.paper_plan(t, i, dynamics="two-body"), impulsive=False)
                for t, i in reproduction_report.paper_engines()]
    return reproduction_report.build(_burns([(150.0, 200.0)]), captures, "t_repro", True,
                                     dict(engines=[[150.0, 200.0]], dynamics="two-body"))


def test_the_public_solves_are_the_sweep_tables_and_chains(page):
    """lunarcap.solve_burn / lunarcap.solve of lunarcap.paper_plan reach the cached solves
    of sweep_table and solve_plan (the same plan keys): the same tables, to the bit."""
    from lunarcap.capture.chain import solve_plan
    from lunarcap.studies import sweeps

    for (t, loi), df in page.data["sweeps"].items():
        ref = sweeps.sweep_table(t, 200.0, loi, reproduction_report.paper_starts(t, loi),
                                 dynamics="two-body")
        pd.testing.assert_frame_equal(df, ref, check_exact=True)
        assert df.attrs == ref.attrs
    sols = solve_plan(paper_plan(300.0, 250.0, dynamics="two-body"))
    pd.testing.assert_frame_equal(
        pd.DataFrame(page.data["chains"][300.0]),
        pd.DataFrame(reproduction.paper_chain_rows([s.summary() for s in sols])),
        check_exact=True)
    assert page.parameters == {"engines": [[150.0, 200.0]], "dynamics": "two-body"}


def test_paper_starts_refuses_an_engine_without_a_table():
    with pytest.raises(ValueError, match="no table for 320 N"):
        reproduction_report.paper_starts(320.0, 1)


def test_tables_set_every_printed_number_beside_ours(page):
    long = page.items["tables_data"].df
    np.testing.assert_allclose(long.difference, long.ours - long.paper)
    dv = long[long.quantity == "delta-V"].set_index(["source", "start_min"])
    for loi in (1, 2, 3):
        t = paper.paper_table(150.0, loi)
        got = dv.loc[t.attrs["source"]].loc[t.start_min.astype(float), "paper"]
        np.testing.assert_allclose(got, t.delta_v_mps)
    # the excess over the paper's impulsive delta-V is computed from our delta-V
    pct = long[long.quantity == "difference from impulsive"].ours.to_numpy()
    imp = np.array(paper.PAPER_IMPULSIVE_DV_MPS)[long[long.quantity == "delta-V"].loi - 1]
    np.testing.assert_allclose(pct, 100 * (long[long.quantity == "delta-V"].ours - imp) / imp)
    # the impulsive rows: the paper's 2009c values against our two-body chain
    rows = long[long.quantity == reproduction.IMPULSE_ROW_TWO_BODY]
    np.testing.assert_allclose(rows.paper, paper.PAPER_IMPULSIVE_DV_MPS)
    np.testing.assert_allclose(rows.ours, [b.delta_v_mps for b in paper_plan().impulsive()])
    assert abs(rows.difference.iloc[0]) < 1e-9          # LOI 1 by construction
    # Table B1 repeats the best row of each table, compared with the same solution
    b1 = long[(long.source == "Table B1") & (long.quantity == "delta-V")]
    np.testing.assert_allclose(b1.paper, [paper.paper_best(150.0, n)["delta_v_mps"]
                                          for n in (1, 2, 3)])
    assert long.verified.all()
    # shown in wide form: one row per row of the paper's tables, every number of the long
    # form in it once
    wide = page.items["tables"].df
    main = long[long.quantity != reproduction.IMPULSE_ROW_TWO_BODY]
    assert len(wide) == len(main) // 3 + 3
    numbers = wide.drop(columns=["source", "thrust_N", "isp_s", "start", "best", "row"]
                        ).to_numpy(dtype=float)
    assert np.isfinite(numbers).sum() == 3 * len(long)
    np.testing.assert_allclose(np.sort(numbers[np.isfinite(numbers)]),
                               np.sort(long[["paper", "ours", "difference"]].to_numpy().ravel()))
    assert (wide.best != "").sum() == (long.paper_best | long.ours_best).sum() // 3
    rows = wide[~wide.row.str.startswith("impulse,")]   # the impulse rows name their source
    assert rows.row.str.endswith(")").sum() == (wide.best != "").sum()
    summary = page.items["tables_summary"].df
    assert list(summary.numbers) == [14, 14, 14]       # 6 + 4 + 4 rows of Tables 1-3
    assert page.values["tables_range"] == "Tables 1–3"
    assert page.values["t300_dur_remark"] == "Table 4 is not in part (a) of this run"


def test_quotes_are_the_papers_with_our_equivalents(page):
    q = page.items["quotes_data"].df.set_index("name")
    assert len(q) == len(paper.QUOTES) and q.index.is_unique
    np.testing.assert_allclose(q.paper, [paper.QUOTES[n].value for n in q.index])
    chain = page.data["chains"][150.0]
    loss = sum(r["delta_v_mps"] for r in chain) - sum(paper.PAPER_IMPULSIVE_DV_MPS)
    assert q.loc["loss_total_150N_mps", "ours"] == pytest.approx(loss)
    assert q.loc["fuel_finite_150N_kg", "ours"] == pytest.approx(
        paper_scenario().mass_kg - chain[2]["m_end_kg"])
    # Eq. (19) from the paper's impulsive delta-V and the arrival mass: 18.854 min
    assert q.loc["eq19_loi1_150N_min", "ours"] == pytest.approx(18.8544, abs=1e-4)
    assert q.loc["best_start_loi1_150N_min", "ours"] > 0  # printed as "minutes before"
    assert q[q.ours.isna()].note.str.contains("no equivalent").all()
    v = page.values
    assert v["n_quotes"] == v["n_quotes_computed"] + v["n_quotes_input"] + v["n_quotes_none"]
    shown = page.items["quotes"].df
    assert len(shown) == len(q) and len(shown.columns) <= 7


def test_epochs_and_audit(page):
    ep = page.items["epochs"].df
    assert list(ep.perilune) == [1, 2, 3]
    assert ep.difference_s.abs().max() <= 4.0          # the rounding of the printed periods
    ft = audit.findings_table()
    bad = page.items["findings_data"].df
    assert len(bad) == (ft.verdict == audit.INCONSISTENT).sum() == page.values["n_inconsistent"]
    groups = page.items["findings_by_group"].df
    assert groups.checks.sum() == len(ft) and groups.inconsistent.sum() == len(bad)
    # book/index.md formats these with :d
    assert isinstance(page.values["n_findings"], int)
    assert isinstance(page.values["n_inconsistent"], int)
    assert page.values["arrival_implied_kg"] == pytest.approx(523.982, abs=1e-3)
    page.check()  # two-body: the agreement with the paper is not asserted, the rest is


def test_paper_chain_rows_measure_losses_as_the_paper():
    rows = reproduction.paper_chain_rows([
        {"burn": 2, "delta_v_mps": 258.0, "m_start_kg": 435.0, "thrust_N": 150.0,
         "isp_s": 200.0, "eq19_duration_min": 0.0}])
    r = rows[0]
    assert r["loss_vs_paper_impulse_mps"] == pytest.approx(258.0 - 254.034)
    assert r["loss_vs_paper_impulse_percent"] == pytest.approx(100 * (258.0 - 254.034) / 254.034)
    ve = C.G0_MPS2 * 200.0
    assert r["eq19_duration_min"] == pytest.approx(
        435.0 * (1 - np.exp(-254.034 / ve)) * ve / 150.0 / 60.0)
