"""The lunar-pole page (notebooks/lunar_pole.ipynb): which pole fixes M-MME2000, and its effect.

The paper's frame, M-MME2000 ("Moon centered Moon mean equator and IAU vector of J2000",
Song 2011, Sec. 1, defined in Song et al. 2010b), has its z axis along the Moon's pole
at J2000 from the IAU orientation model. The IAU (2009) expression (Archinal et al.
2011, Table 2) has constant terms and 13 periodic terms. The notebook solves the paper's
best chains (Table B1's offsets, :func:`lunarcap.paper_plan`) and their impulsive limits
with the full expression and with its constant terms alone
(:data:`lunarcap.physics.frames.LUNAR_POLES`; :func:`lunarcap.load_plan` with
``lunar_pole``, then :func:`lunarcap.solve`); :func:`build` tabulates both poles and the
difference they make: every burn, its impulsive limit in the same dynamics and the loss
between them, so a reader sees what the periodic terms are worth.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.paper.printed import PAPER_ENGINES, paper_table_b1
from lunarcap.physics import frames
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.display import PASSED, verdict
from lunarcap.report.labels import engine_label
from lunarcap.report.page import Page

NOTEBOOK = "notebooks/lunar_pole.ipynb"
BOOK = BookPage(NOTEBOOK, "The problem", 20, (
    Execution(
        "lunar_pole", "The lunar pole of M-MME2000",
        parameters=dict(dynamics="full", thrusts_N=None),
        quick_parameters=dict(dynamics="two-body", thrusts_N=[150.0]),
        expected_s=19,
        outputs=table_files("lunar_pole", "poles", "effect")),
))
#: The poles compared: the whole IAU (2009) expression at J2000 (lunarcap's), and its
#: constant terms alone.
NEW, OLD = frames.LUNAR_POLES


def pole_table() -> pd.DataFrame:
    """Both poles: right ascension and declination (deg), and angles between them (deg)."""
    ecl = frames.moon_pole_icrf(270.0, 90.0 - 23.4392911)  # the J2000 ecliptic pole
    rows = []
    for p in frames.LUNAR_POLES:
        ra, dec = frames.moon_pole_radec_deg(p)
        z = frames.moon_pole_icrf(ra, dec)
        rows.append({"pole": p, "ra_deg": ra, "dec_deg": dec,
                     "from_ecliptic_pole_deg": float(np.degrees(np.arccos(z @ ecl)))})
    return pd.DataFrame(rows)


def paper_engines(thrusts_N=None) -> list:
    """The paper's engines the page compares: [(thrust N, Isp s)] of Table B1.

    ``thrusts_N``: which of 150, 300 and 450 N (None: all three); another thrust is
    refused, since only the paper's engines have Table B1's ignitions to solve at.

    >>> paper_engines([300])
    [(300.0, 250.0)]
    >>> len(paper_engines())
    3
    """
    thrusts = [150.0, 300.0, 450.0] if thrusts_N is None else [float(t) for t in thrusts_N]
    bad = [t for t in thrusts if int(t) not in PAPER_ENGINES]
    if bad:
        raise ValueError(f"thrusts_N must be among the paper's engines 150, 300, 450 N, "
                         f"got {bad}")
    return [(t, PAPER_ENGINES[int(t)]) for t in thrusts]


def effect_table(captures: dict) -> pd.DataFrame:
    """Each burn of the best chains with both poles: delta-V, impulsive limit, loss (m/s).

    ``captures``: {pole: [lunarcap.CaptureResult]}, both poles of :data:`NEW`, :data:`OLD`, the
    same engines in the same order (see :func:`build`).
    """
    rows = []
    for new, old in zip(captures[NEW], captures[OLD]):
        res = {}
        for pole, cap in ((NEW, new), (OLD, old)):
            res[pole] = ([b.solution.delta_v_mps for b in cap.burns],
                         [b.impulsive["delta_v_mps"] for b in cap.burns],
                         [b.solution.verification.passed and b.impulsive["verification_passed"]
                          for b in cap.burns])
        thrust, isp = new.plan.engine.thrust_N, new.plan.engine.isp_s
        for n in range(3):
            dv_new, imp_new, ok_new = (r[n] for r in res[NEW])
            dv_old, imp_old, ok_old = (r[n] for r in res[OLD])
            rows.append({"engine": engine_label(thrust, isp), "loi": n + 1,
                         "start_min": new.plan.burns[n].start_min, "dv_new_mps": dv_new,
                         "dv_old_mps": dv_old, "dv_effect_mps": dv_new - dv_old,
                         "impulsive_limit_effect_mps": imp_new - imp_old,
                         "delta_v_loss_new_mps": dv_new - imp_new,
                         "delta_v_loss_effect_mps": (dv_new - imp_new) - (dv_old - imp_old),
                         "verified": verdict(ok_new and ok_old)})
    return pd.DataFrame(rows)


def _check_captures(captures: dict) -> None:
    """Both poles, the same plans but for the pole, each burn with its impulsive limit.

    The effect table subtracts one pole's chain from the other's burn by burn: a missing
    pole, another engine, ignition or dynamics, or a burn without its impulsive limit
    would make that difference meaningless, so it is refused with what is wrong.
    """
    missing = [p for p in frames.LUNAR_POLES if p not in captures]
    if missing:
        raise ValueError(f"captures: one list per pole {list(frames.LUNAR_POLES)}, missing "
                         f"{missing}")
    plans = {p: [(c.plan.engine, [b.start_min for b in c.plan.burns], str(c.plan.dynamics))
                 for c in captures[p]] for p in (NEW, OLD)}
    if plans[NEW] != plans[OLD] or not plans[NEW]:
        raise ValueError("captures: the same engines, ignitions and dynamics with each pole")
    for c in (*captures[NEW], *captures[OLD]):
        if not c.complete or any(b.impulsive is None for b in c.burns):
            raise ValueError(f"captures: {c.plan.name} needs every burn solved with its "
                             "impulsive limit (lunarcap.solve(..., impulsive=True))")


def build(captures: dict, output_name: str = "lunar_pole", quick: bool = False) -> Page:
    """The page of the captures solved in the notebook (see the module docstring).

    Parameters
    ----------
    captures : dict
        ``{pole: [lunarcap.CaptureResult]}`` for both poles of
        :data:`lunarcap.physics.frames.LUNAR_POLES`
        (``"iau2009-j2000"``, ``"iau-constant"``): per engine of :func:`paper_engines`,
        :func:`lunarcap.solve` (with the impulsive limits) of :func:`lunarcap.paper_plan`
        (Table B1's ignitions) with that pole (:func:`lunarcap.load_plan`,
        ``lunar_pole=``), the same engines in the same order for both.
    output_name : str
        Prefix of the CSV files.
    quick : bool
        Recorded in the provenance only.

    The provenance's parameters (``dynamics``, ``thrusts_N``) are read from the plans.
    """
    _check_captures(captures)
    plans = [c.plan for c in captures[NEW]]
    thrusts = [float(p.engine.thrust_N) for p in plans]
    dynamics = str(plans[0].dynamics)
    page = Page(NOTEBOOK, dict(dynamics=dynamics, thrusts_N=thrusts), output_name, quick)
    poles = pole_table()
    page.table("poles", poles,
               caption="The two lunar poles: right ascension and declination in ICRF (deg) "
                       "and the angle from the J2000 ecliptic pole (deg). iau2009-j2000 is "
                       "the whole IAU (2009) expression at J2000 (Table 2 of "
                       "{cite:t}`archinal2011`); iau-constant its constant terms only.",
               columns={"pole": "pole", "ra_deg": "α₀ (deg)", "dec_deg": "δ₀ (deg)",
                        "from_ecliptic_pole_deg": "from ecliptic pole (deg)"},
               floatfmt={"ra_deg": ".4f", "dec_deg": ".4f", "from_ecliptic_pole_deg": ".3f"})
    eff = effect_table(captures)
    page.table("effect", eff,
               caption=(f"Effect of the pole on the paper's best chains (Table B1 offsets, "
                        f"{dynamics} dynamics): ΔV with the default pole (iau2009-j2000) and "
                        "the constant-term pole, and the differences of ΔV, impulsive limit "
                        "and loss."),
               columns={"start_min": "start (min)", "dv_new_mps": "ΔV, J2000 pole (m/s)",
                        "dv_old_mps": "ΔV, constant pole (m/s)",
                        "dv_effect_mps": "ΔV effect (m/s)",
                        "impulsive_limit_effect_mps": "impulsive effect (m/s)",
                        "delta_v_loss_effect_mps": "loss effect (m/s)"},
               floatfmt={"start_min": ".0f", "dv_new_mps": ".3f", "dv_old_mps": ".3f",
                         "dv_effect_mps": "+.3f", "impulsive_limit_effect_mps": "+.3f",
                         "delta_v_loss_new_mps": ".3f", "delta_v_loss_effect_mps": "+.3f"},
               show_columns=["engine", "loi", "dv_new_mps", "dv_old_mps", "dv_effect_mps",
                             "impulsive_limit_effect_mps", "delta_v_loss_effect_mps"])
    new, old = poles.iloc[0], poles.iloc[1]
    page.value("pole_ra_deg", float(new.ra_deg))
    page.value("pole_dec_deg", float(new.dec_deg))
    page.value("pole_angle_deg", frames.pole_angle_deg(NEW, OLD))
    page.value("new_from_ecliptic_deg", float(new.from_ecliptic_pole_deg))
    page.value("old_from_ecliptic_deg", float(old.from_ecliptic_pole_deg))
    for col in ("dv_effect_mps", "impulsive_limit_effect_mps", "delta_v_loss_effect_mps"):
        page.value(f"max_abs_{col}", float(eff[col].abs().max()))
        page.value(f"min_{col}", float(eff[col].min()))
        page.value(f"max_{col}", float(eff[col].max()))
    b1 = paper_table_b1()
    printed = [float(b1[(b1.thrust_N == float(t)) & (b1.loi == n)].delta_v_mps.iloc[0])
               for t in thrusts for n in (1, 2, 3)]
    page.value("median_abs_vs_paper_mps",
               float(np.median(np.abs(eff.dv_new_mps.to_numpy() - np.array(printed)))))
    page.expect("every solve verified with both poles", bool((eff.verified == PASSED).all()))
    if dynamics == "two-body":  # a rotation of the frame cannot change a two-body capture
        page.expect("two-body: the pole changes no delta-V (< 1 mm/s)",
                    float(eff.dv_effect_mps.abs().max()) < 1e-3)
    else:
        page.expect("the pole changes delta-V by less than 0.1 m/s",
                    float(eff.dv_effect_mps.abs().max()) < 0.1)
    page.headline(f"The choice of IAU pole moves a burn's finite-burn loss by at "
                  f"most {page.text('max_abs_delta_v_loss_effect_mps', '.3f', ' m/s')} "
                  f"({dynamics} dynamics).")
    page.capture("fixed", dynamics)
    return page
