"""One burn's optimal-control problem, apart from how it is transcribed (Song 2011, Sec. 2.2).

Phase 1 burns for a free duration ``t1`` (0 < t1 <= t1_max, Eq. 10) with a free unit thrust
direction ``u = (u_r, u_t, u_n)`` (bounds +-1.01, |u| = 1, Eqs. 12-13); phase 2 coasts
to a fixed epoch (the next nominal perilune); states (MEE and mass) are continuous across
the phases (Eq. 16). The objective is J = Delta-V of the burn + speed at the end of phase 2
(Eq. 9). At the end of phase 2 the burn's :class:`~lunarcap.mission.targets.Target`
holds (Eqs. 17-18). With a free start, a coast from the nominal perilune to the ignition
precedes the burn and the ignition epoch is optimised too.

:func:`burn_problem` builds the problem of burn ``i`` of a capture plan from the state at
the nominal perilune before it; :mod:`lunarcap.optim.nlp` transcribes it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.plan import MAX_START_MIN, CapturePlan
from lunarcap.mission.targets import ELLIPSE, Target
from lunarcap.physics._ops import ops
from lunarcap.physics.dynamics import Model, fit_for
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.forces import force_model
from lunarcap.physics.propagate import propagate
from lunarcap.physics.rocket import burn_duration_estimate_s, check_engine
from lunarcap.physics.steering import law, law_direction

#: Steering laws: the optimal time-varying direction (the paper's), a direction fixed in
#: inertial space (optimised), and thrust opposite the velocity.
STEERING_LAWS = ("optimal", "inertial", "antivelocity")

#: Margin of a burn's ephemeris fit around its pre-ignition coast, burn and coast, s.
FIT_MARGIN_S = 6 * 3600.0


#: Delta-V (m/s) whose burn duration is the least upper bound of any burn's duration.
#: Three times Eq. (19) bounds the burns of the paper (impulses of 245-353 m/s), but not a
#: small burn on a long orbit: besides its two-body impulse it must undo what the Earth
#: does to the next perilune and to the plane over that orbit, several times the impulse
#: (tests/optim/test_targets_as_asked.py has the case).
MIN_BOUND_DELTA_V_MPS = 30.0


@dataclass
class BurnProblem:
    """One burn: initial state, engine and dynamics, epochs, target, steering.

    Attributes
    ----------
    x0 : ndarray (7,)
        (p km, f, g, h, k, L rad, m kg) at ignition (with ``free_start``: at the guessed
        ignition).
    t_ign_s, t_end_s : float
        Ignition epoch and end of the coast, TDB s past J2000.
    model : Model
        Dynamics (mode, engine thrust and Isp, ephemeris fit).
    target : Target
        What must hold at ``t_end_s``.
    dv_impulsive_mps : float
        The two-body impulsive delta-V of this burn: sizes the Eq. (19) duration that
        seeds the guess and bounds the burn.
    index : int
        Burn number in its plan (1-based).
    start_min : float
        Ignition, min from ``t_perilune_s`` (the guess, with ``free_start``).
    t_perilune_s : float
        Nominal perilune epoch the ignition is counted from.
    free_start : bool
        The ignition epoch is a decision variable in ``start_bounds_min``; ``x_ref`` at
        ``t_ref_s`` is the known state the pre-ignition coast starts from.
    steering : {"optimal", "inertial", "antivelocity"}
    end_window_s : (lo, hi) or None
        For a target of free epoch (:attr:`lunarcap.mission.targets.Target.free_epoch`):
        the window of the coast's end around ``t_end_s`` (s, lo < 0 < hi); ``t_end_s`` is
        then the perilune the plan predicts (the guess), and the solution's is the
        perilune where the orbit asked holds. None: the coast ends at ``t_end_s``.
    """

    x0: np.ndarray
    t_ign_s: float
    t_end_s: float
    model: Model
    target: Target
    dv_impulsive_mps: float
    index: int = 1
    start_min: float = float("nan")
    t_perilune_s: float = float("nan")
    free_start: bool = False
    x_ref: np.ndarray | None = None
    t_ref_s: float = float("nan")
    start_bounds_min: tuple = (-60.0, 30.0)
    steering: str = "optimal"
    t1_max_s: float | None = None
    end_window_s: tuple | None = None
    #: Lower bound of the burn duration, s (None: Eq. 10's, min(1 s, half of Eq. 19));
    #: 0-ish lets a make-up burn vanish (lunarcap.studies.missed.cases).
    t1_min_s: float | None = None

    def __post_init__(self):
        self.x0 = np.asarray(self.x0, float)
        check_engine(self.model.thrust_N, self.model.isp_s, self.x0[6])
        if not self.t_end_s > self.t_ign_s:
            raise InputError("the coast must end after ignition (t_end > t_ign)")
        if self.steering not in STEERING_LAWS:
            raise InputError(f"steering must be one of {STEERING_LAWS}, got {self.steering!r}")

    @property
    def circular(self) -> bool:
        """True if the target is the circular kind."""
        return self.target.circular

    @property
    def free_end(self) -> bool:
        """True if the coast's end epoch is a decision variable (``end_window_s``)."""
        return self.end_window_s is not None

    @property
    def released_targets(self) -> frozenset:
        """Terminal conditions a closed-form steering law cannot meet and therefore leaves free.

        Thrust opposite the velocity is in-plane and has only the ignition time and the
        duration free: it keeps the perilune timing (gamma = 0 at the end epoch; for a
        circle f = g = 0) and releases the inclination and the perilune radius (the radius,
        for a circle). A fixed inertial direction (two more parameters) meets every target
        except, for a circle, its radius. What is released is reported, not gated.
        """
        if self.steering == "antivelocity":
            if self.target.kind == ELLIPSE:   # the perilune radius kept, the apolune free
                return frozenset({"inc", "e2"})
            return frozenset({"inc", "p"}) if self.circular else frozenset({"inc", "rp"})
        if self.steering == "inertial" and self.circular:
            return frozenset({"p"})
        return frozenset()

    @property
    def eq19_duration_s(self) -> float:
        """Eq. (19) burn-duration estimate from the impulsive delta-V, s."""
        return burn_duration_estimate_s(self.x0[6], self.dv_impulsive_mps,
                                        self.model.thrust_N, self.model.isp_s)

    @property
    def burn_bounds_s(self) -> tuple:
        """(lower, upper) bounds of the burn duration, s (Eq. 10).

        The upper bound is three times Eq. (19), and never below the duration of
        :data:`MIN_BOUND_DELTA_V_MPS`: a burn whose two-body impulse is a few m/s must
        also undo what the Earth and the Sun do to the next perilune over its orbit.
        """
        t19 = self.eq19_duration_s
        span = self.t_end_s + (self.end_window_s[0] if self.free_end else 0.0) - self.t_ign_s
        floor = burn_duration_estimate_s(self.x0[6], MIN_BOUND_DELTA_V_MPS,
                                         self.model.thrust_N, self.model.isp_s)
        hi = self.t1_max_s or min(max(3.0 * t19, floor), 0.9 * span)
        lo = min(1.0, 0.5 * t19) if self.t1_min_s is None else self.t1_min_s
        return lo, hi


def steering_law_expr(steering: str, X, u_in=None):
    """RTN thrust directions (3, N) of a closed-form steering law at states X (7, N).

    The law of :func:`lunarcap.physics.steering.law_direction` applied column-wise; generic
    over numpy and CasADi (the NLP imposes it at the collocation points).
    """
    import casadi as ca

    rows = law_direction(steering, [X[i, :] for i in range(6)], u_in)
    return ca.vertcat(*rows) if ops(X).casadi else np.vstack(rows)


def anti_velocity_u(x) -> np.ndarray:
    """Unit RTN direction opposite the velocity for one MEE state x (the guess steering)."""
    return law("antivelocity")(x)


#: Least half-width of a free ignition window for an ellipse as asked, and for every burn
#: in perturbed dynamics, min. A short burn that must also undo what the lunar J2, the
#: Earth and the Sun do to the next perilune over an orbit (km of perilune radius,
#: hundredths of a degree of inclination) moves the perilune radius only by burning away
#: from the perilune: within +-2 Eq. (19) durations of it IPOPT finds no solution
#: (tests/optim/test_targets_as_asked.py has the case).
MIN_ORBIT_WINDOW_MIN = 30.0

#: A target of free epoch (an ellipse as asked) holds at the perilune within this fraction
#: of its period of the perilune the plan predicts: one perilune, whatever the shift.
END_WINDOW_FRACTION = 0.2


def burn_epochs(plan: CapturePlan, i: int, t_perilune_s: float | None = None) -> tuple:
    """(perilune before burn ``i``, end of its coast, end window or None), s.

    The perilune before the burn is the plan's nominal one unless ``t_perilune_s`` gives
    the one reached (after an earlier burn whose target had a free epoch). The coast ends
    at that perilune plus the burn's coast (:meth:`CapturePlan.coast_s`): exactly there for
    the paper's formulation and a circle; for an ellipse as asked, at the perilune within
    :data:`END_WINDOW_FRACTION` of its period from there.
    """
    t = plan.nominal_perilunes_s
    t_peri = t[i] if t_perilune_s is None else float(t_perilune_s)
    if plan.start is not None and i == 0:
        t_peri = t[0]
    t_end = t_peri + plan.coast_s(i)
    target = plan.targets[i]
    if not target.free_epoch:
        return t_peri, t_end, None
    w = END_WINDOW_FRACTION * target.period_s()
    return t_peri, t_end, (-w, w)


def burn_fit(plan: CapturePlan, i: int, eph, t_perilune_s: float | None = None
             ) -> ChebyshevFit | None:
    """The ephemeris fit for burn ``i`` (0-based): its orbit and coast, +-6 h.

    None if the plan's forces read none (:func:`lunarcap.physics.dynamics.fit_for`).
    """
    t_peri, t_end, window = burn_epochs(plan, i, t_perilune_s)
    late = window[1] if window else 0.0
    return fit_for(plan.dynamics, eph, t_peri - FIT_MARGIN_S, t_end + late + FIT_MARGIN_S)


def burn_problem(plan: CapturePlan, i: int, x_perilune, eph, start_min=None,
                 thrust_N: float | None = None, start_bounds_min: tuple | None = None,
                 fit: ChebyshevFit | None = None, guess_start_min: float | None = None,
                 t_perilune_s: float | None = None, t_end_s: float | None = None
                 ) -> BurnProblem:
    """The problem of burn ``i`` (0-based) of ``plan`` from the state at its perilune.

    Parameters
    ----------
    plan : CapturePlan
    i : int
        Burn index (0-based).
    x_perilune : (7,)
        State (p, f, g, h, k, L, m) at the nominal perilune epoch before the burn (the
        arrival state, or the previous burn's verified end state).
    eph : Ephemeris
    start_min : float or "free", optional
        Overrides the plan's ignition offset (the impulsive-limit solves use this).
    thrust_N : float, optional
        Overrides the plan's thrust (the impulsive-limit solves use a huge one).
    start_bounds_min : (lo, hi), optional
        Window of a free ignition, min (default: the plan's, else +-2 Eq. (19) durations,
        at least +-:data:`MIN_ORBIT_WINDOW_MIN` for an ellipse as asked and in perturbed
        dynamics, within +-120 min and 0.4 of the orbit before the burn).
    fit : ChebyshevFit, optional
        Reuse a fit (default :func:`burn_fit`).
    guess_start_min : float, optional
        Where a free ignition's guess ignites, min (default: half the Eq. (19) duration
        before perilune, the paper's rule; inside the bounds).
    t_perilune_s : float, optional
        Epoch of ``x_perilune`` when it is not the plan's nominal perilune (the perilune
        reached after an earlier burn whose target had a free epoch), s.
    t_end_s : float, optional
        The end of the coast, fixed there (a leg of the all-burns NLP, verified at the
        perilune it reached), s.
    """
    burn = plan.burns[i]
    thrust = plan.engine.thrust_N if thrust_N is None else float(thrust_N)
    start = burn.start_min if start_min is None else start_min
    t = plan.nominal_perilunes_s
    t_peri, t_end, window = burn_epochs(plan, i, t_perilune_s)
    if t_end_s is not None:
        t_end, window = float(t_end_s), None
    model = Model(mode=plan.dynamics, thrust_N=thrust, isp_s=plan.engine.isp_s,
                  fit=fit or burn_fit(plan, i, eph, t_peri))
    dv_imp = plan.impulsive()[i].delta_v_mps
    x_perilune = np.asarray(x_perilune, float)
    free = start == "free"
    if free:
        t19 = burn_duration_estimate_s(x_perilune[6], dv_imp, thrust, plan.engine.isp_s) / 60
        guess_min = -0.5 * t19 if guess_start_min is None else float(guess_start_min)
        bounds = start_bounds_min or burn.start_bounds_min
        if bounds is None:
            lim = MAX_START_MIN if i == 0 else min(MAX_START_MIN, 0.4 * (t[i] - t[i - 1]) / 60)
            half = 2.0 * t19
            if plan.targets[i].free_epoch or force_model(plan.dynamics).perturbed:
                half = max(half, MIN_ORBIT_WINDOW_MIN)
            bounds = (max(-half, -lim), min(half, lim))
        if not bounds[0] <= guess_min <= bounds[1]:
            guess_min = 0.5 * (bounds[0] + bounds[1])
    else:
        guess_min = float(start)
        bounds = (guess_min, guess_min)
    t_ign = t_peri + 60.0 * guess_min
    x0 = propagate(model, t_peri, x_perilune, t_ign).final
    return BurnProblem(x0, t_ign, t_end, model, plan.targets[i], dv_imp, index=i + 1,
                       start_min=guess_min, t_perilune_s=t_peri, free_start=free,
                       x_ref=x_perilune, t_ref_s=t_peri, start_bounds_min=tuple(bounds),
                       steering=burn.steering, end_window_s=window)
