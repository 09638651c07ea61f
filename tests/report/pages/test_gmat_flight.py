"""The "Flown in GMAT" page: its table comes from a real GMAT run, and its small functions.

The page is built for a generated plan (two burns, free ignition, J2 only: GMAT's force
model then has no third body) in a temporary book: GMAT runs the exported script (not
skipped: gmatpy is in the lock), and the comparison table's first burn row is recomputed
here from GMAT's own report file beside the script and lunarcap's flight, independently of
the page. The settings table quotes lines of that script and GMAT's defaults read from
GMAT.
"""

from pathlib import Path

import numpy as np
import pytest

from lunarcap.capture.chain import plan_result
from lunarcap.capture.export import capture_arcs
from lunarcap.capture.gmat_flight import lunarcap_events
from lunarcap.exchange import gmat
from lunarcap.exchange.ccsds import StateVector
from lunarcap.mission.plan import load_plan
from lunarcap.report.pages import gmat_flight
from lunarcap.repro import paths


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    with paths.using_book(tmp_path_factory.mktemp("book")):
        import lunarcap

        res = lunarcap.solve(lunarcap.load_plan("two-burn-8h", dynamics="j2"), impulsive=False)
        page = gmat_flight.build([res], [res.fly_in_gmat(gmat_flight.export_dir("gmat_test"))],
                                 "gmat_test", quick=True)
        yield page


@pytest.mark.slow
def test_comparison_comes_from_gmats_report(built):
    page = built
    comp = page.items["comparison"].df
    files = {r.file: r for r in page.items["files"].df.itertuples()}
    assert set(files) == {"two-burn-8h.script", "two-burn-8h_gravity.cof",
                          "two-burn-8h_moon.bsp"}
    link = files["two-burn-8h.script"].download
    script = paths.GENERATED / link[link.index("<") + 1:-2]
    assert script.is_file()
    report = script.with_name("two-burn-8h_gmat_burns.txt")
    log = script.with_name("two-burn-8h_gmat.log")
    assert report.stat().st_mtime >= script.stat().st_mtime and log.is_file()
    # burn 1's cut-off as GMAT reported it, against lunarcap's flight
    row = next(r for r in gmat.read_report(report) if (r.burn, r.event) == (1, gmat.CUTOFF))
    res = plan_result(load_plan("two-burn-8h").with_dynamics("j2"), impulsive=False)
    ref = lunarcap_events(res, capture_arcs(res))[(1, gmat.CUTOFF)]
    want = np.linalg.norm(row.r_km - np.array(ref.r_km)) * 1e3
    got = comp.iloc[0]
    assert got.flight.startswith("burn 1 from lunarcap's ignition state")
    assert got.position_diff_m == pytest.approx(want, rel=1e-12)
    assert 0.0 < got.position_diff_m < 0.5        # GMAT's own numbers: close, not equal
    # every burn, every coast and the whole capture's events after the arrival
    n = res.plan.n_burns
    assert len(comp) == n + n + (2 * n + 2 - 1)
    assert not comp.filter(like="_diff").isna().any().any()
    final = page.items["final"].df
    assert (final.final_rp_diff_m.abs() < 50).all() and (final.final_ra_diff_m.abs() < 50).all()
    page.check()


@pytest.mark.slow
def test_settings_quote_the_script_and_gmat(built):
    page = built
    st = page.items["settings"].df
    assert len(st) == 8
    text = Path(next(paths.GENERATED.glob("export/gmat_test_1/two-burn-8h.script"))).read_text()
    lines = set(ln.split("%")[0].strip() for ln in text.splitlines())
    assert all(s in lines for s in st.script)
    assert st.gmat_default.iloc[0] == "9.81 m/s²"          # read from GMAT
    assert "km" in st.cost.iloc[0] and "burn 1" in st.cost.iloc[0]
    assert page.values["inc_icrf_deg"] != pytest.approx(page.values["inc_deg"], abs=1.0)


def test_script_line_and_units():
    text = "% a comment\nX.Mu = 4902.8;   % km^3/s^2\nPropagate Prop(X) {X.Elapsed = 1};\n"
    assert gmat_flight.script_line(text, r"\.Mu =") == "X.Mu = 4902.8;"
    with pytest.raises(ValueError, match="no line"):
        gmat_flight.script_line(text, "GravitationalAccel")
    assert gmat_flight.length_text(1234.0) == "1.23 km"
    assert gmat_flight.speed_text(0.5) == "0.5 mm/s"


def test_tdb_minus_tai_and_icrf_inclination():
    from lunarcap.physics.epochs import seconds_from_calendar

    t = seconds_from_calendar("2017-02-20 03:41:26 TDB")
    # TT - TAI = 32.184 s exactly; TDB - TT is periodic, below 2 ms
    assert abs(gmat_flight.tdb_minus_tai_s(t) - 32.184) < 2e-3
    eq = StateVector(t, (2000.0, 0.0, 0.0), (0.0, 1.5, 0.0))
    polar = StateVector(t, (2000.0, 0.0, 0.0), (0.0, 0.0, 1.5))
    assert gmat_flight.inclination_icrf_deg(eq) == pytest.approx(0.0, abs=1e-12)
    assert gmat_flight.inclination_icrf_deg(polar) == pytest.approx(90.0)
