"""The tutorial page's helper: what it quotes is what the public API computed, and its
checks fail when a physical truth does not hold.

The tutorial's own computation (its notebook's cells, through ``import lunarcap``) is run
here on its plan in two-body dynamics, as the quick book runs it: solve, one missed-thrust
case, two dispersed samples, the export and GMAT's flight. Then each check is shown to
fail on a result that breaks it (GMAT's final orbit 60 m off, a case without recovery, a
dispersed sample lost, the exported OEM missing).
"""

import dataclasses
import re
import tempfile
from pathlib import Path

import nbformat
import pytest

import lunarcap
from lunarcap.report.pages import tutorial
from lunarcap.repro import paths


@pytest.fixture(scope="module")
def computed():
    """The notebook's computation, its cells' calls, in two-body dynamics."""
    plan = lunarcap.load_plan("two-burn-8h", name="my-orbiter", thrust_N=440, isp_s=320,
                              mass_kg=900, targets=[{"target_period_h": 6}, None],
                              dynamics="two-body")
    res = lunarcap.solve(plan).check()
    cutoff = lunarcap.missed(plan, fractions=[0.5], delays_min=[30], workers=1)
    disp = lunarcap.dispersions(plan, samples=2, seed=1, thrust_sigma_pct=1,
                                pointing_sigma_deg=0.3, ignition_sigma_s=1, workers=1)
    out = tempfile.mkdtemp(prefix="my-orbiter-")
    files = res.export(out).files
    flight = res.fly_in_gmat(out)
    return dict(res=res, missed=cutoff, disp=disp, files=files, flight=flight, out=out)


def _page(c, **changed):
    args = dict(c) | changed
    page = tutorial.start({"dynamics": "two-body"}, "tutorial_test", quick=True)
    return tutorial.finish(page, args["res"], args["missed"], args["disp"], args["files"],
                           args["flight"])


class _Study:
    """A study result whose table and verdict are given (the checks read only these)."""

    def __init__(self, real, table, answered, summary=None):
        self._real, self._table, self.answered = real, table, answered
        self._summary = summary

    def to_frame(self):
        return self._table

    def to_dict(self):
        doc = self._real.to_dict()
        return doc | {"summary": doc["summary"] | self._summary} if self._summary else doc


@pytest.mark.slow
def test_the_page_quotes_the_apis_numbers_and_every_check_holds(computed):
    page = _page(computed)
    page.check()
    tot = computed["res"].totals()
    assert page.values["total_delta_v_mps"] == tot["total_delta_v_mps"]
    assert page.values["missed_status"] == "recovered"
    assert page.values["missed_penalty_mps"] > 1.0   # 30 min lost: the recovery costs more
    assert page.values["captured"] == page.values["samples"] == 2
    assert page.values["gmat_final_radii_m"] < 50
    assert "`my-orbiter.oem`" in page.values["files"]
    assert f"{tot['total_delta_v_mps']:.1f} m/s" in page.notes["headline"]
    assert not Path(computed["out"]).exists()   # the temporary export removed once read


@pytest.mark.slow
@pytest.mark.parametrize("breaks, named", [
    ("gmat", "GMAT's final orbit within 50 m"),
    ("missed", "recovered"),
    ("disp", "every dispersed sample captured"),
    ("files", "the export holds the OEM"),
])
def test_each_check_fails_when_its_truth_does_not_hold(computed, breaks, named):
    c = dict(computed)
    if breaks == "gmat":
        comp = c["flight"].comparison
        off = [f | {"rp_diff_m": 60.0} for f in comp.final_orbit]
        c["flight"] = lunarcap.GmatFlight(dataclasses.replace(comp, final_orbit=off))
    elif breaks == "missed":
        t = c["missed"].to_frame().assign(status="no recovery", reason="too far")
        c["missed"] = _Study(c["missed"], t, answered=False)
    elif breaks == "disp":
        s = c["disp"].to_dict()["summary"]
        c["disp"] = _Study(c["disp"], c["disp"].to_frame(), answered=True,
                           summary={"captured_and_corrected": s["samples"] - 1})
    else:
        c["files"] = {k: v for k, v in c["files"].items() if k != "oem"}
    c["files"] = {k: Path(tempfile.gettempdir()) / "kept" / Path(v).name
                  for k, v in c["files"].items()}   # nothing of the fixture's removed
    with pytest.raises(AssertionError, match=named):
        _page(c).check()


def test_only_a_temporary_directory_is_removed(tmp_path, monkeypatch):
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path / "tmp"))
    (tmp_path / "tmp" / "my-orbiter-x").mkdir(parents=True)
    (tmp_path / "mine").mkdir()
    tutorial._remove_temporary([tmp_path / "tmp" / "my-orbiter-x", tmp_path / "mine",
                                tmp_path / "tmp"])
    assert not (tmp_path / "tmp" / "my-orbiter-x").exists()
    assert (tmp_path / "mine").is_dir() and (tmp_path / "tmp").is_dir()


def test_the_notebooks_visible_cells_use_only_the_public_api():
    # the book's helper is imported by the set-up cell alone; every cell a reader sees
    # (tagged show-input) calls lunarcap's public names, and nothing else of lunarcap
    nb = nbformat.read(str(paths.ROOT / tutorial.NOTEBOOK), as_version=4)
    shown = [c.source for c in nb.cells if "show-input" in c.metadata.get("tags", [])]
    assert len(shown) >= 5
    code = "\n".join(shown)
    assert "import lunarcap\n" in code and "from lunarcap" not in code
    assert "tutorial." not in code and "page." not in code
    for used in set(re.findall(r"lunarcap\.(\w+)", code)):
        assert used in lunarcap.__all__, f"lunarcap.{used} is not public"
