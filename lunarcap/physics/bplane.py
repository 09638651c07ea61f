"""The B-plane of a hyperbolic approach, and the perilune state of a B-plane target.

The B-plane (Kizner 1961; the form of Vallado, *Fundamentals of Astrodynamics and
Applications*, 4th ed., Sec. 12.5) is the plane through the body's centre perpendicular
to the incoming asymptote of the osculating two-body hyperbola:

* ``S``: the unit vector along the incoming asymptote, the direction of the approach
  velocity at infinity: S = (1/e) e_hat + sqrt(1 - 1/e^2) (h_hat x e_hat), with e_hat
  the eccentricity (periapsis) direction and h_hat the orbit normal;
* ``T = S x k / |S x k|`` with ``k`` the pole of the reference plane (the frame's third
  axis unless another is given), ``R = S x T``: T lies in the reference plane, and for
  an asymptote along +x with k along +z, T is -y and R is -z;
* the miss vector ``B`` from the centre to the asymptote, perpendicular to it, in the
  orbit plane: B = b (S x h_hat), b = h / v_inf = |a| sqrt(e^2 - 1);
* the target: ``B . R``, ``B . T`` (km), v_inf (km/s) and the epoch of closest approach
  (perilune).

Given S, v_inf and (B.R, B.T) the hyperbola is fixed: h_hat = B_hat x S,
e = sqrt(1 + b^2 v_inf^4 / mu^2), e_hat = (1/e) S + sqrt(1 - 1/e^2) B_hat, and the
perilune is r_p = |a| (e - 1) along e_hat with speed sqrt(v_inf^2 + 2 mu / r_p) along
h_hat x e_hat. Pure functions of arrays; ``mu`` is passed explicitly.

**The reference plane** (:data:`REFERENCE_PLANES`, :func:`reference_pole`) is data: a
B-plane target or covariance handed over by a navigation or trajectory team is, by
convention, referenced to the Earth's mean equator of J2000 (``EME2000``: k the pole of
lunarcap's ICRF axes, which GMAT reads as its ``MJ2000Eq``; GMAT's ``BdotT`` and
``BdotR`` of a state in a Moon-centred ``MJ2000Eq`` coordinate system are these, since
GMAT computes its B-plane in the axes of the parameter's coordinate system with
T = (S_y, -S_x, 0) / |...|, i.e. S x z: GMAT User Guide, "Calculation Parameters", and
``GmatCalcUtil::CalculateBPlaneData`` in GMAT's source), and lunarcap's default is that
one. ``lunar-equator`` (k the plan's lunar pole, the z axis of its M-MME2000) is on
request: for the paper's asymptote the two T axes are 24 deg apart, so a covariance
long in T and short in R given in one and read in the other mixes the two.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError

#: The reference pole of the B-plane's T axis by default: the frame's third axis.
Z_AXIS = (0.0, 0.0, 1.0)
#: The reference planes a B-plane may be given in (see the module docstring), the default
#: first: the Earth's mean equator of J2000, and the lunar equator of the plan's M-MME2000.
REFERENCE_PLANES = ("EME2000", "lunar-equator")
DEFAULT_REFERENCE = REFERENCE_PLANES[0]
#: Axes a B-plane's vectors may be written in (their pole is expressed in them).
AXES = ("ICRF", "M-MME2000")


def check_reference(reference, where: str = "bplane_reference") -> str:
    """``reference`` if it is one of :data:`REFERENCE_PLANES`; else InputError naming ``where``."""
    if reference not in REFERENCE_PLANES:
        raise InputError(f"{where} must be one of {', '.join(REFERENCE_PLANES)} (the plane "
                         f"the B-plane's T axis lies in: the Earth's mean equator of J2000, "
                         f"as GMAT's BdotT/BdotR, or the lunar equator), got {reference!r}")
    return reference


def reference_pole(reference: str, axes: str, lunar_pole: str) -> np.ndarray:
    """The unit pole k of a reference plane (:data:`REFERENCE_PLANES`), in ``axes``.

    ``axes``: ``"ICRF"`` (Moon-centred ICRF, lunarcap's files; GMAT's MJ2000Eq) or
    ``"M-MME2000"`` of the lunar pole choice ``lunar_pole``
    (:data:`lunarcap.physics.frames.LUNAR_POLES`). EME2000's pole is ICRF's z axis;
    the lunar equator's is M-MME2000's z axis.
    """
    from lunarcap.physics.frames import icrf_from_mme, mme_from_icrf

    check_reference(reference)
    if axes not in AXES:
        raise InputError(f"B-plane axes must be one of {', '.join(AXES)}, got {axes!r}")
    z = np.array(Z_AXIS)
    if (reference == "EME2000") == (axes == "ICRF"):
        return z
    k = mme_from_icrf(z, lunar_pole) if axes == "M-MME2000" else icrf_from_mme(z, lunar_pole)
    return k / np.linalg.norm(k)


@dataclass(frozen=True)
class BPlane:
    """A hyperbolic approach in B-plane form (km, km/s; axes in the states' frame).

    Attributes
    ----------
    b_r_km, b_t_km : float
        Components of the miss vector B along R and T, km.
    v_inf_kmps : float
        Hyperbolic excess speed, km/s.
    s_hat : ndarray, shape (3,)
        Incoming asymptote (the approach velocity's direction at infinity), unit.
    t_hat, r_hat : ndarray, shape (3,)
        The B-plane's axes: T = S x k / |S x k|, R = S x T.
    """

    b_r_km: float
    b_t_km: float
    v_inf_kmps: float
    s_hat: np.ndarray
    t_hat: np.ndarray
    r_hat: np.ndarray

    @property
    def b_km(self) -> float:
        """|B|, km: the impact parameter."""
        return float(np.hypot(self.b_r_km, self.b_t_km))


def bplane_axes(s_hat, pole=Z_AXIS) -> tuple:
    """(T, R) unit axes of the B-plane of the asymptote ``s_hat`` about ``pole``.

    InputError if the asymptote lies along the pole (T undefined).
    """
    s = np.asarray(s_hat, float)
    s = s / np.linalg.norm(s)
    t = np.cross(s, np.asarray(pole, float))
    n = np.linalg.norm(t)
    if n < 1e-9:
        raise InputError("the approach asymptote lies along the B-plane's reference pole: "
                         "its T axis is undefined")
    t = t / n
    return t, np.cross(s, t)


def bplane_from_rv(r, v, mu: float, pole=Z_AXIS) -> BPlane:
    """The B-plane of the osculating hyperbola of the state (r km, v km/s).

    InputError if the orbit is not hyperbolic.
    """
    r, v = np.asarray(r, float), np.asarray(v, float)
    rn = float(np.linalg.norm(r))
    vinf2 = float(v @ v) - 2 * mu / rn
    if not vinf2 > 0:
        raise InputError(f"the state is not on a hyperbola (v^2 - 2 mu/r = {vinf2:.4g} "
                         f"km^2/s^2): it has no B-plane")
    h = np.cross(r, v)
    h_hat = h / np.linalg.norm(h)
    e_vec = np.cross(v, h) / mu - r / rn
    e = float(np.linalg.norm(e_vec))
    e_hat = e_vec / e
    s_hat = e_hat / e + np.sqrt(1 - 1 / e ** 2) * np.cross(h_hat, e_hat)
    b = float(np.linalg.norm(h)) / np.sqrt(vinf2)
    b_vec = b * np.cross(s_hat, h_hat)
    t_hat, r_hat = bplane_axes(s_hat, pole)
    return BPlane(float(b_vec @ r_hat), float(b_vec @ t_hat), float(np.sqrt(vinf2)), s_hat,
                  t_hat, r_hat)


def perilune_from_bplane(b_r_km: float, b_t_km: float, v_inf_kmps: float, s_hat, mu: float,
                         pole=Z_AXIS) -> tuple:
    """(r km, v km/s): the perilune (periapsis) state of a B-plane target.

    InputError for a non-positive v_inf or a zero miss vector (a radial fall: no plane).
    """
    if not v_inf_kmps > 0:
        raise InputError(f"v_inf must be positive (km/s), got {v_inf_kmps}")
    s = np.asarray(s_hat, float)
    s = s / np.linalg.norm(s)
    t_hat, r_hat = bplane_axes(s, pole)
    b_vec = b_r_km * r_hat + b_t_km * t_hat
    b = float(np.linalg.norm(b_vec))
    if b == 0.0:
        raise InputError("B . R = B . T = 0: a radial fall onto the centre has no orbit plane")
    b_hat = b_vec / b
    h_hat = np.cross(b_hat, s)
    e = float(np.sqrt(1 + (b * v_inf_kmps ** 2 / mu) ** 2))
    e_hat = s / e + np.sqrt(1 - 1 / e ** 2) * b_hat
    rp = mu / v_inf_kmps ** 2 * (e - 1)
    vp = float(np.sqrt(v_inf_kmps ** 2 + 2 * mu / rp))
    return rp * e_hat, vp * np.cross(h_hat, e_hat)
