"""Earth and Sun positions relative to the Moon, in M-MME2000, from a JPL ephemeris.

The default source is JPL DE405 (Standish 1998) as shipped by the PyPI package
``de405`` and read with jplephem's :class:`jplephem.ephem.Ephemeris`: nothing is
downloaded. Any SPK kernel (``.bsp``: DE405, DE430, DE440, ...) holding the Sun,
the Earth-Moon barycentre, the Earth and the Moon may be named instead.

It also gives the Moon's orientation: the DE405 libration angles (the Euler angles of
the lunar principal-axis frame of DE405, the body-fixed frame GMAT's ``Luna`` uses, read
from the ``de405`` package whatever SPK gives the positions) or the IAU (2009) rotation
model (:func:`lunarcap.physics.frames.iau_moon_euler_rad`).

This is the only module that imports jplephem. For the optimiser, :class:`ChebyshevFit`
fits both vectors (and, when a force needs it, the three Euler angles of the Moon's
body-fixed frame) over a mission window with Chebyshev series whose evaluation is
written over generic operations, so it can be called inside CasADi expressions.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lunarcap.errors import EphemerisRangeError, InputError
from lunarcap.physics.epochs import calendar_from_seconds, jd_split_from_seconds, seconds_from_jd
from lunarcap.physics.frames import (
    DEFAULT_LUNAR_POLE,
    check_lunar_pole,
    iau_moon_euler_rad,
    icrf_to_mme,
    rotation_313,
)

__all__ = ["Ephemeris", "ChebyshevFit", "default_ephemeris", "chebyshev_eval",
           "BODY_FRAMES"]

#: Sources of the Moon's body-fixed frame: the DE405 libration angles (principal axes) or
#: the IAU (2009) rotation model (mean Earth / polar axis approximation).
BODY_FRAMES = ("de405", "iau2009")

_KM_PER_DAY_TO_KMPS = 1.0 / 86400.0


class Ephemeris:
    """Moon-centred positions of the Earth and the Sun in M-MME2000 (km).

    Parameters
    ----------
    source : str or None
        ``None`` for DE405 from the ``de405`` package, or the path of an SPK ``.bsp``
        file with segments (0,3), (0,10), (3,301) and (3,399).
    lunar_pole : str
        The lunar pole that fixes M-MME2000 (:data:`lunarcap.physics.frames.LUNAR_POLES`).
    """

    def __init__(self, source: str | os.PathLike | None = None,
                 lunar_pole: str = DEFAULT_LUNAR_POLE):
        try:
            check_lunar_pole(lunar_pole)
        except ValueError as exc:
            raise InputError(f"lunar_pole: {exc}") from None
        self.lunar_pole = lunar_pole
        #: Rotation ICRF -> M-MME2000 of this pole.
        self.rotation = icrf_to_mme(lunar_pole)
        if source is None:
            import de405
            from jplephem.ephem import Ephemeris as _Eph

            self._kind = "de405"
            self._eph = _Eph(de405)
            self.name = "DE405 (PyPI package de405 1997.1, read by jplephem)"
            self.path = os.path.dirname(de405.__file__)
            self.jd_first = float(self._eph.jalpha)
            self.jd_last = float(self._eph.jomega)
        else:
            from jplephem.spk import SPK

            path = os.fspath(source)
            if not os.path.isfile(path):
                raise InputError(f"ephemeris file not found: {path}")
            try:
                kernel = SPK.open(path)
            except Exception as exc:  # jplephem raises assorted errors on bad files
                raise InputError(f"cannot read SPK file {path}: {exc}") from exc
            need = [(0, 3), (0, 10), (3, 301), (3, 399)]
            have = {(s.center, s.target) for s in kernel.segments}
            missing = [p for p in need if p not in have]
            if missing:
                raise InputError(f"SPK file {path} lacks segments {missing} (center, target)")
            self._kind = "spk"
            self._spk = kernel
            self.name = f"SPK file {os.path.basename(path)}"
            self.path = path
            segs = [s for s in kernel.segments if (s.center, s.target) in need]
            self.jd_first = max(s.start_jd for s in segs)
            self.jd_last = min(s.end_jd for s in segs)

    # ------------------------------------------------------------------ provenance
    def data_files(self) -> list:
        """The files this ephemeris reads: positions, and the Moon's orientation.

        The .bsp file, or the de405 package's arrays of the Earth-Moon barycentre, the
        Moon and the Sun; and in both cases the package's DE405 libration angles
        (``jpl-librations.npy``), which the Moon's DE405 body frame reads whatever gives
        the positions (:meth:`body_angles`).
        """
        if self._kind == "spk":
            import de405

            return [self.path, os.path.join(os.path.dirname(de405.__file__),
                                            "jpl-librations.npy")]
        return [os.path.join(self.path, f"jpl-{n}.npy")
                for n in ("earthmoon", "moon", "sun", "librations")]

    @cached_property
    def sha256(self) -> str:
        """SHA-256 of the ephemeris data, every file of :meth:`data_files` in its order."""
        h = hashlib.sha256()
        for fn in self.data_files():
            with open(fn, "rb") as fh:
                for chunk in iter(lambda: fh.read(1 << 20), b""):
                    h.update(chunk)
        return h.hexdigest()

    @property
    def span_s(self) -> tuple[float, float]:
        """First and last covered epochs, TDB seconds past J2000."""
        return seconds_from_jd(self.jd_first), seconds_from_jd(self.jd_last)

    def check_epochs(self, t_s) -> None:
        """Raise :class:`EphemerisRangeError` if any epoch lies outside the ephemeris."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        a, b = self.span_s
        bad = t[(t < a) | (t > b) | ~np.isfinite(t)]
        if bad.size:
            raise EphemerisRangeError(
                f"epoch {calendar_from_seconds(bad[0]) if np.isfinite(bad[0]) else bad[0]} "
                f"is outside the ephemeris {self.name}, which covers "
                f"{calendar_from_seconds(a, 0)} to {calendar_from_seconds(b, 0)}")

    # ------------------------------------------------------------------ raw vectors (ICRF)
    def _icrf(self, t_s):
        """Geocentric Moon state and Moon-centred Sun position in ICRF (km, km/s)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        self.check_epochs(t)
        whole, frac = np.vectorize(jd_split_from_seconds)(t)
        if self._kind == "de405":
            e = self._eph
            moon, moon_v = e.position_and_velocity("moon", whole, frac)
            emb = e.position("earthmoon", whole, frac)
            sun = e.position("sun", whole, frac)
            moon_ssb = emb + moon * e.moon_share
            return moon, moon_v * _KM_PER_DAY_TO_KMPS, sun - moon_ssb
        k = self._spk
        m, mv = k[3, 301].compute_and_differentiate(whole, frac)
        ea, eav = k[3, 399].compute_and_differentiate(whole, frac)
        moon_geo = m - ea
        moon_geo_v = (mv - eav) * _KM_PER_DAY_TO_KMPS
        sun = k[0, 10].compute(whole, frac) - k[0, 3].compute(whole, frac) - m
        return moon_geo, moon_geo_v, sun

    def earth_sun(self, t_s):
        """Earth and Sun positions relative to the Moon in M-MME2000, km.

        Parameters
        ----------
        t_s : float or array_like, shape (N,)
            TDB seconds past J2000.

        Returns
        -------
        r_earth, r_sun : ndarray, shape (3, N)
        """
        moon, _, sun = self._icrf(t_s)
        return self.rotation @ (-moon), self.rotation @ sun

    def moon_geocentric_state(self, t_s):
        """The Moon's geocentric position (km) and velocity (km/s) in M-MME2000, shape (3, N)."""
        moon, moon_v, _ = self._icrf(t_s)
        return self.rotation @ moon, self.rotation @ moon_v

    def body_angles(self, t_s, source: str = "de405"):
        """Euler angles (phi, theta, psi) of the Moon's body-fixed frame, rad, shape (3, N).

        ICRF -> body = R3(psi) R1(theta) R3(phi). ``source`` "de405": the DE405 libration
        angles (the ``de405`` package, also when this ephemeris is an SPK file: SPK kernels
        carry no orientation); "iau2009": the IAU (2009) rotation model.
        """
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        if source == "iau2009":
            return np.array(iau_moon_euler_rad(t))
        if source != "de405":
            raise InputError(f"body frame must be one of {', '.join(BODY_FRAMES)}, "
                             f"got {source!r}")
        eph = self if self._kind == "de405" else default_ephemeris()
        eph.check_epochs(t)
        whole, frac = np.vectorize(jd_split_from_seconds)(t)
        return np.asarray(eph._eph.position("librations", whole, frac))

    def describe(self) -> dict:
        """Provenance record: name, path, SHA-256 and span."""
        a, b = self.span_s
        return {"ephemeris": self.name, "lunar_pole": self.lunar_pole,
                "path": str(self.path), "sha256": self.sha256,
                "first_epoch": calendar_from_seconds(a, 0),
                "last_epoch": calendar_from_seconds(b, 0)}


_DEFAULT: dict[str, Ephemeris] = {}


def default_ephemeris(lunar_pole: str = DEFAULT_LUNAR_POLE) -> Ephemeris:
    """The process-wide DE405 ephemeris of a lunar pole choice (loaded once)."""
    if lunar_pole not in _DEFAULT:
        _DEFAULT[lunar_pole] = Ephemeris(None, lunar_pole)
    return _DEFAULT[lunar_pole]


def chebyshev_eval(coeffs, tau):
    """sum_j c_j T_j(tau) for each row of ``coeffs``.

    Written over generic arithmetic: ``tau`` may be a float, a numpy array or a CasADi
    symbol; ``coeffs`` is a numpy array of shape (ncomp, ncoef) or, for CasADi, a
    sequence of ncomp sequences of (symbolic or numeric) coefficients.

    The basis T_0..T_{n-1} is evaluated once by its three-term recurrence
    (T_{j+1} = 2 tau T_j - T_{j-1}) and shared by every row, which is then a dot product
    with it. The same polynomial as Clenshaw's recurrence per row (equal to rounding,
    |T_j| <= 1 on the window), in a smaller expression graph: inside the NLP the six
    Earth/Sun components share one basis and its derivatives in the node epoch
    (per node of the full dynamics, 12 % fewer instructions in the Hessian).

    Returns
    -------
    list of ncomp values (numpy arrays or CasADi expressions)
    """
    n = max(len(c) for c in coeffs)
    basis = [1 + 0 * tau, tau]
    for _ in range(2, n):
        basis.append(2 * tau * basis[-1] - basis[-2])
    out = []
    for c in coeffs:
        acc = c[0] * basis[0]
        for j in range(1, len(c)):
            acc = acc + c[j] * basis[j]
        out.append(acc)
    return out


@dataclass(frozen=True)
class ChebyshevFit:
    """Chebyshev fit of the Earth and Sun positions, and optionally the Moon's orientation.

    Rows x, y, z of the Earth then of the Sun (km, the ephemeris's frame); with a
    ``body_frame``, three more rows: the Euler angles (phi, theta, psi) of the Moon's
    body-fixed frame (rad, :meth:`Ephemeris.body_angles`), and the rotation ICRF -> frame
    (``frame_rotation``) that turns them into body axes seen from the plan's frame.

    Attributes
    ----------
    t0_s, t1_s : float
        Window, TDB seconds past J2000.
    coeffs : ndarray, shape (6 or 9, ncoef)
    max_error_km : float
        Largest distance between fit and ephemeris on a dense check grid.
    body_frame : {"de405", "iau2009"} or None
    frame_rotation : ndarray (3, 3) or None
        ICRF -> the ephemeris's frame (M-MME2000 of its lunar pole), with ``body_frame``.
    max_angle_error_rad : float
        Largest error of the fitted Euler angles on the check grid (0 without them).
    """

    t0_s: float
    t1_s: float
    coeffs: np.ndarray
    max_error_km: float
    source: str
    body_frame: str | None = None
    frame_rotation: np.ndarray | None = None
    max_angle_error_rad: float = 0.0

    NCOEF = 10  # fixed so CasADi functions keep one shape for any window (<= 4 days):
    #           10 fit DE405 to its own evaluation noise (6e-5 km) over 4 days (16 no better)
    #: Tolerance of the fitted Euler angles, rad (1e-9 rad: 2 mm on the lunar surface).
    TOL_ANGLE_RAD = 1e-9

    @classmethod
    def fit(cls, eph: Ephemeris, t0_s: float, t1_s: float, ncoef: int | None = None,
            tol_km: float = 1e-3, body_frame: str | None = None) -> "ChebyshevFit":
        """Fit over [t0_s, t1_s] at Chebyshev nodes; check the error on a 4x denser grid.

        ``body_frame`` ("de405" or "iau2009") also fits the Moon's orientation.

        Raises
        ------
        InputError
            If the window is empty or longer than 4 days, or the fit misses ``tol_km``
            (or 1e-9 rad for the angles).
        """
        ncoef = ncoef or cls.NCOEF
        if not t1_s > t0_s:
            raise InputError("ephemeris fit window must have t1 > t0")
        if t1_s - t0_s > 4 * 86400:
            raise InputError("ephemeris fit window longer than 4 days; split the mission")
        eph.check_epochs([t0_s, t1_s])
        nodes = np.cos(np.pi * (np.arange(ncoef) + 0.5) / ncoef)  # Chebyshev-Gauss nodes
        t = 0.5 * (t0_s + t1_s) + 0.5 * (t1_s - t0_s) * nodes
        re, rs = eph.earth_sun(t)
        vals = np.vstack([re, rs] + ([eph.body_angles(t, body_frame)] if body_frame else []))
        coeffs = np.array([np.polynomial.chebyshev.chebfit(nodes, row, ncoef - 1) for row in vals])
        tchk = np.linspace(t0_s, t1_s, 4 * ncoef + 1)
        fit = np.array(chebyshev_eval(coeffs, cls._tau(t0_s, t1_s, tchk)))
        re_c, rs_c = eph.earth_sun(tchk)
        err = max(np.linalg.norm(fit[:3] - re_c, axis=0).max(),
                  np.linalg.norm(fit[3:6] - rs_c, axis=0).max())
        if err > tol_km:
            raise InputError(f"Chebyshev ephemeris fit error {err * 1e3:.3f} m exceeds "
                             f"{tol_km * 1e3:.3f} m; shorten the window")
        err_angle = 0.0
        if body_frame:
            err_angle = float(np.abs(fit[6:] - eph.body_angles(tchk, body_frame)).max())
            if err_angle > cls.TOL_ANGLE_RAD:
                raise InputError(f"Chebyshev fit of the Moon's orientation misses by "
                                 f"{err_angle:.2e} rad; shorten the window")
        return cls(float(t0_s), float(t1_s), coeffs, float(err), eph.name, body_frame,
                   eph.rotation.copy() if body_frame else None, err_angle)

    @staticmethod
    def _tau(t0, t1, t):
        return (2 * t - (t0 + t1)) / (t1 - t0)

    def param_vector(self) -> np.ndarray:
        """[t0, t1, coeffs..., (frame rotation)]: the numbers a CasADi dynamics function takes."""
        parts = [[self.t0_s, self.t1_s], self.coeffs.ravel()]
        if self.body_frame:
            parts.append(self.frame_rotation.ravel())
        return np.concatenate(parts)

    @staticmethod
    def n_params(body_frame: bool) -> int:
        """Length of :meth:`param_vector` with or without the Moon's orientation."""
        n = ChebyshevFit.NCOEF
        return 2 + (9 * n + 9 if body_frame else 6 * n)

    def __call__(self, t_s):
        """Earth and Sun positions (km, M-MME2000) at epochs t_s from the fit, shape (3, N)."""
        vals = np.array(chebyshev_eval(self.coeffs[:6], self._tau(self.t0_s, self.t1_s,
                                                                  np.asarray(t_s, float))))
        return vals[:3], vals[3:]

    def body_axes(self, t_s) -> np.ndarray:
        """Rows of the Moon's body-fixed axes in the fit's frame at an epoch, (3, 3)."""
        return np.array(body_axes_from_params(self.param_vector(), float(t_s)), dtype=float)


def earth_sun_from_params(prm, t_s):
    """Earth and Sun positions from a parameter vector of :meth:`ChebyshevFit.param_vector`.

    Generic over numpy/CasADi (used inside the dynamics Function).
    """
    n = ChebyshevFit.NCOEF
    t0, t1 = prm[0], prm[1]
    tau = (2 * t_s - (t0 + t1)) / (t1 - t0)
    rows = [[prm[2 + i * n + j] for j in range(n)] for i in range(6)]
    v = chebyshev_eval(rows, tau)
    return v[:3], v[3:]


def body_axes_from_params(prm, t_s):
    """Rows of the Moon's body-fixed axes in the plan's frame from a fit's parameter vector.

    R313(phi, theta, psi) C^T, with the fitted Euler angles and C = ICRF -> frame: row i is
    body axis i in the frame, so ``x_body = M x_frame``. Generic over numpy/CasADi.
    """
    n = ChebyshevFit.NCOEF
    t0, t1 = prm[0], prm[1]
    tau = (2 * t_s - (t0 + t1)) / (t1 - t0)
    phi, theta, psi = chebyshev_eval([[prm[2 + i * n + j] for j in range(n)]
                                      for i in range(6, 9)], tau)
    rot = rotation_313(phi, theta, psi)
    c = [[prm[2 + 9 * n + 3 * i + j] for j in range(3)] for i in range(3)]
    # (R C^T)[a][b] = sum_k R[a][k] C[b][k]
    return tuple(tuple(rot[a][0] * c[b][0] + rot[a][1] * c[b][1] + rot[a][2] * c[b][2]
                       for b in range(3)) for a in range(3))
