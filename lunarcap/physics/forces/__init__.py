"""The forces on the spacecraft, as terms composed per plan (Song 2011 Eqs. 4, 6, 7, and more).

A :class:`ForceModel` says which terms act besides the Moon's central attraction (which
the MEE equations carry in their Kepler part, Eq. A3) and the thrust. One module per term:

:mod:`~lunarcap.physics.forces.point`
    ``gravity: point``: nothing more.
:mod:`~lunarcap.physics.forces.zonal_j2`
    ``gravity: j2, pole: frame``: the paper's J2 about the z axis of the plan's frame (Eq. 7).
:mod:`~lunarcap.physics.forces.body_pole`
    ``gravity: j2, pole: of-date``: J2 about the IAU pole of date (and a field's C20).
:mod:`~lunarcap.physics.forces.harmonics`
    ``gravity: LP165P`` (or a file), ``degree``, ``order``, ``body_frame``: a
    spherical-harmonic field.
:mod:`~lunarcap.physics.forces.third_body`
    ``third_bodies``: the Earth's and the Sun's point masses (Eq. 6).

Each owns its plan keys, its parameters and their values, its RTN acceleration (written once
over numpy and CasADi), its label words and what an exporter needs of it
(:class:`~lunarcap.physics.forces.term.Term`); :mod:`~lunarcap.physics.forces.registry`
registers them in :data:`TERMS`, in summation order. :func:`perturbation_rtn` sums a
model's terms; :mod:`lunarcap.physics.dynamics` turns the sum into element rates.

Adding a force is one module with a :class:`Term` and one :func:`register` call.
"""

from lunarcap.physics.forces.model import (
    N_BASE,
    P_MU,
    P_THRUST,
    P_VEX,
    PRESETS,
    ForceModel,
    force_model,
    from_mapping,
    perturbation_rtn,
    plan_keys,
)
from lunarcap.physics.forces.point import POINT
from lunarcap.physics.forces.term import (
    TERMS,
    At,
    MoonField,
    Term,
    ThirdBody,
    register,
    rtn_from_mee,
    zonal_c20,
)
from lunarcap.physics.forces.third_body import THIRD_BODIES
from lunarcap.physics.forces.zonal_j2 import J2, POLES

__all__ = ["J2", "N_BASE", "P_MU", "P_THRUST", "P_VEX", "POINT", "POLES", "PRESETS", "TERMS",
           "THIRD_BODIES", "At", "ForceModel", "MoonField", "Term", "ThirdBody", "force_model",
           "from_mapping", "perturbation_rtn", "plan_keys", "register", "rtn_from_mee",
           "zonal_c20"]
