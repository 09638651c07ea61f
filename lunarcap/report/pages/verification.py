"""The verification page (notebooks/verification.ipynb): how far to trust each number.

Every solution the book shows passed the re-propagation gate
(:mod:`lunarcap.optim.verify`). The notebook solves the evidence with the public API: each
case of Tables 1-5 as :func:`lunarcap.solve_burn` of :func:`lunarcap.paper_plan` (the
cached solve :func:`lunarcap.capture.chain.paper_case` reaches: the same plan key), which
carries its verification, and each engine's best chain as :func:`lunarcap.solve` of
:func:`lunarcap.paper_plan`, which carries the impulsive limits behind the model-to-model
losses. :func:`build` formats them: the residuals of every case
(:func:`lunarcap.studies.sweeps.verification_table`), the largest of each beside its gate,
the impulsive limits. It also runs the one study no public call offers, a mesh-convergence
study of one case per LOI (:func:`lunarcap.optim.verify.mesh_convergence` on meshes other
than the solver's, cached by :func:`mesh_study`) that shows coarse meshes IPOPT solves to
its tolerances and the gate still rejects.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.capture.chain import perilune_state
from lunarcap.mission.plan import paper_plan
from lunarcap.optim import verify
from lunarcap.optim.collocation import DEFAULT_MESHES, Mesh
from lunarcap.optim.problem import burn_problem
from lunarcap.paper.printed import PAPER_BEST_STARTS_MIN, PAPER_ENGINES
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.display import FAILED, PASSED, verdict
from lunarcap.report.figures import verification as draw
from lunarcap.report.page import Page, solver_description
from lunarcap.repro import paths
from lunarcap.repro.cache import cached
from lunarcap.studies import bench, sweeps

NOTEBOOK = "notebooks/verification.ipynb"
BOOK = BookPage(NOTEBOOK, "Verification", 10, (
    Execution(
        "verification", "How far to trust each number",
        parameters=dict(
            cases="paper",  # the 37 cases of Tables 1-5
            mesh_cases=[[150.0, 200.0, 1, -10.0, []], [150.0, 200.0, 2, -6.0, [-10.0]],
                        [150.0, 200.0, 3, -5.0, [-10.0, -6.0]]],
            meshes=[[2, 4, 3], [3, 6, 4], [4, 8, 4], [6, 12, 5], [8, 16, 5], [12, 24, 5],
                    [18, 36, 6]],
            dynamics="full"),
        quick_parameters=dict(
            cases=[[150.0, 200.0, 1, -10.0, []], [150.0, 200.0, 2, -6.0, [-10.0]]],
            mesh_cases=[[150.0, 200.0, 1, -10.0, []], [150.0, 200.0, 2, -6.0, [-10.0]]],
            meshes=[[4, 8, 4], [8, 16, 5]]),
        depends_on=("table3", "table4_loi3", "table5_loi3"),
        expected_s=35,
        outputs=(table_files("verification", "cases", "cases_full", "gate", "impulsive",
                             "mesh", "mesh_full")
                 + figure_files("verification", "mesh"))),
))

#: The default mesh (the first of the refinement sequence).
DEFAULT = DEFAULT_MESHES[0]

#: Gated quantities: (what, unit, column of the verification table, gate). The ΔV
#: difference is reported, not gated (:mod:`lunarcap.optim.verify`: for the same burn
#: duration the re-flown ΔV equals the rocket equation whatever the trajectory).
GATES = (
    ("end position, propagated − collocation", "m", "final_position_diff_m",
     verify.TOL_POSITION_M),
    ("end speed, propagated − collocation", "m/s", "end_speed_diff_mps", verify.TOL_SPEED_MPS),
    ("|objective re-propagated − collocation|", "m/s", "objective_diff_mps", verify.TOL_DV_MPS),
    ("|r_p − target|", "m", "rp_error_m", verify.TOL_RP_M),
    ("|r_a − target| (LOI 3)", "m", "ra_error_m", verify.TOL_RP_M),
    ("|i − 90°|", "deg", "inc_error_deg", verify.TOL_ANGLE_DEG),
    ("|γ| at the end", "deg", "gamma_error_deg", verify.TOL_ANGLE_DEG),
    ("|ΔV re-propagated − ΔV collocation| (not gated)", "m/s", "verified_delta_v_diff_mps",
     np.nan),
)

IPOPT_OK = {"Solve_Succeeded": "succeeded", "Solved_To_Acceptable_Level": "acceptable"}


def cases_of(cases) -> list:
    """The cases a notebook solves: (thrust N, Isp s, LOI, start min, earlier starts min).

    ``cases``: "paper" (the 37 cases of the paper's Tables 1-5, each after Table B1's
    earlier burns) or a list of [thrust_N, isp_s, loi, start_min, [earlier starts]].

    >>> len(cases_of("paper")), cases_of([[150, 200, 2, -6, [-10]]])
    (37, [(150.0, 200.0, 2, -6.0, (-10.0,))])
    """
    if isinstance(cases, str):
        if cases != "paper":
            raise ValueError(f'cases must be "paper" or a list, got {cases!r}')
        return [(float(t), float(i), int(n), float(s), tuple(p))
                for t, i, n, s, p in bench.paper_cases()]
    return [(float(t), float(i), int(n), float(s), tuple(float(x) for x in p))
            for t, i, n, s, p in cases]


def case_of(burn) -> tuple:
    """(thrust N, Isp s, LOI, start min, earlier starts min) of a solved burn.

    ``burn``: a :class:`lunarcap.BurnSolution` (its plan as solved: the ignitions applied).
    """
    plan, n = burn.plan, burn.burn
    return (float(plan.engine.thrust_N), float(plan.engine.isp_s), int(n),
            float(plan.burns[n - 1].start_min),
            tuple(float(b.start_min) for b in plan.burns[:n - 1]))


def fixed_point(v: float, sig: int = 2, sign: bool = False) -> str:
    """``v`` in fixed-point notation with ``sig`` significant digits (no exponent).

    Grouped thousands from 1000 up; "0" for zero and never a negative zero; "—" for NaN.

    Examples
    --------
    >>> fixed_point(3.0e-9), fixed_point(-2.1e5, sign=True), fixed_point(-0.0, sign=True)
    ('0.0000000030', '-210,000', '0')
    """
    if not np.isfinite(v):
        return "—"
    if v == 0:
        return "0"
    exponent = int(np.floor(np.log10(abs(v))))
    digits = sig - 1 - exponent
    return f"{round(v, digits):{'+' if sign else ''},.{max(0, digits)}f}"


def _case_text(thrust_N, loi, start_min, with_engine: bool = True) -> str:
    return (f"{thrust_N:g} N, " if with_engine else "") + f"LOI {loi}, {start_min:g} min"


def cases_table(burns) -> pd.DataFrame:
    """Verification residuals of every case the notebook solved, one row each.

    ``burns``: :class:`lunarcap.BurnSolution` each (their solutions carry the
    verification). The columns of :func:`lunarcap.studies.sweeps.verification_table` plus
    ``case`` (text), ``table_b1`` (yes: a link of a Table B1 chain); ``passed`` as yes /
    no, the mesh as 'n×m LGR-d'.
    """
    case_list = [case_of(b) for b in burns]
    ver = sweeps.verification_table([b.solution for b in burns])
    b1 = ["yes" if tuple(PAPER_BEST_STARTS_MIN.get(t, ())[:n]) == tuple(p) + (s,) else ""
          for t, i, n, s, p in case_list]
    ver.insert(0, "case", [_case_text(t, n, s) + (", B1" if b == "yes" else "")
                           for (t, i, n, s, p), b in zip(case_list, b1)])
    ver.insert(5, "table_b1", b1)
    ver.insert(6, "previous_starts_min", [" ".join(f"{x:g}" for x in p) for *_, p in case_list])
    ver["passed"] = ver.passed.map(verdict)
    ver["mesh"] = ver.mesh.str.replace("x", "×")
    ver["ra_error_m"] = pd.to_numeric(ver.ra_error_m, errors="coerce")  # NaN: not circular
    return ver


def worst(ver: pd.DataFrame, col: str) -> tuple:
    """Largest |value| of a column and the case it belongs to (NaN, "" if none)."""
    a = ver[col].abs()
    if a.notna().sum() == 0:
        return np.nan, ""
    r = ver.loc[a.idxmax()]
    return float(a.max()), _case_text(r.thrust_N, r.loi, r.start_min)


def gate_table(ver: pd.DataFrame) -> pd.DataFrame:
    """The largest residual of each gated quantity beside its gate, and the margin."""
    rows = []
    for q, u, c, g in GATES:
        w, where = worst(ver, c)
        rows.append({"quantity": q, "unit": u, "gate": g, "worst": w,
                     "worst_shown": fixed_point(w), "worst_case": where,
                     "gate_over_worst": g / w})
    return pd.DataFrame(rows)


def impulsive_table(case_list, chains) -> pd.DataFrame:
    """The impulsive limits along each engine's best chain, for the LOIs of ``case_list``.

    ``chains``: :class:`lunarcap.CaptureResult` of the paper's plan per engine of
    ``case_list`` (Table B1's ignitions), solved with its impulsive limits.
    """
    by_engine = {(float(c.plan.engine.thrust_N), float(c.plan.engine.isp_s)): c
                 for c in chains}
    rows = []
    for t, i in sorted({(t, i) for t, i, n, s, p in case_list}):
        for n in sorted({n for tt, _, n, _, _ in case_list if tt == t}):
            imp = by_engine[(t, i)].burns[n - 1].impulsive
            rows.append({"thrust_N": t, "loi": n, "burn_long_s": imp["burn_long_s"],
                         "delta_v_long_mps": imp["delta_v_long_mps"],
                         "burn_short_s": imp["burn_short_s"],
                         "delta_v_short_mps": imp["delta_v_short_mps"],
                         "delta_v_mps": imp["delta_v_mps"],
                         "extrapolation_mps": imp["delta_v_mps"] - imp["delta_v_short_mps"],
                         "verified": verdict(imp["verification_passed"])})
    return pd.DataFrame(rows)


@cached
def mesh_study(thrust_N: float, isp_s: float, loi: int, start_min: float,
               previous_starts: tuple, meshes: tuple, dynamics: str) -> pd.DataFrame:
    """:func:`lunarcap.optim.verify.mesh_convergence` of one burn of the paper's plan (cached).

    The burn starts from the arrival state (LOI 1) or from the verified end state of the
    earlier burns ignited at ``previous_starts`` (min); ``meshes``: (burn intervals, coast
    intervals, LGR degree) each.
    """
    plan = paper_plan(thrust_N, isp_s, dynamics=dynamics)
    for j, s in enumerate((*previous_starts, start_min)):
        plan = plan.with_start(j, s)
    plan = plan.key(loi)
    x_peri = perilune_state(plan, loi - 1)  # arrival state, or the previous verified burn's
    prob = burn_problem(plan, loi - 1, x_peri, plan.ephemeris_model())
    return verify.mesh_convergence(prob, [Mesh(*m) for m in meshes])


def _outside_gate(r) -> str:
    """The gated residuals of a mesh solve that exceed the gate, as text."""
    if r.ipopt_status not in IPOPT_OK.values():
        return "IPOPT did not converge"
    out = ", ".join(
        f"{name} {fixed_point(r[col], sign=True)} {unit}" for name, col, unit, tol in (
            ("end position", "final_position_diff_m", "m", verify.TOL_POSITION_M),
            ("end speed", "end_speed_diff_mps", "m/s", verify.TOL_SPEED_MPS),
            ("J", "objective_diff_mps", "m/s", verify.TOL_DV_MPS),
            ("r_p", "rp_error_m", "m", verify.TOL_RP_M),
            ("r_a", "ra_error_m", "m", verify.TOL_RP_M),
            ("i", "inc_error_deg", "deg", verify.TOL_ANGLE_DEG),
            ("γ", "gamma_error_deg", "deg", verify.TOL_ANGLE_DEG))
        if col in r and np.isfinite(r[col]) and not abs(r[col]) < tol)
    return out or str(r.get("failures", "")) or "another condition (the CSV has the residuals)"


def mesh_table(mesh_cases, meshes, dynamics: str) -> pd.DataFrame:
    """The mesh studies of ``mesh_cases`` in one table (``accepted``: yes / no)."""
    one_engine = len({(c[0], c[1]) for c in mesh_cases}) == 1
    studies = []
    for t, i, n, s, p in mesh_cases:
        df = mesh_study(float(t), float(i), int(n), float(s), tuple(float(x) for x in p),
                        tuple(tuple(int(k) for k in m) for m in meshes), dynamics)
        studies.append(df.assign(case=_case_text(float(t), int(n), float(s), not one_engine)))
    m = pd.concat(studies, ignore_index=True)
    for c in ("verified_delta_v_diff_mps", "objective_diff_mps", "rp_error_m", "ra_error_m",
              "inc_error_deg", "gamma_error_deg", "final_position_diff_m",
              "end_speed_diff_mps"):  # NaN: not solved, or not applicable
        m[c] = pd.to_numeric(m[c], errors="coerce") if c in m else np.nan
    is_default = ((m.n_burn == DEFAULT.n_burn) & (m.n_coast == DEFAULT.n_coast)
                  & (m.degree == DEFAULT.degree))
    m["default"] = np.where(is_default, "yes", "")
    m["mesh"] = [f"{a}×{b} LGR-{d}" + (" (default)" if dflt else "")
                 for a, b, d, dflt in zip(m.n_burn, m.n_coast, m.degree, is_default)]
    passed = m.passed if "passed" in m else pd.Series(False, index=m.index)
    m["accepted"] = passed.astype("boolean").fillna(False).astype(bool).map(verdict)
    m["ipopt_status"] = m.ipopt_status.replace(IPOPT_OK)
    m["outside_gate"] = [_outside_gate(r) if r.accepted == FAILED else ""
                         for _, r in m.iterrows()]
    cols = ["case", "mesh", "ipopt_status", "delta_v_mps", "delta_v_change_vs_finest_mps",
            "outside_gate", "accepted"]
    return m[cols + [c for c in m.columns if c not in cols]]


def _download(name: str) -> str:
    """A MyST download link to ``tables/<name>.csv`` from a generated page."""
    p = paths.table_path(name)
    return f"{{download}}`{p.name} <{paths.relative_to_page(p)}>`"


def case_context(case_list) -> dict:
    """How the captions name the cases: engines text, whether the paper's, after Table B1.

    ``engines_txt`` lists the engines ("150 N / 200 s, ..."); ``paper_txt`` is ", the
    paper's" when every engine is one of the paper's; ``after_b1`` is True when every case
    follows the paper's best earlier burns.
    """
    engines = sorted({(t, i) for t, i, *_ in case_list})
    paper = all(PAPER_ENGINES.get(int(t)) == i for t, i in engines)
    return {"engines_txt": ", ".join(f"{t:g} N / {i:g} s" for t, i in engines),
            "paper_txt": ", the paper's" if paper else "",
            "after_b1": all(tuple(p) == tuple(PAPER_BEST_STARTS_MIN.get(t, ())[:n - 1])
                            for t, i, n, s, p in case_list)}


def gate_verdict(n_passed: int, n_cases: int) -> str:
    """How many solutions pass the gate, in words that follow the counts.

    >>> gate_verdict(37, 37), gate_verdict(35, 37)
    ('All 37 of 37 solutions pass the gate', 'Only 35 of 37 solutions pass the gate')
    """
    return (f"{'All' if n_passed == n_cases else 'Only'} {n_passed} of {n_cases} solutions "
            "pass the gate")


def prose_values(ver: pd.DataFrame, mesh: pd.DataFrame, default_points: int) -> dict:
    """The numbers the prose quotes: the gates, the counts, the meshes IPOPT got wrong."""
    ipopt_ok = mesh.ipopt_status.isin(IPOPT_OK.values())
    fooled = mesh[ipopt_ok & (mesh.accepted == FAILED)]
    at_default = mesh[mesh.default == "yes"]
    values = {"tol_dv_mps": verify.TOL_DV_MPS, "tol_rp_m": verify.TOL_RP_M,
              "tol_angle_deg": verify.TOL_ANGLE_DEG, "tol_position_m": verify.TOL_POSITION_M,
              "tol_speed_mmps": verify.TOL_SPEED_MPS * 1e3,
              "n_cases": len(ver), "n_passed": int((ver.passed == PASSED).sum()),
              "gate_verdict": gate_verdict(int((ver.passed == PASSED).sum()), len(ver)),
              "n_fooled": len(fooled), "n_mesh_solves": len(mesh),
              "fooled_max_rp_m": fooled.rp_error_m.abs().max() if len(fooled) else np.nan,
              "fooled_max_gamma_deg": (fooled.gamma_error_deg.abs().max() if len(fooled)
                                       else np.nan),
              "default_n_burn": DEFAULT.n_burn, "default_n_coast": DEFAULT.n_coast,
              "default_degree": DEFAULT.degree, "default_points": default_points,
              "default_max_change_mps": (at_default.delta_v_change_vs_finest_mps.abs().max()
                                         if len(at_default) else np.nan)}
    for q, u, c, g in GATES:
        values[f"worst_{c}"] = worst(ver, c)[0]
    return values


def _add_cases(page: Page, ver: pd.DataFrame, case_list, dynamics: str) -> None:
    n_passed = int((ver.passed == PASSED).sum())
    ctx = case_context(case_list)
    engines_txt, paper_txt, after_b1 = ctx["engines_txt"], ctx["paper_txt"], ctx["after_b1"]
    output_name = page.output_name
    residuals = ["final_position_diff_m", "end_speed_diff_mps", "objective_diff_mps",
                 "rp_error_m", "ra_error_m", "inc_error_deg", "gamma_error_deg"]
    page.table(
        "cases", ver[["case", "thrust_N", "loi", "start_min", "previous_starts_min", "table_b1",
                      *residuals, "passed"]],
        caption=(f"Verification of {len(ver)} solutions ({dynamics} dynamics; engines "
                 f"{engines_txt}{paper_txt}). "
                 "Case: thrust, LOI, ignition (min); LOI 2 and 3 "
                 + ("after the paper's best earlier burns" if after_b1 else
                    "after the earlier burns of the CSV")
                 + ". Residuals of the re-propagated flight against the collocation and the "
                 f"targets. Passed: {n_passed} of {len(ver)}. Every column: "
                 f"{_download(f'{output_name}_cases_full')}."),
        columns={"final_position_diff_m": "end pos. (m)", "end_speed_diff_mps": "end speed (m/s)",
                 "objective_diff_mps": "J diff (m/s)"},
        floatfmt={"final_position_diff_m": ".2f", "end_speed_diff_mps": "+.6f",
                  "objective_diff_mps": "+.5f", "rp_error_m": "+.3f", "ra_error_m": "+.3f",
                  "inc_error_deg": "+.7f", "gamma_error_deg": "+.7f"},
        show_columns=["case", *[c for c in residuals if c != "objective_diff_mps"]])
    page.table("cases_full", ver, caption=f"Verification of {len(ver)} solutions, every column.")
    gate = gate_table(ver)
    page.table(
        "gate", gate,
        caption=(f"The largest residual of each quantity over the {len(ver)} solutions, beside "
                 "the gate, and the margin gate ÷ worst (the re-flown ΔV is reported, not "
                 "gated: at the same duration it is the rocket equation's)."),
        columns={"quantity": "quantity", "unit": "unit", "gate": "gate",
                 "worst_shown": "worst", "worst_case": "worst case",
                 "gate_over_worst": "gate ÷ worst"},
        floatfmt={"gate": "g", "gate_over_worst": ",.0f"},
        show_columns=["quantity", "unit", "gate", "worst_shown", "worst_case",
                      "gate_over_worst"])



def _add_impulsive(page: Page, imp: pd.DataFrame) -> None:
    n_imp_ok = int((imp.verified == PASSED).sum())
    page.table(
        "impulsive", imp,
        caption=("The impulsive delta-V in our dynamics ({doc}`summary`): a burn of about 4 s "
                 "and one half as long from the same orbit, Richardson-extrapolated to zero "
                 f"duration. Both burns pass the gate in {n_imp_ok} of {len(imp)} rows."),
        columns={"burn_long_s": "long burn (s)", "delta_v_long_mps": "ΔV, long (m/s)",
                 "burn_short_s": "short burn (s)", "delta_v_short_mps": "ΔV, short (m/s)",
                 "delta_v_mps": "ΔV, limit (m/s)", "extrapolation_mps": "limit − short (m/s)",
                 "verified": "both verified"},
        floatfmt={"thrust_N": "g", "burn_long_s": ".2f", "burn_short_s": ".2f",
                  "delta_v_long_mps": ".3f", "delta_v_short_mps": ".3f", "delta_v_mps": ".3f",
                  "extrapolation_mps": "+.4f"},
        show_columns=["thrust_N", "loi", "burn_long_s", "delta_v_long_mps",
                      "delta_v_short_mps", "delta_v_mps", "extrapolation_mps"])



def _add_mesh(page: Page, mesh: pd.DataFrame, mesh_list, default_points: int) -> None:
    output_name = page.output_name
    one_engine = len({(c[0], c[1]) for c in mesh_list}) == 1
    page.table(
        "mesh", mesh[["case", "mesh", "ipopt_status", "delta_v_mps",
                      "delta_v_change_vs_finest_mps", "outside_gate", "accepted"]],
        caption=("Mesh convergence of one case per LOI"
                 + (f" ({mesh_list[0][0]:g} N / {mesh_list[0][1]:g} s)" if one_engine else "")
                 + ". Mesh: burn × coast intervals, LGR degree. Outside the gate: the flown "
                 "solution's residuals that exceed it. All residuals: "
                 f"{_download(f'{output_name}_mesh_full')}."),
        columns={"ipopt_status": "IPOPT", "delta_v_change_vs_finest_mps": "ΔV − finest (m/s)",
                 "outside_gate": "outside the gate", "accepted": "accepted"},
        floatfmt={"delta_v_mps": ".4f", "delta_v_change_vs_finest_mps": "+.6f"})
    page.table("mesh_full", mesh, caption="Mesh convergence, every column.")
    page.figure(
        "mesh_figure",
        draw.plot_mesh_convergence(mesh.assign(accepted=mesh.accepted == PASSED),
                                      verify.TOL_DV_MPS, default_points),
        caption=("Change of ΔV from the finest mesh (m/s, log) against collocation points: "
                 "circles passed the gate, crosses IPOPT solutions it rejected, triangles the "
                 f"finest mesh. Dotted: {verify.TOL_DV_MPS:g} m/s, the objective's gate, for "
                 "scale; dashed: the default mesh."),
        alt="Delta-V change against collocation points for each mesh-convergence case",
        name="mesh")


def _add_checks(page: Page, ver, imp, mesh, values: dict, default_points: int) -> None:
    at_default = mesh[mesh.default == "yes"]
    page.expect("every solution passes the gate", values["n_passed"] == len(ver),
                str(ver[ver.passed != PASSED].case.tolist()))
    page.expect("every impulsive limit passes the gate",
                int((imp.verified == PASSED).sum()) == len(imp))
    page.expect("the default mesh is accepted", bool((at_default.accepted == PASSED).all()))
    # the prose: converged to well below the paper's printed 0.001 m/s
    page.expect("the default mesh within 0.1 mm/s of the finest",
                bool((at_default.delta_v_change_vs_finest_mps.abs() < 1e-4).all()),
                f"{values['default_max_change_mps']:.2g} m/s")
    if (mesh.collocation_points < default_points).any():
        # IPOPT success alone would have accepted a wrong answer (the prose says so)
        page.expect("a coarse mesh IPOPT solved is rejected by the gate",
                    values["n_fooled"] > 0)


def build(burns, chains, mesh_cases=((150.0, 200.0, 1, -10.0, ()),),
          meshes=((4, 8, 4), (8, 16, 5)), output_name: str = "verification",
          quick: bool = False, parameters: dict | None = None) -> Page:
    """The verification page of the solves the notebook made (see the module docstring).

    Parameters
    ----------
    burns : list of lunarcap.BurnSolution
        Each case, :func:`lunarcap.solve_burn` of :func:`lunarcap.paper_plan` (one
        dynamics for all), with its verification.
    chains : list of lunarcap.CaptureResult
        :func:`lunarcap.solve` of :func:`lunarcap.paper_plan` for each engine of ``burns``,
        with its impulsive limits (the model-to-model losses' references).
    mesh_cases : cases (thrust N, Isp s, LOI, start min, [earlier starts min]) of the
        mesh-convergence study the page runs (no public call: meshes other than the solver's)
    meshes : [[burn intervals, coast intervals, LGR degree], ...], coarse to fine (the last
        is the reference)
    output_name, quick : the page's output name and whether it is a quick build.
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance.
    """
    dynamics = burns[0].plan.dynamics
    params = {k: v if isinstance(v, str) else [list(c) for c in v]
              for k, v in (parameters or {}).items()}
    page = Page(NOTEBOOK, params, output_name, quick, solver_description())
    case_list = [case_of(b) for b in burns]
    mesh_list = cases_of(mesh_cases)
    default_points = (DEFAULT.n_burn + DEFAULT.n_coast) * DEFAULT.degree

    ver = cases_table(burns)
    _add_cases(page, ver, case_list, dynamics)
    imp = impulsive_table(case_list, chains)
    _add_impulsive(page, imp)
    mesh = mesh_table(mesh_cases, meshes, dynamics)
    _add_mesh(page, mesh, mesh_list, default_points)
    values = prose_values(ver, mesh, default_points)
    for k, v in values.items():
        page.value(k, v if isinstance(v, str) else float(v))
    _add_checks(page, ver, imp, mesh, values, default_points)
    page.data.update(cases=ver, mesh=mesh, impulsive=imp)
    t = page.text
    page.headline(f"{t('n_passed', '.0f')} of {t('n_cases', '.0f')} solutions pass the "
                  f"re-propagation gate; the flown end positions are within "
                  f"{t('worst_final_position_diff_m', '.1f', ' m')} of the collocation's.")
    return page
