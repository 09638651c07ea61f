"""The glossary of quantities (lunarcap.quantities): every CSV column and JSON key the
package writes is a glossary name, and no bare ``loss_mps`` remains anywhere.

The command lines run for real (two-body dynamics, see tests/cli_outputs.py); the study
tables' declared columns are checked as well, and the source tree is searched for the
retired names (``loss_mps`` had three meanings: delta-V minus our impulsive limit, minus
the paper's printed impulse, and the objective loss).
"""

import re
from pathlib import Path

import cli_outputs
import pandas as pd
import pytest

from lunarcap import quantities as Q

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.slow


# ------------------------------------------------------------------ the glossary itself
def test_every_quantity_has_one_entry_a_label_and_a_sentence():
    names = [q.name for q in Q._Q]
    assert len(names) == len(set(names)), sorted(n for n in names if names.count(n) > 1)
    for q in Q.GLOSSARY.values():
        assert q.label and q.definition.endswith("."), q.name
        assert q.kind in ("number", "integer", "string", "boolean", "array", "object"), q.name
        assert q.unit == (Q.unit_of(q.name) if q.kind in ("number", "integer") else ""), q.name


def test_the_losses_are_told_apart():
    defs = {n: Q.lookup(n).definition for n in ("delta_v_loss_mps", "objective_loss_mps",
                                                "loss_vs_paper_impulse_mps",
                                                "analytic_loss_mps")}
    assert len(set(defs.values())) == 4
    assert "impulsive_limit_mps" in defs["delta_v_loss_mps"]
    assert "paper_impulsive_delta_v_mps" in defs["loss_vs_paper_impulse_mps"]
    assert Q.lookup("impulsive_limit_mps").definition != \
        Q.lookup("impulsive_delta_v_two_body_mps").definition
    assert "end of the last burn" in Q.lookup("time_to_final_orbit_h").definition


def test_composed_names_and_retired_names():
    assert Q.lookup("paper_delta_v_mps").header == "ΔV, paper (m/s)"
    assert Q.lookup("total_delta_v_loss_mps").unit == "m/s"
    assert Q.lookup("objective_loss_percent_loi2").label == "J loss, LOI 2"
    assert Q.lookup("verification_rp_error_m").unit == "m"
    for old in Q.RETIRED:
        assert not Q.is_known(old), old
    with pytest.raises(KeyError, match="not in the glossary"):
        Q.lookup("loss_mps")


def test_a_name_is_defined_once_in_the_glossary_files(tmp_path, monkeypatch):
    """The glossary is data: a key given twice in one file (YAML would keep the last) or a
    name that another file defines (a study's own quantity shadowing a shared one) is an
    error, not a silent choice between two definitions."""
    twice = tmp_path / "twice.yaml"
    twice.write_text("quantities:\n  a_m:\n    label: a\n    definition: A.\n"
                     "  a_m:\n    label: b\n    definition: B.\n", encoding="utf-8")
    with pytest.raises(ValueError, match="line 5: 'a_m' is defined twice"):
        Q.read(twice)
    monkeypatch.setattr(Q, "GLOSSARY", dict(Q.GLOSSARY))
    monkeypatch.setattr(Q, "_Q", list(Q._Q))
    monkeypatch.setattr(Q, "_SOURCES", dict(Q._SOURCES))
    shadow = tmp_path / "glossary.yaml"
    shadow.write_text("quantities:\n  delta_v_mps:\n    label: ΔV\n    definition: Mine.\n",
                      encoding="utf-8")
    with pytest.raises(ValueError, match=r"delta_v_mps \(already in .*data/glossary.yaml\)"):
        Q.merge_file(shadow)
    assert Q.lookup("delta_v_mps").definition.startswith("Delta-V of the finite burn")
    assert Q.merge_file(Q.STUDY_FILES[0]) == []   # a file already read adds nothing
    assert {p.parent.name for p in Q.STUDY_FILES} == {"missed", "dispersions"}


def test_labels_come_from_the_glossary():
    from lunarcap.report.labels import label
    for name in ("delta_v_loss_mps", "impulsive_limit_mps", "time_to_final_orbit_h"):
        assert label(name) == Q.lookup(name).header


# ------------------------------------------------------------------ what the package writes
def test_declared_study_columns_are_glossary_names():
    from lunarcap.studies.burn_count import counts as burns
    from lunarcap.studies.dispersions import samples as dispersions
    from lunarcap.studies.engine_trade import trade as study
    from lunarcap.studies.missed import cases as missed
    for mod, cols in (("study", study.COLUMNS), ("burns", burns.COLUMNS),
                      ("missed", missed.COLUMNS), ("dispersions", dispersions.COLUMNS)):
        assert Q.unknown(cols) == [], mod


@pytest.mark.parametrize("command", list(cli_outputs.COMMANDS))
def test_json_keys_are_glossary_names(command):
    data, _ = cli_outputs.outputs()[command]
    names = sorted(cli_outputs.keys(data))
    assert Q.unknown(names) == [], command
    assert "loss_mps" not in names


@pytest.mark.parametrize("command", [c for c, (_, csv) in cli_outputs.COMMANDS.items() if csv])
def test_csv_columns_are_glossary_names(command):
    _, csv = cli_outputs.outputs()[command]
    columns = list(pd.read_csv(csv, nrows=0).columns)
    assert Q.unknown(columns) == [], command


def test_periods_are_numbers_in_json():
    data, _ = cli_outputs.outputs()["burns"]
    two = [c for c in data["counts"] if c["n_burns"] == 2][0]
    assert isinstance(two["periods_h"], list) and len(two["periods_h"]) == 1
    assert isinstance(two["periods_h"][0], float) and two["periods_h"][0] > 1.0


def test_no_bare_loss_mps_anywhere():
    bare = re.compile(r"(?<![\w@])loss_mps(?![\w@])")
    hits = []
    for pattern in ("lunarcap/**/*.py", "notebooks/*.ipynb", "tests/**/*.py", "book/*.md"):
        for p in ROOT.glob(pattern):
            if p.name in ("quantities.py", "test_glossary.py", "test_json_schemas.py"):
                continue
            for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1):
                if bare.search(line):
                    hits.append(f"{p.relative_to(ROOT)}:{i}")
    assert hits == []
