"""Warm starts of the dispersion re-plans: the nominal's multipliers, the same optimum.

A re-plan (:func:`lunarcap.studies.dispersions.samples._replan`) solves the burn's NLP from
the nominal's steering flown from the state reached; IPOPT may also start from the
nominal's multipliers (``warm_start_init_point``). That must not change which optimum is
found: the same re-plan warm and cold ends on the same burn (delta-V within 1e-6 m/s, far
inside the verification gate's 0.01 m/s), both verified, the warm one in fewer IPOPT
iterations (3-4 against 9-13 here). Cases: the paper's 150 N plan in full dynamics (burn 2
from a perilune reached 1 km and 1 m/s off, the paper's fixed timeline) and a generated
two-burn plan (35 deg, 260 N, 900 kg, its orbit asked) in two-body dynamics.
"""

import numpy as np
import pytest

from lunarcap.mission.plan import load_plan
from lunarcap.optim.nlp import same_nlp, shape_of
from lunarcap.studies.dispersions import samples as D
from lunarcap.studies.families import plan_of

pytestmark = pytest.mark.slow


def _replans(plan, d):
    """Burn 2 re-planned from the nominal perilune displaced by ``d`` (RTN km, km/s),
    cold and warm: (cold Solution, warm Solution, the nominal's)."""
    from lunarcap.capture.chain import perilune_epoch_state

    noms = D.nominal(plan)
    t_p, x_p = perilune_epoch_state(plan, 1)
    x = D.displaced(np.asarray(x_p, float), np.asarray(d, float))
    out = []
    for warm in (False, True):
        old, D.WARM_MULTIPLIERS = D.WARM_MULTIPLIERS, warm
        try:
            out.append(D._replan(plan, 1, t_p, x, noms[1]))
        finally:
            D.WARM_MULTIPLIERS = old
    return out[0], out[1], noms[1]


@pytest.mark.parametrize("which", ["song2011-150N", "family"])
def test_a_warm_replan_ends_on_the_cold_one(which):
    if which == "family":
        plan = plan_of([{"target_period_h": 6.0, "start_min": "free"},
                        {"target": "circular", "start_min": "free"}], inclination=35.0,
                       thrust=260.0, mass=900.0)
        d = [0.5, -0.3, 0.2, 5e-4, -3e-4, 2e-4]
    else:
        plan = load_plan(which)
        d = [1.0, 0.0, 0.0, 0.0, 1e-3, 0.0]
    cold, warm, nom = _replans(plan, d)
    assert cold.verification.passed and warm.verification.passed
    assert abs(warm.delta_v_mps - cold.delta_v_mps) < 1e-6
    assert abs(warm.delta_v_mps - nom.delta_v_mps) > 1e-3   # a real re-plan, not the nominal
    it = [sum(a["iterations"] for a in s.attempts) for s in (cold, warm)]
    assert it[1] < it[0], it   # the multipliers carry what the primal guess does not


def test_multipliers_of_another_nlp_are_not_used():
    """The multipliers are taken only for the NLP they belong to (the same shape)."""
    from dataclasses import replace

    from lunarcap.optim.collocation import DEFAULT_MESHES

    plan = load_plan("song2011-150N").with_dynamics("two-body")
    nom = D.nominal(plan)[1]
    prob, mesh = nom.problem, nom.raw.mesh
    assert same_nlp(nom.raw, prob, mesh)
    other = next(m for m in DEFAULT_MESHES if m != mesh)
    assert not same_nlp(nom.raw, prob, other)
    assert not same_nlp(replace(nom.raw, nlp_shape=shape_of(other, prob)), prob, mesh)
    assert not same_nlp(replace(nom.raw, lam_g=None), prob, mesh)
