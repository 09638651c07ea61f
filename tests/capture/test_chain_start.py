"""A plan's arrival is built once, on entering its chain, and every solve of it receives it.

Before, each solve from the arrival (burn 1, its impulsive limit, each free-start or
steering variant of it) looked the arrival up again on its way (chain -> arrival ->
epochs/ephemeris -> rocket -> impulsive -> chain). Now :func:`lunarcap.capture.chain.labelled`
builds the chain's start once and the solves of plans sharing it (same arrival,
ephemeris, pole and start) take it from there; any other plan builds its own.
"""

from dataclasses import replace

import numpy as np
import pytest

from lunarcap.capture import chain
from lunarcap.mission.plan import load_plan


@pytest.fixture
def counted(monkeypatch):
    """The arrivals built through the chain (each call of ``chain.arrival_for``)."""
    calls = []
    real = chain.arrival_for

    def arrival_for(*args):
        calls.append(args)
        return real(*args)

    monkeypatch.setattr(chain, "arrival_for", arrival_for)
    return calls


def test_the_solves_of_a_plan_receive_the_start_built_on_entering_its_chain(counted):
    plan = load_plan("two-burn-8h")
    expected = chain.chain_start(plan)
    counted.clear()
    with chain.labelled(plan):
        assert len(counted) == 1   # built on entering the chain
        # burn 1, its impulsive limit and a free-start variant: the same start, no build
        for key in (plan.key(1), chain.impulsive_key(plan.key(1)),
                    plan.with_start(0, "free").key(1)):
            t, x = chain.perilune_epoch_state(key, 0)
            assert t == expected[0] and np.array_equal(x, expected[1])
            x[:] = 0.0   # a solve's copy: the chain's start stays as built
    assert len(counted) == 1
    assert np.array_equal(chain.perilune_state(plan, 0), expected[1])   # outside: built
    assert len(counted) == 2


def test_a_plan_with_another_arrival_builds_its_own_start(counted):
    plan = load_plan("two-burn-8h")
    other = replace(plan, arrival=replace(plan.arrival, inclination_deg=60.0))
    with chain.labelled(plan):
        t, x = chain.perilune_epoch_state(other.key(1), 0)
    assert len(counted) == 2
    assert np.array_equal(x, chain.chain_start(other)[1])
    assert not np.array_equal(x, chain.chain_start(plan)[1])
