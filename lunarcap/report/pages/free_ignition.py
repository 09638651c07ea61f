"""The free-ignition page (notebooks/free_ignition.ipynb): what the paper's grid left.

For each engine, the notebook solves each burn of the paper's plan with its ignition time
free (an NLP variable), starting from the free-ignition chain's previous orbit, and at
each of the paper's grid of offsets on that same orbit (:func:`lunarcap.solve_burn`); the
whole chains (:func:`lunarcap.solve`); and the paper's rule of thumb, ignition half the
Eq. (19) duration before the perilune, on the same orbits. :func:`build` sets the free
optimum beside the best grid point, compares the chains and prices the rule against the
optimum. The notes the prose needs (which grid point cost most, where the
free optimum spends more delta-V, what the chain gains) are written from the data.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.mission.plan import paper_plan
from lunarcap.mission.scenario import paper_engines
from lunarcap.paper.printed import PAPER_BEST_STARTS_MIN, PAPER_IMPULSIVE_DV_MPS, PAPER_STARTS_MIN
from lunarcap.quantities import capture_name
from lunarcap.report.contents import BookPage, Execution, figure_files, table_files
from lunarcap.report.figures import free_ignition as draw
from lunarcap.report.labels import engine_label
from lunarcap.report.page import Page, solver_description
from lunarcap.report.pages.other_engines import sequence_of
from lunarcap.studies import sweeps

NOTEBOOK = "notebooks/free_ignition.ipynb"
BOOK = BookPage(NOTEBOOK, "Beyond the paper", 10, (
    Execution(
        "free_ignition", "Free ignition: what the paper's grid left on the table",
        parameters=dict(dynamics="full"),
        quick_parameters=dict(engines=[[450.0, 300.0]],
                              dynamics="two-body"),  # quick: about 5x faster solves
        expected_s=21,
        outputs=(table_files("free_ignition", "gain", "chain", "eq19_rule")
                 + figure_files("free_ignition", "eq19_rule"))),
))

#: A chain gaining this much more than its burn 1 (m/s) has its later burns discussed.
CHAIN_EXTRA_MPS = 0.1

#: The rule "holds well" if the optimum is within this % of the Eq. (19) duration from it.
RULE_GOOD_PERCENT = 10.0




def grid_starts(thrust_N: float, burn: int) -> tuple:
    """The paper's grid of ignition offsets for this burn of its engine, min (Tables 1-5).

    Empty for an engine the paper did not solve: the notebook then solves no grid point.
    """
    if float(thrust_N) not in PAPER_BEST_STARTS_MIN:
        return ()
    return PAPER_STARTS_MIN[(float(thrust_N), int(burn))]


def best_grid_starts(thrust_N: float, isp_s: float):
    """The paper's best offsets of its three burns (Table B1) for its engine, else None."""
    t = float(thrust_N)
    return PAPER_BEST_STARTS_MIN.get(t) if paper_engines().get(t) == float(isp_s) else None


def _gain_rows(t: float, i: float, free: list, grid: list) -> pd.DataFrame:
    """One engine's rows of :func:`gain_table` (free optimum beside the best grid point).

    ``free``: the three free burns (``lunarcap.solve_burn`` with its impulsive limit, each
    on the free chain's pre-burn orbit); ``grid``: per burn the grid points solved on that
    same orbit (empty lists for an engine the paper did not solve).
    """
    rows = []
    for loi, (f, points) in enumerate(zip(free, grid), 1):
        fs = f.row()
        row = {"loi": loi, "free_start_min": fs["start_min"],
               "free_burn_duration_min": fs["burn_duration_min"],
               "free_delta_v_mps": fs["delta_v_mps"], "free_objective_mps": fs["objective_j_mps"],
               "free_impulsive_limit_mps": fs["impulsive_limit_mps"],
               "free_objective_loss_mps": fs["objective_loss_mps"],
               "free_objective_loss_percent": fs["objective_loss_percent"],
               "eq19_half_duration_min": 0.5 * fs["eq19_duration_min"],
               "free_verified": fs["verification_passed"]}
        if points:
            gs = min(points, key=lambda b: b.solution.raw.objective_kmps).row()
            row.update({"grid_start_min": gs["start_min"], "grid_delta_v_mps": gs["delta_v_mps"],
                        "grid_objective_mps": gs["objective_j_mps"],
                        "objective_gain_mps": gs["objective_j_mps"] - fs["objective_j_mps"],
                        "delta_v_gain_mps": gs["delta_v_mps"] - fs["delta_v_mps"]})
        rows.append(row)
    return pd.DataFrame(rows)


def gain_table(engines, free: dict, grid: dict) -> pd.DataFrame:
    """Free optimum beside the best grid point, per engine and burn (one row each).

    ``free``, ``grid``: ``{thrust_N: [...]}`` the notebook's solves (see :func:`_gain_rows`).
    Columns: engine, thrust_N, isp_s, burn, grid_start_min, free_start_min,
    free_burn_duration_min, grid_delta_v_mps, free_delta_v_mps, delta_v_gain_mps and
    objective_gain_mps (grid - free; NaN for an engine the paper did not solve),
    free_objective_j_mps, free_impulsive_limit_mps and free_objective_loss_mps /
    free_objective_loss_percent (against the impulsive limit from the same orbit in the
    same dynamics, by J),
    eq19_duration_min, verified ("passed" / "failed").
    """
    frames = []
    for t, i in engines:
        df = _gain_rows(t, i, free[t], grid[t])
        for c in ("grid_start_min", "grid_delta_v_mps", "objective_gain_mps",
                  "delta_v_gain_mps"):
            if c not in df:
                df[c] = np.nan
        frames.append(df.assign(engine=engine_label(t, i), thrust_N=float(t), isp_s=float(i)))
    rows = pd.concat(frames, ignore_index=True)
    rows["eq19_duration_min"] = 2 * rows.eq19_half_duration_min
    rows["verified"] = np.where(rows.free_verified, "passed", "failed")
    return rows.rename(columns={"loi": "burn", "free_objective_mps": "free_objective_j_mps"})[[
        "engine", "thrust_N", "isp_s", "burn", "grid_start_min", "free_start_min",
        "free_burn_duration_min", "grid_delta_v_mps", "free_delta_v_mps", "delta_v_gain_mps",
        "objective_gain_mps", "free_objective_j_mps", "free_impulsive_limit_mps",
        "free_objective_loss_mps", "free_objective_loss_percent", "eq19_duration_min",
        "verified"]]


def free_chain_table(engines, chains: dict) -> tuple[pd.DataFrame, dict]:
    """The paper's best grid chain (Table B1 offsets) against the free chain, per engine.

    ``chains``: ``{thrust_N: [free chain, best grid chain or None]}``, each the paper's plan
    solved by ``lunarcap.solve`` with those ignitions. Returns the table (engine,
    grid_starts, free_starts, total delta-Vs, gain, final masses, propellant saved,
    verified) and ``{thrust_N: per-burn delta-V gain, m/s}``.
    """
    rows, legs = [], {}
    for t, i in engines:
        t = float(t)
        free_res, grid_res = chains[t]
        free_seq = sequence_of(free_res)
        ft = sweeps.sequence_totals(free_seq)
        grid = best_grid_starts(t, i)
        if grid_res is not None:
            grid_seq = sequence_of(grid_res)
            gt = sweeps.sequence_totals(grid_seq)
            legs[t] = grid_seq.delta_v_mps.to_numpy() - free_seq.delta_v_mps.to_numpy()
            ok = bool(grid_seq.verified.all() and free_seq.verified.all())
        else:
            gt = {"total_delta_v_mps": np.nan, "final_mass_kg": np.nan}
            ok = bool(free_seq.verified.all())
        rows.append({
            "engine": engine_label(t, i),
            "grid_starts": "" if grid is None else ", ".join(f"{s:g}" for s in grid),
            "free_starts": ", ".join(f"{s:.2f}" for s in free_seq.start_min),
            "grid_total_delta_v_mps": gt["total_delta_v_mps"],
            "free_total_delta_v_mps": ft["total_delta_v_mps"],
            "delta_v_gain_mps": gt["total_delta_v_mps"] - ft["total_delta_v_mps"],
            "grid_final_mass_kg": gt["final_mass_kg"],
            "free_final_mass_kg": ft["final_mass_kg"],
            "fuel_saved_kg": ft["final_mass_kg"] - gt["final_mass_kg"],
            "verified": "passed" if ok else "failed"})
    return pd.DataFrame(rows), legs


def rule_table(gain: pd.DataFrame, rule: dict) -> pd.DataFrame:
    """The Eq. (19)/2 rule against the free optimum, one row per engine and burn.

    ``rule``: ``{(thrust_N, burn): lunarcap.BurnSolution}``, each burn solved by the
    notebook with a fixed ignition at minus half its Eq. (19) duration, on the free chain's
    pre-burn orbit. Columns: engine, thrust_N, burn, eq19_duration_min, rule_start_min,
    free_start_min, start_minus_rule_min, burn_midpoint_min (free start + half the free
    duration), grid_start_min, rule_delta_v_cost_mps and rule_objective_cost_mps
    (rule - free), verified.
    """
    rows = []
    for r in gain.itertuples():
        rule_start = -r.eq19_duration_min / 2
        s = rule[(float(r.thrust_N), int(r.burn))].row()
        rows.append({
            "engine": r.engine, "thrust_N": r.thrust_N, "burn": r.burn,
            "eq19_duration_min": r.eq19_duration_min, "rule_start_min": rule_start,
            "free_start_min": r.free_start_min,
            "start_minus_rule_min": r.free_start_min - rule_start,
            "burn_midpoint_min": r.free_start_min + r.free_burn_duration_min / 2,
            "grid_start_min": r.grid_start_min,
            "rule_delta_v_cost_mps": s["delta_v_mps"] - r.free_delta_v_mps,
            "rule_objective_cost_mps": s["objective_j_mps"] - r.free_objective_j_mps,
            "verified": "passed" if s["verification_passed"] else "failed"})
    return pd.DataFrame(rows)


def _grid_text(thrust_N: float, burn: int) -> str:
    starts = PAPER_STARTS_MIN[(float(thrust_N), burn)]
    steps = sorted({round(abs(b - a), 6) for a, b in zip(starts, starts[1:])})
    step = f"steps by {steps[0]:g} min" if len(steps) == 1 else \
        f"steps by {steps[0]:g} to {steps[-1]:g} min"
    return f"{step} ({', '.join(f'{s:g}' for s in starts)} min)"


def _largest_gain_note(g: pd.DataFrame) -> str:
    """Where the paper's grid missed the free optimum by most, in J."""
    if len(g):
        top = g.loc[g.objective_gain_mps.idxmax()]
        rest = g.drop(index=top.name)
        others = (f" Everywhere else the best grid point was within "
                  f"{rest.objective_gain_mps.max():.3f} m/s of the optimum in J."
                  if len(rest) else "")
        return (
            f"The largest is {top.engine}, burn {top.burn:.0f} (LOI {top.burn:.0f}), where the "
            f"paper's grid {_grid_text(top.thrust_N, int(top.burn))} around an optimum at "
            f"{top.free_start_min:.2f} min: the best grid point, {top.grid_start_min:g} min, "
            f"costs {top.objective_gain_mps:.2f} m/s in J and {top.delta_v_gain_mps:.2f} m/s "
            f"in ΔV.{others}")
    else:
        return "No engine of the paper was run: there is no grid to compare with."


def _dv_excess_note(g: pd.DataFrame) -> str:
    """Rows where the free optimum spends more ΔV than the grid point, and why."""
    neg = g[g.delta_v_gain_mps < 0]
    if len(neg):
        items = [f"{r.delta_v_gain_mps * -1:.3f} m/s for {r.engine}, burn {r.burn:.0f}"
                 for r in neg.itertuples()]
        listed = items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]
        return (
            f"The ΔV alone can be *higher* at the free optimum than at a grid point: by "
            f"{listed} (the negative ΔV gains in the table). This is not a solver failure. "
            "The optimiser minimises J, not ΔV, and J is nearly flat along the ignition time: "
            "a later burn needs more ΔV but leaves a slower perilune, and the two terms of J "
            "trade almost one for one. These grid points lie "
            f"{60 * (neg.grid_start_min - neg.free_start_min).abs().max():.0f} s or less from "
            f"the optimum: close enough to spend up to {-neg.delta_v_gain_mps.min():.3f} m/s "
            "less ΔV while ending slightly faster, which the next burn has to remove.")
    elif len(g):
        return ("The free optimum also spends no more ΔV than the best grid point "
                "in any row.")
    else:
        return ""


def _chain_note(gain: pd.DataFrame, chain: pd.DataFrame, legs: dict) -> str:
    """What the free chain saves over the paper's best grid chain."""
    c = chain.dropna(subset=["delta_v_gain_mps"])
    if len(c):
        names = [e.split(" /")[0] for e in c.engine]
        eng = names[0] if len(names) == 1 else ", ".join(names[:-1]) + " and " + names[-1]
        dv = [f"{x:.3f}" for x in c.delta_v_gain_mps]
        kg = [f"{x:.3f}" for x in c.fuel_saved_kg]

        def join(xs):
            return xs[0] if len(xs) == 1 else ", ".join(xs[:-1]) + " and " + xs[-1]
        text = (f"Over the whole sequence the free chain saves {join(dv)} m/s of ΔV for "
                f"{eng} against the paper's best grid chain, or {join(kg)} kg of propellant.")
        # where the chain gains clearly more than its burn 1: a later burn of the grid
        # chain far from the free chain's
        for t, d in legs.items():
            if len(d) < 2 or d.sum() - d[0] <= CHAIN_EXTRA_MPS:
                continue
            k = int(np.argmax(d[1:])) + 2
            free_k = gain[(gain.thrust_N == t) & (gain.burn == k)].free_start_min.iloc[0]
            text += (f" For {t:g} N the chain gains more than its burn 1 alone: on the grid "
                     f"chain, burn {k} at the paper's best offset "
                     f"({PAPER_BEST_STARTS_MIN[t][k - 1]:g} min) spends {d[k - 1]:.2f} m/s "
                     f"more than the free chain's burn {k} (at its optimum, {free_k:.2f} min).")
        return text
    else:
        return ("No engine of the paper was run: there is no grid chain to compare "
                "with.")


def _rule_note(rule: pd.DataFrame) -> str:
    """How well the paper's rule of thumb (ignite at -Eq. (19)/2) holds."""
    w = rule.loc[rule.start_minus_rule_min.abs().idxmax()]
    longest = rule.eq19_duration_min.idxmax() == w.name
    side = ("always *earlier*" if (rule.start_minus_rule_min < 0).all() else
            "always *later*" if (rule.start_minus_rule_min > 0).all() else
            "sometimes earlier, sometimes later")
    worst_percent = 100 * abs(w.start_minus_rule_min) / w.eq19_duration_min
    return (
        ("The rule holds well. " if worst_percent < RULE_GOOD_PERCENT else
         "The rule is a rough guide only. ")
        + f"The optimum ignites between {rule.start_minus_rule_min.abs().min():.2f} and "
        f"{rule.start_minus_rule_min.abs().max():.2f} min away from −Eq. (19)/2, {side}. "
        f"The largest difference, {w.start_minus_rule_min:+.2f} min, is for "
        + ("the longest burn " if longest else "")
        + f"({w.engine.split(' /')[0]}, burn {w.burn:.0f}: optimum {w.free_start_min:.2f} min, "
        f"rule {w.rule_start_min:.2f} min), and amounts to "
        f"{worst_percent:.1f} % of the Eq. (19) duration.")


def notes(gain: pd.DataFrame, chain: pd.DataFrame, legs: dict, rule: pd.DataFrame) -> dict:
    """The MyST paragraphs the prose includes, written from the data."""
    g = gain.dropna(subset=["objective_gain_mps"])
    return {"largest_gain": _largest_gain_note(g), "dv_excess": _dv_excess_note(g),
            "chain": _chain_note(gain, chain, legs), "rule": _rule_note(rule)}


def gate_text(k: int, n: int, plural: str, singular: str) -> str:
    """'All 9 free optima passed the re-propagation gate ...' (k of n passed)."""
    if n == 1:
        verdict = f"The {singular} {'passed' if k else 'failed'}"
    else:
        verdict = f"All {n} {plural} passed" if k == n else f"{k} of {n} {plural} passed"
    return f"{verdict} the re-propagation gate (column verified of the CSV)."


def prose_values(gain: pd.DataFrame, rule: pd.DataFrame) -> dict:
    """The numbers the prose quotes: the range of the J gains, the rule's misses."""
    nan = float("nan")
    jg = gain.objective_gain_mps
    return {"max_j_gain_mps": float(jg.max()) if jg.notna().any() else nan,
            "min_j_gain_mps": float(jg.min()) if jg.notna().any() else nan,
            "max_abs_rule_diff_min": float(rule.start_minus_rule_min.abs().max()),
            "min_abs_rule_diff_min": float(rule.start_minus_rule_min.abs().min()),
            "max_rule_j_cost_mps": float(rule.rule_objective_cost_mps.max()),
            "max_abs_midpoint_min": float(rule.burn_midpoint_min.abs().max())}


def _add_tables(page: Page, gain: pd.DataFrame, chain: pd.DataFrame, dynamics: str) -> None:
    n_free_ok = int((gain.verified == "passed").sum())
    gate = gate_text
    page.table(
        "gain", gain,
        caption=(f"Free ignition against the best of the paper's offsets on the same orbit, "
                 f"ranked by J of Eq. (9) ({dynamics} dynamics). Gain: grid − free (m/s; "
                 "positive: free is better). "
                 + gate(n_free_ok, len(gain), "free optima", "free optimum")),
        columns={"grid_start_min": "start, best grid (min)",
                 "free_start_min": "start, free (min)", "free_delta_v_mps": "ΔV, free (m/s)",
                 "delta_v_gain_mps": "ΔV gain (m/s)", "objective_gain_mps": "J gain (m/s)"},
        floatfmt={"grid_start_min": "g", "free_start_min": ".2f", "free_delta_v_mps": ".3f",
                  "delta_v_gain_mps": "+.3f", "objective_gain_mps": "+.4f"},
        show_columns=["engine", "burn", "grid_start_min", "free_start_min", "free_delta_v_mps",
                      "delta_v_gain_mps", "objective_gain_mps"])
    page.table(
        "chain", chain,
        caption=("The whole sequence: the paper's grid chain (Table B1 offsets) against the "
                 "free-ignition chain. Gain: grid − free; propellant saved: free − grid final "
                 "mass. "
                 + gate(int((chain.verified == "passed").sum()), len(chain), "chains", "chain")),
        columns={"grid_starts": "starts, grid (min)",
                 "free_starts": "starts, free (min)",
                 "grid_total_delta_v_mps": "total ΔV, grid (m/s)",
                 "free_total_delta_v_mps": "total ΔV, free (m/s)",
                 "delta_v_gain_mps": "ΔV gain (m/s)", "fuel_saved_kg": "propellant saved (kg)"},
        floatfmt={"grid_total_delta_v_mps": ".3f", "free_total_delta_v_mps": ".3f",
                  "delta_v_gain_mps": "+.3f", "grid_final_mass_kg": ".3f",
                  "free_final_mass_kg": ".3f", "fuel_saved_kg": "+.3f"},
        show_columns=["engine", "grid_starts", "free_starts", "grid_total_delta_v_mps",
                      "free_total_delta_v_mps", "delta_v_gain_mps", "fuel_saved_kg"])


def _add_rule(page: Page, rule: pd.DataFrame, engines) -> None:
    n_rule_ok = int((rule.verified == "passed").sum())
    gate = gate_text
    imp = [b.delta_v_mps for b in paper_plan(*engines[0]).impulsive()]
    imp_diff = max(abs(a - b) for a, b in zip(imp, PAPER_IMPULSIVE_DV_MPS))
    page.table(
        "rule", rule, name="eq19_rule",
        caption=("The paper's rule of thumb (ignite half the Eq. (19) duration before "
                 "perilune; impulses within "
                 f"{imp_diff:.2f} m/s of the paper's) against the free optimum; cost in J "
                 "(m/s). "
                 + gate(n_rule_ok, len(rule), "solves at the rule's start",
                        "solve at the rule's start")),
        columns={"rule_start_min": "rule start −Eq. (19)/2 (min)",
                 "free_start_min": "optimal start (min)",
                 "start_minus_rule_min": "optimal − rule (min)",
                 "burn_midpoint_min": "burn midpoint (min)",
                 "rule_objective_cost_mps": "J cost of the rule (m/s)"},
        floatfmt={"eq19_duration_min": ".2f", "rule_start_min": ".2f", "free_start_min": ".2f",
                  "start_minus_rule_min": "+.2f", "burn_midpoint_min": "+.2f",
                  "grid_start_min": "g", "rule_delta_v_cost_mps": "+.3f",
                  "rule_objective_cost_mps": "+.4f"},
        show_columns=["engine", "burn", "rule_start_min", "free_start_min",
                      "start_minus_rule_min", "burn_midpoint_min", "rule_objective_cost_mps"])
    page.figure(
        "rule_figure", draw.plot_free_ignition_rule(rule), name="eq19_rule",
        caption=("Top: optimal ignition (filled; open: the paper's best grid point) against "
                 "half the Eq. (19) duration, min (dashed: the rule). Bottom: optimum − rule "
                 "against the Eq. (19) duration, min. Colours: engines; markers: LOI 1-3."),
        alt="Scatter plots of the optimal ignition time against minus half the Eq. 19 duration")



def _add_checks(page: Page, gain, chain, rule, engines, dynamics: str) -> None:
    n_free_ok = int((gain.verified == "passed").sum())
    n_rule_ok = int((rule.verified == "passed").sum())
    jg = gain.objective_gain_mps
    page.expect("every free optimum passes the gate", n_free_ok == len(gain))
    page.expect("every solve at the rule's start passes the gate", n_rule_ok == len(rule))
    page.expect("every chain passes the gate", bool((chain.verified == "passed").all()))
    page.expect("the free optimum is never worse than the grid in J (1 mm/s)",
                bool((jg.dropna() >= -1e-3).all()), f"min {jg.min():+.4f} m/s")
    page.expect("the free chain never spends 0.05 m/s more than the grid chain",
                bool((chain.delta_v_gain_mps.dropna() > -0.05).all()))
    page.expect("the optimum ignites earlier than the rule",
                bool((rule.start_minus_rule_min < 0).all()))
    page.expect("... by less than 1.5 min", bool((rule.start_minus_rule_min > -1.5).all()))
    page.expect("every optimal burn's midpoint is before the perilune",
                bool((rule.burn_midpoint_min < 0).all()))
    page.expect("following the rule costs at least 0 in J (the optimum is a minimum; 1 mm/s)",
                bool((rule.rule_objective_cost_mps >= -1e-3).all()))
    if dynamics == "full" and (300.0, 250.0) in engines:
        # measured: 300 N burn 1 optimum -4.99 min vs grid -4 min, J gain 0.58 m/s
        sel = (gain.thrust_N == 300.0) & (gain.burn == 1)
        j = float(gain[sel].objective_gain_mps.iloc[0])
        page.expect("300 N burn 1: J gain between 0.4 and 0.8 m/s", 0.4 < j < 0.8, f"{j:.3f}")
        page.expect("300 N burn 1 is the largest J gain", j == jg.max())


def build(free: dict, grid: dict, rule: dict, chains: dict,
          output_name: str = "free_ignition", quick: bool = False,
          parameters: dict | None = None) -> Page:
    """The free-ignition page of the solves made in the notebook (see the module docstring).

    Parameters
    ----------
    free : dict
        ``{thrust_N: [BurnSolution] * 3}``: each burn of the paper's plan with that engine,
        its ignition free, on the free chain's pre-burn orbit, with its impulsive limit
        (``lunarcap.solve_burn(plan, burn, start="free", previous_starts=["free"] * ...)``).
    grid : dict
        ``{thrust_N: [[BurnSolution, ...]] * 3}``: per burn, each offset of
        :func:`grid_starts` solved on that same orbit (``impulsive=False``).
    rule : dict
        ``{(thrust_N, burn): BurnSolution}``: each burn ignited at minus half its Eq. (19)
        duration (the free optimum's ``eq19_duration_min``) on that same orbit.
    chains : dict
        ``{thrust_N: [free chain, best grid chain or None]}``: ``lunarcap.solve`` of the
        plan with every ignition free, and with :func:`best_grid_starts`.
    output_name, quick : the tables' prefix; recorded in the provenance
    parameters : dict
        The notebook's ``engines`` ([thrust N, Isp s] each) and ``dynamics``.
    """
    prm = dict(parameters or {})
    engines = [(float(t), float(i)) for t, i in prm["engines"]]
    dynamics = prm.get("dynamics", "full")
    params = dict(engines=[list(e) for e in engines], dynamics=dynamics)
    solver = dict(solver_description())
    solver["ignition"] = "free (an NLP variable), or fixed for the grid points"
    solver["gate"] = solver.pop("gate")
    page = Page(NOTEBOOK, params, output_name, quick, solver)
    gain = gain_table(engines, free, grid)
    chain, legs = free_chain_table(engines, chains)
    rule = rule_table(gain, rule)
    _add_tables(page, gain, chain, dynamics)
    _add_rule(page, rule, engines)
    for name, v in prose_values(gain, rule).items():
        page.value(name, v)
    for name, md in notes(gain, chain, legs, rule).items():
        page.note(name, md or " ")
    _add_checks(page, gain, chain, rule, engines, dynamics)
    page.data.update({"gain": gain, "chain": chain, "rule": rule, "chain_legs": legs})
    t = page.text
    page.headline(f"Optimising the ignition time (*{capture_name('free')}*) instead of picking it "
                  f"from the paper's grid gains {t('min_j_gain_mps', '.4f')} to "
                  f"{t('max_j_gain_mps', '.2f', ' m/s')} per burn in the objective of Eq. (9) "
                  f"({dynamics} dynamics).")
    page.capture("free", dynamics)
    return page
