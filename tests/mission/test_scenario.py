"""The paper's scenario and engines have one source: the packaged song2011-*.yaml plans.

(issue 17, deliverable 2.) :mod:`lunarcap.mission.scenario` reads them; no other module
of the package writes the engines or the scenario again. Broken on purpose: putting the
engines back as a literal in a page module, or ``ARRIVAL_MASS_KG`` back in
``physics/constants.py``, fails :func:`test_no_module_writes_the_paper_engines_again` and
:func:`test_physics_constants_are_physical_only`; a plan whose arrival mass differs from the
others fails :func:`test_plans_that_disagree_are_refused`.
"""

import re
from pathlib import Path

import pytest

from lunarcap.mission import scenario
from lunarcap.mission.plan import load_plan, paper_plan
from lunarcap.physics import constants as C

PACKAGE = Path(scenario.__file__).resolve().parents[1]


def test_reader_matches_the_packaged_plans():
    for name, (thrust, isp) in zip(scenario.PAPER_PLANS, scenario.paper_engine_pairs()):
        plan = load_plan(name)
        assert (plan.engine.thrust_N, plan.engine.isp_s) == (thrust, isp)
        assert scenario.paper_plan_name(thrust, isp) == name
        assert paper_plan(thrust, isp).name == name
        s = scenario.paper_scenario()
        assert plan.arrival.mass_kg == s.mass_kg
        assert plan.arrival.perilune_altitude_km == s.perilune_altitude_km
        assert plan.arrival.epoch == s.epoch_tdb
        assert plan.burns[-1].coast_s == s.capture_periods_s[-1]
        assert [b.period_s for b in plan.burns[:-1]] == list(s.capture_periods_s[:-1])
    assert scenario.paper_plan_name(320.0, 200.0) is None
    assert scenario.paper_scenario().capture_periods_s == pytest.approx(
        (12.235 * 3600.0, 3.525 * 3600.0, 117.848 * 60.0), rel=1e-15)


def test_plans_that_disagree_are_refused(monkeypatch):
    raw = {n: scenario._raw(n) for n in scenario.PAPER_PLANS}
    odd = dict(raw[scenario.PAPER_PLANS[2]], arrival=dict(raw[scenario.PAPER_PLANS[2]]["arrival"],
                                                          mass_kg=600.0))
    monkeypatch.setattr(scenario, "_raw", lambda n: odd if n == scenario.PAPER_PLANS[2] else raw[n])
    scenario.paper_scenario.cache_clear()
    try:
        with pytest.raises(ValueError, match="arrival.mass_kg"):
            scenario.paper_scenario()
    finally:
        scenario.paper_scenario.cache_clear()


def test_physics_constants_are_physical_only():
    for name in ("ARRIVAL_MASS_KG", "ARRIVAL_EPOCH_TDB", "PERILUNE_ALTITUDE_KM",
                 "CAPTURE_PERIODS_S", "PAPER_ENGINES"):
        assert not hasattr(C, name), f"physics.constants.{name}: the scenario is the plans'"


#: The three engines written out as pairs or as a mapping (either spelling, any spacing).
_ENGINES = re.compile(r"150(\.0)?\s*[,:]\s*200(\.0)?\s*\)?\s*,\s*\(?\s*300(\.0)?\s*[,:]\s*"
                      r"250(\.0)?\s*\)?\s*,\s*\(?\s*450(\.0)?\s*[,:]\s*300")


def test_no_module_writes_the_paper_engines_again():
    found = [p.relative_to(PACKAGE).as_posix() for p in PACKAGE.rglob("*.py")
             if _ENGINES.search(p.read_text(encoding="utf-8"))
             and p.name != "scenario.py"]   # the reader's doctest shows what it reads
    assert found == [], f"the paper's engines written again (read mission.scenario): {found}"
    assert _ENGINES.search("{150: 200.0, 300: 250.0, 450: 300.0}")   # the pattern bites
    assert _ENGINES.search("((150.0, 200.0), (300.0, 250.0), (450.0, 300.0))")
