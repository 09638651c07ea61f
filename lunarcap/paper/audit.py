"""Internal consistency of Song et al. (2011), recomputed from the printed numbers.

Song, Park, Kim, Lee & Sim (2011), J. Astron. Space Sci. 28(3) 203-216 ("Song 2011").
Every finding takes the numbers of :mod:`lunarcap.paper.printed` as printed, recomputes one of
them from the others (arithmetic, the rocket equation, Eq. (19), the two-body period,
the epochs) and compares. Nothing is concluded by hand: each verdict is
``|printed - computed| <= tolerance`` and each explanation is formatted from computed
numbers.

Tolerances
----------
* **Rounding.** Half a unit of the last printed digit of the checked number, plus the
  linear propagation of half a unit of the last digit of every printed input
  (:func:`_propagate`).
* **Truncation.** The paper sometimes truncates instead of rounding (e.g. Table 1,
  -12 min: 4.3188 % printed 4.31). Percentages and "about" restatements of printed
  numbers are therefore also accepted when they equal the exact value truncated to the
  printed digits (``rule="round-or-truncate"``); the explanation says which applied.
* **Solver.** Relations between two outputs of the optimiser (a mass and a delta-V, a
  burn duration and a delta-V) hold exactly for the continuous problem: with constant
  thrust T and mass flow T/(g0 Isp), the finite-burn delta-V of Eq. (11) integrates to
  the rocket equation, dV = g0 Isp ln(m0/mf), and the burn lasts (m0 - mf) g0 Isp / T.
  The paper does not state SOCS's tolerances; :data:`SOLVER_REL_TOL` (1e-4 of the
  computed value) is allowed on top of rounding for these relations.
* **Print resolution of a compared duration.** A table row's burn duration is compared
  with the duration recomputed from the same row's delta-V, and the audit states that
  recomputation at the printed resolution (0.01 min, "printed 11.74 min, recomputed
  11.73 min"). Two durations each known only to the printed digit cannot contradict
  each other by less than one unit of that digit, so the rows allow half a unit for the
  printed duration plus half a unit for the recomputed one
  (:data:`DURATION_RESOLUTION_MIN`), on top of the propagated rounding of the row's
  delta-V and start mass and the solver allowance. Table 2, -3 min (11.74 printed,
  11.7301 recomputed: 0.0099 min, 0.85e-3 relative) is within this; Table 3, -3 min
  (10.81 against 10.02 min) is not.

g0 = 9.80665 m/s^2 (:data:`lunarcap.physics.constants.G0_MPS2`).

Examples
--------
>>> t = findings_table()
>>> bool((t.verdict == "inconsistent").any())
True
>>> f = {x.id: x for x in audit_findings()}["sun-gm"]
>>> round(f.computed / f.printed, 6)
10.0
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from lunarcap.mission.impulsive import impulsive_sequence
from lunarcap.paper import printed as P
from lunarcap.physics import constants as C
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar

__all__ = [
    "CONSISTENT",
    "INCONSISTENT",
    "L_B",
    "SOLVER_REL_TOL",
    "Finding",
    "audit_findings",
    "findings_table",
    "fuel_sentence_check",
    "implied_arrival_mass_kg",
]

CONSISTENT = "consistent"
INCONSISTENT = "inconsistent"

#: Relative allowance for the optimiser's discretisation error in relations between two
#: of its outputs (masses, delta-Vs, burn durations); see the module docstring.
SOLVER_REL_TOL = 1e-4

#: One unit of the last printed digit of the paper's burn durations (Tables 1-5), min.
DURATION_RESOLUTION_MIN = 0.01

#: TCB-TDB rate, L_B = 1 - d(TDB)/d(TCB) (IAU 2006 Resolution B3). A gravitational
#: parameter in TCB-compatible units is (1 + L_B) times its TDB-compatible value
#: (IERS Conventions 2010, Sec. 1.2).
L_B = 1.550519768e-8

_G0 = C.G0_MPS2
_THRUSTS = (150, 300, 450)
_LOIS = (1, 2, 3)
_IMP = P.PAPER_IMPULSIVE_DV_MPS


@dataclass(frozen=True)
class Finding:
    """One consistency check of Song 2011.

    Attributes
    ----------
    id : str
        Short unique key, e.g. ``"pct/150N/LOI1/start-10min"``.
    check : str
        Group of checks, "a" to "k" (see :func:`audit_findings`).
    where : str
        Where the checked number is printed (table, section and paragraph, equation).
    quantity : str
        What is compared.
    printed : float
        The number as printed (or a difference of printed numbers), in ``unit``.
    computed : float
        What arithmetic or physics gives from the paper's other numbers, in ``unit``.
    unit : str
        Unit of ``printed``, ``computed``, ``difference`` and ``tolerance``.
    tolerance : float
        Largest ``|printed - computed|`` accepted as rounding (and solver) error.
    rule : str
        ``"abs"`` (``|difference| <= tolerance``) or ``"round-or-truncate"`` (also
        accepted if ``printed`` is ``computed`` truncated to ``resolution``).
    resolution : float
        One unit of the last printed digit, in ``unit``.
    explanation : str
        How the computed value was obtained and what the numbers show.
    extra : dict
        Further computed numbers (implied masses, thrusts, flags).
    """

    id: str
    check: str
    where: str
    quantity: str
    printed: float
    computed: float
    unit: str
    tolerance: float
    explanation: str
    rule: str = "abs"
    resolution: float = 0.0
    extra: dict = field(default_factory=dict, compare=False, hash=False)

    @property
    def difference(self) -> float:
        """``printed - computed``, in ``unit``."""
        return self.printed - self.computed

    @property
    def relative_difference(self) -> float:
        """``(printed - computed) / computed`` (nan if ``computed`` is 0)."""
        return self.difference / self.computed if self.computed else float("nan")

    @property
    def verdict(self) -> str:
        """``"consistent"`` or ``"inconsistent"`` by the tolerance and rule."""
        return CONSISTENT if _accepted(self.printed, self.computed, self.tolerance,
                                       self.rule, self.resolution) else INCONSISTENT

    def to_dict(self) -> dict:
        """The finding as a flat dict (without ``extra``)."""
        return {"id": self.id, "check": self.check, "where": self.where,
                "quantity": self.quantity, "printed": self.printed,
                "computed": self.computed, "difference": self.difference,
                "tolerance": self.tolerance, "unit": self.unit, "verdict": self.verdict,
                "rule": self.rule, "explanation": self.explanation}


def _accepted(printed, computed, tol, rule="abs", resolution=0.0) -> bool:
    """Whether a printed number agrees with its recomputation (see :class:`Finding`)."""
    d = printed - computed
    slack = 1e-12 * max(1.0, abs(computed))
    if abs(d) <= tol + slack:
        return True
    if rule == "round-or-truncate" and computed > 0:
        u = max(tol - resolution / 2, 0.0)  # propagated input uncertainty
        return -(resolution + u) - slack < d <= u + slack
    return False


_ok = _accepted


def _propagate(f, *inputs):
    """Value of f at the inputs and the linear bound of its change.

    Parameters
    ----------
    f : callable
        Function of the input values.
    *inputs : tuple of (value, half_width)
        Each input and the half-width of its rounding interval.

    Returns
    -------
    tuple of float
        ``f(values)`` and ``sum_i |f(x_i + h_i) - f(x_i - h_i)| / 2``.
    """
    vals = [v for v, _ in inputs]
    y = f(*vals)
    bound = 0.0
    for i, (v, h) in enumerate(inputs):
        if h:
            up, dn = list(vals), list(vals)
            up[i], dn[i] = v + h, v - h
            bound += abs(f(*up) - f(*dn)) / 2
    return y, bound


def _half(name: str) -> float:
    return P.quote(name).resolution / 2


def _qv(name: str) -> float:
    return P.quote(name).value


def _where(name: str) -> str:
    return P.quote(name).where


def _rounding_note(printed: float, exact: float, resolution: float) -> str:
    """Say whether ``printed`` is ``exact`` rounded or truncated to ``resolution``."""
    nd = max(0, -int(math.floor(math.log10(resolution) + 1e-9)))
    r = round(exact / resolution) * resolution
    t = math.floor(exact / resolution + 1e-9) * resolution
    if abs(r - printed) < resolution / 10:
        how = "rounded"
    elif abs(t - printed) < resolution / 10:
        how = f"truncated (rounded it would be {r:.{nd}f})"
    else:
        how = f"neither rounded ({r:.{nd}f}) nor truncated ({t:.{nd}f})"
    return f"exact {exact:.{nd + 3}f}; the printed {printed:.{nd}f} is {how}"


# ---------------------------------------------------------------------------------------
# physics helpers (SI-ish units of the paper: kg, m/s, N, s, min)
# ---------------------------------------------------------------------------------------


def _ve(isp_s: float) -> float:
    """Effective exhaust speed g0 Isp, m/s."""
    return _G0 * isp_s


def _mass_after(m0_kg, dv_mps, isp_s):
    """Rocket equation, kg."""
    return m0_kg * math.exp(-dv_mps / _ve(isp_s))


def _fuel(m0_kg, dv_mps, isp_s):
    """Propellant for a delta-V by the rocket equation, kg."""
    return m0_kg - _mass_after(m0_kg, dv_mps, isp_s)


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
        "150N mass after LOI 1": _qv("mass_after_loi1_150N_kg")
        * math.exp(_best_dvs(150)[0] / _ve(isp150)),
        "300N final mass": _qv("mass_final_300N_kg") * math.exp(sum(_best_dvs(300)) / _ve(isp300)),
        "450N final mass": _qv("mass_final_450N_kg") * math.exp(sum(_best_dvs(450)) / _ve(isp450)),
        "150N total burn time": _qv("mass_final_150N_kg")
        + _fuel_from_burn(150, _qv("burn_total_150N_min"), isp150),
        "450N total burn time": _qv("mass_final_450N_kg")
        + _fuel_from_burn(450, _qv("burn_total_450N_min"), isp450),
        "150N Eq. (19) LOI 1": _fuel_from_burn(150, _qv("eq19_loi1_150N_min"), isp150)
        / (1 - math.exp(-_IMP[0] / _ve(isp150))),
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
    starts[150] = [(m1 * math.exp(_best_dvs(150)[0] / _ve(isp150)), 0.0006), (m1, 0.0005),
                   (m2, 0.0005)]
    src[150] = ["printed 434.471 kg after LOI 1 taken back through 367.415 m/s",
                "printed mass after LOI 1", "printed mass after LOI 2"]
    for t in (300, 450):
        isp = P.PAPER_ENGINES[t]
        dvs = _best_dvs(t)
        mf = _qv(f"mass_final_{t}N_kg")
        starts[t] = [(mf * math.exp(sum(dvs[n:]) / _ve(isp)), 0.0006) for n in range(3)]
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


# ---------------------------------------------------------------------------------------
# (a) constants
# ---------------------------------------------------------------------------------------


def _check_a() -> list[Finding]:
    p = _qv("mu_sun_km3s2")
    c = C.MU_SUN
    ratio = c / p
    tcb = c * (1 + L_B)
    rel_tcb = 10 * p / tcb - 1
    tcb_note = (f"Ten times the printed value, {10 * p:,.1f}, equals the DE405 value in "
                f"TCB-compatible units, GM (1 + L_B) = {tcb:,.1f} km³/s² (relative "
                f"difference {rel_tcb:.1e}), which is why the ratio is {ratio:.11f} and not "
                "exactly 10: the printed number is the TCB-compatible GM with its decimal "
                "point one place off." if abs(rel_tcb) < 1e-10 else
                f"Ten times the printed value differs from GM (1 + L_B) by {rel_tcb:.1e}.")
    return [Finding(
        "sun-gm", "a", _where("mu_sun_km3s2"), "gravitational parameter of the Sun",
        p, c, "km³/s²", _half("mu_sun_km3s2") + 0.5,
        f"DE405 value (Standish 1998) {c:,.0f} km³/s² (lunarcap.physics.constants.MU_SUN). "
        f"The printed value is {ratio:.9f} times too small. {tcb_note}",
        extra={"ratio_correct_over_printed": ratio, "tcb_value": tcb,
               "rel_diff_10x_printed_vs_tcb": rel_tcb})]


# ---------------------------------------------------------------------------------------
# (b) the "difference %" column and the best rows
# ---------------------------------------------------------------------------------------


def _check_b() -> list[Finding]:
    out = []
    b1 = P.paper_table_b1()
    for (t, n) in [(t, n) for t in _THRUSTS for n in _LOIS]:
        tab = P.paper_table(t, n)
        imp = tab.attrs["impulsive_delta_v_mps"]
        for row in tab.itertuples():
            x, u = _propagate(lambda dv, i: 100 * (dv - i) / i, (row.delta_v_mps, 0.0005),
                              (imp, 0.0005))
            p = row.diff_percent
            implied_dv = imp * (1 + p / 100)
            ok = _ok(p, x, 0.005 + u, "round-or-truncate", 0.01)
            tail = "" if ok else (f" The printed {p:.2f} % would need a delta-V of "
                                  f"{implied_dv:.3f} m/s instead of {row.delta_v_mps:.3f}.")
            out.append(Finding(
                f"pct/{t}N/LOI{n}/start{row.start_min}min", "b",
                f"{tab.attrs['source']}, row {row.start_min} min"
                + (" (also Table B1 and the text)" if row.best else ""),
                "difference in delta-V, 100 (dV_finite - dV_impulsive) / dV_impulsive",
                p, x, "%", 0.005 + u,
                f"({row.delta_v_mps:.3f} - {imp:.3f}) / {imp:.3f}: "
                f"{_rounding_note(p, x, 0.01)}.{tail}",
                rule="round-or-truncate", resolution=0.01,
                extra={"implied_delta_v_mps": implied_dv}))
        # best flag and Table B1
        flagged = tab[tab.best]
        imin = int(tab.delta_v_mps.idxmin())
        b = b1[(b1.thrust_N == t) & (b1.loi == n)].iloc[0]
        fl = flagged.iloc[0]
        same_b1 = all(float(b[k]) == float(fl[k]) for k in
                      ("start_min", "burn_duration_min", "delta_v_mps", "diff_percent"))
        out.append(Finding(
            f"best/{t}N/LOI{n}", "b", f"{tab.attrs['source']}, footnote a; Table B1",
            "delta-V of the row marked 'Best solution' vs the smallest delta-V of the table",
            float(fl.delta_v_mps), float(tab.delta_v_mps.min()), "m/s", 0.0,
            f"{len(flagged)} row(s) flagged; the smallest delta-V is at "
            f"{int(tab.start_min[imin])} min, the flagged row at {int(fl.start_min)} min. "
            f"Table B1's row for {t} N, LOI {n} "
            + ("equals" if same_b1 else "differs from")
            + " the flagged row in start, duration, delta-V and %.",
            extra={"n_flagged": len(flagged), "table_b1_matches": same_b1}))
    return out


# ---------------------------------------------------------------------------------------
# (c) masses vs the rocket equation and vs the burn durations
# ---------------------------------------------------------------------------------------


def _check_c() -> list[Finding]:
    out = []
    m0 = _qv("arrival_mass_kg")
    hm = _half("arrival_mass_kg")
    isp = {t: P.PAPER_ENGINES[t] for t in _THRUSTS}
    dv150 = _best_dvs(150)

    def mass_finding(fid, qname, m_before, h_before, dvs, isp_s, before_label, dv_label):
        p = _qv(qname)
        inputs = [(m_before, h_before)] + [(dv, 0.0005) for dv in dvs]
        x, u = _propagate(lambda m, *d: _mass_after(m, sum(d), isp_s), *inputs)
        tol = _half(qname) + u + SOLVER_REL_TOL * x
        implied_m = p * math.exp(sum(dvs) / _ve(isp_s))
        implied_dv = _ve(isp_s) * math.log(m_before / p)
        note = (f" The printed mass implies a starting mass of {implied_m:.3f} kg (not "
                f"{m_before:.3f}), or a delta-V of {implied_dv:.3f} m/s (not "
                f"{sum(dvs):.3f})." if not _ok(p, x, tol) else
                f" Difference {p - x:+.4f} kg ({(p - x) / x:+.1e} relative).")
        return Finding(fid, "c", _where(qname), f"mass after {dv_label}", p, x, "kg", tol,
                       f"Rocket equation {before_label} {m_before:.3f} kg x exp(-{sum(dvs):.3f}"
                       f" / (g0 x {isp_s:.0f} s)) = {x:.3f} kg.{note}",
                       extra={"implied_start_mass_kg": implied_m, "implied_dv_mps": implied_dv})

    m1, m2 = _qv("mass_after_loi1_150N_kg"), _qv("mass_after_loi2_150N_kg")
    out.append(mass_finding("mass/150N/after-LOI1", "mass_after_loi1_150N_kg", m0, hm,
                            dv150[:1], isp[150], "from", "LOI 1 (150 N)"))
    out.append(mass_finding("mass/150N/after-LOI2", "mass_after_loi2_150N_kg", m1,
                            _half("mass_after_loi1_150N_kg"), dv150[1:2], isp[150],
                            "from the printed", "LOI 2 (150 N)"))
    out.append(mass_finding("mass/150N/after-LOI3", "mass_final_150N_kg", m2,
                            _half("mass_after_loi2_150N_kg"), dv150[2:], isp[150],
                            "from the printed", "LOI 3 (150 N)"))
    out.append(mass_finding("mass/150N/final-from-arrival", "mass_final_150N_kg", m0, hm,
                            dv150, isp[150], "from the arrival mass",
                            "LOI 1-3 (150 N, Table B1 delta-Vs)"))
    for t in (300, 450):
        out.append(mass_finding(f"mass/{t}N/final", f"mass_final_{t}N_kg", m0, hm, _best_dvs(t),
                                isp[t], "from the arrival mass",
                                f"LOI 1-3 ({t} N, Table B1 delta-Vs)"))

    # the arrival mass the results imply
    imp = implied_arrival_mass_kg()
    precise = [imp[k] for k in ("150N mass after LOI 1", "300N final mass", "450N final mass")]
    x = float(np.mean(precise))
    spread = max(precise) - min(precise)
    listing = "; ".join(f"{k}: {v:.3f}" for k, v in imp.items())
    out.append(Finding(
        "mass/arrival-implied", "c", _where("arrival_mass_kg"),
        "arrival mass vs the arrival mass implied by the printed results (mean of the "
        "150 N mass after LOI 1 and the 300 N and 450 N final masses)",
        m0, x, "kg", hm + spread / 2 + SOLVER_REL_TOL * x,
        f"Arrival masses implied (rocket equation / T t/(g0 Isp)), kg: {listing}. The three "
        f"mass-based values agree to {spread:.3f} kg; their mean is {x:.3f} kg, "
        f"{m0 - x:.3f} kg below the printed {m0:.3f} kg. The burn-time-based values carry "
        "the rounding of the durations (about 0.1 kg).",
        extra={"implied": imp, "mean_of_mass_based": x, "spread": spread}))

    # fuel vs burn durations: fuel = T t / (g0 Isp)
    pairs = [("150N/LOI1", 150, m0 - m1, 2 * hm, "burn_loi1_150N_min",
              f"524.895 - 434.471 kg ({_where('mass_after_loi1_150N_kg')})"),
             ("150N/LOI2", 150, m1 - m2, 2 * hm, "burn_loi2_150N_min",
              f"434.471 - 381.005 kg ({_where('mass_after_loi2_150N_kg')})"),
             ("150N/LOI3", 150, m2 - _qv("mass_final_150N_kg"), 2 * hm, "burn_loi3_150N_min",
              f"381.005 - 335.750 kg ({_where('mass_final_150N_kg')})"),
             ("150N/total", 150, m0 - _qv("mass_final_150N_kg"), 2 * hm, "burn_total_150N_min",
              "524.895 - 335.750 kg"),
             ("300N/total", 300, m0 - _qv("mass_final_300N_kg"), 2 * hm, "burn_total_300N_min",
              f"524.895 - 369.289 kg ({_where('mass_final_300N_kg')})"),
             ("450N/total", 450, m0 - _qv("mass_final_450N_kg"), 2 * hm, "burn_total_450N_min",
              f"524.895 - 391.722 kg ({_where('mass_final_450N_kg')})")]
    for tag, t, p, hp, tname, src in pairs:
        tb = _qv(tname)
        x, u = _propagate(lambda tt: _fuel_from_burn(t, tt, isp[t]), (tb, _half(tname)))
        tol = hp + u + SOLVER_REL_TOL * x
        implied_t = p * _ve(isp[t]) / t / 60
        out.append(Finding(
            f"fuel-vs-burn/{tag}", "c", f"{_where(tname)}; masses: {src}",
            "propellant from the printed masses vs T t / (g0 Isp) from the printed burn time",
            p, x, "kg", tol,
            f"{t} N x {tb:.2f} min x 60 / (g0 x {isp[t]:.0f} s) = {x:.3f} kg. The printed "
            f"masses imply a burn of {implied_t:.2f} min.",
            extra={"implied_burn_min": implied_t}))

    # every table row: burn duration vs delta-V. Start masses: those consistent with the
    # paper's printed masses (see _printed_mass_starts); the printed arrival mass is used
    # for comparison in the explanation.
    starts, src = _printed_mass_starts()
    starts_printed_m0 = {150: [m0, m1, m2]}
    for t in (300, 450):
        starts_printed_m0[t] = _finite_chain(t, m0)[:3]
    thrust_rows = {}
    for t in _THRUSTS:
        for n in _LOIS:
            tab = P.paper_table(t, n)
            ms, hms = starts[t][n - 1]
            for row in tab.itertuples():
                x, u = _propagate(lambda m, dv: _burn_min(m, dv, t, isp[t]), (ms, hms),
                                  (row.delta_v_mps, 0.0005))
                # half a unit of the printed duration + half a unit of the recomputed one
                # at the printed resolution (see the module docstring)
                tol = DURATION_RESOLUTION_MIN + u + SOLVER_REL_TOL * x
                implied_T = _fuel(ms, row.delta_v_mps, isp[t]) * _ve(isp[t]) / (
                    row.burn_duration_min * 60)
                implied_m = (_fuel_from_burn(t, row.burn_duration_min, isp[t])
                             / (1 - math.exp(-row.delta_v_mps / _ve(isp[t]))))
                m_alt = starts_printed_m0[t][n - 1]
                x0 = _burn_min(m_alt, row.delta_v_mps, t, isp[t])
                if n == 1:
                    alt = (f" Starting instead from the printed arrival mass {m0:.3f} kg "
                           f"gives {x0:.3f} min.")
                elif abs(m_alt - ms) < 1e-9:  # the start mass already is a printed mass
                    alt = ""
                else:
                    alt = (f" Starting instead from the printed arrival mass {m0:.3f} kg, "
                           f"taken through Table B1's delta-Vs of the earlier LOIs "
                           f"({m_alt:.3f} kg at ignition), gives {x0:.3f} min.")
                thrust_rows.setdefault((t, n), []).append(implied_T)
                out.append(Finding(
                    f"burn/{t}N/LOI{n}/start{row.start_min}min", "c",
                    f"{tab.attrs['source']}, row {row.start_min} min",
                    "burn duration vs the duration of a constant-thrust burn giving the "
                    "row's delta-V", row.burn_duration_min, x, "min", tol,
                    f"Start mass {ms:.3f} kg ({src[t][n - 1]}); t = m0 [1 - exp(-dV/(g0 Isp))] "
                    f"g0 Isp / T = {x:.3f} min. The row implies a start mass of "
                    f"{implied_m:.2f} kg or a thrust of {implied_T:.1f} N.{alt}",
                    resolution=DURATION_RESOLUTION_MIN,
                    extra={"implied_thrust_N": implied_T, "implied_start_mass_kg": implied_m,
                           "start_mass_from_printed_arrival_mass_kg": m_alt,
                           "duration_from_printed_arrival_mass_min": x0}))
    # the thrust implied by Table 4's LOI-1 rows
    vals = thrust_rows[(300, 1)]
    rows = list(P.paper_table(300, 1).itertuples())
    x = float(np.mean(vals))
    vals0 = [_fuel(m0, r.delta_v_mps, isp[300]) * _ve(isp[300]) / (r.burn_duration_min * 60)
             for r in rows]
    out.append(Finding(
        "thrust/300N/LOI1", "c", "Table 4 (1st LOI), all rows",
        "engine thrust vs the thrust implied by each row's delta-V and duration (mean of the "
        "rows)", 300.0, x, "N",
        300 * (0.005 / min(r.burn_duration_min for r in rows) + SOLVER_REL_TOL),
        f"Implied thrusts {', '.join(f'{v:.1f}' for v in vals)} N from a start mass of "
        f"{starts[300][0][0]:.3f} kg ({', '.join(f'{v:.1f}' for v in vals0)} N from "
        f"{m0:.3f} kg); the LOI-2 and LOI-3 rows of Table 4 imply "
        + " and ".join(f"{np.mean(thrust_rows[(300, k)]):.1f}" for k in (2, 3)) + " N.",
        extra={"implied_thrust_N": vals, "implied_thrust_from_printed_m0_N": vals0}))
    return out


# ---------------------------------------------------------------------------------------
# (d) the fuel-mass sentences
# ---------------------------------------------------------------------------------------


def _check_d() -> list[Finding]:
    out = []
    m0 = _qv("arrival_mass_kg")
    hm = _half("arrival_mass_kg")
    for t in _THRUSTS:
        isp = P.PAPER_ENGINES[t]
        fs = fuel_sentence_check(t)
        pf, pi = fs["printed_finite_kg"], fs["printed_impulsive_kg"]
        cf, ci = fs["computed_finite_kg"], fs["computed_impulsive_kg"]
        qf, qi = f"fuel_finite_{t}N_kg", f"fuel_impulsive_{t}N_kg"
        # impulsive: pure arithmetic on printed numbers
        _, ui = _propagate(lambda m, a, b, c: m * (1 - math.exp(-(a + b + c) / _ve(isp))),
                           (m0, hm), *[(d, 0.0005) for d in _IMP])
        tol_i = _half(qi) + ui
        dv_impl = _ve(isp) * math.log(m0 / (m0 - pi))
        sw = (f" The number printed for *finite* thrust, {pf:.3f} kg, is within "
              f"{abs(pf - ci):.3f} kg of this." if fs["labels_swapped"] else "")
        out.append(Finding(
            f"fuel/{t}N/impulsive", "d", _where(qi),
            "total propellant of the impulsive sequence (as labelled)", pi, ci, "kg", tol_i,
            f"{m0:.3f} kg x [1 - exp(-{sum(_IMP):.3f} / (g0 x {isp:.0f} s))] = {ci:.3f} kg.{sw} "
            f"With the arrival mass {m0:.3f} kg the printed {pi:.3f} kg implies a total "
            f"impulsive delta-V of {dv_impl:.3f} m/s.",
            extra={"implied_total_impulsive_dv_mps": dv_impl}))
        # finite: rocket equation through Table B1's delta-Vs
        _, uf = _propagate(lambda m, a, b, c: m * (1 - math.exp(-(a + b + c) / _ve(isp))),
                           (m0, hm), *[(d, 0.0005) for d in _best_dvs(t)])
        tol_f = _half(qf) + uf + SOLVER_REL_TOL * cf
        final = _qv(f"mass_final_{t}N_kg")
        sw = (f" The number printed for *impulsive* thrust, {pi:.3f} kg, is within "
              f"{abs(pi - cf):.3f} kg of this and equals {m0:.3f} - {final:.3f} = "
              f"{m0 - final:.3f} kg from the printed masses." if fs["labels_swapped"] else
              f" From the printed masses, {m0:.3f} - {final:.3f} = {m0 - final:.3f} kg.")
        m_star = _m0_star()
        sw += (f" From the arrival mass implied by the printed masses ({m_star:.3f} kg, "
               f"finding mass/arrival-implied) the rocket equation gives "
               f"{m_star - _finite_chain(t, m_star)[-1]:.3f} kg.")
        out.append(Finding(
            f"fuel/{t}N/finite", "d", _where(qf),
            "total propellant of the finite-burn sequence (as labelled)", pf, cf, "kg", tol_f,
            f"{m0:.3f} kg x [1 - exp(-{sum(_best_dvs(t)):.3f} / (g0 x {isp:.0f} s))] "
            f"(Table B1 delta-Vs) = {cf:.3f} kg.{sw}"))
        # which needs more fuel
        out.append(Finding(
            f"fuel/{t}N/which-is-larger", "d", f"{_where(qf)}",
            "sign of (finite - impulsive propellant) as labelled", float(np.sign(pf - pi)),
            float(np.sign(cf - ci)), "", 0.0,
            f"Finite burns have the larger delta-V, so they need more propellant: computed "
            f"{cf:.3f} - {ci:.3f} = {cf - ci:+.3f} kg; printed {pf:.3f} - {pi:.3f} = "
            f"{pf - pi:+.3f} kg. Summed absolute mismatch as labelled "
            f"{fs['mismatch_as_labelled_kg']:.3f} kg, with the labels swapped "
            f"{fs['mismatch_if_swapped_kg']:.3f} kg"
            + (": the two numbers are swapped." if fs["labels_swapped"] else "."),
            extra=fs))
        if t == 450:
            p = _qv("fuel_finite_450N_kg")
            x = m0 - final
            out.append(Finding(
                "fuel/450N/finite-vs-final-mass", "d", _where("fuel_finite_450N_kg"),
                "finite-burn propellant vs arrival mass minus printed final mass", p, x, "kg",
                _half("fuel_finite_450N_kg") + 2 * hm,
                f"{m0:.3f} - {final:.3f} = {x:.3f} kg (Sec. 3.2.2, para 3 prints both)."))

    # the stated differences
    f150 = fuel_sentence_check(150)
    pf, pi = f150["printed_finite_kg"], f150["printed_impulsive_kg"]
    x = 100 * (pf - pi) / pi
    xs = 100 * (pi - pf) / pf
    out.append(Finding(
        "fuel/150N/difference-percent", "d", _where("fuel_difference_150N_percent"),
        "'about 2.24% more' fuel for finite thrust, from the printed masses as labelled",
        _qv("fuel_difference_150N_percent"), x, "%", _half("fuel_difference_150N_percent"),
        f"100 ({pf:.3f} - {pi:.3f}) / {pi:.3f} = {x:.3f} % (finite needs less, as labelled). "
        f"With the labels swapped, 100 ({pi:.3f} - {pf:.3f}) / {pf:.3f} = {xs:.3f} %: "
        + _rounding_note(_qv("fuel_difference_150N_percent"), xs, 0.01) + ".",
        rule="round-or-truncate", resolution=0.01, extra={"if_swapped_percent": xs}))
    x = abs(pf - pi)
    out.append(Finding(
        "fuel/150N/difference-kg", "d", _where("fuel_difference_150N_kg"),
        "'about 4 kg' of extra fuel", _qv("fuel_difference_150N_kg"), x, "kg", 0.5 + 0.001,
        f"|{pf:.3f} - {pi:.3f}| = {x:.3f} kg: " + _rounding_note(4, x, 1) + ".",
        rule="round-or-truncate", resolution=1.0))
    pf3, pi3 = _qv("fuel_finite_300N_kg"), _qv("fuel_impulsive_300N_kg")
    x = 100 * (pf3 - pi3) / pi3
    out.append(Finding(
        "fuel/300N/difference-percent", "d", _where("fuel_difference_300N_percent"),
        "'about 0.9% of difference' in fuel", _qv("fuel_difference_300N_percent"), x, "%",
        0.05, f"100 ({pf3:.3f} - {pi3:.3f}) / {pi3:.3f} = {x:.3f} %: "
        + _rounding_note(0.9, x, 0.1) + ".", rule="round-or-truncate", resolution=0.1))
    p150 = _qv("arrival_mass_kg") - _qv("mass_final_150N_kg")
    x = p150 - pf3
    out.append(Finding(
        "fuel/300N/saving-vs-150N", "d", _where("fuel_saving_300N_vs_150N_kg"),
        "'about 34 kg less' fuel than with 150 N", _qv("fuel_saving_300N_vs_150N_kg"), x, "kg",
        0.5 + 0.002, f"(524.895 - 335.750) - {pf3:.3f} = {x:.3f} kg: "
        + _rounding_note(34, x, 1) + ".", rule="round-or-truncate", resolution=1.0))
    nearest = min((("impulsive", pi), ("finite", pf)), key=lambda kv: abs(kv[1] - 189))
    out.append(Finding(
        "fuel/300N/150N-recalled", "d", _where("fuel_150N_recalled_kg"),
        "the 150 N finite-burn fuel recalled as 'about 189 kg' vs 524.895 - 335.750 kg",
        _qv("fuel_150N_recalled_kg"), p150, "kg", 0.5 + 0.001,
        f"524.895 - 335.750 = {p150:.3f} kg. Sec. 3.2.2 calls 'about 189 kg' the fuel used "
        f"'when the on-board engine of 150 N ... is used' (finite burns); Sec. 3.2.1, para 5 "
        f"prints the nearest number, {nearest[1]:.3f} kg, as the {nearest[0]}-thrust fuel.",
        rule="round-or-truncate", resolution=1.0))
    p450f, p450i = _qv("fuel_finite_450N_kg"), _qv("fuel_impulsive_450N_kg")
    x = p450f - p450i
    out.append(Finding(
        "fuel/450N/difference-kg", "d", _where("fuel_difference_450N_kg"),
        "'about 1.2 kg of fuel' difference", _qv("fuel_difference_450N_kg"), x, "kg", 0.05 + 0.001,
        f"{p450f:.3f} - {p450i:.3f} = {x:.3f} kg: " + _rounding_note(1.2, x, 0.1) + ".",
        rule="round-or-truncate", resolution=0.1))
    x = 100 * (p450f - p450i) / p450i
    out.append(Finding(
        "fuel/450N/difference-percent", "d", _where("fuel_difference_450N_percent"),
        "'(0.8%)' fuel difference", _qv("fuel_difference_450N_percent"), x, "%", 0.05,
        f"100 ({p450f:.3f} - {p450i:.3f}) / {p450i:.3f} = {x:.3f} %: "
        + _rounding_note(0.8, x, 0.1) + ".", rule="round-or-truncate", resolution=0.1))
    # "about N kg" per burn and totals
    about = [("fuel_loi1_150N_about_kg", m0 - _qv("mass_after_loi1_150N_kg"), "524.895 - 434.471"),
             ("fuel_loi2_150N_about_kg",
              _qv("mass_after_loi1_150N_kg") - _qv("mass_after_loi2_150N_kg"), "434.471 - 381.005"),
             ("fuel_loi3_150N_about_kg",
              _qv("mass_after_loi2_150N_kg") - _qv("mass_final_150N_kg"), "381.005 - 335.750"),
             ("fuel_finite_300N_about_kg", m0 - _qv("mass_final_300N_kg"), "524.895 - 369.289"),
             ("fuel_finite_450N_about_kg", m0 - _qv("mass_final_450N_kg"), "524.895 - 391.722")]
    for name, x, expr in about:
        p = _qv(name)
        out.append(Finding(
            f"fuel/about/{name}", "d", _where(name), f"'about {p:.0f} kg' of fuel", p, x, "kg",
            0.5 + 0.001, f"{expr} = {x:.3f} kg: " + _rounding_note(p, x, 1) + ".",
            rule="round-or-truncate", resolution=1.0))
    return out


# ---------------------------------------------------------------------------------------
# (e) delta-V losses and their percentages
# ---------------------------------------------------------------------------------------


def _check_e() -> list[Finding]:
    out = []
    for t in _THRUSTS:
        dvs = _best_dvs(t)
        losses = [d - i for d, i in zip(dvs, _IMP)]
        for n in _LOIS:
            name = f"loss_loi{n}_{t}N_mps"
            p = _qv(name)
            res = P.quote(name).resolution
            x = losses[n - 1]
            out.append(Finding(
                f"loss/{t}N/LOI{n}", "e", _where(name), f"delta-V loss of LOI {n}", p, x, "m/s",
                res / 2 + 0.001,
                f"Table B1: {dvs[n - 1]:.3f} - {_IMP[n - 1]:.3f} = {x:.3f} m/s: "
                + _rounding_note(p, x, res) + ".", rule="round-or-truncate", resolution=res))
        name = f"loss_total_{t}N_mps"
        p = _qv(name)
        x = sum(losses)
        out.append(Finding(
            f"loss/{t}N/total", "e", _where(name), "total delta-V loss of LOI 1-3", p, x, "m/s",
            0.005 + 0.003,
            f"Sum of the Table B1 losses {' + '.join(f'{v:.3f}' for v in losses)} = {x:.3f} m/s: "
            + _rounding_note(p, x, 0.01) + ".", rule="round-or-truncate", resolution=0.01))
        # percentage: total loss / total impulsive vs mean of the per-burn percentages
        name = f"loss_total_{t}N_percent"
        p = _qv(name)
        x, u = _propagate(lambda *d: 100 * sum(a - b for a, b in zip(d, _IMP)) / sum(_IMP),
                          *[(d, 0.0005) for d in dvs])
        pcts = [P.paper_best(t, n)["diff_percent"] for n in _LOIS]
        mean_printed = float(np.mean(pcts))
        mean_exact = float(np.mean([100 * (d - i) / i for d, i in zip(dvs, _IMP)]))
        unit_note = ("" if "%" in P.quote(name).text else
                     " The sentence prints the number without '%' ('5.11 m/s is about 0.55.').")
        out.append(Finding(
            f"loss-percent/{t}N/total", "e", _where(name),
            "total loss in % of the total impulsive delta-V", p, x, "%", 0.005 + u,
            f"100 x {sum(losses):.3f} / {sum(_IMP):.3f} = {x:.3f} %. The mean of the three "
            f"printed per-burn percentages ({', '.join(f'{v:.2f}' for v in pcts)}) is "
            f"{mean_printed:.3f} %, which "
            + ("matches" if _ok(p, mean_printed, 0.005, "round-or-truncate", 0.01)
               else "does not match") + f" the printed {p:.2f} % (mean of the exact "
            f"per-burn percentages: {mean_exact:.3f} %).{unit_note}",
            rule="round-or-truncate", resolution=0.01,
            extra={"mean_of_printed_percentages": mean_printed,
                   "mean_of_exact_percentages": mean_exact}))
        out.append(Finding(
            f"loss-percent/{t}N/mean-of-burns", "e", _where(name),
            "total loss % vs the mean of the printed per-burn percentages", p, mean_printed,
            "%", 0.005, f"mean({', '.join(f'{v:.2f}' for v in pcts)}) = {mean_printed:.4f} %: "
            + _rounding_note(p, mean_printed, 0.01) + ".", rule="round-or-truncate",
            resolution=0.01))
    # precision of the 300 N losses sentence
    names = ["loss_total_300N_mps", "loss_loi1_300N_mps", "loss_loi2_300N_mps",
             "loss_loi3_300N_mps"]
    decs = {n: P.quote(n).decimals for n in names}
    others = max(decs[n] for n in names[:3])
    out.append(Finding(
        "precision/300N/LOI3-loss", "e", _where("loss_loi3_300N_mps"),
        "decimals of '1.152 m/s' vs the other losses of the same sentence",
        float(decs["loss_loi3_300N_mps"]), float(others), "digits", 0.0,
        "Printed decimals: " + ", ".join(f"{P.quote(n).printed} -> {d}" for n, d in decs.items())
        + ". Every other delta-V loss in the paper is printed to 0.01 m/s."))
    # abstract and conclusions: "up to about 2%"
    mx = max(_qv(f"loss_total_{t}N_percent") for t in _THRUSTS)
    for name in ("abstract_max_loss_percent", "conclusion_max_loss_percent"):
        out.append(Finding(
            f"loss-percent/{name}", "e", _where(name), "'up to about 2%' total delta-V loss",
            _qv(name), mx, "%", 0.5,
            f"Largest printed total-loss percentage: {mx:.2f} % (150 N). Computed as total "
            f"loss / total impulsive delta-V it would be "
            f"{100 * (sum(_best_dvs(150)) - sum(_IMP)) / sum(_IMP):.2f} %."))
    return out


# ---------------------------------------------------------------------------------------
# (f) burn-duration totals
# ---------------------------------------------------------------------------------------


def _check_f() -> list[Finding]:
    out = []
    for t in _THRUSTS:
        parts = ([_qv("burn_loi1_150N_min"), _qv("burn_loi2_150N_summary_min"),
                  _qv("burn_loi3_150N_summary_min")] if t == 150 else
                 [_qv(f"burn_loi{n}_{t}N_min") for n in _LOIS])
        b1 = [P.paper_best(t, n)["burn_duration_min"] for n in _LOIS]
        name = f"burn_total_{t}N_min"
        x = sum(parts)
        out.append(Finding(
            f"burn-total/{t}N", "f", _where(name), "total burn duration of LOI 1-3",
            _qv(name), x, "min", 0.005 + 0.015,
            f"{' + '.join(f'{v:.2f}' for v in parts)} = {x:.2f} min; the parts "
            + ("equal" if parts == b1 else "differ from") + " Table B1's durations."))
    p = _qv("burn_loi1_150N_about_min")
    x = P.paper_best(150, 1)["burn_duration_min"]
    out.append(Finding(
        "burn-total/150N/LOI1-about", "f", _where("burn_loi1_150N_about_min"),
        "'about 19.5 minutes' of LOI-1 burn", p, x, "min", 0.05,
        f"Table 1: {x:.2f} min: " + _rounding_note(p, x, 0.1) + ".",
        rule="round-or-truncate", resolution=0.1))
    return out


# ---------------------------------------------------------------------------------------
# (g) the final orbit's period
# ---------------------------------------------------------------------------------------


def _check_g() -> list[Finding]:
    mu, R = _qv("mu_moon_km3s2"), _qv("r_moon_km")
    h = _qv("final_altitude_km")
    p = _qv("period_final_min")

    def period(mu_, r_):
        return 2 * math.pi * math.sqrt((r_ + h) ** 3 / mu_) / 60

    x, u = _propagate(period, (mu, _half("mu_moon_km3s2")), (R, _half("r_moon_km")))
    r_impl = (mu * (p * 60 / (2 * math.pi)) ** 2) ** (1 / 3)
    mu_impl = 4 * math.pi ** 2 * (R + h) ** 3 / (p * 60) ** 2
    out = [Finding(
        "period/final", "g", _where("period_final_min"),
        "period of the 100 km circular orbit", p, x, "min", _half("period_final_min") + u,
        f"2 pi sqrt(({R:.1f} + {h:.0f})^3 / {mu:.3f}) = {x:.4f} min. The printed period "
        f"implies a radius of {r_impl:.3f} km (altitude {r_impl - R:.3f} km) with the printed "
        f"mu, or mu = {mu_impl:.2f} km³/s² with the printed radius.",
        extra={"implied_radius_km": r_impl, "implied_mu_km3s2": mu_impl})]
    q = _qv("period_final_about_min")
    out.append(Finding(
        "period/final-about", "g", _where("period_final_about_min"),
        "'about 118 minutes'", q, x, "min", 0.5, f"{x:.3f} min rounds to {round(x)} min."))
    return out


# ---------------------------------------------------------------------------------------
# (h) the perilune epochs
# ---------------------------------------------------------------------------------------


def _check_h() -> list[Finding]:
    out = []
    e = {k: seconds_from_calendar(v) for k, v in P.PAPER_EPOCHS_TDB.items()}
    T1, T2 = _qv("period_capture1_h") * 3600, _qv("period_capture2_h") * 3600
    hT1, hT2 = _half("period_capture1_h") * 3600, _half("period_capture2_h") * 3600
    cases = [("epoch/perilune2", 1, 2, T1, hT1, "perilune 1 + 12.235 h"),
             ("epoch/perilune3", 2, 3, T2, hT2, "perilune 2 (as printed) + 3.525 h"),
             ("epoch/perilune3-from-perilune1", 1, 3, T1 + T2, hT1 + hT2,
              "perilune 1 + 12.235 h + 3.525 h")]
    for fid, a, b, dt, hdt, how in cases:
        p = e[b] - e[a]
        out.append(Finding(
            fid, "h", P.PAPER_EPOCHS_WHERE[b],
            f"time from perilune {a} to perilune {b} (printed epochs) vs the printed periods",
            p, dt, "s", 1.0 + hdt,
            f"{how} = {calendar_from_seconds(e[a] + dt, 1)}; printed "
            f"{P.PAPER_EPOCHS_TDB[b]}. The epochs imply a period of {p / 3600:.5f} h; "
            f"the periods are printed to 0.001 h (3.6 s) and the epochs to 1 s.",
            extra={"implied_period_h": p / 3600}))
    # Sec. 2.2: t2 = tp - t1, i.e. ignition-to-next-perilune = tp
    for a, b, T, hT, loi in ((1, 2, T1, hT1, 1), (2, 3, T2, hT2, 2)):
        s = P.paper_best(150, loi)["start_min"] * 60.0
        p = e[b] - e[a]
        x = T + s
        out.append(Finding(
            f"epoch/perilune{b}-ignition-reading", "h",
            f"{P.PAPER_EPOCHS_WHERE[b]}; Sec. 2.2 ('Using the fixed tp and controlled t1, "
            "phase 2's duration t2 can be easily determined simply by subtracting')",
            f"time from perilune {a} to perilune {b} vs t1 + t2 = tp counted from the LOI-{loi} "
            "ignition (Sec. 2.2)", p, x, "s", 1.0 + hT,
            f"Ignition {abs(s) / 60:.0f} min before perilune {a} plus tp gives perilune {b} at "
            f"{calendar_from_seconds(e[a] + x, 0)}, {p - x:.0f} s before the printed epoch. "
            "The printed epochs instead follow perilune-to-perilune spacing equal to tp."))
    return out


# ---------------------------------------------------------------------------------------
# (i) Eq. (19) and (j) half-durations vs best ignition offsets
# ---------------------------------------------------------------------------------------


def _check_i() -> list[Finding]:
    out = []
    m0 = _qv("arrival_mass_kg")
    isp = P.PAPER_ENGINES[150]
    ve = _ve(isp)
    p = _qv("eq19_loi1_150N_min")
    mf_printed = m0 * (1 - math.exp(-_IMP[0] / ve))  # Eq. (19a) as printed
    x_typo = (m0 - mf_printed) * ve / 150 / 60  # Eq. (19b)
    out.append(Finding(
        "eq19a/as-printed", "i",
        "Sec. 2.2, Eq. (19a)-(19b); value: " + _where("eq19_loi1_150N_min"),
        "LOI-1 (150 N) duration from Eq. (19b) with m_f from Eq. (19a) as printed", p, x_typo,
        "min", 0.005,
        f"Eq. (19a) as printed, m0 [1 - exp(-dV/(g0 Isp))] = {mf_printed:.3f} kg, is the "
        f"propellant, not the mass after burnout ({m0 - mf_printed:.3f} kg); put into Eq. (19b) "
        f"it gives {x_typo:.2f} min. With m_f = m0 exp(-dV/(g0 Isp)) it gives "
        f"{_burn_min(m0, _IMP[0], 150, isp):.3f} min."))
    x, u = _propagate(lambda m, dv: _burn_min(m, dv, 150, isp), (m0, _half("arrival_mass_kg")),
                      (_IMP[0], 0.0005))
    m_impl = implied_arrival_mass_kg()["150N Eq. (19) LOI 1"]
    m_star = _m0_star()
    out.append(Finding(
        "eq19/150N/LOI1", "i", _where("eq19_loi1_150N_min"),
        "Eq. (19) LOI-1 estimate (150 N, impulsive 353.272 m/s, m0 = 524.895 kg)", p, x, "min",
        0.005 + u,
        f"Eq. (19) with m0 = {m0:.3f} kg: {x:.3f} min. 18.82 min implies m0 = {m_impl:.2f} kg; "
        f"with the arrival mass implied by the LOI-1 mass ({m_star:.3f} kg) Eq. (19) gives "
        f"{_burn_min(m_star, _IMP[0], 150, isp):.3f} min.", extra={"implied_m0_kg": m_impl}))
    fin = [m0, _qv("mass_after_loi1_150N_kg"), _qv("mass_after_loi2_150N_kg")]
    imp = _impulsive_chain(isp, m0)
    for n, name in ((2, "eq19_loi2_150N_min"), (3, "eq19_loi3_150N_min")):
        p = _qv(name)
        for chain, label in ((fin, "finite-chain"), (imp, "impulsive-chain")):
            x, u = _propagate(lambda m, dv: _burn_min(m, dv, 150, isp), (chain[n - 1], 0.0005),
                              (_IMP[n - 1], 0.0005))
            out.append(Finding(
                f"eq19/150N/LOI{n}-{label}", "i", _where(name),
                f"Eq. (19) LOI-{n} estimate (150 N) with the {label.replace('-', ' ')} mass",
                p, x, "min", 0.005 + u,
                f"Eq. (19) with dV = {_IMP[n - 1]:.3f} m/s and m0 = {chain[n - 1]:.3f} kg ("
                + ("printed mass after the previous finite burn" if label == "finite-chain"
                   else "rocket-equation mass after the previous impulsive burns")
                + f"): {x:.3f} min."))
    # halves
    p = _qv("eq19_half_loi1_150N_min")
    x = _qv("eq19_loi1_150N_min") / 2
    out.append(Finding(
        "eq19/150N/LOI1-half", "i", _where("eq19_half_loi1_150N_min"),
        "'about 9.5 minutes' = half of 18.82 min", p, x, "min", 0.05 + 0.0025,
        f"18.82 / 2 = {x:.2f} min: " + _rounding_note(p, x, 0.1) + ".",
        rule="round-or-truncate", resolution=0.1))
    p = _qv("eq19_half_loi3_150N_min")
    x = _qv("eq19_loi3_150N_min") / 2
    out.append(Finding(
        "eq19/150N/LOI3-half", "i", _where("eq19_half_loi3_150N_min"),
        "'about 4.88 minutes' = half of 9.76 min", p, x, "min", 0.005 + 0.0025,
        f"9.76 / 2 = {x:.3f} min."))
    isp3 = P.PAPER_ENGINES[300]
    fchain = _finite_chain(300, m0)
    ichain = _impulsive_chain(isp3, m0)
    for n in _LOIS:
        name = f"eq19_half_loi{n}_300N_min"
        p = _qv(name)
        x, u = _propagate(lambda m, dv: _burn_min(m, dv, 300, isp3) / 2,
                          (fchain[n - 1], 0.0005 if n > 1 else _half("arrival_mass_kg")),
                          (_IMP[n - 1], 0.0005))
        xi = _burn_min(ichain[n - 1], _IMP[n - 1], 300, isp3) / 2
        t_impl = _fuel(fchain[n - 1], _IMP[n - 1], isp3) * _ve(isp3) / (2 * p * 60)
        out.append(Finding(
            f"eq19/300N/LOI{n}-half", "i", _where(name),
            f"half the Eq. (19) LOI-{n} estimate (300 N, Isp 250 s)", p, x, "min",
            0.005 + u + SOLVER_REL_TOL * x,
            f"Eq. (19) / 2 with m0 = {fchain[n - 1]:.3f} kg (finite chain through Table B1): "
            f"{x:.3f} min; with the impulsive chain ({ichain[n - 1]:.3f} kg): {xi:.3f} min. "
            f"The printed half-duration implies a thrust of {t_impl:.1f} N.",
            extra={"impulsive_chain_min": xi, "implied_thrust_N": t_impl}))
    return out


def _check_j() -> list[Finding]:
    out = []
    m0 = _qv("arrival_mass_kg")
    halves = {
        (150, 1): (_qv("eq19_loi1_150N_min") / 2, "18.82 / 2 (Sec. 3.2.1, para 2)"),
        (150, 2): (_qv("eq19_loi2_150N_min") / 2, "11.50 / 2 (Sec. 3.2.1, para 3)"),
        (150, 3): (_qv("eq19_half_loi3_150N_min"), "4.88 (Sec. 3.2.1, para 4)"),
    }
    for n in _LOIS:
        halves[(300, n)] = (_qv(f"eq19_half_loi{n}_300N_min"), "printed (Sec. 3.2.2, para 2)")
    ch = _finite_chain(450, m0)
    for n in _LOIS:
        halves[(450, n)] = (_burn_min(ch[n - 1], _IMP[n - 1], 450, P.PAPER_ENGINES[450]) / 2,
                            "Eq. (19) / 2 computed here (not printed)")
    for (t, n), (h, src) in halves.items():
        tab = P.paper_table(t, n)
        tested = sorted(abs(int(s)) for s in tab.start_min)
        nearest = min(tested, key=lambda s: (abs(s - h), s))
        best = abs(P.paper_best(t, n)["start_min"])
        out.append(Finding(
            f"half-vs-best/{t}N/LOI{n}", "j",
            f"{tab.attrs['source']}; Sec. 4 ('Half the value of estimated finite burn duration "
            "almost matches the best burn ignition time')",
            "best ignition offset (min before perilune) vs the tested offset nearest to half "
            "the Eq. (19) duration", float(best), float(nearest), "min", 0.0,
            f"Half-duration {h:.2f} min ({src}); tested offsets {tested} min; nearest "
            f"{nearest} min, best {best} min (|half - best| = {abs(h - best):.2f} min).",
            extra={"half_duration_min": h}))
    return out


# ---------------------------------------------------------------------------------------
# (k) other checks
# ---------------------------------------------------------------------------------------


def _check_k() -> list[Finding]:
    out = []
    m1 = _qv("mass_after_loi1_150N_kg")
    mf = _qv("mass_final_150N_kg")
    p = _qv("fig4_mass_end_kg")
    out.append(Finding(
        "fig4/mass-end", "k", _where("fig4_mass_end_kg"),
        "mass at the end of the LOI-1 burn (Fig. 4 shows the 1st LOI only)", p, m1, "kg",
        0.05 + 0.0005,
        f"Mass after LOI 1: {m1:.3f} kg (Sec. 3.2.1, para 2). The printed {p:.1f} kg "
        + ("is" if abs(p - mf) <= 0.05 + 0.0005 else "is not")
        + f" the final mass after LOI 3, {mf:.3f} kg, rounded."))
    p = _qv("fig4_mass_start_kg")
    out.append(Finding(
        "fig4/mass-start", "k", _where("fig4_mass_start_kg"),
        "mass at the start of the LOI-1 burn", p, _qv("arrival_mass_kg"), "kg", 0.05 + 0.0005,
        "Arrival mass 524.895 kg (Sec. 3.2.1, para 1)."))
    p = _qv("fig4_burn_loi1_150N_min")
    out.append(Finding(
        "fig4/burn", "k", _where("fig4_burn_loi1_150N_min"), "LOI-1 burn duration of Fig. 4",
        p, P.paper_best(150, 1)["burn_duration_min"], "min", 0.0, "Table 1 best row."))
    # two-body impulsive LOI 2 and LOI 3 from the printed periods
    seq = impulsive_sequence()
    for n in (2, 3):
        x = float(seq[n - 1].delta_v_mps)
        p = _IMP[n - 1]
        out.append(Finding(
            f"impulsive/LOI{n}-two-body", "k", "Tables 1-5 and B1, impulsive rows",
            f"impulsive LOI-{n} delta-V vs the two-body tangential impulse between the printed "
            "periods at 100 km perilune altitude", p, x, "m/s", 1e-3 * x,
            f"Two-body (mu = 4902.800 km³/s², r_p = 1838.2 km, v_inf fixed by LOI 1 = "
            f"353.272 m/s): {x:.3f} m/s. Tolerance 0.1 % allows for the N-body and J2 model of "
            "Song et al. (2009c), whence the impulsive values come."))
    return out


_CHECKS = (_check_a, _check_b, _check_c, _check_d, _check_e, _check_f, _check_g, _check_h,
           _check_i, _check_j, _check_k)


#: Titles of the audit's groups of checks (:func:`lunarcap.paper.audit.audit_findings`).
AUDIT_CHECK_TITLES = {
    "a": "constants of Sec. 3.1",
    "b": "the 'difference %' of Tables 1-5 and B1",
    "c": "masses, propellant and burn durations vs the rocket equation",
    "d": "the fuel-mass sentences of Sec. 3.2",
    "e": "delta-V losses and their percentages",
    "f": "burn-duration totals",
    "g": "the period of the 100 km circular orbit",
    "h": "the perilune epochs vs the periods",
    "i": "Eq. (19) and its estimates",
    "j": "half the Eq. (19) duration vs the best ignition time",
    "k": "other checks (Fig. 4, two-body impulsive delta-Vs)",
}


def audit_findings() -> list[Finding]:
    """All consistency checks of Song 2011.

    Groups (``Finding.check``):

    * a -- constants of Sec. 3.1 (the Sun's gravitational parameter);
    * b -- the "difference %" of every row of Tables 1-5, and the best rows vs Table B1;
    * c -- masses vs the rocket equation, the arrival mass the results imply, propellant
      vs burn durations, every row's burn duration vs its delta-V, Table 4's LOI-1 thrust;
    * d -- the fuel-mass sentences of Sec. 3.2.1-3.2.2;
    * e -- delta-V losses and their percentages;
    * f -- burn-duration totals;
    * g -- the 100 km circular orbit's period;
    * h -- the perilune epochs vs the periods (and vs Sec. 2.2's t2 = tp - t1);
    * i -- Eq. (19) (its typo, and which masses reproduce the printed estimates);
    * j -- half the Eq. (19) duration vs the best ignition offset;
    * k -- other checks (Fig. 4, the two-body impulsive delta-Vs).

    Returns
    -------
    list of Finding
    """
    out = []
    for check in _CHECKS:
        out.extend(check())
    ids = [f.id for f in out]
    if len(ids) != len(set(ids)):  # pragma: no cover - guards the ids' uniqueness
        raise RuntimeError("duplicate finding ids")
    return out


def findings_table(only_inconsistent: bool = False) -> pd.DataFrame:
    """The findings of :func:`audit_findings` as a table.

    Parameters
    ----------
    only_inconsistent : bool
        Keep only the findings whose verdict is "inconsistent".

    Returns
    -------
    pandas.DataFrame
        Columns ``id``, ``check``, ``where``, ``quantity``, ``printed``, ``computed``,
        ``difference`` (printed - computed), ``tolerance``, ``unit``, ``verdict``,
        ``rule`` and ``explanation``.
    """
    df = pd.DataFrame([f.to_dict() for f in audit_findings()])
    if only_inconsistent:
        df = df[df.verdict == INCONSISTENT].reset_index(drop=True)
    return df
