"""Array-namespace dispatch so one formula serves numpy and CasADi symbols.

A function written with ``xp = ops(x)`` and ``xp.sin``, ``xp.sqrt``, ``xp.atan2`` ...
evaluates on numpy arrays (vectorised over nodes) and builds CasADi expressions
(SX/MX/DM) from the same source. This is how each equation is written once.
"""

from __future__ import annotations

import types

import casadi as ca
import numpy as np

_CASADI_TYPES = (ca.SX, ca.MX, ca.DM)

NP = types.SimpleNamespace(
    sin=np.sin, cos=np.cos, sqrt=np.sqrt, atan2=np.arctan2, arctan=np.arctan,
    arcsin=np.arcsin, log=np.log, exp=np.exp, fabs=np.abs, casadi=False)

CA = types.SimpleNamespace(
    sin=ca.sin, cos=ca.cos, sqrt=ca.sqrt, atan2=ca.atan2, arctan=ca.atan,
    arcsin=ca.asin, log=ca.log, exp=ca.exp, fabs=ca.fabs, casadi=True)


def ops(*xs):
    """Return the CasADi namespace if any argument is a CasADi type, else numpy's."""
    for x in xs:
        if isinstance(x, _CASADI_TYPES):
            return CA
    return NP
