"""The audit's findings: one verdict type, the tolerance rules, the printed quantities.

A :class:`Finding` compares one number Song et al. (2011) print with the same number
recomputed from others; the rules of its tolerance (rounding, truncation, solver
allowance, print resolution) are described in :mod:`lunarcap.paper.audit`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from lunarcap.paper import printed as P
from lunarcap.physics import constants as C

CONSISTENT = "consistent"
INCONSISTENT = "inconsistent"

#: Relative allowance for the optimiser's discretisation error in relations between two
#: of its outputs (masses, delta-Vs, burn durations); see the module docstring.
SOLVER_REL_TOL = 1e-4

#: One unit of the last printed digit of the paper's burn durations (Tables 1-5), min.
DURATION_RESOLUTION_MIN = 0.01

#: TCB-TDB rate, L_B = 1 - d(TDB)/d(TCB) (IAU 2006 Resolution B3). A gravitational
#: parameter in TCB-compatible units is (1 + L_B) times its TDB-compatible value
#: (IERS Conventions 2010, Sec. 1.2).
L_B = 1.550519768e-8

_G0 = C.G0_MPS2
_THRUSTS = (150, 300, 450)
_LOIS = (1, 2, 3)
_IMP = P.PAPER_IMPULSIVE_DV_MPS


@dataclass(frozen=True)
class Finding:
    """One consistency check of Song 2011.

    Attributes
    ----------
    id : str
        Short unique key, e.g. ``"pct/150N/LOI1/start-10min"``.
    check : str
        Group of checks, "a" to "k" (see :func:`audit_findings`).
    where : str
        Where the checked number is printed (table, section and paragraph, equation).
    quantity : str
        What is compared.
    printed : float
        The number as printed (or a difference of printed numbers), in ``unit``.
    computed : float
        What arithmetic or physics gives from the paper's other numbers, in ``unit``.
    unit : str
        Unit of ``printed``, ``computed``, ``difference`` and ``tolerance``.
    tolerance : float
        Largest ``|printed - computed|`` accepted as rounding (and solver) error.
    rule : str
        ``"abs"`` (``|difference| <= tolerance``) or ``"round-or-truncate"`` (also
        accepted if ``printed`` is ``computed`` truncated to ``resolution``).
    resolution : float
        One unit of the last printed digit, in ``unit``.
    explanation : str
        How the computed value was obtained and what the numbers show.
    extra : dict
        Further computed numbers (implied masses, thrusts, flags).
    """

    id: str
    check: str
    where: str
    quantity: str
    printed: float
    computed: float
    unit: str
    tolerance: float
    explanation: str
    rule: str = "abs"
    resolution: float = 0.0
    extra: dict = field(default_factory=dict, compare=False, hash=False)

    @property
    def difference(self) -> float:
        """``printed - computed``, in ``unit``."""
        return self.printed - self.computed

    @property
    def relative_difference(self) -> float:
        """``(printed - computed) / computed`` (nan if ``computed`` is 0)."""
        return self.difference / self.computed if self.computed else float("nan")

    @property
    def verdict(self) -> str:
        """``"consistent"`` or ``"inconsistent"`` by the tolerance and rule."""
        return CONSISTENT if _accepted(self.printed, self.computed, self.tolerance,
                                       self.rule, self.resolution) else INCONSISTENT

    def to_dict(self) -> dict:
        """The finding as a flat dict (without ``extra``)."""
        return {"id": self.id, "check": self.check, "where": self.where,
                "quantity": self.quantity, "printed": self.printed,
                "computed": self.computed, "difference": self.difference,
                "tolerance": self.tolerance, "unit": self.unit, "verdict": self.verdict,
                "rule": self.rule, "explanation": self.explanation}


def _accepted(printed, computed, tol, rule="abs", resolution=0.0) -> bool:
    """Whether a printed number agrees with its recomputation (see :class:`Finding`)."""
    d = printed - computed
    slack = 1e-12 * max(1.0, abs(computed))
    if abs(d) <= tol + slack:
        return True
    if rule == "round-or-truncate" and computed > 0:
        u = max(tol - resolution / 2, 0.0)  # propagated input uncertainty
        return -(resolution + u) - slack < d <= u + slack
    return False


_ok = _accepted


def _propagate(f, *inputs):
    """Value of f at the inputs and the linear bound of its change.

    Parameters
    ----------
    f : callable
        Function of the input values.
    *inputs : tuple of (value, half_width)
        Each input and the half-width of its rounding interval.

    Returns
    -------
    tuple of float
        ``f(values)`` and ``sum_i |f(x_i + h_i) - f(x_i - h_i)| / 2``.
    """
    vals = [v for v, _ in inputs]
    y = f(*vals)
    bound = 0.0
    for i, (v, h) in enumerate(inputs):
        if h:
            up, dn = list(vals), list(vals)
            up[i], dn[i] = v + h, v - h
            bound += abs(f(*up) - f(*dn)) / 2
    return y, bound


def _half(name: str) -> float:
    return P.quote(name).resolution / 2


def _qv(name: str) -> float:
    return P.quote(name).value


def _where(name: str) -> str:
    return P.quote(name).where


def _rounding_note(printed: float, exact: float, resolution: float) -> str:
    """Say whether ``printed`` is ``exact`` rounded or truncated to ``resolution``."""
    nd = max(0, -int(math.floor(math.log10(resolution) + 1e-9)))
    r = round(exact / resolution) * resolution
    t = math.floor(exact / resolution + 1e-9) * resolution
    if abs(r - printed) < resolution / 10:
        how = "rounded"
    elif abs(t - printed) < resolution / 10:
        how = f"truncated (rounded it would be {r:.{nd}f})"
    else:
        how = f"neither rounded ({r:.{nd}f}) nor truncated ({t:.{nd}f})"
    return f"exact {exact:.{nd + 3}f}; the printed {printed:.{nd}f} is {how}"


