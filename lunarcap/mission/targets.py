r"""Terminal conditions of a burn: the orbit its coast must reach (Song 2011, Eqs. 17-18).

Each kind of target is written **once**, over generic operations (numpy or CasADi), as a
function of the modified equinoctial elements at the end of the coast. The single-burn
NLP and the all-burns NLP (:mod:`lunarcap.optim`) impose these residuals as constraints,
and the verification (:mod:`lunarcap.optim.verify`) evaluates the very same functions on
the re-propagated state and turns them into physical errors (m, deg) with
:meth:`Target.errors`.

Two kinds:

``perilune`` (an intermediate ellipse, LOI 1 and 2 of the paper)
    Eq. (17) at the end of the coast: perilune radius, inclination and flight-path angle,

    .. math::

        r_p - r_p^{tar} = 0, \qquad h^2 + k^2 - \tan^2(i^{tar}/2) = 0, \qquad
        e\sin\nu = f \sin L - g \cos L = 0,

    with :math:`r_p = p/(1+e)` (Eq. 18a) and :math:`\tan^2(i/2) = h^2 + k^2` (Eq. 18b;
    squared so that no square root appears in the constraint). :math:`\gamma = 0`
    (Eq. 17c) holds where :math:`e \sin\nu = 0`, at perilune *and* at apolune; the
    inequality :math:`e\cos\nu = f\cos L + g\sin L \ge 0` keeps the perilune branch.

``circular`` (the final orbit, LOI 3 of the paper)
    The literal Eq. (17) is degenerate for a circle (:math:`\gamma \equiv 0` and the
    perilune undefined). We impose :math:`p = r^{tar}`, :math:`f = g = 0` (so
    :math:`r_p = r_a = r^{tar}`) and the inclination as above.

Length arguments (``p`` and the target radius) may be in any one unit: the NLPs pass
lunar units, the verification kilometres.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops

PERILUNE = "perilune"
CIRCULAR = "circular"
KINDS = (PERILUNE, CIRCULAR)


def perilune_conditions(mee, r_target, tan2_inc):
    """Residuals of an intermediate-orbit target, Eqs. (17)-(18) (see the module docstring).

    Parameters
    ----------
    mee : sequence of 6 (p, f, g, h, k, L); p in the unit of ``r_target``, L in rad
    r_target : target perilune radius (same length unit as p)
    tan2_inc : tan^2 of half the target inclination

    Returns
    -------
    equalities : list of 3 (rp, inc, gamma), each to be 0
    inequalities : list of 1 (branch = e cos nu), to be >= 0
    """
    p, f, g, h, k, L = (mee[i] for i in range(6))
    xp = ops(p, f, g, h, k, L)
    e = xp.sqrt(f * f + g * g)
    sL, cL = xp.sin(L), xp.cos(L)
    return ([p / (1 + e) - r_target, h * h + k * k - tan2_inc, f * sL - g * cL],
            [f * cL + g * sL])


def circular_conditions(mee, r_target, tan2_inc):
    """Residuals of a circular target: p = r, f = g = 0 and the inclination.

    Returns
    -------
    equalities : list of 4 (p, f, g, inc), each to be 0
    inequalities : empty list
    """
    p, f, g, h, k = (mee[i] for i in range(5))
    return [p - r_target, f, g, h * h + k * k - tan2_inc], []


#: Per kind: the condition function, the names of its equalities and inequalities.
CONDITIONS = {
    PERILUNE: (perilune_conditions, ("rp", "inc", "gamma"), ("branch",)),
    CIRCULAR: (circular_conditions, ("p", "f", "g", "inc"), ()),
}


@dataclass(frozen=True)
class Target:
    """The orbit a burn's coast must reach, with numeric target values.

    Attributes
    ----------
    kind : {"perilune", "circular"}
    radius_km : float
        Target perilune radius (``perilune``) or circle radius (``circular``), km.
    inclination_deg : float
        Target inclination, deg (0 < i < 180).
    """

    kind: str
    radius_km: float
    inclination_deg: float

    def __post_init__(self):
        if self.kind not in KINDS:
            raise InputError(f"target kind must be one of {KINDS}, got {self.kind!r}")
        if not np.isfinite(self.radius_km) or self.radius_km <= 0:
            raise InputError(f"target radius must be a positive number of km, "
                             f"got {self.radius_km!r}")
        if not 0.0 < self.inclination_deg < 180.0:
            raise InputError(f"target inclination must lie strictly between 0 and 180 deg, "
                             f"got {self.inclination_deg!r}")

    @property
    def circular(self) -> bool:
        """True for the circular kind."""
        return self.kind == CIRCULAR

    @property
    def equality_names(self) -> tuple:
        """Names of the equality residuals, in order."""
        return CONDITIONS[self.kind][1]

    @property
    def inequality_names(self) -> tuple:
        """Names of the inequality residuals (each >= 0), in order."""
        return CONDITIONS[self.kind][2]

    def values(self, length_unit_km: float = 1.0) -> np.ndarray:
        """The two numeric target values (radius in ``length_unit_km``, tan^2(i/2))."""
        return np.array([self.radius_km / length_unit_km,
                         np.tan(np.radians(self.inclination_deg) / 2) ** 2])

    def conditions(self, mee, values):
        """Equality and inequality residuals of ``mee`` (generic ops) for ``values``.

        ``values`` are those of :meth:`values` (numbers or CasADi parameters) in the length
        unit of ``mee``'s p.
        """
        return conditions(self.kind, mee, values)

    def errors(self, mee_km) -> dict:
        """Physical errors of a numeric state from the residuals of :meth:`conditions`.

        Parameters
        ----------
        mee_km : sequence of 6 (p km, f, g, h, k, L rad)

        Returns
        -------
        dict
            ``rp_error_m`` (perilune radius minus target, m), ``ra_error_m`` (apolune
            radius minus target, m; circular only, else None), ``inc_error_deg``,
            ``gamma_error_deg`` (flight-path angle at the end, deg; None for a circle,
            where it is not a condition), ``branch`` (e cos nu; must be >= 0 for a
            perilune target, None for a circle), ``residuals`` (name -> value).
        """
        r, tan2 = self.values()
        eq, ineq = self.conditions([float(v) for v in mee_km[:6]], (r, tan2))
        res = dict(zip(self.equality_names + self.inequality_names, map(float, eq + ineq)))
        inc = np.degrees(2 * np.arctan(np.sqrt(max(tan2 + res["inc"], 0.0))))
        out = {"inc_error_deg": float(inc - self.inclination_deg), "residuals": res}
        if self.circular:
            p = r + res["p"]
            e = float(np.hypot(res["f"], res["g"]))
            out.update(rp_error_m=(p / (1 + e) - r) * 1e3,
                       ra_error_m=(p / (1 - e) - r) * 1e3 if e < 1 else float("inf"),
                       gamma_error_deg=None, branch=None)
        else:
            out.update(rp_error_m=res["rp"] * 1e3, ra_error_m=None,
                       gamma_error_deg=float(np.degrees(np.arctan2(res["gamma"],
                                                                   1 + res["branch"]))),
                       branch=res["branch"])
        return out


def conditions(kind: str, mee, values):
    """Residuals of target ``kind`` at ``mee`` for ``values = (r_target, tan^2(i/2))``.

    The one definition used by the NLPs and the verification (generic over numpy floats
    and CasADi symbols). Returns ``(equalities, inequalities)`` as lists.
    """
    if kind not in CONDITIONS:
        raise InputError(f"target kind must be one of {KINDS}, got {kind!r}")
    return CONDITIONS[kind][0](mee, values[0], values[1])
