"""Seeded families of generated capture plans: the ranges an analyst might write.

A result that must hold for any plan the load-time checks accept (the solver meets every
target as asked, a missed-thrust recovery is found or refused with a reason) is checked
on plans drawn at random from these ranges, not only on the paper's: the tests draw small
families, ``tools/missed_family.py`` bigger ones. A family is a function of its seed
alone (:func:`numpy.random.default_rng`), so a plan is named by its seed and its index
in the family and drawn again identically anywhere.

Examples
--------
Two plans of one seed, named by their index, none refused:

>>> plans, refused = plan_family(24, 2)
>>> [p.name for p in plans] == [f"family-{k}" for k in range(2)], refused
(True, [])
"""

from __future__ import annotations

import math

import numpy as np

from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.physics import constants as C


def plan_of(burns, dynamics="two-body", inclination=90.0, formulation="orbit", thrust=120.0,
            mass=700.0, name="asked", isp=220.0) -> CapturePlan:
    """A plan of ``burns`` (plan-file mappings) arriving at the paper's epoch and v_inf.

    The arrival of the paper's plans (Song et al. 2011: 2017-02-20 03:41:26 TDB, 100 km
    perilune, v_inf 0.8 km/s) at ``inclination`` deg; ``thrust`` N, ``mass`` kg, ``isp``
    s. PlanError if the load-time checks refuse it.
    """
    return CapturePlan.from_dict({
        "name": name, "formulation": formulation, "dynamics": dynamics,
        "arrival": {"epoch": "2017-02-20 03:41:26 TDB", "perilune_altitude_km": 100,
                    "inclination_deg": inclination, "v_inf_kmps": 0.8, "mass_kg": mass},
        "engine": {"thrust_N": thrust, "isp_s": isp}, "burns": burns})


def field_dynamics(degree: int) -> dict:
    """The plan mapping of LP165P of ``degree`` x ``degree`` with the Earth and the Sun."""
    return {"gravity": "LP165P", "degree": int(degree), "third_bodies": ["earth", "sun"]}


def random_plan(rng, index, dynamics="two-body", mass_kg=(400, 1200), formulations=("orbit",),
                burns=(2, 5), degrees=None):
    """A plan drawn from the ranges an analyst might write (may be refused at load).

    ``burns`` (2-5 by default) burns; intermediate ellipses of 2.5-14 h, each asked by its
    period or by its apolune (drawn with equal odds, so both kinds of target are
    exercised); the last a circle or a 100 x 150-600 km ellipse; 20-170 deg; 100-600 N;
    ``mass_kg`` (kg). With more than one ``formulations`` one is drawn per plan, after the
    other draws, so that a family drawn with the default keeps its plans; the paper's
    (``song2011``, Eq. 17 targets) ends on a circle, the only final orbit it can name.
    ``degrees`` (lo, hi): the plan's dynamics is LP165P of a degree drawn in that range
    (:func:`field_dynamics`), drawn last for the same reason; ``dynamics`` is then unused.
    """
    n = int(rng.integers(burns[0], burns[1] + 1))
    periods = np.sort(rng.uniform(2.5, 14.0, n - 1))[::-1]
    asked = []
    for p in periods:
        if rng.random() < 0.5:
            asked.append({"target_period_h": float(round(p, 3)), "start_min": "free"})
        else:   # the apolune of that period's ellipse at 100 km perilune
            a = (C.MU_MOON * (p * 3600 / (2 * math.pi)) ** 2) ** (1 / 3)
            asked.append({"target_apolune_altitude_km": float(round(2 * a - 2 * (C.R_MOON + 100)
                                                                    + 100, 1)),
                          "start_min": "free"})
    last = rng.choice(["circular", "ellipse"])
    asked.append({"target": "circular", "start_min": "free"} if last == "circular" else
                 {"target": {"perilune_altitude_km": 100,
                             "apolune_altitude_km": float(round(rng.uniform(150, 600)))},
                  "start_min": "free"})
    inclination = float(round(rng.uniform(20, 170), 1))
    thrust = float(round(rng.uniform(100, 600)))
    mass = float(round(rng.uniform(*mass_kg)))
    formulation = "orbit"
    if len(formulations) > 1:
        formulation = str(rng.choice(formulations))
        if formulation == "song2011":
            asked[-1] = {"target": "circular", "start_min": "free"}
    if degrees is not None:
        dynamics = field_dynamics(rng.integers(degrees[0], degrees[1] + 1))
    return plan_of(asked, dynamics, inclination=inclination, thrust=thrust, mass=mass,
                   name=f"family-{index}", formulation=formulation)


def plan_family(seed, count, **kwargs) -> tuple[list, list]:
    """(accepted plans, refusals) of ``count`` plans drawn with ``seed``.

    ``kwargs``: :func:`random_plan`'s options. Plan ``k`` is named ``family-k`` whether or
    not those before it were refused, so a name means the same plan at any ``count``.
    """
    rng = np.random.default_rng(seed)
    plans, refused = [], []
    for i in range(count):
        try:
            plans.append(random_plan(rng, i, **kwargs))
        except PlanError as exc:
            refused.append(str(exc))
    return plans, refused
