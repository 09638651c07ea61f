"""A rerun whose results are all in the disk cache builds no NLP (issue 16, item 6).

``plan_result`` prebuilds the NLP shapes of the burns and impulsive limits it will solve,
asking the cache first (:func:`lunarcap.capture.chain.prebuild_for`); a shape built for a
result that is already on disk costs 1.2-1.6 s per shape for nothing. Reverting
``prebuild_for`` to ask with another key than :func:`lunarcap.capture.chain.impulsive_key`
(as before: the first burn's impulsive limit is keyed by a sized thrust) fails it.
"""

import joblib
import pytest

from lunarcap.capture import chain
from lunarcap.mission.plan import paper_plan
from lunarcap.optim.nlp import clear_nlps, n_built
from lunarcap.repro import cache

pytestmark = pytest.mark.slow


@pytest.mark.parametrize("starts", [(-10.0, -6.0), ("free", "free")])
def test_cached_plan_builds_no_nlp(tmp_path, monkeypatch, starts):
    monkeypatch.setattr(cache, "memory", joblib.Memory(str(tmp_path), verbose=0))
    monkeypatch.delenv("LUNARCAP_NO_CACHE", raising=False)
    plan = paper_plan(450.0, 300.0, starts=starts + ("free",), dynamics="two-body").key(2)
    first = chain.plan_result(plan).to_dict()
    clear_nlps()
    again = chain.plan_result(plan).to_dict()
    assert n_built() == 0, "an NLP was built for cached results"
    assert again["totals"] == first["totals"]
