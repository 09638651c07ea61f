"""``lunarcap burns``: how many capture burns, on the command line (:mod:`.counts`).

The plan's capture in N burns for each N asked, the intermediate periods optimised under
a longest period and a longest time; one Dask task per count. Its ``--json`` records:
the document (the plan, the bounds, the table and run, one record per count) and each
count's burns.
"""

from __future__ import annotations

from lunarcap.errors import number
from lunarcap.studies.registry import StudyCommand, StudyRun


def options(p) -> None:
    """The counts tried and the bounds of the intermediate orbits."""
    p.add_argument("--counts", default="1,2,3,4,5", metavar="N1,N2,...",
                   help="numbers of burns to try (default 1,2,3,4,5)")
    p.add_argument("--max-period-h", default="12.235", metavar="H",
                   help="longest intermediate period, h (default 12.235)")
    p.add_argument("--max-days", default="3", metavar="D",
                   help="longest time from the arrival perilune to the end of the last burn, "
                        "days (default 3)")


def prepare(args, plan) -> StudyRun:
    """The burns study of ``plan``: counts and bounds checked (InputError) first.

    Any force model the plan names is accepted (in a gravity field the all-burns NLP
    carries it: :func:`lunarcap.optim.joint.solve_joint`); what is refused is refused here,
    before the cluster starts: a count whose capture could outlast the ephemeris fit its
    dynamics read (:func:`.counts.check_counts`).
    """
    from lunarcap.studies.burn_count import counts as burns

    counts = burns.parse_counts(args.counts)
    max_period_h = number("--max-period-h", args.max_period_h, "h", positive=True)
    max_days = number("--max-days", args.max_days, "days", positive=True)
    burns.check_counts(plan, counts, max_period_h * 3600.0, max_days * 86400.0)
    return StudyRun.of(burns.STUDY, lambda: burns.run_burns(
        [plan], counts, max_period_h, max_days, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress),
        {"plan": plan.to_dict(), "max_period_h": max_period_h, "max_days": max_days},
        plan=plan)


#: The ``--json`` records of ``lunarcap burns`` (see :data:`lunarcap.schemas.RECORDS`).
RECORDS = {
    "burns": [{"plan": "plan_file"}, "max_period_h", "max_days", "table", {"run": "run"},
              {"counts": "burns_count"}],
    "burns_count": ["plan", "plan_id", "thrust_N", "isp_s", "dynamics", "n_burns",
                    "max_period_h", "max_days", "status", "reason", "periods_h",
                    "total_delta_v_mps", "total_impulsive_limit_mps", "total_delta_v_loss_mps",
                    "total_impulsive_delta_v_two_body_mps", "total_fuel_kg", "final_mass_kg",
                    "total_burn_duration_min", "time_to_final_orbit_h", "all_verified",
                    "ipopt_status", "total_ipopt_iterations", "task_wall_s", "worker",
                    "code_version", "completed_utc", "error", {"burns": "burns_count_burn"}],
    "burns_count_burn": ["burn", "target_orbit", "period_after_h", "nominal_perilune_epoch",
                         "ignition_epoch", "start_min", "burn_duration_min", "delta_v_mps",
                         "impulsive_limit_mps", "delta_v_loss_mps", "m_start_kg", "m_end_kg",
                         "fuel_kg", "rp_end_km", "ra_end_km", "verified", "impulsive_verified"],
}

COMMAND = StudyCommand(
    "burns", "how many capture burns: N burns, periods optimised", options, prepare,
    dask="count", signed=("--counts", "--max-period-h", "--max-days"), records=RECORDS,
    arrays=frozenset({"burns_count", "burns_count_burn"}))
