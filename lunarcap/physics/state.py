"""A spacecraft's state at an epoch, by name: the epoch, the MEE, the mass.

Everywhere else a state is the array (p, f, g, h, k, L, m) that the dynamics, the
propagator and the collocation share (:data:`lunarcap.physics.propagate.N_X` = 7);
:class:`State` names its parts where one is read, so that ``state.mass_kg`` is written
instead of an index into the array, and ``state.mee`` for the elements.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Index of the mass in a state array (p, f, g, h, k, L, m).
MASS = 6
#: The modified equinoctial elements of a state array.
MEE = slice(0, 6)


@dataclass(frozen=True)
class State:
    """A state at an epoch.

    Attributes
    ----------
    t_s : float
        Epoch, TDB s past J2000.
    x : ndarray, shape (7,)
        p km, f, g, h, k, L rad (M-MME2000), m kg.
    """

    t_s: float
    x: np.ndarray

    @property
    def mee(self) -> np.ndarray:
        """(p km, f, g, h, k, L rad)."""
        return self.x[MEE]

    @property
    def mass_kg(self) -> float:
        """Mass, kg."""
        return float(self.x[MASS])

    @property
    def eccentricity(self) -> float:
        """Osculating eccentricity, hypot(f, g)."""
        return float(np.hypot(self.x[1], self.x[2]))
