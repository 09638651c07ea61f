"""The steering-laws page (notebooks/steering_laws.ipynb): what the optimal steering is worth.

Each burn of the paper's plan, ignition free, is flown with three steering laws: the
paper's optimal steering, one fixed inertial direction (optimised) and thrust opposite
the velocity. The notebook solves them with the public API (:func:`lunarcap.paper_plan`,
:func:`lunarcap.solve_burn` with ``steering=``); :func:`build` sets their delta-V and J
(Eq. 9) penalties against the optimal steering side by side, per engine and LOI
(:func:`lunarcap.studies.sweeps.steering_frame`), with the terminal conditions the
antivelocity law cannot meet and how far it misses them.
"""

from __future__ import annotations

import pandas as pd

from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.display import verdict
from lunarcap.report.figures import steering_laws as draw
from lunarcap.report.labels import engine_label
from lunarcap.report.page import Page, solver_description
from lunarcap.studies import sweeps

NOTEBOOK = "notebooks/steering_laws.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 30, (
    Execution(
        "steering_laws", "Steering laws: optimal, fixed inertial, opposite the velocity",
        parameters=dict(dynamics="full"),
        quick_parameters=dict(engines=[[450.0, 300.0]],
                              dynamics="two-body"),  # quick: about 5x faster solves
        outputs=(table_files("steering_laws", "penalty", "targets")
                 + figure_files("steering_laws", "penalty"))),
))

#: The laws compared with the optimal steering, in the order of the table and figure.
SIMPLE_LAWS = ("inertial", "antivelocity")

#: Columns of the penalty table shown in the book (its CSV keeps every column).
PENALTY_SHOWN = ["engine", "loi", "steering", "start_min", "burn_duration_min", "delta_v_mps",
                 "delta_v_penalty_mps", "objective_penalty_mps"]

#: Columns of the targets table (released targets, misses, verification).
TARGETS_SHOWN = ["engine", "loi", "steering", "released_targets", "rp_miss_km",
                 "inc_miss_deg", "verified"]

#: The engines the prose quotes (glued values are NaN for an engine not built).
PROSE_THRUSTS_N = (150.0, 300.0, 450.0)



def steering_rows(burns) -> tuple[pd.DataFrame, list]:
    """The steering comparison of every engine, one frame, and the engines in order.

    ``burns``: :func:`lunarcap.solve_burn` of burns of the paper's plan
    (:func:`lunarcap.paper_plan`), ignition free, with each steering law of
    :data:`lunarcap.studies.sweeps.STEERING_LAWS`, engine by engine, each LOI's optimal
    steering first. Columns of :func:`lunarcap.studies.sweeps.steering_frame`, plus engine
    (label), thrust_N and isp_s; the engines as (thrust N, Isp s).
    """
    by_engine = {}
    for b in burns:
        e = b.plan.engine
        by_engine.setdefault((float(e.thrust_N), float(e.isp_s)), []).append(b)
    frames = [sweeps.steering_frame([b.solution for b in group], t, i,
                                    str(group[0].plan.dynamics)).assign(
        engine=engine_label(t, i), thrust_N=float(t), isp_s=float(i))
        for (t, i), group in by_engine.items()]
    return pd.concat(frames, ignore_index=True), list(by_engine)


def _pick(steer: pd.DataFrame, thrust: float, loi: int, law: str, col: str) -> float:
    s = steer[(steer.thrust_N == thrust) & (steer.loi == loi) & (steer.steering == law)]
    return float(s[col].iloc[0]) if len(s) else float("nan")


def prose_values(steer: pd.DataFrame) -> dict:
    """The numbers the prose quotes (NaN for an engine not built, e.g. in a quick build)."""
    out = {}
    for thrust in PROSE_THRUSTS_N:
        tag = f"{thrust:g}N"
        for n in (1, 2, 3):
            for law, short in (("inertial", "inertial"), ("antivelocity", "anti")):
                out[f"{short}_dv_loi{n}_{tag}_mps"] = _pick(steer, thrust, n, law,
                                                            "delta_v_penalty_mps")
                out[f"{short}_j_loi{n}_{tag}_mps"] = _pick(steer, thrust, n, law,
                                                           "objective_penalty_mps")
            out[f"anti_rp_miss_loi{n}_{tag}_km"] = _pick(steer, thrust, n, "antivelocity",
                                                         "rp_miss_km")
            out[f"duration_loi{n}_{tag}_min"] = _pick(steer, thrust, n, "optimal",
                                                      "burn_duration_min")
            out[f"start_loi{n}_{tag}_min"] = _pick(steer, thrust, n, "optimal", "start_min")
            out[f"inertial_start_loi{n}_{tag}_min"] = _pick(steer, thrust, n, "inertial",
                                                            "start_min")
    inert = steer[steer.steering == "inertial"]
    anti = steer[steer.steering == "antivelocity"]
    out["max_inertial_j_mps"] = float(inert.objective_penalty_mps.max())
    out["max_abs_inertial_j_loi3_mps"] = float(
        inert[inert.loi == 3].objective_penalty_mps.abs().max())
    out["min_anti_j_mps"] = float(anti.objective_penalty_mps.min())
    out["max_anti_j_mps"] = float(anti.objective_penalty_mps.max())
    out["max_anti_rp_miss_km"] = float(anti.rp_miss_km.abs().max())
    out["max_anti_inc_miss_deg"] = float(anti.inc_miss_deg.abs().max())
    return out


def _add_items(page: Page, steer: pd.DataFrame, engines, dynamics: str) -> None:
    table = steer.assign(verified=steer.verified.map(verdict))[[
        "engine", "loi", "steering", "start_min", "burn_duration_min", "delta_v_mps",
        "delta_v_penalty_mps", "objective_penalty_mps", "released_targets", "rp_miss_km",
        "inc_miss_deg", "verified"]]
    page.table(
        "penalty", table,
        caption=("Three steering laws per engine and LOI, ignition and duration optimised "
                 f"({dynamics} dynamics). Penalties against the optimal steering of the same "
                 "burn, in ΔV and in J of Eq. (9). Targets released and misses: next table."),
        columns={"engine": "engine (thrust / Isp)", "delta_v_penalty_mps": "ΔV penalty (m/s)",
                 "objective_penalty_mps": "J penalty (m/s)"},
        floatfmt={"start_min": ".2f", "burn_duration_min": ".2f", "delta_v_mps": ".3f",
                  "delta_v_penalty_mps": "+.3f", "objective_penalty_mps": "+.3f",
                  "rp_miss_km": "+.2f", "inc_miss_deg": ".4f"},
        show_columns=PENALTY_SHOWN)
    page.table(
        "targets", table[TARGETS_SHOWN],
        caption=("Terminal conditions of the same solutions. Released: what a law cannot "
                 "meet and leaves free (rp, inc; none: meets all). Misses of the verified "
                 "flight (negative: low); verified: on the conditions it keeps."),
        columns={"engine": "engine (thrust / Isp)", "released_targets": "released",
                 "rp_miss_km": "perilune miss (km)", "inc_miss_deg": "inclination miss (deg)"},
        floatfmt={"rp_miss_km": "+.2f", "inc_miss_deg": ".4f"})
    page.figure(
        "penalty_figure",
        draw.plot_steering_penalty(steer, [engine_label(t, i) for t, i in engines],
                                      SIMPLE_LAWS),
        caption=("Penalty of fixed inertial and antivelocity thrust against optimal "
                 "steering, per LOI and engine: ΔV (top, m/s), J of Eq. (9) (bottom). "
                 "Antivelocity misses the perilune radius (labels, km), so only J compares."),
        alt="Bar charts of the delta-V and J penalties of the inertial and antivelocity laws",
        name="penalty")


def _add_checks(page: Page, steer: pd.DataFrame, dynamics: str) -> None:
    inert = steer[steer.steering == "inertial"]
    anti = steer[steer.steering == "antivelocity"]
    page.expect("every solution passes the verification gate", bool(steer.verified.all()),
                str(steer[~steer.verified][["engine", "loi", "steering"]].values.tolist()))
    page.expect("optimal is optimal: no inertial J penalty below -1 mm/s",
                bool((inert.objective_penalty_mps >= -1e-3).all()))
    page.expect("the inertial law costs J on every LOI 1",
                bool((inert[inert.loi == 1].objective_penalty_mps > 0).all()))
    page.expect("the antivelocity law costs J on every burn",
                bool((anti.objective_penalty_mps > 0).all()))
    page.expect("the antivelocity law costs more J than the inertial law everywhere",
                bool((anti.objective_penalty_mps.to_numpy()
                      > inert.objective_penalty_mps.to_numpy()).all()))
    page.expect("the antivelocity law spends less ΔV than the optimum on every burn",
                bool((anti.delta_v_penalty_mps < 0).all()))
    page.expect("the antivelocity law ends low on LOIs 1 and 2",
                bool((anti[anti.loi < 3].rp_miss_km < 0).all()))
    if 150.0 in steer.thrust_N.values:
        # the prose names 150 N LOI 1 as the longest burn, with the largest penalties
        opt = steer[steer.steering == "optimal"]
        longest = opt.loc[opt.burn_duration_min.idxmax()]
        page.expect("150 N LOI 1 is the longest burn", longest.thrust_N == 150.0
                    and longest.loi == 1, f"{longest.engine} LOI {longest.loi}")
        page.expect("150 N LOI 1 has the largest inertial J penalty",
                    _pick(steer, 150.0, 1, "inertial", "objective_penalty_mps")
                    == inert.objective_penalty_mps.max())
        page.expect("150 N LOI 1 has the largest antivelocity perilune miss",
                    abs(_pick(steer, 150.0, 1, "antivelocity", "rp_miss_km"))
                    == anti.rp_miss_km.abs().max())
        page.expect("150 N LOI 2: inertial ignites later, spends less ΔV, costs more J",
                    _pick(steer, 150.0, 2, "inertial", "start_min")
                    > _pick(steer, 150.0, 2, "optimal", "start_min")
                    and _pick(steer, 150.0, 2, "inertial", "delta_v_penalty_mps") < 0
                    < _pick(steer, 150.0, 2, "inertial", "objective_penalty_mps"))
    if dynamics == "full" and 450.0 in steer.thrust_N.values:
        # measured: inertial +0.10 m/s dV (LOI 1); antivelocity +0.88 m/s J and 2.6 km low
        dv = _pick(steer, 450.0, 1, "inertial", "delta_v_penalty_mps")
        j = _pick(steer, 450.0, 1, "antivelocity", "objective_penalty_mps")
        rp = _pick(steer, 450.0, 1, "antivelocity", "rp_miss_km")
        page.expect("450 N LOI 1: inertial ΔV penalty 0.05-0.2 m/s", 0.05 < dv < 0.2, f"{dv}")
        page.expect("450 N LOI 1: antivelocity J penalty 0.6-1.2 m/s", 0.6 < j < 1.2, f"{j}")
        page.expect("450 N LOI 1: antivelocity 1.5-4 km low", -4.0 < rp < -1.5, f"{rp}")


def build(burns, output_name: str = "steering_laws", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The page of the steering-law comparison computed in the notebook (see the module docstring).

    Parameters
    ----------
    burns : list of lunarcap.BurnSolution
        The burns of :func:`steering_rows`, every one in the same dynamics.
    output_name, quick : the page's output name and whether it is a quick build.
    parameters : dict, optional
        The notebook's parameters, shown in the page's provenance.
    """
    steer, engines = steering_rows(burns)
    dynamics = str(burns[0].plan.dynamics)
    params = dict(parameters or {})
    if "engines" in params:
        params["engines"] = [[float(t), float(i)] for t, i in params["engines"]]
    solver = solver_description()
    solver.update({
        "ignition": "free (an NLP variable)",
        "steering": "optimal u(t); fixed inertial u (optimised); u = -v/|v| (state feedback)",
        "gate": solver["gate"] + "; released targets reported, not gated"})
    page = Page(NOTEBOOK, params, output_name, quick, solver)
    _add_items(page, steer, engines, dynamics)
    for name, v in prose_values(steer).items():
        page.value(name, v)
    _add_checks(page, steer, dynamics)
    page.data["steering"] = steer
    cost = page.listing([(f"inertial_j_loi1_{e}N_mps", f"{e} N") for e in (150, 300, 450)],
                        ".2f", " m/s")
    page.headline(f"Holding one optimised inertial direction through LOI 1, the longest burn, "
                  f"costs {cost} in the objective of Eq. (9); thrust opposite the velocity "
                  f"misses the paper's targets ({dynamics} dynamics).")
    page.capture("free", dynamics)
    return page
