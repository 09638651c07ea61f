"""Audit checks (a)-(e): constants, the difference column, masses, fuel, losses.

Each ``_check_<x>`` returns the findings of one group (titles in
:data:`lunarcap.paper.audit.AUDIT_CHECK_TITLES`).
"""

from __future__ import annotations

import numpy as np

from lunarcap.paper import printed as P
from lunarcap.paper.finding import (
    _IMP,
    _LOIS,
    _THRUSTS,
    DURATION_RESOLUTION_MIN,
    L_B,
    SOLVER_REL_TOL,
    Finding,
    _half,
    _ok,
    _propagate,
    _qv,
    _rounding_note,
    _where,
)
from lunarcap.paper.recompute import (
    _best_dvs,
    _burn_min,
    _finite_chain,
    _fuel,
    _fuel_from_burn,
    _m0_star,
    _mass_after,
    _printed_mass_starts,
    _ve,
    fuel_sentence_check,
    implied_arrival_mass_kg,
)
from lunarcap.physics import constants as C
from lunarcap.physics.rocket import rocket_delta_v_mps, rocket_mass_before

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
    """(c) masses vs the rocket equation and the implied arrival mass.

    Also fuel vs burn time, every row's burn duration, and the thrust Table 4's LOI-1 rows
    imply.
    """
    out = _masses_vs_rocket_equation()
    out.append(_arrival_mass_implied())
    out.extend(_fuel_vs_burn_durations())
    rows, thrust_rows, starts = _row_durations()
    out.extend(rows)
    out.append(_thrust_300N_loi1(thrust_rows, starts))
    return out


def _masses_vs_rocket_equation() -> list[Finding]:
    """Each printed mass against the rocket equation from the mass before it."""
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
        implied_m = rocket_mass_before(p, sum(dvs), isp_s)
        implied_dv = rocket_delta_v_mps(m_before, p, isp_s)
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
    return out


def _arrival_mass_implied() -> Finding:
    """The printed arrival mass against the one the printed results imply."""
    m0 = _qv("arrival_mass_kg")
    hm = _half("arrival_mass_kg")
    imp = implied_arrival_mass_kg()
    precise = [imp[k] for k in ("150N mass after LOI 1", "300N final mass", "450N final mass")]
    x = float(np.mean(precise))
    spread = max(precise) - min(precise)
    listing = "; ".join(f"{k}: {v:.3f}" for k, v in imp.items())
    return Finding(
        "mass/arrival-implied", "c", _where("arrival_mass_kg"),
        "arrival mass vs the arrival mass implied by the printed results (mean of the "
        "150 N mass after LOI 1 and the 300 N and 450 N final masses)",
        m0, x, "kg", hm + spread / 2 + SOLVER_REL_TOL * x,
        f"Arrival masses implied (rocket equation / T t/(g0 Isp)), kg: {listing}. The three "
        f"mass-based values agree to {spread:.3f} kg; their mean is {x:.3f} kg, "
        f"{m0 - x:.3f} kg below the printed {m0:.3f} kg. The burn-time-based values carry "
        "the rounding of the durations (about 0.1 kg).",
        extra={"implied": imp, "mean_of_mass_based": x, "spread": spread})


def _fuel_vs_burn_durations() -> list[Finding]:
    """Propellant from the printed masses against T t / (g0 Isp) from the burn times."""
    out = []
    m0 = _qv("arrival_mass_kg")
    hm = _half("arrival_mass_kg")
    isp = {t: P.PAPER_ENGINES[t] for t in _THRUSTS}
    m1, m2 = _qv("mass_after_loi1_150N_kg"), _qv("mass_after_loi2_150N_kg")
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
    return out


def _row_durations() -> tuple[list[Finding], dict, dict]:
    """Every table row's burn duration against its delta-V.

    Start masses: those consistent with the paper's printed masses (see
    :func:`_printed_mass_starts`); the printed arrival mass is used for comparison in the
    explanation. Returns the findings, the thrust each row implies per (thrust, LOI), and
    the start masses.
    """
    out = []
    m0 = _qv("arrival_mass_kg")
    isp = {t: P.PAPER_ENGINES[t] for t in _THRUSTS}
    m1, m2 = _qv("mass_after_loi1_150N_kg"), _qv("mass_after_loi2_150N_kg")
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
                             / _fuel(1.0, row.delta_v_mps, isp[t]))
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
    return out, thrust_rows, starts


def _thrust_300N_loi1(thrust_rows: dict, starts: dict) -> Finding:
    """The 300 N engine's thrust against the thrust Table 4's LOI-1 rows imply."""
    m0 = _qv("arrival_mass_kg")
    isp = {t: P.PAPER_ENGINES[t] for t in _THRUSTS}
    vals = thrust_rows[(300, 1)]
    rows = list(P.paper_table(300, 1).itertuples())
    x = float(np.mean(vals))
    vals0 = [_fuel(m0, r.delta_v_mps, isp[300]) * _ve(isp[300]) / (r.burn_duration_min * 60)
             for r in rows]
    return Finding(
        "thrust/300N/LOI1", "c", "Table 4 (1st LOI), all rows",
        "engine thrust vs the thrust implied by each row's delta-V and duration (mean of the "
        "rows)", 300.0, x, "N",
        300 * (0.005 / min(r.burn_duration_min for r in rows) + SOLVER_REL_TOL),
        f"Implied thrusts {', '.join(f'{v:.1f}' for v in vals)} N from a start mass of "
        f"{starts[300][0][0]:.3f} kg ({', '.join(f'{v:.1f}' for v in vals0)} N from "
        f"{m0:.3f} kg); the LOI-2 and LOI-3 rows of Table 4 imply "
        + " and ".join(f"{np.mean(thrust_rows[(300, k)]):.1f}" for k in (2, 3)) + " N.",
        extra={"implied_thrust_N": vals, "implied_thrust_from_printed_m0_N": vals0})


# ---------------------------------------------------------------------------------------
# (d) the fuel-mass sentences
# ---------------------------------------------------------------------------------------


def _check_d() -> list[Finding]:
    """(d) the fuel-mass sentences of Sec. 3.2.1-3.2.2."""
    out = []
    for t in _THRUSTS:
        out.extend(_fuel_as_labelled(t))
    out.extend(_fuel_stated_differences())
    out.extend(_fuel_about())
    return out


def _fuel_as_labelled(t: int) -> list[Finding]:
    """One engine's printed finite and impulsive propellant, as labelled."""
    out = []
    m0 = _qv("arrival_mass_kg")
    hm = _half("arrival_mass_kg")
    isp = P.PAPER_ENGINES[t]
    fs = fuel_sentence_check(t)
    pf, pi = fs["printed_finite_kg"], fs["printed_impulsive_kg"]
    cf, ci = fs["computed_finite_kg"], fs["computed_impulsive_kg"]
    qf, qi = f"fuel_finite_{t}N_kg", f"fuel_impulsive_{t}N_kg"
    # impulsive: pure arithmetic on printed numbers
    _, ui = _propagate(lambda m, a, b, c: _fuel(m, a + b + c, isp),
                       (m0, hm), *[(d, 0.0005) for d in _IMP])
    tol_i = _half(qi) + ui
    dv_impl = rocket_delta_v_mps(m0, m0 - pi, isp)
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
    _, uf = _propagate(lambda m, a, b, c: _fuel(m, a + b + c, isp),
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
    return out


def _fuel_stated_differences() -> list[Finding]:
    """The differences of propellant the text states ("about 2.24% more", ...)."""
    out = []
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
    return out


def _fuel_about() -> list[Finding]:
    """The "about N kg" of propellant per burn and in total."""
    out = []
    m0 = _qv("arrival_mass_kg")
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


