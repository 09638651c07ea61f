"""``lunarcap missed``: missed thrust and late ignition on the command line (:mod:`.cases`).

A burn of the plan cut short at each fraction asked (or ignited late), the capture
re-planned after each delay and re-optimised; one Dask task per case. Its ``--json``
records: the document (the plan, the burn, the bound, the table and run, the cases) and
each case's recovery burns; its own quantities are in ``glossary.yaml`` beside this file.
"""

from __future__ import annotations

from lunarcap.errors import integer, number, number_list
from lunarcap.studies.registry import StudyCommand, StudyRun

#: The cut-offs when none are asked (and no late ignition is): fractions of the burn flown.
DEFAULT_FRACTIONS = "0.25,0.5,0.75,0.9"


def options(p) -> None:
    """The burn cut short, the faults (cut-offs, late ignitions), the recovery's bounds."""
    p.add_argument("--burn", default="1", metavar="N", help="the burn cut short (default 1)")
    p.add_argument("--fractions", default=None, metavar="F1,F2,...",
                   help=f"fractions of the burn flown before the engine stops, in (0, 1] "
                        f"(default {DEFAULT_FRACTIONS}; none if only --late-min is given)")
    p.add_argument("--delays-min", default="0,30,120,720", metavar="D1,D2,...",
                   help="minutes from the cut-off to the recovery window (default "
                        "0,30,120,720)")
    p.add_argument("--late-min", default=None, metavar="L1,L2,...",
                   help="late ignition: the burn ignites these minutes after its planned "
                        "ignition, is re-optimised from there and the later burns re-planned "
                        "(default: none)")
    p.add_argument("--max-period-h", default="24", metavar="H",
                   help="longest period of the orbit after the burn, in the recovery and "
                        "in the nominal it is compared with, h (default 24); a row it "
                        "decides says so, and what a longer one would take")
    p.add_argument("--max-days", default="3", metavar="D",
                   help="the capture's last burn ends within D days of the arrival perilune; "
                        "a make-up may wait for a later perilune within it (default 3, as "
                        "lunarcap burns); a row it decides says so")


def prepare(args, plan) -> StudyRun:
    """The missed-thrust study of ``plan``: every number checked (InputError) first.

    Any force model the plan names is accepted: in a gravity field the recoveries and their
    nominal are solved by the all-burns NLP with the field's outer correction
    (:func:`lunarcap.optim.joint.solve_joint`) and verified in the whole field.
    """
    from lunarcap.studies.missed import cases as missed

    burn = integer("--burn", args.burn, minimum=1)
    max_period_h = number("--max-period-h", args.max_period_h, "h", positive=True)
    max_days = number("--max-days", args.max_days, "days", positive=True)
    fractions = args.fractions
    if fractions is None:   # the default cut-offs, unless only late ignitions are asked
        fractions = None if args.late_min else DEFAULT_FRACTIONS
    if fractions is not None:
        fractions = number_list("--fractions", fractions, "", positive=True, maximum=1.0,
                                distinct=True)
    delays = number_list("--delays-min", args.delays_min, "min", minimum=0.0, distinct=True)
    late = None if args.late_min is None else \
        number_list("--late-min", args.late_min, "min", minimum=0.0, distinct=True)
    missed.check_max_days(plan, burn, max_period_h, max_days)
    return StudyRun.of(missed.STUDY, lambda: missed.run_missed(
        plan, burn, fractions, delays, max_period_h, out=args.out,
        workers=args.workers, scheduler=args.scheduler, progress=not args.no_progress,
        late_min=late, max_days=max_days),
        {"plan": plan.to_dict(), "burn": burn, "max_period_h": max_period_h,
         "max_days": max_days}, plan=plan, burn=burn)


#: The ``--json`` records of ``lunarcap missed`` (see :data:`lunarcap.schemas.RECORDS`).
RECORDS = {
    "missed": [{"plan": "plan_file"}, "burn", "max_period_h", "max_days", "table",
               {"run": "run"}, {"cases": "missed_case"}],
    "missed_case": ["plan", "plan_id", "thrust_N", "isp_s", "dynamics", "burn", "contingency",
                    "fraction", "delay_min", "late_min", "max_period_h", "max_days", "status",
                    "reason",
                    "captured", "cutoff_orbit", "cutoff_epoch", "cutoff_min_after_ignition",
                    "nominal_burn_duration_min", "partial_delta_v_mps",
                    "nominal_burn_delta_v_mps", "cutoff_energy_km2ps2", "cutoff_e",
                    "cutoff_rp_km", "cutoff_ra_km", "cutoff_period_h", "cutoff_soi_radius_km",
                    "recovery_start_e", "recovery_delta_v_mps", "total_delta_v_mps",
                    "nominal_remaining_delta_v_mps", "penalty_mps", "make_up_delta_v_mps",
                    "make_up_estimate_mps", "make_up_period_h", "nominal_period_after_burn_h",
                    "first_coast_h", "make_up_estimate_h", "time_to_final_orbit_h",
                    "nominal_time_to_final_orbit_h", "all_verified", "ipopt_status",
                    "solver_warnings", "task_wall_s", "worker", "code_version", "completed_utc",
                    "error",
                    {"recovery_burns": "recovery_burn"}],
    "recovery_burn": ["burn", "target_orbit", "ignition_epoch", "ignition_min_after_fault",
                      "burn_duration_min", "delta_v_mps", "verified"],
}

COMMAND = StudyCommand(
    "missed", "missed thrust or late ignition: a burn gone wrong, the capture re-planned",
    options, prepare, dask="case",
    signed=("--burn", "--fractions", "--delays-min", "--late-min", "--max-period-h",
            "--max-days"),
    records=RECORDS, arrays=frozenset({"missed_case", "recovery_burn"}),
    run_keys=("nominal_solver_warnings",), glossary="glossary.yaml")
