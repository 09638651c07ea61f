"""Shared fixtures: the paper's mission window and arrival state.

The window is the one a capture of the paper's plan spans: from 6 h before the first
perilune (2017-02-20 03:41:26 TDB) to 6 h after the last (12.235 h + 3.525 h +
117.848 min later), the margin every burn's ephemeris fit keeps.
"""

import pytest

from lunarcap.physics.constants import ARRIVAL_EPOCH_TDB, CAPTURE_PERIODS_S
from lunarcap.physics.ephemeris import ChebyshevFit, default_ephemeris
from lunarcap.physics.epochs import seconds_from_calendar

T_ARRIVAL_S = seconds_from_calendar(ARRIVAL_EPOCH_TDB)
T_LAST_PERILUNE_S = T_ARRIVAL_S + sum(CAPTURE_PERIODS_S)


@pytest.fixture(scope="session")
def mission_fit():
    """Chebyshev fit of the Earth and Sun over the paper's capture, +-6 h."""
    return ChebyshevFit.fit(default_ephemeris(), T_ARRIVAL_S - 6 * 3600.0,
                            T_LAST_PERILUNE_S + 6 * 3600.0)


@pytest.fixture(scope="session")
def paper_arrival():
    """The reconstructed arrival state of the paper's plans (north hemisphere)."""
    from lunarcap.mission.arrival import arrival_state

    return arrival_state()
