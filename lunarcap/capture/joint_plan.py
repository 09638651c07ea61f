"""All burns of a plan in one NLP, beside the same plan solved one burn at a time.

Both with free ignition times: the one-at-a-time chain (:func:`lunarcap.capture.chain.solve_plan`
with every ``start_min`` free) is the warm start of the all-burns NLP
(:func:`lunarcap.optim.joint.solve_joint`), and the comparison of the two totals says what
the paper's burn-by-burn approach, with its proxy objective Eq. (9), loses.
"""

from __future__ import annotations

from dataclasses import dataclass

from lunarcap.capture.chain import solve_plan
from lunarcap.mission.plan import CapturePlan
from lunarcap.optim.collocation import Mesh
from lunarcap.optim.joint import JointResult, solve_joint
from lunarcap.repro.cache import cached


@dataclass
class JointComparison:
    """The joint optimum and the one-at-a-time chain it started from (both free ignition)."""

    joint: JointResult
    sequential: list

    @property
    def total_delta_v_mps(self) -> float:
        """Joint optimum's total delta-V, m/s."""
        return self.joint.total_delta_v_mps

    @property
    def sequential_total_delta_v_mps(self) -> float:
        """One-at-a-time chain's total delta-V, m/s."""
        return sum(s.delta_v_mps for s in self.sequential)


def solve_plan_jointly(plan: CapturePlan, mesh: Mesh = Mesh(8, 16, 5),
                       verbose: bool = False, whole_field: bool = False) -> JointComparison:
    """Solve ``plan`` (ignitions set free) as one NLP, warm-started burn by burn.

    In a gravity field the NLP carries the field as :func:`lunarcap.optim.joint.solve_joint`
    does (cut, plus an outer correction; ``whole_field``: whole, for bounding what the
    correction leaves out).
    """
    free = plan.with_starts(["free"] * plan.n_burns)
    seq = solve_plan(free, verbose=verbose)
    return JointComparison(solve_joint(free, seq, plan.ephemeris_model(), mesh,
                                       whole_field=whole_field), seq)


@cached
def joint_summary(plan: CapturePlan) -> dict:
    """Cached plain-dict form of :func:`solve_plan_jointly` (pass ``plan.key()``)."""
    r = solve_plan_jointly(plan)
    return {"legs": [s.summary() for s in r.joint.legs],
            "sequential": [s.summary() for s in r.sequential],
            "ipopt_status": r.joint.ipopt_status, "iterations": r.joint.iterations,
            "solve_s": r.joint.solve_s, "total_delta_v_mps": r.total_delta_v_mps,
            "sequential_total_delta_v_mps": r.sequential_total_delta_v_mps}
