"""The Earth's and the Sun's point-mass attraction, Song 2011 Eq. (6) (``third_bodies``).

Their positions come from the plan's ephemeris through the Chebyshev fit the model carries
(:class:`lunarcap.physics.ephemeris.ChebyshevFit`); each body's acceleration relative to
the Moon is projected on RTN (Eq. A5).
"""

from __future__ import annotations

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops
from lunarcap.physics.forces.term import Term, ThirdBody

#: The bodies a plan may name, in the order of the ephemeris fit (its Earth, its Sun).
THIRD_BODIES = ("earth", "sun")


def third_body_accel(r, rj, muj):
    """Point-mass third-body acceleration on the spacecraft, km/s^2, Eq. (6).

    a = mu_j [ (r_j - r)/|r_j - r|^3 - r_j/|r_j|^3 ], with r the spacecraft and r_j
    the body relative to the Moon (component tuples or arrays).
    """
    xp = ops(*r, *rj)
    d = [rj[i] - r[i] for i in range(3)]
    dn = xp.sqrt(d[0] ** 2 + d[1] ** 2 + d[2] ** 2)
    rn = xp.sqrt(rj[0] ** 2 + rj[1] ** 2 + rj[2] ** 2)
    return tuple(muj * (d[i] / dn ** 3 - rj[i] / rn ** 3) for i in range(3))


def third_body_rtn(r, rtn, rj, muj):
    """Point-mass third-body acceleration in RTN, km/s^2: Eq. (6) rotated by Eq. (A5).

    The acceleration of :func:`third_body_accel` projected on the RTN unit vectors
    ``rtn = (i_r, i_t, i_n)`` of a spacecraft at distance ``r`` (position r i_r), written
    with the body's RTN components (c_r, c_t, c_n) = (i_r.r_j, i_t.r_j, i_n.r_j):
    |r_j - r|^2 = |r_j|^2 - 2 r c_r + r^2, and

        a = mu_j [ (c - r e_r)/|r_j - r|^3 - c/|r_j|^3 ].

    The same quantity as ``dot(i, third_body_accel(r i_r, r_j, mu_j))``, in fewer
    operations (no Cartesian spacecraft position, three dot products instead of nine).
    """
    xp = ops(r, *rj)
    c = [a[0] * rj[0] + a[1] * rj[1] + a[2] * rj[2] for a in rtn]
    rj2 = rj[0] ** 2 + rj[1] ** 2 + rj[2] ** 2
    d2 = rj2 - 2 * r * c[0] + r * r
    kd = muj / (d2 * xp.sqrt(d2))
    kj = muj / (rj2 * xp.sqrt(rj2))
    return ((kd - kj) * c[0] - kd * r, (kd - kj) * c[1], (kd - kj) * c[2])


class PointMass:
    """One body's point-mass attraction in RTN, Eq. (6) rotated by Eq. (A5)."""

    def __init__(self, body: str):
        self.body = body
        self.params = (f"mu_{body}",)

    def rtn(self, at):
        """Acceleration (a_r, a_t, a_n), km/s^2."""
        rj = at.earth_sun[THIRD_BODIES.index(self.body)]
        return third_body_rtn(at.r, at.rtn, rj, at.prm_of(f"mu_{self.body}"))


class ThirdBodies(Term):
    """The Earth and/or the Sun as point masses (the plan key ``third_bodies``)."""

    name = "third-bodies"
    keys = ("third_bodies",)
    ephemeris = True

    def read(self, d: dict, gravity: str, base_dir=None) -> dict:
        """``third_bodies``: a list (default both)."""
        bodies = d.get("third_bodies", list(THIRD_BODIES))
        if not isinstance(bodies, (list, tuple)):
            raise InputError(f"dynamics.third_bodies: a list (earth, sun or both), got "
                             f"{bodies!r}")
        return {"third_bodies": tuple(bodies)}

    def check(self, forces) -> None:
        """Distinct names among :data:`THIRD_BODIES`."""
        b = forces.third_bodies
        if any(x not in THIRD_BODIES for x in b) or len(set(b)) != len(b):
            raise InputError(f"dynamics.third_bodies: a list of distinct names among "
                             f"{', '.join(THIRD_BODIES)}, got {list(b)}")

    def acts(self, forces) -> bool:
        """True if the model names a body."""
        return bool(forces.third_bodies)

    def accelerations(self, forces) -> tuple:
        """One point mass per body, the Earth's first."""
        return tuple(PointMass(b) for b in THIRD_BODIES if b in forces.third_bodies)

    def values(self, forces, model) -> dict:
        """The bodies' GMs, km^3/s^2, from the model."""
        return {"mu_earth": model.mu_earth, "mu_sun": model.mu_sun}

    def words(self, forces) -> str:
        """"Earth, Sun"."""
        return ", ".join(b.capitalize() for b in forces.third_bodies)

    def to_plan(self, forces) -> dict:
        """``third_bodies`` (written even when empty: the default is both)."""
        return {"third_bodies": list(forces.third_bodies)}

    def export(self, forces, model, pole: str):
        """Each body's point mass (its DE405 position), Earth first."""
        mu = {"earth": model.mu_earth, "sun": model.mu_sun}
        return tuple(ThirdBody(b.capitalize(), mu[b]) for b in THIRD_BODIES
                     if b in forces.third_bodies)
