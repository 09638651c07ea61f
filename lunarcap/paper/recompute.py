"""The paper's own arithmetic redone: rocket equation, Eq. (19), mass chains, fuel.

Helpers of the audit (:mod:`lunarcap.paper.audit`) that recompute, in the paper's
units (kg, m/s, N, s, min), the masses, propellant and burn durations its printed
delta-Vs imply, and the arrival mass its printed results imply.
"""

from __future__ import annotations

from lunarcap.paper import printed as P
from lunarcap.paper.finding import (
    _IMP,
    _LOIS,
    _THRUSTS,
    _qv,
)
from lunarcap.physics.rocket import (
    exhaust_speed_mps,
    rocket_mass_after,
    rocket_mass_before,
    rocket_propellant_kg,
)

# ---------------------------------------------------------------------------------------
# physics helpers (SI-ish units of the paper: kg, m/s, N, s, min)
# ---------------------------------------------------------------------------------------


# The rocket equation is physics.rocket's (named as the audit's modules call it).
_ve = exhaust_speed_mps
_mass_after = rocket_mass_after
_fuel = rocket_propellant_kg


def _burn_min(m0_kg, dv_mps, thrust_N, isp_s):
    """Duration of a constant-thrust burn giving dv (= Eq. (19) with m_f corrected), min."""
    return _fuel(m0_kg, dv_mps, isp_s) * _ve(isp_s) / thrust_N / 60.0


def _fuel_from_burn(thrust_N, t_min, isp_s):
    """Propellant burnt at constant thrust in t minutes, T t / (g0 Isp), kg."""
    return thrust_N * t_min * 60.0 / _ve(isp_s)


def _best_dvs(thrust_N):
    return [P.paper_best(thrust_N, n)["delta_v_mps"] for n in _LOIS]


def _finite_chain(thrust_N, m0_kg):
    """Masses before LOI 1, 2, 3 and after LOI 3 with Table B1's best delta-Vs, kg."""
    isp = P.PAPER_ENGINES[thrust_N]
    ms = [m0_kg]
    for dv in _best_dvs(thrust_N):
        ms.append(_mass_after(ms[-1], dv, isp))
    return ms


def _impulsive_chain(isp_s, m0_kg):
    """Masses before LOI 1, 2, 3 and after LOI 3 with the impulsive delta-Vs, kg."""
    ms = [m0_kg]
    for dv in _IMP:
        ms.append(_mass_after(ms[-1], dv, isp_s))
    return ms


def implied_arrival_mass_kg() -> dict:
    """Arrival mass implied by each printed result that depends on it, kg.

    Returns
    -------
    dict
        ``"150N mass after LOI 1"``: 434.471 exp(367.415/(g0 200));
        ``"300N final mass"``: 369.289 exp(sum of Table B1 300 N delta-Vs/(g0 250));
        ``"450N final mass"``: likewise with 391.722 kg; ``"150N total burn time"``:
        335.750 + T t/(g0 Isp) with t = 41.02 min; ``"450N total burn time"``;
        ``"150N Eq. (19) LOI 1"``: the m0 for which Eq. (19) gives 18.82 min.
    """
    isp150, isp300, isp450 = (P.PAPER_ENGINES[t] for t in _THRUSTS)
    out = {
        "150N mass after LOI 1": rocket_mass_before(_qv("mass_after_loi1_150N_kg"),
                                                    _best_dvs(150)[0], isp150),
        "300N final mass": rocket_mass_before(_qv("mass_final_300N_kg"), sum(_best_dvs(300)),
                                              isp300),
        "450N final mass": rocket_mass_before(_qv("mass_final_450N_kg"), sum(_best_dvs(450)),
                                              isp450),
        "150N total burn time": _qv("mass_final_150N_kg")
        + _fuel_from_burn(150, _qv("burn_total_150N_min"), isp150),
        "450N total burn time": _qv("mass_final_450N_kg")
        + _fuel_from_burn(450, _qv("burn_total_450N_min"), isp450),
        "150N Eq. (19) LOI 1": _fuel_from_burn(150, _qv("eq19_loi1_150N_min"), isp150)
        / rocket_propellant_kg(1.0, _IMP[0], isp150),
    }
    return out


def _m0_star() -> float:
    """Arrival mass implied by the printed mass after LOI 1 (150 N), kg."""
    return implied_arrival_mass_kg()["150N mass after LOI 1"]


def _printed_mass_starts():
    """Start masses of LOI 1-3 consistent with the paper's printed masses, kg.

    150 N: LOI 1 starts at 434.471 exp(367.415/(g0 Isp)) (the printed mass after LOI 1
    taken back through Table B1's delta-V), LOI 2 and 3 at the printed 434.471 and
    381.005 kg. 300 N and 450 N: the printed final mass taken back through Table B1's
    delta-Vs. Returns ``({thrust: [(mass, half_width), ...]}, {thrust: [label, ...]})``.
    """
    starts, src = {}, {}
    m1, m2 = _qv("mass_after_loi1_150N_kg"), _qv("mass_after_loi2_150N_kg")
    isp150 = P.PAPER_ENGINES[150]
    starts[150] = [(rocket_mass_before(m1, _best_dvs(150)[0], isp150), 0.0006), (m1, 0.0005),
                   (m2, 0.0005)]
    src[150] = ["printed 434.471 kg after LOI 1 taken back through 367.415 m/s",
                "printed mass after LOI 1", "printed mass after LOI 2"]
    for t in (300, 450):
        isp = P.PAPER_ENGINES[t]
        dvs = _best_dvs(t)
        mf = _qv(f"mass_final_{t}N_kg")
        starts[t] = [(rocket_mass_before(mf, sum(dvs[n:]), isp), 0.0006) for n in range(3)]
        src[t] = [f"printed final mass {mf:.3f} kg taken back through Table B1's delta-Vs"] * 3
    return starts, src


def fuel_sentence_check(thrust_N: int) -> dict:
    """Compare a fuel-mass sentence of Sec. 3.2 with the rocket equation.

    Parameters
    ----------
    thrust_N : {150, 300, 450}
        Engine thrust, N.

    Returns
    -------
    dict
        ``printed_finite_kg``, ``printed_impulsive_kg`` (as labelled in the paper),
        ``computed_finite_kg`` (524.895 kg through Table B1's best delta-Vs),
        ``computed_impulsive_kg`` (524.895 kg through 353.272 + 254.034 + 245.363 m/s),
        ``mismatch_as_labelled_kg`` and ``mismatch_if_swapped_kg`` (sums of absolute
        differences) and ``labels_swapped`` (True if swapping the two printed labels
        fits the computation better).
    """
    key = {150: ("fuel_finite_150N_kg", "fuel_impulsive_150N_kg"),
           300: ("fuel_finite_300N_kg", "fuel_impulsive_300N_kg"),
           450: ("fuel_finite_450N_kg", "fuel_impulsive_450N_kg")}[int(thrust_N)]
    isp = P.PAPER_ENGINES[int(thrust_N)]
    m0 = _qv("arrival_mass_kg")
    pf, pi = _qv(key[0]), _qv(key[1])
    cf = m0 - _finite_chain(int(thrust_N), m0)[-1]
    ci = m0 - _impulsive_chain(isp, m0)[-1]
    as_lab = abs(pf - cf) + abs(pi - ci)
    swapped = abs(pf - ci) + abs(pi - cf)
    return {"printed_finite_kg": pf, "printed_impulsive_kg": pi, "computed_finite_kg": cf,
            "computed_impulsive_kg": ci, "mismatch_as_labelled_kg": as_lab,
            "mismatch_if_swapped_kg": swapped, "labels_swapped": swapped < as_lab}


