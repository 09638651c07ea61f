"""Every burn of a plan in one optimisation: the joint optimum of the whole capture.

:func:`lunarcap.solve` solves a plan as Song et al. (2011) do, one burn at a time, each
burn minimising its own objective (their Eq. 9: its delta-V plus the speed it leaves at
the next perilune, a proxy for what the next burn must remove). :func:`solve_joint` asks
what that costs: every burn, ignition and coast of the plan is one NLP (Legendre-Gauss-
Radau collocation, IPOPT) minimising the *sum* of the burns' delta-V, with the plan's
terminal conditions, warm-started from the plan solved one burn at a time with every
ignition free, each leg then verified as a single burn is (flown again from the previous
leg's verified end by an independent integrator). The result (:class:`JointSolution`) is
read as every result of the API (:class:`.results.Result`) and is cached on disk by the
plan as given (:func:`lunarcap.capture.joint_plan.joint_summary`).

A separate function rather than a keyword of :func:`lunarcap.solve`: its result is not a
:class:`~lunarcap.api.capture.CaptureResult` (no impulsive limit per burn, one IPOPT run
for all legs), and ``solve``'s ``impulsive``, ``after_days`` and ``on_burn`` have no
meaning for it, as :func:`lunarcap.solve_burn` is separate for one burn.
"""

from __future__ import annotations

from lunarcap.api.capture import _cache, _plan
from lunarcap.api.results import Result


def _flat(summary: dict) -> dict:
    """One leg's record: its solution's summary with the verification flattened.

    The keys of :meth:`lunarcap.CaptureResult.to_frame`'s burn records (``delta_v_mps``,
    ``start_min``, ``verification_passed``, ...), without the impulsive limit and the
    loss, which the joint NLP does not compute.
    """
    row = {k: v for k, v in summary.items() if k not in ("verification", "u_inertial")}
    row.update({f"verification_{k}": v for k, v in summary["verification"].items()})
    return row


class JointSolution(Result):
    """Every burn of a plan solved as one NLP, each leg verified (:func:`solve_joint`).

    Attributes
    ----------
    plan : CapturePlan
        The plan as given (the NLP frees every ignition).
    legs : list of dict
        One record per burn of the joint optimum (:meth:`rows`), in order.
    warm_start : list of dict
        The same records of the plan solved one burn at a time with every ignition free
        (each burn minimising its own Eq. 9), from which the NLP started.
    ipopt_status : str
        IPOPT's return status of the joint NLP.
    iterations : int
        IPOPT's iterations.
    solve_s : float
        Wall time of the NLP's solve, s (when it was computed; the result is cached).

    Examples
    --------
    The plan of :func:`solve_joint`'s example (read from the cache): its record per burn,
    its ``--json``-style document and its figure:

    >>> import lunarcap
    >>> joint = lunarcap.solve_joint(lunarcap.load_plan("two-burn-8h", dynamics="two-body"))
    >>> joint
    <JointSolution two-burn-8h: 2 burn(s) in one NLP, 890.253 m/s, verified>
    >>> joint.to_frame()[["burn", "delta_v_mps", "verification_passed"]].round(1)
       burn  delta_v_mps  verification_passed
    0     1        435.4                 True
    1     2        454.8                 True
    >>> sorted(joint.to_dict()["totals"])
    ['total_delta_v_mps', 'warm_start_total_delta_v_mps']
    >>> len(joint.plot().axes)
    2
    """

    def __init__(self, plan, summary: dict):
        self.plan = plan
        self.legs = [_flat(s) for s in summary["legs"]]
        self.warm_start = [_flat(s) for s in summary["sequential"]]
        self.ipopt_status = summary["ipopt_status"]
        self.iterations = int(summary["iterations"])
        self.solve_s = float(summary["solve_s"])

    def __repr__(self) -> str:
        return (f"<JointSolution {self.plan.name}: {len(self.legs)} burn(s) in one NLP, "
                f"{self.total_delta_v_mps:.3f} m/s, "
                f"{'verified' if self.verified else 'NOT verified'}>")

    @property
    def stem(self) -> str:
        """``<plan>_joint`` (the files' stem)."""
        return f"{self.plan.name}_joint"

    @property
    def verified(self) -> bool:
        """True if every leg passed verification."""
        return all(r["verification_passed"] for r in self.legs)

    @property
    def total_delta_v_mps(self) -> float:
        """The joint optimum's total delta-V (the NLP's objective), m/s."""
        return sum(r["delta_v_mps"] for r in self.legs)

    @property
    def warm_start_total_delta_v_mps(self) -> float:
        """The one-at-a-time chain's total delta-V, m/s (never below the joint optimum's)."""
        return sum(r["delta_v_mps"] for r in self.warm_start)

    def rows(self) -> list:
        """One record per burn of the joint optimum, units in the keys (as ``legs``)."""
        return [dict(r) for r in self.legs]

    def document(self) -> dict:
        """The plan, the legs, the warm start, the totals and IPOPT's run."""
        return {"plan": self.plan.to_dict(), "legs": self.rows(),
                "warm_start": [dict(r) for r in self.warm_start],
                "totals": {"total_delta_v_mps": self.total_delta_v_mps,
                           "warm_start_total_delta_v_mps": self.warm_start_total_delta_v_mps},
                "ipopt_status": self.ipopt_status, "ipopt_iterations": self.iterations,
                "solve_s": self.solve_s}

    def to_frame(self):
        """One row per burn of the joint optimum (the ``legs`` of :meth:`to_dict`)."""
        import pandas as pd

        return pd.DataFrame(self.rows())

    def plot(self):
        """Per burn, what the joint optimum changes: delta-V (m/s) and ignition (s).

        Both against the one-at-a-time warm start: its delta-V minus the joint one's
        (positive: the joint optimum spends less on that burn), and the joint ignition
        minus the warm start's.
        """
        import matplotlib.pyplot as plt

        from lunarcap.report.figstyle import FIG_WIDTH_IN, OTHER_COLOURS

        burns = [r["burn"] for r in self.legs]
        saved = [w["delta_v_mps"] - j["delta_v_mps"] for j, w in zip(self.legs, self.warm_start)]
        moved = [60.0 * (j["start_min"] - w["start_min"])
                 for j, w in zip(self.legs, self.warm_start)]
        fig, axes = plt.subplots(1, 2, figsize=(FIG_WIDTH_IN, 3.2), layout="constrained")
        for ax, values, label, colour in (
                (axes[0], saved, "ΔV one at a time − joint (m/s)", OTHER_COLOURS[0]),
                (axes[1], moved, "ignition, joint − one at a time (s)", OTHER_COLOURS[1])):
            ax.bar(burns, values, color=colour)
            ax.axhline(0.0, color="0.3", lw=0.8)
            ax.set_xticks(burns, [str(b) for b in burns])
            ax.set_xlabel("burn")
            ax.set_ylabel(label)
            ax.grid(alpha=0.3, axis="y")
        return fig


def solve_joint(plan, *, use_cache: bool = True) -> JointSolution:
    """Solve every burn of a plan as one NLP minimising the total delta-V, each leg verified.

    Every ignition is free (the plan's offsets are not used): the plan is first solved one
    burn at a time with free ignitions (each burn minimising its own objective, Eq. 9 of
    Song et al. 2011, as :func:`lunarcap.solve` does), which starts the NLP of all burns,
    ignitions and coasts together; each leg of its optimum is then verified from the
    previous leg's verified end. The difference of the two totals is what optimising burn
    by burn loses. In a gravity field the NLP carries the field as the single burns do
    (an outer correction).

    Parameters
    ----------
    plan : CapturePlan, or anything :func:`lunarcap.load_plan` takes
    use_cache : bool
        False: solved again, the one-at-a-time chain included (``--no-cache``); else read
        from the disk cache when this plan (as given) was solved before.

    Returns
    -------
    JointSolution
        Its ``legs`` (the optimum, burn by burn: ``start_min`` in min from each nominal
        perilune, ``delta_v_mps``, ...), ``warm_start`` (the one-at-a-time chain) and
        IPOPT's status.

    Raises
    ------
    SolveError
        IPOPT did not converge on the joint NLP or a leg failed verification (its status
        in the error), or a burn of the warm start could not be solved.

    Examples
    --------
    The two burns of a packaged plan in two-body dynamics (seconds; read back from the
    disk cache once solved), beside the same plan solved one burn at a time:

    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", dynamics="two-body")
    >>> joint = lunarcap.solve_joint(plan)
    >>> joint.verified, joint.ipopt_status
    (True, 'Solve_Succeeded')
    >>> chain = lunarcap.solve(plan.with_starts(["free"] * plan.n_burns), impulsive=False)
    >>> saved_mps = chain.totals()["total_delta_v_mps"] - joint.total_delta_v_mps
    >>> -1e-3 < saved_mps < 0.1
    True
    """
    from lunarcap.capture.joint_plan import joint_summary

    plan = _plan(plan)
    with _cache(use_cache):
        return JointSolution(plan, joint_summary(plan.key()))
