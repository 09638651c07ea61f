"""The computing parts of the verification page, on hand-made tables."""

import math

import numpy as np
import pandas as pd
import pytest

from lunarcap.report.display import FAILED, PASSED
from lunarcap.report.pages import verification as V


def test_case_context_names_the_engines_and_the_chains():
    paper = [(150.0, 200.0, 1, -10.0, ()), (150.0, 200.0, 2, -6.0, (-10.0,))]
    c = V.case_context(paper)
    assert c == {"engines_txt": "150 N / 200 s", "paper_txt": ", the paper's",
                 "after_b1": True}
    other = [(150.0, 250.0, 2, -6.0, (-8.0,))]
    c = V.case_context(other)
    assert c["paper_txt"] == "" and c["after_b1"] is False


def _ver():
    n = 3
    df = pd.DataFrame({"passed": [PASSED, PASSED, FAILED], "thrust_N": [150.0] * n,
                       "loi": [1, 2, 3], "start_min": [-10.0, -6.0, -5.0]})
    for _, _, col, _ in V.GATES:
        df[col] = [1e-3, -2e-3, np.nan]
    return df


def _mesh():
    return pd.DataFrame({
        "ipopt_status": ["succeeded", "succeeded", "failed", "acceptable"],
        "accepted": [FAILED, PASSED, FAILED, PASSED],
        "rp_error_m": [-120.0, 0.1, 500.0, 0.2], "gamma_error_deg": [0.01, 0.0, 0.5, 0.0],
        "default": ["", "yes", "", ""],
        "delta_v_change_vs_finest_mps": [0.3, -2e-6, 1.0, 0.0]})


def test_prose_values_count_the_meshes_ipopt_got_wrong():
    v = V.prose_values(_ver(), _mesh(), default_points=60)
    assert v["n_cases"] == 3 and v["n_passed"] == 2
    assert v["n_fooled"] == 1                 # IPOPT succeeded, the gate rejected it
    assert v["fooled_max_rp_m"] == pytest.approx(120.0)
    assert v["default_max_change_mps"] == pytest.approx(2e-6)
    assert v["worst_rp_error_m"] == pytest.approx(2e-3)
    v = V.prose_values(_ver(), _mesh().iloc[[1, 3]], default_points=60)
    assert v["n_fooled"] == 0 and math.isnan(v["fooled_max_rp_m"])
