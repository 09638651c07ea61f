"""The computing parts of the joint-capture page, on hand-made leg tables and results."""

import math
from types import SimpleNamespace

import pandas as pd
import pytest

from lunarcap.report.pages import joint_capture as jc
from lunarcap.repro import paths


def _legs(diffs):
    return pd.DataFrame({"loi": [1, 2, 3], "sequential_start_min": [-10.0, -6.0, -5.0],
                         "joint_start_min": [-10.0, -6.1, -4.9],
                         "sequential_burn_duration_min": [19.5, 9.0, 8.0],
                         "joint_burn_duration_min": [19.5, 9.1, 7.9],
                         "sequential_delta_v_mps": [360.0, 256.0, 247.0],
                         "joint_delta_v_mps": [360.0, 256.1, 246.9],
                         "difference_mps": diffs, "joint_verified": [True, True, False]})


def test_legs_frame_labels_every_leg():
    f = jc.legs_frame({"150 N / 200 s": _legs([0.0, -0.1, 0.1]),
                       "300 N / 250 s": _legs([0.0, 0.0, 0.0])})
    assert len(f) == 6 and f.engine.iloc[3] == "300 N / 250 s"
    assert f.joint_verified.tolist()[:3] == ["passed", "passed", "failed"]


def test_prose_values_leg_differences():
    totals = pd.DataFrame({"total_difference_mps": [0.0004, 0.0001],
                           "largest_leg_shift_mps": [0.1, 0.02],
                           "largest_start_shift_s": [6.0, 1.0]})
    v = jc.prose_values({150.0: _legs([0.0, -0.1, 0.1004])}, totals)
    assert v["total_difference_150N_mps"] == pytest.approx(0.0004)
    assert v["leg2_difference_150N_mps"] == -0.1 and v["leg2_extra_150N_mps"] == 0.1
    assert v["leg3_difference_150N_mps"] == 0.1004
    assert math.isnan(v["leg3_difference_300N_mps"])
    assert v["max_start_shift_s"] == 6.0


class _Chain:
    """A stand-in of lunarcap.solve's CaptureResult: its plan's engine and burn records."""

    def __init__(self, dv):
        self.plan = SimpleNamespace(engine=SimpleNamespace(thrust_N=150.0, isp_s=200.0))
        self._rows = [{"start_min": -10.0 + k, "burn_duration_min": 20.0 - 5 * k,
                       "delta_v_mps": v} for k, v in enumerate(dv)]

    def rows(self):
        return [dict(r) for r in self._rows]


class _Joint:
    """A stand-in of lunarcap.solve_joint's JointSolution, started from ``warm_dv``."""

    ipopt_status, iterations, solve_s = "Solve_Succeeded", 12, 3.5

    def __init__(self, dv, warm_dv):
        self._rows = [{"start_min": -10.1 + k, "burn_duration_min": 20.0 - 5 * k,
                       "delta_v_mps": v, "verification_passed": True}
                      for k, v in enumerate(dv)]
        self.warm_start = [{"delta_v_mps": v} for v in warm_dv]

    def rows(self):
        return [dict(r) for r in self._rows]


def test_legs_table_sets_the_joint_optimum_beside_the_chain():
    chain = _Chain([360.0, 256.0, 247.0])
    df = jc.legs_table(chain, _Joint([360.0, 256.1, 246.9], [360.0, 256.0, 247.0]))
    assert df.loi.tolist() == [1, 2, 3]
    assert df.difference_mps.tolist() == pytest.approx([0.0, -0.1, 0.1])
    assert df.joint_start_min.tolist() == pytest.approx([-10.1, -9.1, -8.1])
    assert df.sequential_start_min.tolist() == [-10.0, -9.0, -8.0]
    assert df.attrs["ipopt_status"] == "Solve_Succeeded" and df.attrs["iterations"] == 12
    assert df.attrs["thrust_N"] == 150.0


def test_a_chain_the_joint_nlp_did_not_start_from_fails_the_page(tmp_path):
    # the chain shown must be the one the joint NLP started from (same plan, dynamics,
    # free ignitions): else the legs compare two captures, and the page's check says so
    chain = _Chain([360.0, 256.0, 247.0])
    same = _Joint([360.0, 256.1, 246.9], [360.0, 256.0, 247.0])
    other = _Joint([360.0, 256.1, 246.9], [361.0, 256.0, 247.0])
    assert jc.warm_start_gap_mps(chain, same) == 0.0
    assert jc.warm_start_gap_mps(chain, other) == pytest.approx(1.0)
    assert math.isnan(jc.warm_start_gap_mps(chain, _Joint([1.0], [1.0])))
    with paths.using_book(tmp_path / "book"):
        good = jc.build({(150.0, 200.0): (chain, same)}, "two-body", "t_joint_fake", True)
        bad = jc.build({(150.0, 200.0): (chain, other)}, "two-body", "t_joint_fake", True)
    assert all(ok for what, ok, _ in good.checks if "started from" in what)
    with pytest.raises(AssertionError, match="started from the one-at-a-time chain"):
        bad.check()
