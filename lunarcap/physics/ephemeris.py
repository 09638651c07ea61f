"""Earth and Sun positions relative to the Moon, in M-MME2000, from a JPL ephemeris.

The default source is JPL DE405 (Standish 1998) as shipped by the PyPI package
``de405`` and read with jplephem's :class:`jplephem.ephem.Ephemeris`: nothing is
downloaded. Any SPK kernel (``.bsp``: DE405, DE430, DE440, ...) holding the Sun,
the Earth-Moon barycentre, the Earth and the Moon may be named instead.

This is the only module that imports jplephem. For the optimiser, :class:`ChebyshevFit`
fits both vectors over a mission window with Chebyshev series whose evaluation (the
Clenshaw recurrence) is written over generic operations, so it can be called inside
CasADi expressions.
"""

from __future__ import annotations

import hashlib
import os
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from lunarcap.errors import EphemerisRangeError, InputError
from lunarcap.physics.epochs import calendar_from_seconds, jd_split_from_seconds, seconds_from_jd
from lunarcap.physics.frames import DEFAULT_LUNAR_POLE, LUNAR_POLES, icrf_to_mme

__all__ = ["Ephemeris", "ChebyshevFit", "default_ephemeris", "chebyshev_eval"]

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
        if lunar_pole not in LUNAR_POLES:
            raise InputError(f"lunar_pole must be one of {', '.join(LUNAR_POLES)}, "
                             f"got {lunar_pole!r}")
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
    @cached_property
    def sha256(self) -> str:
        """SHA-256 of the ephemeris data (the .bsp file, or the de405 arrays used)."""
        h = hashlib.sha256()
        files = ([self.path] if self._kind == "spk" else
                 [os.path.join(self.path, f"jpl-{n}.npy") for n in ("earthmoon", "moon", "sun")])
        for fn in files:
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
    """Chebyshev fit of the Earth and Sun positions (rows x,y,z Earth then x,y,z Sun, km).

    Attributes
    ----------
    t0_s, t1_s : float
        Window, TDB seconds past J2000.
    coeffs : ndarray, shape (6, ncoef)
    max_error_km : float
        Largest distance between fit and ephemeris on a dense check grid.
    """

    t0_s: float
    t1_s: float
    coeffs: np.ndarray
    max_error_km: float
    source: str

    NCOEF = 10  # fixed so CasADi functions keep one shape for any window (<= 4 days):
    #           10 fit DE405 to its own evaluation noise (6e-5 km) over 4 days (16 no better)

    @classmethod
    def fit(cls, eph: Ephemeris, t0_s: float, t1_s: float, ncoef: int | None = None,
            tol_km: float = 1e-3) -> "ChebyshevFit":
        """Fit over [t0_s, t1_s] at Chebyshev nodes; check the error on a 4x denser grid.

        Raises
        ------
        InputError
            If the window is empty or longer than 4 days, or the fit misses ``tol_km``.
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
        vals = np.vstack([re, rs])
        coeffs = np.array([np.polynomial.chebyshev.chebfit(nodes, row, ncoef - 1) for row in vals])
        tchk = np.linspace(t0_s, t1_s, 4 * ncoef + 1)
        fit = np.array(chebyshev_eval(coeffs, cls._tau(t0_s, t1_s, tchk)))
        re_c, rs_c = eph.earth_sun(tchk)
        err = max(np.linalg.norm(fit[:3] - re_c, axis=0).max(),
                  np.linalg.norm(fit[3:] - rs_c, axis=0).max())
        if err > tol_km:
            raise InputError(f"Chebyshev ephemeris fit error {err * 1e3:.3f} m exceeds "
                             f"{tol_km * 1e3:.3f} m; shorten the window")
        return cls(float(t0_s), float(t1_s), coeffs, float(err), eph.name)

    @staticmethod
    def _tau(t0, t1, t):
        return (2 * t - (t0 + t1)) / (t1 - t0)

    def param_vector(self) -> np.ndarray:
        """[t0, t1, coeffs...]: the numeric parameters a CasADi dynamics function takes."""
        return np.concatenate([[self.t0_s, self.t1_s], self.coeffs.ravel()])

    def __call__(self, t_s):
        """Earth and Sun positions (km, M-MME2000) at epochs t_s from the fit, shape (3, N)."""
        vals = np.array(chebyshev_eval(self.coeffs, self._tau(self.t0_s, self.t1_s,
                                                              np.asarray(t_s, float))))
        return vals[:3], vals[3:]


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
