"""The rocket equation written once (physics.rocket), its four forms consistent.

The paper's audit (lunarcap.paper.recompute, checks_masses, checks_timing) calls these
instead of its own exp/log (issue 17, deliverable 2). Broken on purpose (g0 Isp replaced by
Isp in rocket_mass_before) the inverse checks fail.
"""

import math

import numpy as np
import pytest

from lunarcap.physics import constants as C
from lunarcap.physics import rocket


@pytest.mark.parametrize("m0, dv, isp", [(524.895, 353.272, 200.0), (1000.0, 2500.0, 320.0)])
def test_forms_invert_each_other(m0, dv, isp):
    m1 = rocket.rocket_mass_after(m0, dv, isp)
    assert m1 == pytest.approx(m0 * math.exp(-dv / (C.G0_MPS2 * isp)), rel=1e-15)
    assert rocket.rocket_mass_before(m1, dv, isp) == pytest.approx(m0, rel=1e-14)
    assert rocket.rocket_delta_v_mps(m0, m1, isp) == pytest.approx(dv, rel=1e-12)
    assert rocket.rocket_propellant_kg(m0, dv, isp) == pytest.approx(m0 - m1, rel=1e-14)
    assert rocket.exhaust_speed_mps(isp) == C.G0_MPS2 * isp
    # scalars come back as Python floats (the audit's findings compare and print them)
    assert type(m1) is float and type(rocket.rocket_delta_v_mps(m0, m1, isp)) is float


def test_arrays_stay_arrays():
    m1 = rocket.rocket_mass_after(np.array([500.0, 600.0]), 100.0, 300.0)
    assert isinstance(m1, np.ndarray) and m1.shape == (2,)
