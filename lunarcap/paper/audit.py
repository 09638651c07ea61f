"""Internal consistency of Song et al. (2011), recomputed from the printed numbers.

Song, Park, Kim, Lee & Sim (2011), J. Astron. Space Sci. 28(3) 203-216 ("Song 2011").
Every finding takes the numbers of :mod:`lunarcap.paper.printed` as printed, recomputes one of
them from the others (arithmetic, the rocket equation, Eq. (19), the two-body period,
the epochs) and compares. Nothing is concluded by hand: each verdict is
``|printed - computed| <= tolerance`` and each explanation is formatted from computed
numbers.

Tolerances
----------
* **Rounding.** Half a unit of the last printed digit of the checked number, plus the
  linear propagation of half a unit of the last digit of every printed input
  (:func:`_propagate`).
* **Truncation.** The paper sometimes truncates instead of rounding (e.g. Table 1,
  -12 min: 4.3188 % printed 4.31). Percentages and "about" restatements of printed
  numbers are therefore also accepted when they equal the exact value truncated to the
  printed digits (``rule="round-or-truncate"``); the explanation says which applied.
* **Solver.** Relations between two outputs of the optimiser (a mass and a delta-V, a
  burn duration and a delta-V) hold exactly for the continuous problem: with constant
  thrust T and mass flow T/(g0 Isp), the finite-burn delta-V of Eq. (11) integrates to
  the rocket equation, dV = g0 Isp ln(m0/mf), and the burn lasts (m0 - mf) g0 Isp / T.
  The paper does not state SOCS's tolerances; :data:`SOLVER_REL_TOL` (1e-4 of the
  computed value) is allowed on top of rounding for these relations.
* **Print resolution of a compared duration.** A table row's burn duration is compared
  with the one recomputed from the same row's delta-V and stated at the printed
  resolution (0.01 min). Two durations each known only to the printed digit cannot
  contradict each other by less than one unit of it, so the rows allow half a unit for
  each (:data:`DURATION_RESOLUTION_MIN`), on top of the propagated rounding of the row's
  delta-V and start mass and the solver allowance.

g0 = 9.80665 m/s^2 (:data:`lunarcap.physics.constants.G0_MPS2`).

Examples
--------
>>> t = findings_table()
>>> bool((t.verdict == "inconsistent").any())
True
>>> f = {x.id: x for x in audit_findings()}["sun-gm"]
>>> round(f.computed / f.printed, 6)
10.0
"""

from __future__ import annotations

import pandas as pd

from lunarcap.paper.checks_masses import _check_a, _check_b, _check_c, _check_d, _check_e
from lunarcap.paper.checks_timing import _check_f, _check_g, _check_h, _check_i, _check_j, _check_k
from lunarcap.paper.finding import (
    CONSISTENT,
    INCONSISTENT,
    L_B,
    SOLVER_REL_TOL,
    Finding,
)
from lunarcap.paper.recompute import fuel_sentence_check, implied_arrival_mass_kg

__all__ = [
    "CONSISTENT",
    "INCONSISTENT",
    "L_B",
    "SOLVER_REL_TOL",
    "Finding",
    "audit_findings",
    "findings_table",
    "fuel_sentence_check",
    "implied_arrival_mass_kg",
]

_CHECKS = (_check_a, _check_b, _check_c, _check_d, _check_e, _check_f, _check_g, _check_h,
           _check_i, _check_j, _check_k)


#: Titles of the audit's groups of checks (:func:`lunarcap.paper.audit.audit_findings`).
AUDIT_CHECK_TITLES = {
    "a": "constants of Sec. 3.1",
    "b": "the 'difference %' of Tables 1-5 and B1",
    "c": "masses, propellant and burn durations vs the rocket equation",
    "d": "the fuel-mass sentences of Sec. 3.2",
    "e": "delta-V losses and their percentages",
    "f": "burn-duration totals",
    "g": "the period of the 100 km circular orbit",
    "h": "the perilune epochs vs the periods",
    "i": "Eq. (19) and its estimates",
    "j": "half the Eq. (19) duration vs the best ignition time",
    "k": "other checks (Fig. 4, two-body impulsive delta-Vs)",
}


def audit_findings() -> list[Finding]:
    """All consistency checks of Song 2011.

    Groups (``Finding.check``):

    * a -- constants of Sec. 3.1 (the Sun's gravitational parameter);
    * b -- the "difference %" of every row of Tables 1-5, and the best rows vs Table B1;
    * c -- masses vs the rocket equation, the arrival mass the results imply, propellant
      vs burn durations, every row's burn duration vs its delta-V, Table 4's LOI-1 thrust;
    * d -- the fuel-mass sentences of Sec. 3.2.1-3.2.2;
    * e -- delta-V losses and their percentages;
    * f -- burn-duration totals;
    * g -- the 100 km circular orbit's period;
    * h -- the perilune epochs vs the periods (and vs Sec. 2.2's t2 = tp - t1);
    * i -- Eq. (19) (its typo, and which masses reproduce the printed estimates);
    * j -- half the Eq. (19) duration vs the best ignition offset;
    * k -- other checks (Fig. 4, the two-body impulsive delta-Vs).

    Returns
    -------
    list of Finding
    """
    out = []
    for check in _CHECKS:
        out.extend(check())
    ids = [f.id for f in out]
    if len(ids) != len(set(ids)):  # pragma: no cover - guards the ids' uniqueness
        raise RuntimeError("duplicate finding ids")
    return out


def findings_table(only_inconsistent: bool = False) -> pd.DataFrame:
    """The findings of :func:`audit_findings` as a table.

    Parameters
    ----------
    only_inconsistent : bool
        Keep only the findings whose verdict is "inconsistent".

    Returns
    -------
    pandas.DataFrame
        Columns ``id``, ``check``, ``where``, ``quantity``, ``printed``, ``computed``,
        ``difference`` (printed - computed), ``tolerance``, ``unit``, ``verdict``,
        ``rule`` and ``explanation``.
    """
    df = pd.DataFrame([f.to_dict() for f in audit_findings()])
    if only_inconsistent:
        df = df[df.verdict == INCONSISTENT].reset_index(drop=True)
    return df

