"""The lunar-pole page: the pole choice reaches the dynamics, and only where it should.

* two-body dynamics: the pole only rotates the frame, so no delta-V may change (the
  capture is invariant under rotations; tolerance 1 mm/s, far above IPOPT's 1e-8 km/s);
* J2 dynamics: J2 acts about the pole, so the chain changes, by more than the solver's
  noise (1e-4 m/s) and less than the page's 0.1 m/s headline bound.
"""

import numpy as np
import pytest

from lunarcap.report.pages import lunar_pole

pytestmark = pytest.mark.slow


def _captures(dynamics: str, thrusts_N) -> dict:
    """The captures as the notebook solves them: the paper's plan with each pole."""
    import lunarcap

    out = {pole: [] for pole in (lunar_pole.NEW, lunar_pole.OLD)}
    for thrust_N, isp_s in lunar_pole.paper_engines(thrusts_N):
        capture = lunarcap.paper_plan(thrust_N, isp_s, dynamics=dynamics)
        for pole in out:
            out[pole].append(lunarcap.solve(lunarcap.load_plan(capture, lunar_pole=pole)))
    return out


def test_pole_table_angles():
    poles = lunar_pole.pole_table().set_index("pole")
    # Cassini: the Moon's axis at J2000 is ~1.5 deg from the ecliptic pole; the constant
    # terms are the centre of its precession circle, close to the ecliptic pole
    assert 1.50 < poles.loc["iau2009-j2000", "from_ecliptic_pole_deg"] < 1.60
    assert poles.loc["iau-constant", "from_ecliptic_pole_deg"] < 0.03


def test_two_body_chain_does_not_depend_on_the_pole():
    page = lunar_pole.build(_captures("two-body", [150.0]))
    assert page.parameters == {"dynamics": "two-body", "thrusts_N": [150.0]}
    eff = page.items["effect"].df
    assert len(eff) == 3 and (eff.verified == "passed").all()
    assert np.abs(eff.dv_effect_mps).max() < 1e-3
    assert np.abs(eff.impulsive_limit_effect_mps).max() < 1e-3
    page.check()


def test_j2_chain_feels_the_pole():
    eff = lunar_pole.build(_captures("j2", [450.0])).items["effect"].df
    assert (eff.verified == "passed").all()
    assert np.abs(eff.dv_effect_mps).max() > 1e-4
    assert np.abs(eff.dv_effect_mps).max() < 0.1


def test_only_the_papers_engines_and_both_poles_of_the_same_plans_are_compared():
    assert lunar_pole.paper_engines() == [(150.0, 200.0), (300.0, 250.0), (450.0, 300.0)]
    with pytest.raises(ValueError, match="among the paper's engines"):
        lunar_pole.paper_engines([200.0])
    caps = _captures("two-body", [150.0])
    with pytest.raises(ValueError, match="missing \\['iau-constant'\\]"):
        lunar_pole.build({lunar_pole.NEW: caps[lunar_pole.NEW]})
    other = _captures("two-body", [300.0])
    with pytest.raises(ValueError, match="the same engines"):
        lunar_pole.build({lunar_pole.NEW: caps[lunar_pole.NEW],
                          lunar_pole.OLD: other[lunar_pole.OLD]})
