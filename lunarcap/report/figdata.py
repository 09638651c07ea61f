"""Data behind the book's figures: computed (and tested) here, drawn by :mod:`.figures`.

Each figure has a data function returning plain arrays in a dataclass; the drawing
functions of :mod:`lunarcap.report.figures` only draw them. Trajectories are sampled from
verified solutions (:class:`lunarcap.optim.solution.Solution`) and coasts flown by
:func:`lunarcap.optim.flight.coast`; each drawn arc keeps the
:class:`~lunarcap.physics.propagate.Trajectory` it samples.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.optim.flight import coast
from lunarcap.physics import constants as C
from lunarcap.physics.elements import rv_from_mee
from lunarcap.physics.propagate import Trajectory
from lunarcap.physics.state import State


# =============================================================================== Figs. 2-5
def orbit_plane_basis(r_km, v_kmps) -> np.ndarray:
    """Projection basis of the orbit plane through ``r`` and ``v`` (M-MME2000).

    Rows ``e_x, e_y, e_n``: ``e_n`` along the angular momentum ``r x v``; ``e_y`` the
    M-MME2000 z axis projected on the orbit plane (for the paper's polar orbit, the
    z axis itself); ``e_x = e_y x e_n``, which for a polar orbit is the direction of the
    ascending node on the M-MME2000 equator. The basis is right-handed, so the orbit
    runs counter-clockwise in (x, y).

    Parameters
    ----------
    r_km, v_kmps : array_like, shape (3,)
        Position (km) and velocity (km/s), M-MME2000.

    Returns
    -------
    ndarray, shape (3, 3)
        Rows ``e_x, e_y, e_n`` (``xy = B[:2] @ r``).
    """
    r = np.asarray(r_km, float)
    v = np.asarray(v_kmps, float)
    h = np.cross(r, v)
    if not np.isfinite(h).all() or np.linalg.norm(h) == 0:
        raise ValueError("r and v must be finite and not parallel")
    e_n = h / np.linalg.norm(h)
    z = np.array([0.0, 0.0, 1.0])
    e_y = z - (z @ e_n) * e_n
    if np.linalg.norm(e_y) < 1e-9:   # equatorial orbit: use the direction of r instead
        e_y = r - (r @ e_n) * e_n
    e_y = e_y / np.linalg.norm(e_y)
    e_x = np.cross(e_y, e_n)
    return np.vstack([e_x, e_y, e_n])


@dataclass
class DrawnArc:
    """One piece of the capture trajectory as drawn: a sampled Trajectory, projected.

    Attributes
    ----------
    kind : str
        "hyperbola" (arrival, up to the first ignition), "uncaptured" (the arrival
        hyperbola continued without the first burn), "burn", "coast" (after a burn, up to
        the next ignition) or "final" (the extra revolution after the last coast).
    burn : int
        The burn (1-based), or the burn a coast follows (0 for the hyperbola).
    label : str
        Legend text.
    traj : Trajectory
        The samples: epochs (TDB s past J2000) and MEE states.
    xy_LU : ndarray, shape (2, N)
        Position projected on the drawing plane (:func:`orbit_plane_basis`), LU.
    out_of_plane_km : ndarray, shape (N,)
        Distance from the drawing plane, km.
    """

    kind: str
    burn: int
    label: str
    traj: Trajectory
    xy_LU: np.ndarray
    out_of_plane_km: np.ndarray

    @property
    def t_s(self) -> np.ndarray:
        """Epochs, TDB s past J2000."""
        return self.traj.t

    @property
    def r_km(self) -> np.ndarray:
        """Position, M-MME2000, km, shape (3, N)."""
        return np.array(rv_from_mee(*self.traj.x[:6], C.MU_MOON)[0], float)

    @property
    def radius_km(self) -> np.ndarray:
        """Distance from the Moon's centre, km."""
        return np.linalg.norm(self.r_km, axis=0)

    @property
    def angle_deg(self) -> np.ndarray:
        """Polar angle in the drawing plane, deg (counter-clockwise from e_x)."""
        return np.degrees(np.arctan2(self.xy_LU[1], self.xy_LU[0]))


@dataclass
class CaptureGeometry:
    """Data of Figs. 2 and 3: the whole capture sequence projected on the orbit plane.

    Attributes
    ----------
    basis : ndarray, shape (3, 3)
        Rows e_x, e_y, e_n of the drawing plane in M-MME2000 (:func:`orbit_plane_basis`
        of the arrival perilune state).
    arcs : list of DrawnArc
        In time order (the "uncaptured" arc last).
    burns : pandas.DataFrame
        One row per burn: ignition and cutoff epochs and polar angles, the pass's perilune
        (the flown point of least radius within 30 min of the nominal perilune epoch) and
        the angles of ignition and cutoff from it, the burn's radii.
    hyperbola_hours : float
        Length of the drawn arrival hyperbola before the arrival perilune, h.
    """

    basis: np.ndarray
    arcs: list
    burns: object
    hyperbola_hours: float

    def select(self, kind: str, burn: int | None = None) -> list:
        """The arcs of one kind (and burn)."""
        return [a for a in self.arcs if a.kind == kind and (burn is None or a.burn == burn)]

    @property
    def max_out_of_plane_km(self) -> float:
        """Largest distance of any drawn point from the drawing plane, km."""
        return float(max(np.abs(a.out_of_plane_km).max() for a in self.arcs))

    def pass_profiles(self, window_s: float = 2400.0) -> list[dict]:
        """Altitude against angle from each pass's perilune, around each burn (Fig. 3b).

        Returns
        -------
        list of dict
            One per (burn, flown arc) overlapping [ignition - window, cutoff + window]:
            ``burn``, ``kind`` ("burn" or the coasting kinds), ``angle_deg`` (polar angle
            in the orbit plane from that pass's perilune, wrapped to [-180, 180)),
            ``altitude_km``.
        """
        flown = [a for a in self.arcs if a.kind in ("hyperbola", "coast", "burn", "final")]
        out = []
        for _, row in self.burns.iterrows():
            t_lo, t_hi = row.ignition_s - window_s, row.cutoff_s + window_s
            for a in flown:
                m = (a.t_s >= t_lo) & (a.t_s <= t_hi)
                if m.any():
                    out.append({"burn": int(row.burn), "kind": a.kind,
                                "angle_deg": _wrap180(a.angle_deg[m] - row.perilune_angle_deg),
                                "altitude_km": a.radius_km[m] - C.R_MOON})
        return out


def _project(basis, r_km):
    r = np.asarray(r_km, float)
    return (basis[:2] @ r) / C.LU_KM, basis[2] @ r


def _make_arc(basis, kind, burn, label, t, x):
    """A DrawnArc of MEE states x (7, N) at epochs t."""
    traj = Trajectory(np.asarray(t, float), np.asarray(x, float)[:7])
    r = np.array(rv_from_mee(*traj.x[:6], C.MU_MOON)[0], float)
    xy, oop = _project(basis, r)
    return DrawnArc(kind, burn, label, traj, xy, oop)


def _ordinal(n: int) -> str:
    return f"{n}{'th' if 10 <= n % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(n % 10, 'th')}"


def orbit_name(prob) -> str:
    """Legend name of the orbit a burn reaches: '1st capture orbit (12.235 h)', ..."""
    coast = prob.t_end_s - prob.t_perilune_s
    if prob.target.circular:
        return f"final circular orbit ({coast / 60:.6g} min)"
    return f"{_ordinal(prob.index)} capture orbit ({coast / 3600:.6g} h)"


def _dense_grid(t0, t1, n, edge_s=1800.0):
    """Epochs from t0 to t1: n uniform plus n/2 within ``edge_s`` of each end (perilunes)."""
    lo, hi = min(t0, t1), max(t0, t1)
    parts = [np.linspace(lo, hi, n),
             np.linspace(lo, min(lo + edge_s, hi), n // 2),
             np.linspace(max(hi - edge_s, lo), hi, n // 2)]
    return np.unique(np.concatenate(parts))


def _wrap180(a):
    return (np.asarray(a, float) + 180.0) % 360.0 - 180.0


def _hyperbola_arc(basis, arrival, p1, hyperbola_hours: float) -> DrawnArc:
    """The arrival hyperbola, propagated backward from the arrival perilune, to ignition 1."""
    model = p1.model
    t_peri = float(arrival.epoch_s)
    # arrival hyperbola: backward from the arrival perilune, drawn up to LOI-1 ignition
    t_start = t_peri - 3600.0 * float(hyperbola_hours)
    if not t_start < p1.t_ign_s:
        raise ValueError("hyperbola_hours must reach back before the first ignition")
    x_peri = np.asarray(arrival.state, float)
    t_back = np.linspace(p1.t_ign_s, t_start, 1500)
    peri = State(t_peri, x_peri)
    if p1.t_ign_s < t_peri:
        tr = coast(model, peri, t_start, t_eval=t_back).arc
        t_h, x_h = tr.t[::-1], tr.x[:, ::-1]
    else:  # ignition at or after the arrival perilune
        tr = coast(model, peri, t_start, t_eval=np.linspace(t_peri, t_start, 1500)).arc
        fw = coast(model, peri, p1.t_ign_s,
                   t_eval=np.linspace(t_peri, p1.t_ign_s, 200)[1:]).arc
        t_h = np.concatenate([tr.t[::-1], fw.t])
        x_h = np.column_stack([tr.x[:, ::-1], fw.x])
    return _make_arc(basis, "hyperbola", 0, "arrival hyperbola", t_h, x_h)


def _burn_and_coast_arcs(basis, sols: list, n_burn: int, n_coast: int) -> list:
    """Each burn's arc and the coast after it, up to the next ignition (or the last end)."""
    arcs = []
    coasts_end = [s.problem.t_ign_s for s in sols[1:]] + [sols[-1].problem.t_end_s]
    for i, sol in enumerate(sols):
        prob = sol.problem
        k = prob.index
        hist = sol.history(n_burn=n_burn, n_coast=2)
        b = hist[hist.phase == "burn"]
        xb = b[["p_km", "f", "g", "h", "k", "L_rad", "m_kg"]].to_numpy().T
        arcs.append(_make_arc(basis, "burn", k, f"burn {k}", b.t_s.to_numpy(), xb))
        t_cut = float(b.t_s.iloc[-1])
        tc = _dense_grid(t_cut, coasts_end[i], n_coast)
        arcs.append(_make_arc(basis, "coast", k, orbit_name(prob), tc, sol.flight.coast(tc)))
    return arcs


def _extra_arcs(basis, sols: list, arrival, final_revolutions: float,
                uncaptured_hours: float) -> list:
    """One more revolution of a final circle, and the hyperbola flown on without burn 1."""
    arcs = []
    last, p1 = sols[-1], sols[0].problem
    if final_revolutions > 0 and last.problem.target.circular:
        t0 = last.problem.t_end_s
        t1 = t0 + final_revolutions * (t0 - last.problem.t_perilune_s)
        tf = np.linspace(t0, t1, max(int(600 * final_revolutions), 50))
        tr = coast(last.problem.model, State(t0, last.end_state), t1, t_eval=tf).arc
        arcs.append(_make_arc(basis, "final", last.problem.index,
                              "final orbit, one more revolution", tr.t, tr.x))
    if uncaptured_hours and uncaptured_hours > 0:
        t1 = float(arrival.epoch_s) + 3600.0 * float(uncaptured_hours)
        tu = np.linspace(p1.t_ign_s, t1, 1500)
        tr = coast(p1.model, State(p1.t_ign_s, p1.x0), t1, t_eval=tu).arc
        arcs.append(_make_arc(basis, "uncaptured", 0, "arrival hyperbola without burn 1",
                              tr.t, tr.x))
    return arcs


def flown_perilune(t_s, r_km, xy, t_nominal_s: float, window_s: float) -> tuple:
    """The flown point of least radius within ``window_s`` of a nominal perilune epoch.

    ``t_s`` (n,), ``r_km`` (3, n) and ``xy`` (2, n, the drawing plane) sample the flight.
    Returns its epoch (s), radius (km) and polar angle in the drawing plane (deg).
    """
    near = np.abs(t_s - t_nominal_s) <= window_s
    rad = np.linalg.norm(r_km[:, near], axis=0)
    j = int(np.argmin(rad))
    ang = float(np.degrees(np.arctan2(xy[1, near][j], xy[0, near][j])))
    return float(t_s[near][j]), float(rad[j]), ang


def _burn_rows(arcs: list, sols: list, perilune_window_s: float):
    """One row per burn: timing, the flown perilune, angles and radii of the burn arc."""
    import pandas as pd

    flown = [a for a in arcs if a.kind != "uncaptured"]
    t_all = np.concatenate([a.t_s for a in flown])
    r_all = np.concatenate([a.r_km for a in flown], axis=1)
    xy_all = np.concatenate([a.xy_LU for a in flown], axis=1)
    rows = []
    for sol in sols:
        prob = sol.problem
        burn = [a for a in arcs if a.kind == "burn" and a.burn == prob.index][0]
        t_p, r_p, ang_p = flown_perilune(t_all, r_all, xy_all, prob.t_perilune_s,
                                         perilune_window_s)
        ang = burn.angle_deg
        rows.append({
            "burn": prob.index, "ignition_s": float(burn.t_s[0]), "cutoff_s": float(burn.t_s[-1]),
            "burn_duration_min": float(burn.t_s[-1] - burn.t_s[0]) / 60.0,
            "ignition_from_nominal_perilune_min": (burn.t_s[0] - prob.t_perilune_s) / 60.0,
            "perilune_from_ignition_min": (t_p - burn.t_s[0]) / 60.0,
            "perilune_radius_km": r_p,
            "perilune_angle_deg": ang_p,
            "ignition_angle_deg": float(ang[0]), "cutoff_angle_deg": float(ang[-1]),
            "ignition_from_perilune_deg": float(_wrap180(ang[0] - ang_p)),
            "cutoff_from_perilune_deg": float(_wrap180(ang[-1] - ang_p)),
            "ignition_radius_km": float(burn.radius_km[0]),
            "cutoff_radius_km": float(burn.radius_km[-1]),
            "min_radius_km": float(burn.radius_km.min()),
        })
    burns = pd.DataFrame(rows)
    burns["arc_asymmetry_deg"] = burns.cutoff_from_perilune_deg + burns.ignition_from_perilune_deg
    return burns


def capture_geometry(solutions, arrival, hyperbola_hours: float = 3.0,
                     uncaptured_hours: float | None = None, n_coast: int = 3000,
                     n_burn: int = 241, final_revolutions: float = 1.0,
                     perilune_window_s: float = 1800.0) -> CaptureGeometry:
    """Sample the capture sequence for Figs. 2 and 3.

    Parameters
    ----------
    solutions : list of Solution
        A plan's burns in order (:func:`lunarcap.capture.chain.solve_plan`).
    arrival : lunarcap.mission.arrival.Arrival
        The arrival perilune state; defines the drawing plane.
    hyperbola_hours : float
        The arrival hyperbola is drawn from this many hours before the arrival perilune
        (propagated backward from it, coasting, in the first burn's dynamics) to the first
        ignition.
    uncaptured_hours : float, optional
        Draw the hyperbola without the first burn, from its ignition to this many hours
        after the arrival perilune (default ``hyperbola_hours``; 0 to leave it out).
    n_coast, n_burn : int
        Samples per coast (plus extra near its ends) and per burn.
    final_revolutions : float
        Revolutions of the final orbit propagated after the last coast (coasting), in
        units of the last coast (for the paper: the final period 117.848 min).
    perilune_window_s : float
        Half-width of the window around each nominal perilune epoch in which the flown
        perilune of a pass is looked for, s.

    Returns
    -------
    CaptureGeometry
    """
    sols = list(solutions)
    if not sols or [s.problem.index for s in sols] != list(range(1, len(sols) + 1)):
        raise ValueError("solutions must be a plan's burns 1, 2, ... in order")
    basis = orbit_plane_basis(arrival.r_km, arrival.v_kmps)
    hu = hyperbola_hours if uncaptured_hours is None else uncaptured_hours
    arcs = ([_hyperbola_arc(basis, arrival, sols[0].problem, hyperbola_hours)]
            + _burn_and_coast_arcs(basis, sols, n_burn, n_coast)
            + _extra_arcs(basis, sols, arrival, final_revolutions, hu))
    burns = _burn_rows(arcs, sols, perilune_window_s)
    return CaptureGeometry(basis, arcs, burns, float(hyperbola_hours))


@dataclass
class Fig4Steering:
    """Data of Fig. 4: thrust angles and mass during one burn.

    Attributes
    ----------
    t_min : ndarray, shape (N,)
        Time from ignition, min.
    alpha_deg, beta_deg : ndarray, shape (N,)
        In-plane and out-of-plane thrust angles of Eq. (14), deg.
    m_kg : ndarray, shape (N,)
        Mass, kg.
    perilune_min : float
        Nominal perilune epoch of the pass, min from ignition.
    burn : int
    thrust_N, isp_s : float
    """

    t_min: np.ndarray
    alpha_deg: np.ndarray
    beta_deg: np.ndarray
    m_kg: np.ndarray
    perilune_min: float
    burn: int
    thrust_N: float
    isp_s: float

    @property
    def burn_duration_min(self) -> float:
        """Burn duration, min."""
        return float(self.t_min[-1] - self.t_min[0])

    def table(self):
        """The data as a DataFrame (CSV-ready, units in the column names)."""
        import pandas as pd

        return pd.DataFrame({"min_from_ignition": self.t_min, "alpha_deg": self.alpha_deg,
                             "beta_deg": self.beta_deg, "m_kg": self.m_kg})


def fig4_steering(solution, n: int = 241) -> Fig4Steering:
    """Thrust angles (Eq. (14)) and mass along the burn of a Solution (Fig. 4).

    Parameters
    ----------
    solution : Solution
    n : int
        Samples over the burn.

    Returns
    -------
    Fig4Steering
    """
    h = solution.history(n_burn=n, n_coast=2)
    b = h[h.phase == "burn"]
    prob = solution.problem
    return Fig4Steering(b.min_from_ignition.to_numpy(), b.alpha_deg.to_numpy(),
                        b.beta_deg.to_numpy(), b.m_kg.to_numpy(),
                        (prob.t_perilune_s - prob.t_ign_s) / 60.0, int(prob.index),
                        float(prob.model.thrust_N), float(prob.model.isp_s))
