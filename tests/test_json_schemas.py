"""The JSON Schemas of the ``--json`` outputs (lunarcap/schemas): generated from the glossary,
stored as package data, and met by the real outputs of every command (two-body runs, see
tests/cli_outputs.py).
"""

import copy

import cli_outputs
import jsonschema
import pytest

from lunarcap import quantities as Q
from lunarcap import schemas

pytestmark = pytest.mark.slow


def test_stored_schemas_are_the_generated_ones():
    # after a change of the glossary or the records: python -m lunarcap.schemas
    for cmd, s in schemas.schemas().items():
        assert schemas.path(cmd).read_text(encoding="utf-8") == schemas.text(s), cmd


def test_every_command_with_json_has_a_schema():
    assert set(schemas.COMMANDS) == set(cli_outputs.COMMANDS)


def _properties(schema):
    """Every property name of a schema, nested."""
    out = set()
    for k, v in schema.get("properties", {}).items():
        out.add(k)
        out |= _properties(v)
        out |= _properties(v.get("items", {}))
    return out


def test_schemas_know_only_glossary_names_and_state_units():
    for cmd, s in schemas.schemas().items():
        jsonschema.Draft202012Validator.check_schema(s)
        assert Q.unknown(sorted(_properties(s))) == [], cmd
    leaf = schemas.schemas()["plan"]["properties"]["totals"]["properties"]
    assert leaf["time_to_final_orbit_h"]["x-unit"] == "h"
    assert "end of the last burn" in leaf["time_to_final_orbit_h"]["description"]


def test_package_data_includes_the_schemas():
    import tomllib
    from pathlib import Path

    pyproject = tomllib.loads((Path(__file__).resolve().parents[1] / "pyproject.toml")
                              .read_text())
    assert "*.schema.json" in pyproject["tool"]["setuptools"]["package-data"]["lunarcap.schemas"]


@pytest.mark.parametrize("plan", cli_outputs.PLANS)
@pytest.mark.parametrize("command", list(cli_outputs.COMMANDS))
def test_real_output_validates(command, plan):
    data, _ = cli_outputs.outputs(plan)[command]
    jsonschema.validate(data, schemas.load(command), cls=jsonschema.Draft202012Validator)


@pytest.mark.parametrize("command", ["plan", "burns", "missed", "dispersions"])
def test_outputs_carry_free_ignitions_both_altitudes_and_a_state_arrival(command):
    # what test_real_output_validates must meet: the plans as the user wrote them
    tb = cli_outputs.outputs("two-burn-8h")[command][0]["plan"]
    sa = cli_outputs.outputs("state-arrival")[command][0]["plan"]
    assert [b["start_min"] for b in tb["burns"]] == ["free", "free"]
    assert tb["burns"][1]["target"] == "circular"
    assert sa["burns"][1]["target"] == {"perilune_altitude_km": 100.0,
                                        "apolune_altitude_km": 300.0}
    assert sa["arrival"]["epoch"].endswith("UTC") and len(sa["arrival"]["position_km"]) == 3


def test_plan_file_schema_knows_every_key_a_plan_file_takes():
    from lunarcap.mission import plan_io

    plan = schemas.load("plan")["properties"]["plan"]["properties"]
    assert set(plan) == plan_io.TOP_KEYS
    assert set(plan["arrival"]["properties"]) == \
        plan_io.ARRIVAL_KEYS | plan_io.STATE_ARRIVAL_KEYS | plan_io.BPLANE_ARRIVAL_KEYS | {"opm"}
    assert set(plan["burns"]["items"]["properties"]) == plan_io.BURN_KEYS
    assert set(plan["start"]["properties"]) == plan_io.START_KEYS


def test_plan_file_values_outside_their_kinds_fail_validation():
    from lunarcap.mission.targets import CIRCULAR, PERILUNE

    data, _ = cli_outputs.outputs("state-arrival")["plan"]
    schema = schemas.load("plan")
    target = schema["properties"]["plan"]["properties"]["burns"]["items"]["properties"]["target"]
    assert set(target["anyOf"][0]["enum"]) == {CIRCULAR, PERILUNE}
    for where, bad in ((("start_min",), "fixed"), (("target",), "elliptic"),
                       (("target", "apolune_altitude_km"), None),
                       (("target", "apolune_altitude_km"), "300")):
        wrong = copy.deepcopy(data)
        burn = wrong["plan"]["burns"][1]
        *path, last = where
        for k in path:
            burn = burn[k]
        if bad is None:
            del burn[last]
        else:
            burn[last] = bad
        with pytest.raises(jsonschema.ValidationError):
            jsonschema.validate(wrong, schema, cls=jsonschema.Draft202012Validator)


def test_a_stray_key_or_a_string_period_fails_validation():
    data, _ = cli_outputs.outputs()["burns"]
    schema = schemas.load("burns")
    stray = copy.deepcopy(data)
    stray["counts"][0]["loss_mps"] = 1.0
    with pytest.raises(jsonschema.ValidationError, match="loss_mps"):
        jsonschema.validate(stray, schema, cls=jsonschema.Draft202012Validator)
    text = copy.deepcopy(data)
    text["counts"][-1]["periods_h"] = "8.365138"
    with pytest.raises(jsonschema.ValidationError, match="periods_h|is not of type"):
        jsonschema.validate(text, schema, cls=jsonschema.Draft202012Validator)


def test_ellipse_burns_say_which_orbit_they_target():
    data, _ = cli_outputs.outputs()["plan"]
    first = data["burns"][0]
    assert first["target_kind"] == "perilune"       # the paper's formulation ...
    assert first["target_orbit"].startswith("ellipse")  # ... of an ellipse
    assert isinstance(first["verification_end_e_cos_nu"], float)
