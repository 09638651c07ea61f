"""Dispersions: the error model and the draws (common random numbers).

The one-sigma execution and navigation errors of :mod:`lunarcap.runs.dispersions`
(:class:`ErrorModel`), the fixed block of standard normals each sample draws
(:func:`draws`: sample ``k`` of seed ``s`` from ``numpy.random.default_rng([s, k])``,
whatever the sigmas) and their scaling into one sample's errors (:func:`realise`).
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError
from lunarcap.optim.flight import ExecutionErrors

#: Most burns a plan may have in this study (the draws' block is sized for it).
MAX_BURNS = 8
#: Standard normals per burn: thrust, Isp, two pointing angles, ignition offset.
PER_BURN = 5
#: Standard normals drawn per sample, whatever the sigmas: 6 (arrival) + 5 per burn.
BLOCK = 6 + PER_BURN * MAX_BURNS


# ====================================================================== error model
@dataclass(frozen=True)
class ErrorModel:
    """One-sigma execution and navigation errors (every default 0: nothing assumed).

    Attributes
    ----------
    thrust_sigma_pct, isp_sigma_pct : float
        Thrust and specific impulse, % of nominal, drawn per burn.
    pointing_sigma_deg : float
        Each of two tilt angles of the thrust direction (perpendicular to the burn's mean
        direction, fixed over the burn), deg, drawn per burn.
    ignition_sigma_s : float
        Ignition epoch, s, per burn (the steering follows the time since ignition).
    arrival_sigma_km, arrival_sigma_mps : float
        Arrival position (km) and velocity (m/s) errors per axis of the arrival RTN frame.
    arrival_cov : tuple of 36 floats, optional
        Instead: the 6x6 covariance (km, km/s; RTN at the arrival perilune), row-major.
    """

    thrust_sigma_pct: float = 0.0
    isp_sigma_pct: float = 0.0
    pointing_sigma_deg: float = 0.0
    ignition_sigma_s: float = 0.0
    arrival_sigma_km: float = 0.0
    arrival_sigma_mps: float = 0.0
    arrival_cov: tuple | None = None

    def __post_init__(self):
        for name in ("thrust_sigma_pct", "isp_sigma_pct", "pointing_sigma_deg",
                     "ignition_sigma_s", "arrival_sigma_km", "arrival_sigma_mps"):
            v = getattr(self, name)
            opt = "--" + name.replace("_", "-")
            if isinstance(v, bool) or not isinstance(v, (int, float)) or \
                    not math.isfinite(v) or v < 0:
                raise InputError(f"{opt} must be a non-negative number, got {v!r}")
            object.__setattr__(self, name, float(v))
        if self.thrust_sigma_pct >= 30 or self.isp_sigma_pct >= 30:
            raise InputError("thrust and Isp sigmas must be below 30 % (a 3-sigma draw would "
                             "stop or reverse the engine)")
        if self.pointing_sigma_deg > 30:
            raise InputError(f"--pointing-sigma-deg must be at most 30 deg, got "
                             f"{self.pointing_sigma_deg:g}")
        if self.arrival_cov is not None:
            if self.arrival_sigma_km or self.arrival_sigma_mps:
                raise InputError("give --arrival-cov or --arrival-sigma-km/-mps, not both")
            cov = np.asarray(self.arrival_cov, float)
            object.__setattr__(self, "arrival_cov", tuple(float(v) for v in cov.ravel()))
            arrival_factor(self.arrival_cov)  # checks it

    @property
    def is_zero(self) -> bool:
        """True if no error is dispersed."""
        return not any((self.thrust_sigma_pct, self.isp_sigma_pct, self.pointing_sigma_deg,
                        self.ignition_sigma_s, self.arrival_sigma_km, self.arrival_sigma_mps,
                        self.arrival_cov is not None and any(self.arrival_cov)))

    def key(self) -> dict:
        """The error model as the table's key columns."""
        cov = "" if self.arrival_cov is None else \
            hashlib.sha256(np.asarray(self.arrival_cov).tobytes()).hexdigest()[:12]
        return {"thrust_sigma_pct": self.thrust_sigma_pct, "isp_sigma_pct": self.isp_sigma_pct,
                "pointing_sigma_deg": self.pointing_sigma_deg,
                "ignition_sigma_s": self.ignition_sigma_s,
                "arrival_sigma_km": self.arrival_sigma_km,
                "arrival_sigma_mps": self.arrival_sigma_mps, "arrival_cov": cov}

    def describe(self) -> str:
        """One line: the one-sigma errors."""
        arr = ("arrival covariance from a file" if self.arrival_cov is not None else
               f"arrival {self.arrival_sigma_km:g} km / {self.arrival_sigma_mps:g} m/s per axis")
        return (f"1-sigma: thrust {self.thrust_sigma_pct:g} %, Isp {self.isp_sigma_pct:g} %, "
                f"pointing {self.pointing_sigma_deg:g} deg per axis, ignition "
                f"{self.ignition_sigma_s:g} s, {arr}")


def arrival_factor(cov) -> np.ndarray:
    """L with L L^T = the 6x6 covariance (km, km/s); InputError if it is not one."""
    c = np.asarray(cov, float)
    if c.size != 36 or not np.all(np.isfinite(c)):
        raise InputError(f"--arrival-cov must be 36 finite numbers (a 6x6 matrix, km and "
                         f"km/s), got {c.size}")
    c = c.reshape(6, 6)
    if not np.allclose(c, c.T, rtol=1e-9, atol=1e-15):
        raise InputError("--arrival-cov is not symmetric")
    w, v = np.linalg.eigh(c)
    if w.min() < -1e-9 * max(1.0, abs(w).max()):
        raise InputError(f"--arrival-cov is not positive semi-definite (eigenvalue "
                         f"{w.min():.3g})")
    return v * np.sqrt(np.clip(w, 0.0, None))


def read_covariance(path) -> tuple:
    """A 6x6 covariance from a text file (whitespace or commas; '#' comments), row-major."""
    p = Path(path).expanduser()
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"--arrival-cov {p}: cannot read it ({exc})") from None
    vals = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].replace(",", " ")
        try:
            vals += [float(t) for t in line.split()]
        except ValueError:
            raise InputError(f"--arrival-cov {p}: not numbers: {line.strip()!r}") from None
    if len(vals) != 36:
        raise InputError(f"--arrival-cov {p}: a 6x6 matrix has 36 numbers, the file has "
                         f"{len(vals)}")
    arrival_factor(vals)
    return tuple(vals)


# ====================================================================== draws
def draws(seed: int, index: int) -> np.ndarray:
    """The sample's :data:`BLOCK` standard normals, from ``default_rng([seed, index])``."""
    return np.random.default_rng([int(seed), int(index)]).standard_normal(BLOCK)


def sample_draws(seed: int, index: int, antithetic: bool = False) -> np.ndarray:
    """:func:`draws`, or with ``antithetic`` the negated draws of the pair's first sample."""
    if antithetic and index % 2:
        return -draws(seed, index - 1)
    return draws(seed, index)


def realise(z: np.ndarray, model: ErrorModel, n_burns: int) -> tuple:
    """(arrival error (6,) km and km/s in RTN, [ExecutionErrors per burn]) from the draws."""
    z = np.asarray(z, float)
    if model.arrival_cov is not None:
        d_arr = arrival_factor(model.arrival_cov) @ z[:6]
    else:
        d_arr = np.concatenate([model.arrival_sigma_km * z[:3],
                                model.arrival_sigma_mps * 1e-3 * z[3:6]])
    out = []
    for i in range(n_burns):
        b = z[6 + PER_BURN * i: 6 + PER_BURN * (i + 1)]
        out.append(ExecutionErrors(1.0 + model.thrust_sigma_pct / 100 * b[0],
                              1.0 + model.isp_sigma_pct / 100 * b[1],
                              (math.radians(model.pointing_sigma_deg) * b[2],
                               math.radians(model.pointing_sigma_deg) * b[3]),
                              model.ignition_sigma_s * b[4]))
    return d_arr, out
