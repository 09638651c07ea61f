"""A solved capture flown open loop in other conditions: other forces, GMAT's defaults.

:func:`fly_open_loop` flies the burns of a solved plan one after the other from the
state of its first ignition, with nothing closing the loop: each burn ignites at its
planned epoch, lasts its planned duration and steers as planned, then the spacecraft
coasts to the next ignition and, after the last burn, to the epoch where the design's
last target holds (the circle's epoch of the paper's capture). The steering is *held*

* ``rtn``: the collocated steering as a function of the time since ignition, in the RTN
  axes of the orbit actually flown (an attitude law referenced to the local orbit);
* ``inertial``: the direction the design flew, fixed in inertial axes over segments of
  :data:`lunarcap.capture.export.GMAT_SEGMENT_S` (as the exported GMAT script flies it,
  :func:`lunarcap.capture.export.gmat_burn`);
* ``one-direction``: one inertial direction per burn, the burn's mean thrust direction
  (:func:`lunarcap.exchange.burn_files.mean_direction`): what a thruster pointed once does.

The flight starts at the design's state at the first ignition, or ``approach_s`` before
it (the design's state flown back there: the approach is then flown in the other forces
too, as GMAT flies the exported capture from its start). The forces may be other than
the design's (``dynamics``: a lunar gravity field, the pole
of date), and so may the engine's standard gravity (``g0_mps2``) and the Moon's GM
(``mu``): the defaults GMAT would otherwise take. :class:`OpenLoop` holds the states at
each event, their distances from the design's (m, mm/s) and the final orbit.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from lunarcap.capture.chain import after_capture, plan_result
from lunarcap.capture.export import burn_samples, gmat_burn
from lunarcap.errors import InputError
from lunarcap.exchange.burn_files import mean_direction
from lunarcap.optim.flight import BurnPlan, burn_arc, coast, fly
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model, fit_for, force_model
from lunarcap.physics.elements import mee_from_rv, orbit_summary, rv_from_mee
from lunarcap.physics.frames import mme_from_icrf
from lunarcap.physics.propagate import propagate
from lunarcap.physics.state import MASS, State
from lunarcap.physics.steering import law
from lunarcap.repro.cache import cached

HOLDS = ("rtn", "inertial", "one-direction")
IGNITION, CUTOFF, END = "ignition", "cut-off", "end"


@dataclass
class OpenLoop:
    """A capture flown open loop, against its design.

    Attributes
    ----------
    dynamics : str
        The forces flown (label).
    hold : str
        How the steering was held (:data:`HOLDS`).
    events : list of dict
        Per event (``burn``, ``event``: ignition, cut-off or end; ``epoch_s``): the
        distance of the flown state from the design's, ``position_diff_m`` and
        ``velocity_diff_mmps``, and ``mass_diff_kg``.
    final : dict
        At the end: the osculating perilune and apolune altitudes (km) and inclination
        (deg, about the plan's frame's pole) flown (``rp_alt_km``, ``ra_alt_km``,
        ``inc_deg``) and the design's (``design_rp_alt_km``, ...), and the distance from
        the design's state, ``miss_km`` (and ``miss_mps``).
    states : dict
        (burn, event) -> State flown.
    mu : float
        The Moon's GM of the flight (km^3/s^2): its states' elements are with it.
    """

    dynamics: str
    hold: str
    events: list
    final: dict
    states: dict = field(default_factory=dict, repr=False)
    mu: float = C.MU_MOON

    @property
    def end(self) -> State:
        """The state flown at the end (the epoch where the design's last target holds)."""
        return next(s for (_, e), s in self.states.items() if e == END)


def design_states(result) -> dict:
    """(burn, event) -> State of the design's verified flight: each ignition and cut-off, end.

    ``end``: the end of the last burn's coast (where its target holds).
    """
    out = {}
    for k, b in enumerate(result.burns, 1):
        fl = b.solution.flight
        out[(k, IGNITION)] = State(float(fl.burn.t[0]), fl.burn.x[:MASS + 1, 0])
        out[(k, CUTOFF)] = fl.cutoff
    fl = result.burns[-1].solution.flight
    out[(len(result.burns), END)] = State(float(fl.coast.t[-1]), fl.end_state[:MASS + 1])
    return out


def capture_model(result, dynamics=None, mu: float | None = None, approach_s: float = 0.0
                  ) -> Model:
    """A coast model of ``dynamics`` (default the plan's) over the whole capture.

    Its ephemeris fit spans ``approach_s`` before the first ignition to the end, 1 h more
    on each side; ``mu``: the Moon's GM (km^3/s^2), default lunarcap's.
    """
    ev = design_states(result)
    t0 = ev[(1, IGNITION)].t_s - approach_s
    t1 = ev[(len(result.burns), END)].t_s
    dyn = result.plan.dynamics if dynamics is None else dynamics
    fit = fit_for(dyn, result.plan.ephemeris_model(), t0 - 3600.0, t1 + 3600.0)
    return Model(dyn, 0.0, result.plan.engine.isp_s, fit, mu=C.MU_MOON if mu is None else mu)


def _inertial_segments(sol, pole: str, hold: str) -> tuple:
    """(durations (N,) s, M-MME2000 unit directions (3, N)) of a burn held in inertial axes."""
    arc = burn_arc("burn", sol.raw, sol.flight)
    if hold == "inertial":
        b = gmat_burn(sol, arc, pole)
        return b.durations_s, mme_from_icrf(b.u_icrf, pole)
    smp = burn_samples(sol, arc, pole)
    u = mean_direction(smp["t_s"], smp["u_icrf"], smp["thrust_N"], smp["mass_kg"])
    return np.array([sol.raw.t1_s]), mme_from_icrf(u[:, None], pole)


def _fly_burn(sol, model: Model, start: State, hold: str, pole: str) -> tuple:
    """(state at ignition, state at cut-off) of one burn flown from ``start``."""
    plan = BurnPlan.of(sol.raw)
    burn_model = replace(model, thrust_N=plan.model.thrust_N)
    if hold == "rtn":
        flown = fly(plan.moved(plan.t_ign_s, burn_model), start)
        return flown.start, flown.end
    x = np.asarray(start.x, float)
    if start.t_s != plan.t_ign_s:
        x = propagate(burn_model, start.t_s, x, plan.t_ign_s).final
    ignition, t = State(plan.t_ign_s, x), 0.0
    durations, u = _inertial_segments(sol, pole, hold)
    for j, dt in enumerate(durations):
        x = propagate(burn_model, plan.t_ign_s + t, x, None, u=law("inertial", u[:, j]),
                      duration_s=dt).final
        t += dt
    return ignition, State(plan.t_ign_s + t, x)


def _diff(a: State, b: State, mu_a: float = C.MU_MOON, mu_b: float = C.MU_MOON) -> dict:
    (ra, va), (rb, vb) = (rv_from_mee(*s.x[:6], mu) for s, mu in ((a, mu_a), (b, mu_b)))
    return {"position_diff_m": float(np.linalg.norm(np.subtract(ra, rb)) * 1e3),
            "velocity_diff_mmps": float(np.linalg.norm(np.subtract(va, vb)) * 1e6),
            "mass_diff_kg": a.mass_kg - b.mass_kg}


def apart(a: OpenLoop, b: OpenLoop, key=None) -> dict:
    """How far two flights of one plan are apart at an event (default the end).

    ``key``: (burn, event) of :attr:`OpenLoop.states`. Returns ``position_diff_m``,
    ``velocity_diff_mmps``, ``mass_diff_kg`` (a's minus b's), and at the end the changes of
    the final orbit's perilune and apolune altitudes, ``rp_diff_m`` and ``ra_diff_m``.
    """
    if key is None:
        key = next(k for k in a.states if k[1] == END)
    out = _diff(a.states[key], b.states[key], a.mu, b.mu)
    if key[1] == END:
        out["rp_diff_m"] = (a.final["rp_alt_km"] - b.final["rp_alt_km"]) * 1e3
        out["ra_diff_m"] = (a.final["ra_alt_km"] - b.final["ra_alt_km"]) * 1e3
    return out


def _orbit(x, prefix: str = "", mu: float = C.MU_MOON) -> dict:
    o = orbit_summary(x, mu)
    return {f"{prefix}rp_alt_km": o["rp_km"] - C.R_MOON, f"{prefix}ra_alt_km":
            o["ra_km"] - C.R_MOON, f"{prefix}inc_deg": o["inc_deg"]}


def approach_start(result, approach_s: float) -> State:
    """The design's state ``approach_s`` before its first ignition, in the design's forces.

    Where the exported capture starts (:data:`lunarcap.capture.export.APPROACH_MIN`), flown
    back from the first ignition in the first burn's model.
    """
    ign = design_states(result)[(1, IGNITION)]
    model = result.burns[0].solution.problem.model
    return State(ign.t_s - approach_s,
                 propagate(model, ign.t_s, ign.x, ign.t_s - approach_s).final)


def fly_open_loop(result, dynamics=None, hold: str = "rtn", g0_mps2: float | None = None,
                  mu: float | None = None, approach_s: float = 0.0) -> OpenLoop:
    """Fly a solved plan's burns open loop (see the module docstring).

    Parameters
    ----------
    result : PlanResult
        The design (every burn verified).
    dynamics : a preset word, ForceModel or ``dynamics`` mapping, optional
        The forces flown (default the plan's).
    hold : {"rtn", "inertial", "one-direction"}
    g0_mps2 : float, optional
        The standard gravity of the engine's mass flow T / (g0 Isp), m/s^2 (default
        lunarcap's 9.80665).
    mu : float, optional
        The Moon's GM, km^3/s^2 (default lunarcap's).
    approach_s : float
        Start this long before the first ignition (s; the design's state there,
        :func:`approach_start`), so that the approach too is flown in ``dynamics``; 0:
        from the design's state at the first ignition.
    """
    if hold not in HOLDS:
        raise InputError(f"hold must be one of {', '.join(HOLDS)}, got {hold!r}")
    if not all(b.solution.verification.passed for b in result.burns):
        raise InputError(f"plan {result.plan.name}: a burn failed verification")
    design = design_states(result)
    model = capture_model(result, dynamics, mu, approach_s)
    if g0_mps2 is not None:   # T / (g0' Isp) = T / (g0 Isp'), Isp' = Isp g0' / g0
        model = replace(model, isp_s=model.isp_s * g0_mps2 / C.G0_MPS2)
    pole = result.plan.lunar_pole
    state, flown = design[(1, IGNITION)], {}
    if approach_s > 0:
        state = approach_start(result, approach_s)
    if model.mu != C.MU_MOON:   # the same position and velocity, elements of the other GM
        r, v = rv_from_mee(*state.x[:6], C.MU_MOON)
        state = State(state.t_s, np.append(mee_from_rv(r, v, model.mu), state.x[MASS]))
    for k, b in enumerate(result.burns, 1):
        flown[(k, IGNITION)], state = _fly_burn(b.solution, model, state, hold, pole)
        flown[(k, CUTOFF)] = state
    n = len(result.burns)
    t_end = design[(n, END)].t_s
    flown[(n, END)] = coast(model, state, t_end).end
    events = [{"burn": k, "event": e, "epoch_s": flown[(k, e)].t_s,
               **_diff(flown[(k, e)], design[(k, e)], model.mu)} for (k, e) in flown]
    end = _diff(flown[(n, END)], design[(n, END)], model.mu)
    final = {**_orbit(flown[(n, END)].x, mu=model.mu), **_orbit(design[(n, END)].x, "design_"),
             "miss_km": end["position_diff_m"] * 1e-3,
             "miss_mps": end["velocity_diff_mmps"] * 1e-3}
    return OpenLoop(force_model(model.mode).label, hold, events, final, flown, model.mu)


# ---------------------------------------------------------------------- cached, by plan
@cached
def open_loop(plan, dynamics=None, hold: str = "rtn", approach_s: float = 0.0,
              g0_mps2: float | None = None, mu: float | None = None) -> OpenLoop:
    """:func:`fly_open_loop` of a plan's verified design (solved or fetched), cached on disk."""
    return fly_open_loop(plan_result(plan, impulsive=False), dynamics, hold, g0_mps2, mu,
                         approach_s)


@cached
def evolution(plan, days: float, dynamics=None, rtol: float | None = None):
    """The design's final orbit flown ``days`` in ``dynamics``, cached on disk.

    :func:`lunarcap.capture.chain.after_capture` of the plan's verified design (``rtol``:
    the propagation's tolerance, default the propagator's); the
    :class:`~lunarcap.physics.evolution.Evolution` keeps its per-revolution histories,
    and of its sampled states (10 s apart) only the first and the last.
    """
    from lunarcap.physics.propagate import Trajectory

    ev = after_capture(plan_result(plan, impulsive=False), days, dynamics, rtol)
    tr = ev.trajectory
    return replace(ev, trajectory=Trajectory(tr.t[[0, -1]], tr.x[:, [0, -1]], tr.nfev))
