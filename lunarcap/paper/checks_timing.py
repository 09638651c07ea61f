"""Audit checks (f)-(k): burn-duration totals, periods, epochs, Eq. (19), the rest.

Each ``_check_<x>`` returns the findings of one group (titles in
:data:`lunarcap.paper.audit.AUDIT_CHECK_TITLES`).
"""

from __future__ import annotations

import math

from lunarcap.mission.impulsive import impulsive_sequence
from lunarcap.paper import printed as P
from lunarcap.paper.finding import (
    _IMP,
    _LOIS,
    _THRUSTS,
    SOLVER_REL_TOL,
    Finding,
    _half,
    _propagate,
    _qv,
    _rounding_note,
    _where,
)
from lunarcap.paper.recompute import (
    _burn_min,
    _finite_chain,
    _fuel,
    _impulsive_chain,
    _m0_star,
    _ve,
    implied_arrival_mass_kg,
)
from lunarcap.physics.elements import period_from_semi_major_axis, semi_major_axis_from_period
from lunarcap.physics.epochs import calendar_from_seconds, seconds_from_calendar
from lunarcap.physics.rocket import rocket_propellant_kg

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
        return float(period_from_semi_major_axis(r_ + h, mu_)) / 60

    x, u = _propagate(period, (mu, _half("mu_moon_km3s2")), (R, _half("r_moon_km")))
    r_impl = float(semi_major_axis_from_period(p * 60, mu))
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
    mf_printed = rocket_propellant_kg(m0, _IMP[0], isp)  # Eq. (19a) as printed: m0 [1 - e^-x]
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

