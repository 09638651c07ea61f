"""Dispersions: the error model and the draws (common random numbers).

The one-sigma execution and navigation errors of :mod:`lunarcap.studies.dispersions.samples`
(:class:`ErrorModel`), the fixed block of standard normals each sample draws
(:func:`draws`: sample ``k`` of seed ``s`` from ``numpy.random.default_rng([s, k])``,
whatever the sigmas and the plan) and their scaling into one sample's errors
(:func:`realise`, :func:`knowledge_error`, :func:`gates_errors`, :func:`bplane_error`).

The block's layout (indices into the draws): the arrival's RTN error (0-5), then per burn
thrust, Isp, two pointing angles and the ignition offset (6-45: the first layout, whose
numbers never change), then per burn the knowledge error of the re-plan (6, RTN), then
per burn the four Gates errors (proportional and fixed magnitude, proportional and
fixed pointing about two axes: 6), then the B-plane error (B.R, B.T, time of closest
approach: 3). numpy's generator fills the block in order, so the first 46 numbers of a
(seed, k) are those the first layout drew: a model with only the first layout's errors
flies today's samples bit for bit.
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
#: End of the first layout: 6 (arrival) + 5 per burn.
FIRST_LAYOUT = 6 + PER_BURN * MAX_BURNS
#: Standard normals of a re-plan's knowledge error (RTN position and velocity).
PER_KNOWLEDGE = 6
#: First index of the knowledge errors (burn i's at KNOWLEDGE + 6 i).
KNOWLEDGE = FIRST_LAYOUT
#: Standard normals of a burn's Gates errors: magnitude (proportional, fixed), pointing
#: proportional (two axes), pointing fixed (two axes).
PER_GATES = 6
#: First index of the Gates errors (burn i's at GATES + 6 i).
GATES = KNOWLEDGE + PER_KNOWLEDGE * MAX_BURNS
#: First index of the B-plane error (B.R, B.T, time of closest approach).
BPLANE = GATES + PER_GATES * MAX_BURNS
#: Standard normals drawn per sample, whatever the sigmas.
BLOCK = BPLANE + 3

#: The sigmas of an ErrorModel (non-negative numbers), with their units.
SIGMAS = {"thrust_sigma_pct": "%", "isp_sigma_pct": "%", "pointing_sigma_deg": "deg",
          "ignition_sigma_s": "s", "arrival_sigma_km": "km", "arrival_sigma_mps": "m/s",
          "knowledge_sigma_km": "km", "knowledge_sigma_mps": "m/s",
          "gates_magnitude_pct": "%", "gates_magnitude_mps": "m/s",
          "gates_pointing_deg": "deg", "gates_pointing_mps": "m/s"}
#: The covariances of an ErrorModel: the option's name, its size and its units.
COVARIANCES = {"arrival_cov": ("--arrival-cov", (36,), "km and km/s, RTN"),
               "knowledge_cov": ("--knowledge-cov", (36,), "km and km/s, RTN"),
               "bplane_cov": ("--bplane-cov", (4, 9), "km (B.R, B.T) and s (time)")}


# ====================================================================== error model
@dataclass(frozen=True)
class ErrorModel:
    """One-sigma execution and navigation errors (every default 0: nothing assumed).

    What is modelled (each error independent, normal, of the given one-sigma):

    * **per burn, execution** (the per-quantity form): thrust and Isp factors, a fixed
      tilt of the thrust direction about two axes perpendicular to the burn's mean
      direction, an ignition offset;
    * **per burn, execution in the Gates form** (Gates 1963, JPL TR 32-504): the delta-V
      magnitude in error by a proportional (``gates_magnitude_pct``) and a fixed
      (``gates_magnitude_mps``) part, its direction by a proportional part (an angle,
      ``gates_pointing_deg`` per axis) and a fixed part (a transverse velocity,
      ``gates_pointing_mps`` per axis, i.e. an angle of that over the burn's planned
      delta-V). A finite burn realises the magnitude error as a thrust error at the
      nominal Isp (the mass flow scales with the thrust, so the delta-V delivered costs
      its propellant; :func:`gates_errors`) and the pointing error as a tilt added to
      the per-quantity one;
    * **arrival**: the arrival perilune state in error in RTN (per axis or a 6x6
      covariance), and/or the B-plane target in error (B.R, B.T and, with a 3x3
      covariance, the time of closest approach);
    * **knowledge, per re-plan**: the orbit-determination error of the state a re-plan
      starts from (per RTN axis, or a 6x6 covariance): the re-plan is solved from the
      estimate, the burn is flown from the truth.

    Not modelled: errors of the dynamics model (gravity field, ephemeris, solar pressure),
    an attitude that wanders during a burn, correlations between burns or between error
    sources, knowledge errors of the mass, thrust or Isp estimate, and the execution
    errors of the trim that follows the last burn (the trim itself is flown:
    :mod:`lunarcap.studies.dispersions.trim`).

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
    knowledge_sigma_km, knowledge_sigma_mps : float
        Orbit-determination error of the state each re-plan starts from, per axis of the
        RTN frame there, km and m/s.
    knowledge_cov : tuple of 36 floats, optional
        Instead: its 6x6 covariance (km, km/s; RTN), row-major, the same for every re-plan.
    gates_magnitude_pct, gates_magnitude_mps : float
        Gates magnitude errors: proportional (% of the burn's planned delta-V) and fixed
        (m/s), per burn.
    gates_pointing_deg, gates_pointing_mps : float
        Gates pointing errors per transverse axis: proportional (an angle, deg) and fixed
        (a transverse delta-V, m/s), per burn.
    bplane_cov : tuple of 4 or 9 floats, optional
        The B-plane covariance: 2x2 of (B.R, B.T) in km, or 3x3 with the time of closest
        approach (s) third; in the B-plane of the arrival's osculating hyperbola about the
        plan's ``arrival.bplane_reference`` (EME2000 by default; :func:`bplane_error`). A
        ``--bplane-cov`` file is (B.T, B.R) unless labelled (:func:`read_covariance`).
    """

    thrust_sigma_pct: float = 0.0
    isp_sigma_pct: float = 0.0
    pointing_sigma_deg: float = 0.0
    ignition_sigma_s: float = 0.0
    arrival_sigma_km: float = 0.0
    arrival_sigma_mps: float = 0.0
    arrival_cov: tuple | None = None
    knowledge_sigma_km: float = 0.0
    knowledge_sigma_mps: float = 0.0
    knowledge_cov: tuple | None = None
    gates_magnitude_pct: float = 0.0
    gates_magnitude_mps: float = 0.0
    gates_pointing_deg: float = 0.0
    gates_pointing_mps: float = 0.0
    bplane_cov: tuple | None = None

    def __post_init__(self):
        for name in SIGMAS:
            v = getattr(self, name)
            opt = "--" + name.replace("_", "-")
            if isinstance(v, bool) or not isinstance(v, (int, float)) or \
                    not math.isfinite(v) or v < 0:
                raise InputError(f"{opt} must be a non-negative number, got {v!r}")
            object.__setattr__(self, name, float(v))
        for name in ("thrust_sigma_pct", "isp_sigma_pct", "gates_magnitude_pct"):
            if getattr(self, name) >= 30:
                raise InputError(f"--{name.replace('_', '-')} must be below 30 % (a 3-sigma "
                                 f"draw would stop or reverse the engine)")
        for name in ("pointing_sigma_deg", "gates_pointing_deg"):
            if getattr(self, name) > 30:
                raise InputError(f"--{name.replace('_', '-')} must be at most 30 deg, got "
                                 f"{getattr(self, name):g}")
        for name, sigmas in (("arrival_cov", ("arrival_sigma_km", "arrival_sigma_mps")),
                             ("knowledge_cov", ("knowledge_sigma_km", "knowledge_sigma_mps"))):
            if getattr(self, name) is not None and any(getattr(self, s) for s in sigmas):
                raise InputError(f"give {COVARIANCES[name][0]} or --{sigmas[0][:-3]}-km/-mps"
                                 .replace("_", "-") + ", not both")
        for name in COVARIANCES:
            if getattr(self, name) is not None:
                cov = np.asarray(getattr(self, name), float)
                object.__setattr__(self, name, tuple(float(v) for v in cov.ravel()))
                covariance_factor(getattr(self, name), name)  # checks it

    @property
    def is_zero(self) -> bool:
        """True if no error is dispersed."""
        return not any([*(getattr(self, s) for s in SIGMAS),
                        *(getattr(self, c) is not None and any(getattr(self, c))
                          for c in COVARIANCES)])

    def key(self) -> dict:
        """The error model as the table's key columns (a covariance by its hash)."""
        out = {s: getattr(self, s) for s in SIGMAS}
        for c in COVARIANCES:
            v = getattr(self, c)
            out[c] = "" if v is None else \
                hashlib.sha256(np.asarray(v).tobytes()).hexdigest()[:12]
        return out

    def describe(self) -> str:
        """One line: the one-sigma errors (those not zero beyond the first four)."""
        arr = ("arrival covariance from a file" if self.arrival_cov is not None else
               f"arrival {self.arrival_sigma_km:g} km / {self.arrival_sigma_mps:g} m/s per axis")
        out = (f"1-sigma: thrust {self.thrust_sigma_pct:g} %, Isp {self.isp_sigma_pct:g} %, "
               f"pointing {self.pointing_sigma_deg:g} deg per axis, ignition "
               f"{self.ignition_sigma_s:g} s, {arr}")
        if self.knowledge_cov is not None:
            out += ", knowledge at each re-plan: covariance from a file"
        elif self.knowledge_sigma_km or self.knowledge_sigma_mps:
            out += (f", knowledge at each re-plan {self.knowledge_sigma_km:g} km / "
                    f"{self.knowledge_sigma_mps:g} m/s per axis")
        if any((self.gates_magnitude_pct, self.gates_magnitude_mps, self.gates_pointing_deg,
                self.gates_pointing_mps)):
            out += (f", Gates magnitude {self.gates_magnitude_pct:g} % + "
                    f"{self.gates_magnitude_mps:g} m/s, pointing {self.gates_pointing_deg:g} "
                    f"deg + {self.gates_pointing_mps:g} m/s per axis")
        if self.bplane_cov is not None:
            out += ", B-plane covariance from a file"
        return out

    def only(self, name: str, value: float) -> "ErrorModel":
        """The model with every error 0 but sigma ``name`` at ``value`` (a sensitivity)."""
        if name not in SIGMAS:
            raise InputError(f"unknown error source {name!r}: one of {', '.join(SIGMAS)}")
        return ErrorModel(**{name: value})


def covariance_factor(cov, name: str = "arrival_cov") -> np.ndarray:
    """L with L L^T = the covariance ``name`` (see :data:`COVARIANCES`); else InputError."""
    opt, sizes, units = COVARIANCES[name]
    c = np.asarray(cov, float)
    if c.size not in sizes or not np.all(np.isfinite(c)):
        dims = " or ".join(f"{int(math.isqrt(s))}x{int(math.isqrt(s))}" for s in sizes)
        raise InputError(f"{opt} must be {' or '.join(str(s) for s in sizes)} finite numbers "
                         f"(a {dims} matrix, {units}), got {c.size}")
    m = math.isqrt(c.size)
    c = c.reshape(m, m)
    if not np.allclose(c, c.T, rtol=1e-9, atol=1e-15):
        raise InputError(f"{opt} is not symmetric")
    w, v = np.linalg.eigh(c)
    if w.min() < -1e-9 * max(1.0, abs(w).max()):
        raise InputError(f"{opt} is not positive semi-definite (eigenvalue {w.min():.3g})")
    return v * np.sqrt(np.clip(w, 0.0, None))


def arrival_factor(cov) -> np.ndarray:
    """L with L L^T = the 6x6 arrival covariance (km, km/s); InputError if it is not one."""
    return covariance_factor(cov, "arrival_cov")


#: The quantities a B-plane covariance file may name in its ``order:`` line, and the order
#: a file without one is read in: B.T, B.R (km), then the time of closest approach (s).
BPLANE_LABELS = ("B.T", "B.R", "t")
#: The order lunarcap keeps a B-plane covariance in (:attr:`ErrorModel.bplane_cov`).
BPLANE_STORED = ("B.R", "B.T", "t")


def _bplane_order(line: str, opt: str, p) -> tuple:
    """The quantities of an ``order: B.T B.R [t]`` line of a B-plane covariance file."""
    names = tuple(line.split(":", 1)[1].replace(",", " ").split())
    if sorted(names) not in (sorted(BPLANE_LABELS[:2]), sorted(BPLANE_LABELS)):
        raise InputError(f"{opt} {p}: the order line must name B.T and B.R (and t, the time "
                         f"of closest approach), each once, got {line.strip()!r}")
    return names


def read_covariance(path, name: str = "arrival_cov") -> tuple:
    """The covariance ``name`` from a text file (whitespace or commas; '#' comments).

    A B-plane covariance (``bplane_cov``) is read in the order navigation teams write it,
    (B.T, B.R) and then the time of closest approach, unless the file has a line
    ``order: B.R B.T t`` (any order of those names, the matrix's size) saying its own;
    it is returned in lunarcap's order :data:`BPLANE_STORED`. Its axes are the plan's
    B-plane (``arrival.bplane_reference``, :func:`bplane_error`).
    """
    opt = COVARIANCES[name][0]
    p = Path(path).expanduser()
    try:
        text = p.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"{opt} {p}: cannot read it ({exc})") from None
    vals, order = [], None
    for line in text.splitlines():
        line = line.split("#", 1)[0].replace(",", " ")
        if name == "bplane_cov" and line.strip().lower().startswith("order:"):
            if order is not None:
                raise InputError(f"{opt} {p}: two order lines")
            order = _bplane_order(line, opt, p)
            continue
        try:
            vals += [float(t) for t in line.split()]
        except ValueError:
            raise InputError(f"{opt} {p}: not numbers: {line.strip()!r}") from None
    sizes = COVARIANCES[name][1]
    if len(vals) not in sizes:
        raise InputError(f"{opt} {p}: the matrix has {' or '.join(str(s) for s in sizes)} "
                         f"numbers, the file has {len(vals)}")
    covariance_factor(vals, name)
    if name != "bplane_cov":
        return tuple(vals)
    m = math.isqrt(len(vals))
    order = order or BPLANE_LABELS[:m]
    if len(order) != m:
        raise InputError(f"{opt} {p}: the order line names {len(order)} quantities, the "
                         f"matrix is {m}x{m}")
    idx = [order.index(q) for q in BPLANE_STORED[:m]]
    c = np.reshape(vals, (m, m))[np.ix_(idx, idx)]
    return tuple(float(v) for v in c.ravel())


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
    """(arrival error (6,) km and km/s in RTN, [ExecutionErrors per burn]) from the draws.

    The per-quantity execution errors; the Gates errors, which depend on each burn's
    planned delta-V, are added by :func:`gates_errors`.
    """
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


def knowledge_error(z: np.ndarray, model: ErrorModel, i: int) -> np.ndarray:
    """The estimate's error (6,) (km, km/s; RTN) of the state burn ``i`` is re-planned from."""
    b = np.asarray(z, float)[KNOWLEDGE + PER_KNOWLEDGE * i: KNOWLEDGE + PER_KNOWLEDGE * (i + 1)]
    if model.knowledge_cov is not None:
        return covariance_factor(model.knowledge_cov, "knowledge_cov") @ b
    return np.concatenate([model.knowledge_sigma_km * b[:3],
                           model.knowledge_sigma_mps * 1e-3 * b[3:6]])


def gates_errors(z: np.ndarray, model: ErrorModel, i: int, planned_delta_v_mps: float,
                 base: ExecutionErrors, exhaust_speed_mps: float) -> ExecutionErrors:
    """Burn ``i``'s execution errors: ``base`` with its Gates errors added (Gates 1963).

    Magnitude: the delta-V flown is (1 + eps) dV with eps = eps_p + eps_f / dV (dV the
    planned delta-V, ``exhaust_speed_mps`` the engine's g0 Isp), realised as a thrust
    error at the nominal Isp over the planned duration: the mass flow T / (g0 Isp) scales
    with the thrust, so the propellant is the rocket equation's for the delta-V delivered.
    The factor f on thrust and mass flow that delivers exactly (1 + eps) dV follows from
    dV = g0 Isp ln(m0 / (m0 - mdot t)): f = (1 - exp(-(1 + eps) dV / c)) /
    (1 - exp(-dV / c)), c = g0 Isp (the start mass cancels). A timer cut-off with a thrust
    error and a delta-V cut-off with a sensor error both spend that propellant; scaling
    thrust and Isp alike instead would deliver the delta-V at the planned propellant.
    Pointing: tilts of sigma_p z + sigma_f z' / dV rad about the two axes of the
    per-quantity tilt (the fixed part a transverse delta-V over the planned one).
    ``base`` itself when every Gates sigma is 0; InputError when a draw leaves 5 % of the
    burn or less.
    """
    m = model
    if not any((m.gates_magnitude_pct, m.gates_magnitude_mps, m.gates_pointing_deg,
                m.gates_pointing_mps)):
        return base
    b = np.asarray(z, float)[GATES + PER_GATES * i: GATES + PER_GATES * (i + 1)]
    dv = float(planned_delta_v_mps)
    ratio = 1.0 + m.gates_magnitude_pct / 100 * b[0] + m.gates_magnitude_mps * b[1] / dv
    if ratio <= 0.05:
        raise InputError(f"a Gates magnitude draw leaves {100 * ratio:.1f} % of burn {i + 1}'s "
                         f"{dv:.1f} m/s: the fixed magnitude sigma is too large for it")
    c = float(exhaust_speed_mps)
    flow = -math.expm1(-ratio * dv / c) / -math.expm1(-dv / c)
    tilt = tuple(t + math.radians(m.gates_pointing_deg) * b[2 + a] +
                 m.gates_pointing_mps * b[4 + a] / dv
                 for a, t in enumerate(base.tilt_rad))
    return ExecutionErrors(base.thrust_factor * flow, base.isp_factor, tilt, base.ignition_s)


def bplane_error(z: np.ndarray, model: ErrorModel, plan=None) -> np.ndarray:
    """The B-plane error (3,): B.R (km), B.T (km), time of closest approach (s).

    Drawn from ``model.bplane_cov`` (L z, L L^T the covariance, in its stored order
    :data:`BPLANE_STORED`) in the B-plane of the plan's ``arrival.bplane_reference``
    (EME2000 by default: T = S x k / |S x k| with k the Earth's mean equator pole of
    J2000, as GMAT's BdotT/BdotR; lunar-equator on request), and with ``plan`` given,
    expressed in lunarcap's own axes, those the dispersed arrival is built in
    (:func:`lunarcap.studies.dispersions.samples.fly_sample`): the same miss vector
    B.R R + B.T T projected on the axes about the plan's lunar pole, at the nominal
    arrival's asymptote (a rotation about S, 24 deg for the paper's arrival). Without
    ``plan``: the draw in the covariance's own axes.
    """
    if model.bplane_cov is None:
        return np.zeros(3)
    L = covariance_factor(model.bplane_cov, "bplane_cov")
    d = L @ np.asarray(z, float)[BPLANE: BPLANE + L.shape[0]]
    d = np.concatenate([d, np.zeros(3 - d.size)])
    if plan is None or plan.arrival.bplane_reference == "lunar-equator" or not np.any(d[:2]):
        return d
    from lunarcap.capture.chain import perilune_epoch_state
    from lunarcap.physics import constants as C
    from lunarcap.physics.bplane import bplane_from_rv, reference_pole
    from lunarcap.physics.elements import rv_from_mee

    _, x0 = perilune_epoch_state(plan, 0)
    r, v = (np.asarray(q, float) for q in rv_from_mee(*np.asarray(x0, float)[:6], C.MU_MOON))
    given = bplane_from_rv(r, v, C.MU_MOON, reference_pole(plan.arrival.bplane_reference,
                                                           "M-MME2000", plan.lunar_pole))
    own = bplane_from_rv(r, v, C.MU_MOON)
    miss = d[0] * given.r_hat + d[1] * given.t_hat
    return np.array([miss @ own.r_hat, miss @ own.t_hat, d[2]])
