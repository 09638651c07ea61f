"""The "Hand the plan to other tools" page: its small functions on a two-body export."""

import numpy as np
import pytest

from lunarcap.report.pages import exchange
from lunarcap.repro import paths

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def page(tmp_path_factory):
    import lunarcap

    with paths.using_book(tmp_path_factory.mktemp("book")):
        res = lunarcap.solve(lunarcap.load_plan("song2011-150N", dynamics="two-body"),
                             impulsive=False)
        out = exchange.export_dir("exchange_test")
        yield exchange.build(res, res.export(out), res.export(out / "utc", time_system="UTC"),
                             "exchange_test")


def test_page_tables_values_and_checks(page):
    files = page.items["files"].df
    assert list(files.kind) == ["oem", "spk", "attitude", "maneuvers", "gmat_script",
                                "gmat_gravity", "gmat_moon"]
    assert (files.size_kB > 0.1).all()
    seg = page.items["segments"].df
    assert list(seg.segment)[0] == "approach" and list(seg.segment)[-1] == "final orbit"
    assert seg.interpolation_error_m.max() < 1.0
    assert page.values["spk_vs_oem_m"] < 1.0
    assert page.values["utc_vs_tdb_s"] < 1.2e-6
    # the first ignition of the paper's plan: 03:31:26 TDB = 03:30:16.815 UTC (69.185 s)
    assert page.values["first_ignition_tdb"] == "2017-02-20 03:31:26.000 TDB"
    assert page.values["first_ignition_utc"] == "2017-02-20 03:30:16.815 UTC"
    page.check()


def test_spk_residual_detects_a_moved_state(page, tmp_path):
    # the residual function must see a difference: an OEM with one state moved by 10 m
    from lunarcap.exchange import ccsds

    oem = paths.export_dir("exchange_test") / "song2011-150N.oem"
    segs = ccsds.read_oem(oem)
    segs[1].r_km[0, 3] += 0.010
    moved = ccsds.write_oem(tmp_path / "moved.oem", segs, "x", "-310001")
    assert exchange.spk_against_oem_m(moved, oem.with_suffix(".bsp")) == pytest.approx(
        10.0, abs=0.01)
    arcs = exchange.trajectory_arcs(oem)
    assert [a[2] for a in arcs].count(True) == 3
    assert np.all(np.linalg.norm(arcs[0][1], axis=0) > 1737.4)
