"""``lunarcap dispersions``: the capture's delta-V budget under errors, on the command line.

The capture flown with execution, arrival and navigation errors drawn per sample and
re-planned after each burn (:mod:`.samples`); one Dask task per sample. With
``--sensitivity``, each non-zero sigma alone at 0.5, 1 and 2 times its value instead
(:mod:`.sensitivity`). Its ``--json`` records: the document (the plan, the error model,
the seed, the table and run, the summary, the samples), the summary's failures and each
sample's burns; its own quantities are in ``glossary.yaml`` beside this file.
"""

from __future__ import annotations

from dataclasses import replace

from lunarcap.errors import InputError, integer, number, number_list
from lunarcap.studies.registry import PLAN_DEFAULT, StudyCommand, StudyRun

#: The 1-sigma options: (option, unit, the error it draws).
SIGMA_OPTIONS = (
    ("--thrust-sigma-pct", "%", "thrust, per burn"),
    ("--isp-sigma-pct", "%", "specific impulse, per burn"),
    ("--pointing-sigma-deg", "deg", "thrust direction, each of two tilt angles, fixed over "
                                    "a burn"),
    ("--ignition-sigma-s", "s", "ignition epoch, per burn"),
    ("--arrival-sigma-km", "km", "arrival position, per RTN axis"),
    ("--arrival-sigma-mps", "m/s", "arrival velocity, per RTN axis"),
    ("--knowledge-sigma-km", "km", "orbit-determination position error of the state each "
                                   "re-plan starts from, per RTN axis"),
    ("--knowledge-sigma-mps", "m/s", "orbit-determination velocity error of the state each "
                                     "re-plan starts from, per RTN axis"),
    ("--gates-magnitude-pct", "%", "Gates proportional magnitude error, per burn"),
    ("--gates-magnitude-mps", "m/s", "Gates fixed magnitude error, per burn"),
    ("--gates-pointing-deg", "deg", "Gates proportional pointing error, per axis and burn"),
    ("--gates-pointing-mps", "m/s", "Gates fixed pointing error (a transverse delta-V), per "
                                    "axis and burn"))


def options(p) -> None:
    """Samples and seed, the sigmas, the covariance files, the variant and the formulation."""
    p.add_argument("--samples", default="100", metavar="N", help="samples (default 100)")
    p.add_argument("--seed", default="0", metavar="S",
                   help="seed: sample k draws its errors from numpy's generator seeded by "
                        "(S, k), the same whatever the sigmas (default 0)")
    for opt, unit, what in SIGMA_OPTIONS:
        p.add_argument(opt, default="0", metavar=unit.upper().replace("/", "").replace(
            "%", "PCT"), help=f"1-sigma error of the {what}, {unit.replace('%', '%%')} "
                                   "(default 0)")
    p.add_argument("--arrival-cov", default=None, metavar="FILE",
                   help="instead of --arrival-sigma-*: a 6x6 covariance of the arrival state "
                        "in its RTN frame, km and km/s (36 numbers, whitespace or commas)")
    p.add_argument("--knowledge-cov", default=None, metavar="FILE",
                   help="instead of --knowledge-sigma-*: a 6x6 covariance of the "
                        "orbit-determination error at each re-plan, RTN, km and km/s "
                        "(default none)")
    p.add_argument("--bplane-cov", default=None, metavar="FILE",
                   help="a 2x2 (B.T, B.R; km) or 3x3 (and the time of closest approach, s) "
                        "covariance of the arrival's B-plane target (4 or 9 numbers; a line "
                        "'order: B.R B.T t' in the file gives another order), in the B-plane "
                        "about the plan's arrival.bplane_reference: EME2000 by default (T = "
                        "S x k / |S x k|, R = S x T, S the incoming asymptote, k the pole of "
                        "the Earth's mean equator of J2000, as GMAT's BdotT and BdotR and "
                        "trajectory teams give it), lunar-equator on request (default none)")
    p.add_argument("--sensitivity", action="store_true",
                   help="instead of one budget: each non-zero sigma alone at 0.5, 1 and 2 "
                        "times its value (the others 0, the same draws), the mean and the "
                        "99 %% budget of each")
    p.add_argument("--factors", default=None, metavar="F1,F2,...",
                   help="with --sensitivity: the multiples of each sigma run (default "
                        "0.5,1,2)")
    p.add_argument("--antithetic", action="store_true",
                   help="fly the samples in antithetic pairs: sample 2j+1 draws the negated "
                        "numbers of sample 2j, a pair one independent draw (--samples even)")
    p.add_argument("--formulation", choices=["orbit", "song2011"], default=None,
                   help=f"how the re-planned burns meet a period: orbit (the orbit asked, its "
                        f"perilune epoch free) or song2011 (the paper's: at the plan's nominal "
                        f"perilune epochs, a fixed timeline) ({PLAN_DEFAULT})")


def prepare(args, plan) -> StudyRun:
    """The dispersions of ``plan`` (or their sensitivity): the error model checked first."""
    from lunarcap.studies.dispersions import samples as disp

    if args.formulation is not None and args.formulation != plan.formulation:
        plan = replace(plan, formulation=args.formulation)
    samples = integer("--samples", args.samples, minimum=1)
    seed = integer("--seed", args.seed, minimum=0)
    covs = {name: disp.read_covariance(getattr(args, name), name)
            for name in ("arrival_cov", "knowledge_cov", "bplane_cov")
            if getattr(args, name) is not None}
    model = disp.ErrorModel(**{name: number("--" + name.replace("_", "-"), getattr(args, name),
                                              "", minimum=0.0) for name in disp.SIGMAS},
                            **covs)
    if args.antithetic and samples % 2:
        raise InputError(f"antithetic samples come in pairs: --samples must be even, got "
                         f"{samples}")
    if args.sensitivity:
        return _sensitivity(args, plan, samples, seed, model)
    if args.factors is not None:
        raise InputError("--factors: the multiples of a sensitivity, needs --sensitivity")
    return StudyRun.of(disp.STUDY, lambda: disp.run_dispersions(
        plan, samples, seed, model, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress,
        antithetic=args.antithetic),
        {"plan": plan.to_dict(),
         "error_model": model.key() | {"description": model.describe()}, "seed": seed},
        lambda res: {"summary": disp.summarise(res.table.to_dict("records"))},
        plan=plan, model=model)


def _sensitivity(args, plan, samples: int, seed: int, model) -> StudyRun:
    """``--sensitivity``: each non-zero sigma alone at 0.5, 1, 2 times its value.

    The run's result is ``(models, campaign result)``; the document and the text give one
    row per source and sigma (:func:`.sensitivity.sensitivity_rows`) and each source's
    law with its standard error, or why it has none (:func:`.sensitivity.laws`).
    """
    from lunarcap.studies.dispersions import samples as disp
    from lunarcap.studies.dispersions import sensitivity as sens

    factors = sens.FACTORS if args.factors is None else number_list(
        "--factors", args.factors, "", positive=True, distinct=True)

    def rows(out) -> list:
        models, res = out
        return sens.sensitivity_rows(res.table, models)

    def document(out) -> dict:
        return {"plan": plan.to_dict(), "seed": seed, "table": str(out[1].path),
                "run": out[1].run, "sensitivity": rows(out),
                "laws": sens.laws(out[1].table, out[0])}

    return StudyRun(
        lambda: sens.run_sensitivity(plan, samples, seed, model, factors=factors,
                                     out=args.out, workers=args.workers,
                                     scheduler=args.scheduler, progress=not args.no_progress,
                                     antithetic=args.antithetic),
        "samples", document,
        lambda out: sens.format_sensitivity(plan, rows(out), out[1],
                                            sens.laws(out[1].table, out[0])),
        lambda out: all(s in disp.OK_STATUSES for s in out[1].table.status))


#: The ``--json`` records of ``lunarcap dispersions`` (see :data:`lunarcap.schemas.RECORDS`).
RECORDS = {
    "dispersions": [{"plan": "plan_file"}, {"error_model": "error_model"}, "seed", "table",
                    {"run": "run"}, {"summary": "dispersions_summary"},
                    {"samples": "dispersions_sample"}],
    "error_model": ["thrust_sigma_pct", "isp_sigma_pct", "pointing_sigma_deg",
                    "ignition_sigma_s", "arrival_sigma_km", "arrival_sigma_mps", "arrival_cov",
                    "knowledge_sigma_km", "knowledge_sigma_mps", "knowledge_cov",
                    "gates_magnitude_pct", "gates_magnitude_mps", "gates_pointing_deg",
                    "gates_pointing_mps", "bplane_cov", "description"],
    "dispersions_summary": [
        ("samples", "integer"), "captured_and_corrected", "nominal_delta_v_mps",
        "nominal_propellant_kg", *[f"{q}_p{p}_{u}" for p in (50, 90, 95, 99)
                                   for q, u in (("delta_v", "mps"), ("propellant", "kg"))],
        *[f"{k}_p{p}{u}" for p in (50, 90, 95, 99)
          for k, u in (("delta_v", "_ci_mps"), ("samples_needed", ""))],
        "mean_above_nominal_mps", "mean_above_nominal_se_mps",
        "budget_p99_above_nominal_mps", "budget_p99_ci_mps", "budget_p99_ci_ranks",
        "budget_p99_burns_above_nominal_mps", "budget_p99_burns_ci_mps", "antithetic",
        "ci_level", "p_not_captured", "p_not_captured_upper95", "p_correction_failed",
        "p_correction_failed_upper95", {"failures": "failed_sample"},
        *[f"final_{s}_{e}" for e in ("rp_error_km", "ra_error_km", "inc_error_deg")
          for s in ("rms", "max_abs")],
        "trim_p50_mps", "trim_p90_mps", "trim_p99_mps", "trim_p99_ci_mps", "trim_mean_mps",
        "trim_mean_se_mps", "trim_max_mps", "trimmed_share", "trim_propellant_p99_kg",
        "trimmed_max_abs_rp_error_m", "trimmed_max_abs_ra_error_m",
        "trimmed_max_abs_inc_error_deg"],
    "failed_sample": ["sample", "status", "reason"],
    "dispersions_sample": ["plan", "plan_id", "thrust_N", "isp_s", "dynamics", "seed",
                           "sample", "antithetic", "thrust_sigma_pct", "isp_sigma_pct",
                           "pointing_sigma_deg", "ignition_sigma_s", "arrival_sigma_km",
                           "arrival_sigma_mps", "arrival_cov", "status", "reason",
                           "burns_flown", "total_delta_v_mps", "propellant_kg",
                           "nominal_delta_v_mps", "nominal_propellant_kg",
                           "delta_v_above_nominal_mps", "final_rp_error_km",
                           "final_ra_error_km", "final_inc_error_deg", "final_rp_altitude_km",
                           "final_ra_altitude_km", "arrival_dr_km", "arrival_dv_mps",
                           "task_wall_s", "task_cpu_s", "worker", "code_version",
                           "completed_utc", "error", "knowledge_sigma_km",
                           "knowledge_sigma_mps", "knowledge_cov", "gates_magnitude_pct",
                           "gates_magnitude_mps", "gates_pointing_deg", "gates_pointing_mps",
                           "bplane_cov", "arrival_db_km", "arrival_dt_s",
                           "burns_delta_v_mps", "trim_delta_v_mps", "trim_propellant_kg",
                           "trimmed_rp_error_m", "trimmed_ra_error_m", "trimmed_inc_error_deg",
                           {"burns": "dispersed_burn"}, {"trim": "trim_impulse"}],
    "dispersed_burn": ["burn", "delta_v_mps", "planned_delta_v_mps", "ignition_min",
                       "duration_min", "thrust_error_pct", "isp_error_pct",
                       "pointing_error_deg", "ignition_error_s", "knowledge_dr_km",
                       "knowledge_dv_mps"],
    "trim_impulse": ["after_end_min", "delta_v_mps", "radial_mps", "transverse_mps",
                     "normal_mps"],
}

COMMAND = StudyCommand(
    "dispersions", "the capture's delta-V budget under execution and arrival errors (Monte "
                   "Carlo, closed loop)", options, prepare, dask="sample",
    signed=("--samples", "--seed", *(opt for opt, _, _ in SIGMA_OPTIONS)), records=RECORDS,
    arrays=frozenset({"dispersions_sample", "dispersed_burn", "failed_sample",
                      "trim_impulse"}),
    glossary="glossary.yaml")
