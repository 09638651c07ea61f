r"""Terminal conditions of a burn: the orbit its coast must reach.

Each kind of target is written **once**, over generic operations (numpy or CasADi), as a
function of the modified equinoctial elements at the end of the burn's coast: the NLPs
(:mod:`lunarcap.optim`) impose these residuals as constraints, and the verification
(:mod:`lunarcap.optim.verify`) evaluates the same functions on the re-propagated state,
as physical errors (m, s, deg) through :meth:`Target.errors`.

Three kinds:

``ellipse`` (the orbit as asked: a period, an apolune, or both altitudes)
    The osculating orbit **at the first perilune after the burn** has the target perilune
    radius, apolune radius (equivalently semi-major axis and period) and inclination:

    .. math::

        p - p^{tar} = 0, \qquad f^2 + g^2 - e_{tar}^2 = 0, \qquad
        h^2 + k^2 - \tan^2(i^{tar}/2) = 0, \qquad f \sin L - g \cos L = 0,

    with :math:`p^{tar} = 2 r_p r_a/(r_p + r_a)` and :math:`e_{tar} = (r_a - r_p)/(r_a +
    r_p)`, and the branch inequality :math:`f\cos L + g\sin L \ge 0` (a perilune, not an
    apolune). The epoch of that perilune is free (a decision variable of the NLP, within a
    fifth of the target period of the perilune the plan predicts), so a finite burn that
    shifts the perilune passage still leaves the orbit asked. It is the perilune, not the
    end of the burn, because the perilune radius is only meaningful there and in full
    dynamics the osculating elements vary along the orbit (lunar J2: ~0.1 km in the
    semi-major axis): one physical point keeps every element one orbit, and it is where
    the next burn starts.

``perilune`` (Song et al. 2011, Eq. 17: the paper's formulation)
    At a **fixed** epoch, the next nominal perilune (the perilune before the burn plus the
    target period): perilune radius, inclination and flight-path angle,

    .. math::

        r_p - r_p^{tar} = 0, \qquad h^2 + k^2 - \tan^2(i^{tar}/2) = 0, \qquad
        e\sin\nu = f \sin L - g \cos L = 0,

    with :math:`r_p = p/(1+e)` (Eq. 18a) and :math:`\tan^2(i/2) = h^2 + k^2` (Eq. 18b),
    and the perilune branch as above. The period is imposed only through the timing, so
    a finite burn that shifts the perilune passage leaves an orbit of another period (the
    book's model page). The packaged ``song2011-*`` plans keep this formulation so that
    the paper's numbers are reproduced as the paper defined them; the studies use it with
    a free epoch when the orbit itself is what they optimise (:mod:`lunarcap.optim.joint`).

``circular`` (the final circle)
    The literal Eq. (17) is degenerate for a circle (:math:`\gamma \equiv 0` and the
    perilune undefined). We impose :math:`p = r^{tar}`, :math:`f = g = 0` (so
    :math:`r_p = r_a = r^{tar}`) and the inclination, at the end of the coast after the
    burn.

Length arguments may be in any one unit: the NLPs pass lunar units, the verification km.
The NLP parameter vector of every kind is :meth:`Target.values`: (radius, tan^2(i/2),
apolune radius).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops
from lunarcap.physics.constants import MU_MOON

PERILUNE = "perilune"
CIRCULAR = "circular"
ELLIPSE = "ellipse"
KINDS = (PERILUNE, CIRCULAR, ELLIPSE)

#: Largest inclination a target may have, deg: the modified equinoctial elements are
#: singular at 180 deg (h, k = tan(i/2) (cos, sin) of the node grow without bound); at
#: 175 deg they reach 23, within the transcription's bounds.
MAX_INCLINATION_DEG = 175.0


def perilune_conditions(mee, values):
    """Residuals of Song 2011 Eq. (17)-(18) at a fixed epoch (see the module docstring).

    Parameters
    ----------
    mee : sequence of 6 (p, f, g, h, k, L); p in the unit of the radius, L in rad
    values : (r_target, tan^2(i/2), unused)

    Returns
    -------
    equalities : list of 3 (rp, inc, gamma), each to be 0
    inequalities : list of 1 (branch = e cos nu), to be >= 0
    """
    p, f, g, h, k, L = (mee[i] for i in range(6))
    xp = ops(p, f, g, h, k, L)
    e = xp.sqrt(f * f + g * g)
    sL, cL = xp.sin(L), xp.cos(L)
    return ([p / (1 + e) - values[0], h * h + k * k - values[1], f * sL - g * cL],
            [f * cL + g * sL])


def ellipse_conditions(mee, values):
    """Residuals of an ellipse target at its perilune: p, e^2, inclination, gamma = 0.

    Parameters
    ----------
    mee : sequence of 6 (p, f, g, h, k, L); p in the unit of the radii, L in rad
    values : (r_p target, tan^2(i/2), r_a target)

    Returns
    -------
    equalities : list of 4 (p, e2, inc, gamma), each to be 0
    inequalities : list of 1 (branch = e cos nu), to be >= 0
    """
    p, f, g, h, k, L = (mee[i] for i in range(6))
    xp = ops(p, f, g, h, k, L)
    rp, tan2, ra = values[0], values[1], values[2]
    sL, cL = xp.sin(L), xp.cos(L)
    e_t = (ra - rp) / (ra + rp)
    return ([p - 2 * rp * ra / (rp + ra), f * f + g * g - e_t * e_t, h * h + k * k - tan2,
             f * sL - g * cL], [f * cL + g * sL])


def circular_conditions(mee, values):
    """Residuals of a circular target: p = r, f = g = 0 and the inclination.

    Returns
    -------
    equalities : list of 4 (p, f, g, inc), each to be 0
    inequalities : empty list
    """
    p, f, g, h, k = (mee[i] for i in range(5))
    return [p - values[0], f, g, h * h + k * k - values[1]], []


#: Per kind: the condition function, the names of its equalities and inequalities.
CONDITIONS = {
    PERILUNE: (perilune_conditions, ("rp", "inc", "gamma"), ("branch",)),
    CIRCULAR: (circular_conditions, ("p", "f", "g", "inc"), ()),
    ELLIPSE: (ellipse_conditions, ("p", "e2", "inc", "gamma"), ("branch",)),
}

#: Number of target values every kind takes as an NLP parameter.
N_VALUES = 3


def check_inclination(where: str, inclination_deg) -> float:
    """The inclination (deg) if a target can have it, else InputError naming ``where``."""
    inc = float(inclination_deg)
    if not math.isfinite(inc) or not 0.0 < inc <= MAX_INCLINATION_DEG:
        raise InputError(
            f"{where}: {inclination_deg!r} deg is outside (0, {MAX_INCLINATION_DEG:g}] deg: "
            "the modified equinoctial elements lunarcap integrates are singular at 180 deg "
            "(and an inclination of exactly 0 leaves the node undefined)")
    return inc


@dataclass(frozen=True)
class Target:
    """The orbit a burn's coast must reach, with numeric target values.

    Attributes
    ----------
    kind : {"ellipse", "perilune", "circular"}
    radius_km : float
        Target perilune radius (``ellipse``, ``perilune``) or circle radius, km.
    inclination_deg : float
        Target inclination, deg (0 < i <= 175).
    apolune_radius_km : float or None
        Target apolune radius (``ellipse`` only), km.
    """

    kind: str
    radius_km: float
    inclination_deg: float
    apolune_radius_km: float | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"target kind must be one of {KINDS}, got {self.kind!r}")
        if not np.isfinite(self.radius_km) or self.radius_km <= 0:
            raise InputError(f"target radius must be a positive number of km, "
                             f"got {self.radius_km!r}")
        check_inclination("target inclination", self.inclination_deg)
        if self.kind == ELLIPSE:
            ra = self.apolune_radius_km
            if ra is None or not np.isfinite(ra) or not ra > self.radius_km:
                raise InputError(f"an ellipse target needs an apolune radius above its "
                                 f"perilune radius {self.radius_km:g} km, got {ra!r}")

    @property
    def circular(self) -> bool:
        """True for the circular kind."""
        return self.kind == CIRCULAR

    @property
    def free_epoch(self) -> bool:
        """True if the conditions hold at a perilune of free epoch (the ellipse kind)."""
        return self.kind == ELLIPSE

    @property
    def semi_major_axis_km(self) -> float | None:
        """Semi-major axis of an ellipse target, km (None for the other kinds)."""
        if self.kind != ELLIPSE:
            return None
        return 0.5 * (self.radius_km + self.apolune_radius_km)

    def period_s(self, mu: float = MU_MOON) -> float | None:
        """Kepler period of an ellipse target, s (None for the other kinds)."""
        from lunarcap.physics.elements import period_from_semi_major_axis

        a = self.semi_major_axis_km
        return None if a is None else float(period_from_semi_major_axis(a, mu))

    @property
    def equality_names(self) -> tuple:
        """Names of the equality residuals, in order."""
        return CONDITIONS[self.kind][1]

    @property
    def inequality_names(self) -> tuple:
        """Names of the inequality residuals (each >= 0), in order."""
        return CONDITIONS[self.kind][2]

    def values(self, length_unit_km: float = 1.0) -> np.ndarray:
        """The target values: (radius, tan^2(i/2), apolune radius), lengths in ``length_unit_km``.

        The apolune entry is the radius itself for the kinds that have none (unused).
        """
        ra = self.apolune_radius_km if self.kind == ELLIPSE else self.radius_km
        return np.array([self.radius_km / length_unit_km,
                         np.tan(np.radians(self.inclination_deg) / 2) ** 2,
                         ra / length_unit_km])

    def conditions(self, mee, values):
        """Equality and inequality residuals of ``mee`` (generic ops) for ``values``."""
        return conditions(self.kind, mee, values)

    def errors(self, mee_km, mu: float = MU_MOON) -> dict:
        """Physical errors of a numeric state (p km, f, g, h, k, L rad) against the target.

        Returns
        -------
        dict
            ``rp_error_m`` (perilune radius minus target, m), ``ra_error_m`` (apolune
            radius minus target, m; ellipse and circle, else None), ``period_error_s``
            (osculating Kepler period minus the target's, s; ellipse only, else None),
            ``inc_error_deg``, ``gamma_error_deg`` (flight-path angle at the end, deg;
            None for a circle), ``branch`` (e cos nu; >= 0 at a perilune; None for a
            circle), ``residuals`` (name -> value).
        """
        from lunarcap.physics.elements import orbit_summary

        vals = self.values()
        x = np.array([float(v) for v in mee_km[:6]])
        eq, ineq = self.conditions(x, vals)
        res = dict(zip(self.equality_names + self.inequality_names, map(float, eq + ineq)))
        o = orbit_summary(np.append(x, 1.0), mu)
        inc = o["inc_deg"]
        e = float(np.hypot(x[1], x[2]))
        out = {"inc_error_deg": float(inc - self.inclination_deg), "residuals": res,
               "rp_error_m": (x[0] / (1 + e) - self.radius_km) * 1e3, "ra_error_m": None,
               "period_error_s": None, "gamma_error_deg": None, "branch": None}
        if self.kind in (CIRCULAR, ELLIPSE):
            ra = x[0] / (1 - e) if e < 1 else float("inf")
            out["ra_error_m"] = (ra - vals[2]) * 1e3
        if self.kind == ELLIPSE:
            from lunarcap.physics.elements import period_from_semi_major_axis

            a = x[0] / (1 - e * e) if e < 1 else float("inf")
            out["period_error_s"] = (float(period_from_semi_major_axis(a, mu)) - self.period_s(mu)
                                     if math.isfinite(a) else float("inf"))
        if self.kind != CIRCULAR:
            out.update(gamma_error_deg=float(np.degrees(np.arctan2(res["gamma"],
                                                                   1 + res["branch"]))),
                       branch=res["branch"])
        return out


def conditions(kind: str, mee, values):
    """Residuals of target ``kind`` at ``mee`` for ``values`` (see :meth:`Target.values`).

    The one definition used by the NLPs and the verification (generic over numpy floats
    and CasADi symbols). Returns ``(equalities, inequalities)`` as lists.
    """
    if kind not in CONDITIONS:
        raise InputError(f"target kind must be one of {KINDS}, got {kind!r}")
    return CONDITIONS[kind][0](mee, values)
