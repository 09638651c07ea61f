"""The joint-capture page (notebooks/joint_capture.ipynb): all burns in one NLP.

For each engine the notebook solves, with lunarcap's public API, the paper's plan one burn
at a time with every ignition free (:func:`lunarcap.solve`: each burn minimising its own
J, Eq. 9) and as one NLP whose objective is the total delta-V
(:func:`lunarcap.solve_joint`, which starts from that chain). :func:`build` is the page's
display helper: it sets the two side by side per burn and in total, with the page's
glued numbers and checks.
"""

from __future__ import annotations

import inspect

import pandas as pd

from lunarcap.capture import joint_plan as joint
from lunarcap.quantities import capture_name
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.display import PASSED, verdict
from lunarcap.report.labels import engine_label
from lunarcap.report.page import Page

NOTEBOOK = "notebooks/joint_capture.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 40, (
    Execution(
        "joint_capture", "All three burns in one optimisation",
        parameters=dict(dynamics="full"),
        quick_parameters=dict(engines=[[450.0, 300.0]],
                              dynamics="two-body"),  # quick: about 5x faster solves
        outputs=table_files("joint_capture", "legs", "timing", "totals", "solve")),
))

#: The engines the prose quotes (glued values are NaN for an engine not built).
PROSE_THRUSTS_N = (150.0, 300.0, 450.0)

#: Columns of the per-burn table: delta-V (shown first) and timing (shown second).
DV_SHOWN = ["engine", "loi", "sequential_delta_v_mps", "joint_delta_v_mps", "difference_mps",
            "joint_verified"]
TIMING_SHOWN = ["engine", "loi", "sequential_start_min", "joint_start_min",
                "sequential_burn_duration_min", "joint_burn_duration_min"]

LEG_LABELS = {"engine": "engine (thrust / Isp)",
              "sequential_start_min": "start, sequential (min)",
              "joint_start_min": "start, joint (min)",
              "sequential_burn_duration_min": "duration, sequential (min)",
              "joint_burn_duration_min": "duration, joint (min)",
              "sequential_delta_v_mps": "ΔV, sequential (m/s)",
              "joint_delta_v_mps": "ΔV, joint (m/s)", "difference_mps": "difference (m/s)",
              "joint_verified": "verified"}
LEG_FORMATS = {"sequential_start_min": ".3f", "joint_start_min": ".3f",
               "sequential_burn_duration_min": ".3f", "joint_burn_duration_min": ".3f",
               "sequential_delta_v_mps": ".4f", "joint_delta_v_mps": ".4f",
               "difference_mps": "+.4f"}



def joint_mesh_label() -> str:
    """The mesh of the all-burns NLP (the default of :func:`joint.solve_plan_jointly`)."""
    m = inspect.signature(joint.solve_plan_jointly).parameters["mesh"].default
    return f"{m.n_burn}×{m.n_coast} LGR-{m.degree}"


def legs_table(chain, joint_solution) -> pd.DataFrame:
    """One engine's burns, one at a time (``chain``) beside the joint optimum, per LOI.

    ``chain``: :func:`lunarcap.solve`'s CaptureResult of the plan with every ignition
    free; ``joint_solution``: :func:`lunarcap.solve_joint`'s JointSolution of the plan.
    Columns: loi, joint and sequential start (min from the nominal perilune), burn
    duration (min) and delta-V (m/s), difference_mps (sequential - joint), joint_verified;
    IPOPT's status, iterations and solve time (s) of the joint NLP in ``attrs``.
    """
    rows = []
    for k, (j, s) in enumerate(zip(joint_solution.rows(), chain.rows())):
        rows.append({"loi": k + 1, "joint_start_min": j["start_min"],
                     "sequential_start_min": s["start_min"],
                     "joint_burn_duration_min": j["burn_duration_min"],
                     "sequential_burn_duration_min": s["burn_duration_min"],
                     "joint_delta_v_mps": j["delta_v_mps"],
                     "sequential_delta_v_mps": s["delta_v_mps"],
                     "difference_mps": s["delta_v_mps"] - j["delta_v_mps"],
                     "joint_verified": j["verification_passed"]})
    df = pd.DataFrame(rows)
    df.attrs.update({"thrust_N": chain.plan.engine.thrust_N,
                     "isp_s": chain.plan.engine.isp_s,
                     "ipopt_status": joint_solution.ipopt_status,
                     "iterations": joint_solution.iterations,
                     "solve_s": joint_solution.solve_s})
    return df


def warm_start_gap_mps(chain, joint_solution) -> float:
    """Largest |delta-V| difference (m/s) of a burn between ``chain`` and the joint's warm start.

    Zero when the chain shown is the one the joint NLP started from (same plan, dynamics
    and free ignitions); NaN if the two differ in their number of burns.
    """
    ours = [r["delta_v_mps"] for r in chain.rows()]
    theirs = [r["delta_v_mps"] for r in joint_solution.warm_start]
    if len(ours) != len(theirs):
        return float("nan")
    return max(abs(a - b) for a, b in zip(ours, theirs))


def totals_table(legs: dict) -> pd.DataFrame:
    """Totals per engine from ``{label: legs_table}``: both totals, shifts, the solve.

    Columns: engine, sequential_total_delta_v_mps, joint_total_delta_v_mps,
    total_difference_mps (sequential - joint), largest_leg_shift_mps,
    largest_start_shift_s, ipopt_status, ipopt_iterations, joint_solve_s.
    """
    return pd.DataFrame([{
        "engine": e, "sequential_total_delta_v_mps": df.sequential_delta_v_mps.sum(),
        "joint_total_delta_v_mps": df.joint_delta_v_mps.sum(),
        "total_difference_mps": df.difference_mps.sum(),
        "largest_leg_shift_mps": df.difference_mps.abs().max(),
        "largest_start_shift_s": 60 * (df.joint_start_min - df.sequential_start_min).abs().max(),
        "ipopt_status": df.attrs["ipopt_status"], "ipopt_iterations": df.attrs["iterations"],
        "joint_solve_s": df.attrs["solve_s"]} for e, df in legs.items()])


def legs_frame(legs: dict) -> pd.DataFrame:
    """Every leg of every engine (``legs``: engine label -> legs_table), verdicts in words."""
    per_leg = pd.concat([df.assign(engine=e) for e, df in legs.items()], ignore_index=True)
    return per_leg.assign(joint_verified=per_leg.joint_verified.map(verdict))[[
        "engine", "loi", "sequential_start_min", "joint_start_min",
        "sequential_burn_duration_min", "joint_burn_duration_min", "sequential_delta_v_mps",
        "joint_delta_v_mps", "difference_mps", "joint_verified"]]


def prose_values(by_thrust: dict, totals: pd.DataFrame) -> dict:
    """The numbers the prose quotes (NaN for an engine not built); ``by_thrust``: N -> legs."""
    nan = float("nan")
    out = {}
    for thrust in PROSE_THRUSTS_N:
        tag = f"{thrust:g}N"
        df = by_thrust.get(thrust)
        out[f"total_difference_{tag}_mps"] = (float(df.difference_mps.sum()) if df is not None
                                              else nan)
        for n in (2, 3):
            out[f"leg{n}_difference_{tag}_mps"] = (float(df.difference_mps.iloc[n - 1])
                                                   if df is not None else nan)
        out[f"leg2_extra_{tag}_mps"] = (-float(df.difference_mps.iloc[1]) if df is not None
                                        else nan)
    out["max_total_difference_mps"] = float(totals.total_difference_mps.max())
    out["max_leg_shift_mps"] = float(totals.largest_leg_shift_mps.max())
    out["max_start_shift_s"] = float(totals.largest_start_shift_s.max())
    return out


def _add_legs(page: Page, per_leg: pd.DataFrame, dynamics: str) -> None:
    case = (f"The three LOIs optimised together (joint) and one at a time with free ignition "
            f"(sequential, Eq. 9; {dynamics} dynamics).")
    page.table(
        "legs", per_leg,
        caption=(f"{case} Difference: sequential − joint; verified: each joint leg re-flown "
                 "from the previous leg's verified end. Ignitions and durations: next table."),
        columns=LEG_LABELS, floatfmt=LEG_FORMATS, show_columns=DV_SHOWN)
    page.table(
        "timing", per_leg[TIMING_SHOWN],
        caption=(f"{case} Start: ignition, min from each nominal perilune (negative: "
                 "before); duration in min."),
        columns=LEG_LABELS, floatfmt=LEG_FORMATS)


def _add_totals(page: Page, totals: pd.DataFrame) -> None:
    total_labels = {"engine": "engine (thrust / Isp)",
                    "sequential_total_delta_v_mps": "total ΔV, sequential (m/s)",
                    "joint_total_delta_v_mps": "total ΔV, joint (m/s)",
                    "total_difference_mps": "total difference (m/s)",
                    "largest_leg_shift_mps": "largest leg change (m/s)",
                    "largest_start_shift_s": "largest start change (s)",
                    "ipopt_status": "IPOPT status", "ipopt_iterations": "iterations",
                    "joint_solve_s": "solve (s)"}
    page.table(
        "totals", totals,
        caption=("Total ΔV, one burn at a time against all three in one NLP: difference "
                 "sequential − joint (the joint optimum cannot be worse), and the largest "
                 "change of one leg's ΔV and ignition between the two."),
        columns=total_labels,
        floatfmt={"sequential_total_delta_v_mps": ".4f", "joint_total_delta_v_mps": ".4f",
                  "total_difference_mps": "+.4f", "largest_leg_shift_mps": ".4f",
                  "largest_start_shift_s": ".1f", "joint_solve_s": ".1f"},
        show_columns=["engine", "sequential_total_delta_v_mps", "joint_total_delta_v_mps",
                      "total_difference_mps", "largest_leg_shift_mps",
                      "largest_start_shift_s"])
    page.table(
        "solve", totals[["engine", "ipopt_status", "ipopt_iterations", "joint_solve_s"]],
        caption=("The joint NLP per engine, warm-started from the sequential chain: IPOPT "
                 "status, iterations and wall time of the solve (s, when it was computed; "
                 "the result is cached)."),
        columns=total_labels, floatfmt={"joint_solve_s": ".1f"})


def _add_checks(page: Page, per_leg: pd.DataFrame, totals: pd.DataFrame,
                by_thrust: dict, gaps: list) -> None:
    """Headline checks: the book build fails if these drift."""
    page.expect("each joint NLP started from the one-at-a-time chain shown (1e-9 m/s)",
                all(g <= 1e-9 for g in gaps), str(gaps))
    page.expect("every joint leg passes the verification gate",
                bool((per_leg.joint_verified == PASSED).all()))
    page.expect("every joint NLP converged", bool((totals.ipopt_status == "Solve_Succeeded")
                                                  .all()), str(totals.ipopt_status.tolist()))
    page.expect("the joint optimum is never worse (1 mm/s)",
                bool((totals.total_difference_mps >= -1e-3).all()))
    # measured: at most 0.0005 m/s
    page.expect("the joint optimum saves less than 0.01 m/s",
                bool((totals.total_difference_mps < 0.01).all()),
                str(totals.total_difference_mps.tolist()))
    page.expect("ignition times move by less than 10 s",
                bool((totals.largest_start_shift_s < 10).all()))
    if 150.0 in by_thrust:
        d = by_thrust[150.0].difference_mps
        # the prose: at 150 N the joint optimum spends more on LOI 2, saves on LOI 3
        page.expect("150 N: more ΔV on LOI 2, less on LOI 3, mostly cancelling",
                    d.iloc[1] < 0 < d.iloc[2] and abs(d.sum()) < 0.1 * d.abs().max())


def build(solved: dict, dynamics: str = "full", output_name: str = "joint_capture",
          quick: bool = False) -> Page:
    """The page of the joint capture from what the notebook solved (see the module docstring).

    Parameters
    ----------
    solved : dict
        ``{(thrust N, Isp s): (chain, joint)}`` per engine, in the page's order: ``chain``
        the paper's plan with every ignition free solved one burn at a time
        (:func:`lunarcap.solve`, a CaptureResult), ``joint`` the same plan as one NLP
        (:func:`lunarcap.solve_joint`, a JointSolution).
    dynamics : str
        The plans' dynamics, as named in the captions.
    output_name, quick : the page's output name and whether it is a quick build.
    """
    engines = [(float(t), float(i)) for t, i in solved]
    params = dict(engines=[list(e) for e in engines], dynamics=dynamics)
    page = Page(NOTEBOOK, params, output_name, quick, {
        "transcription": "Legendre-Gauss-Radau collocation, one NLP for all legs, mesh "
                         + joint_mesh_label(),
        "NLP": "IPOPT (MUMPS), warm start: the one-at-a-time free-ignition chain",
        "gate": "re-propagation of each leg from the previous leg's verified end state"})
    legs = {engine_label(t, i): legs_table(*solved[t, i]) for t, i in engines}
    per_leg = legs_frame(legs)
    _add_legs(page, per_leg, dynamics)
    totals = totals_table(legs)
    _add_totals(page, totals)
    by_thrust = {t: legs[engine_label(t, i)] for t, i in engines}
    for name, v in prose_values(by_thrust, totals).items():
        page.value(name, v)
    _add_checks(page, per_leg, totals, by_thrust,
                [warm_start_gap_mps(*solved[e]) for e in engines])
    page.data["legs"] = legs
    page.headline(f"Solving the capture as one problem (*{capture_name('joint')}*) saves at "
                  f"most {page.text('max_total_difference_mps', '.4f', ' m/s')} over solving it "
                  f"one burn at a time (*{capture_name('free')}*; {dynamics} dynamics).")
    page.capture("joint", dynamics)
    return page
