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


@pytest.mark.parametrize("command", list(cli_outputs.COMMANDS))
def test_real_output_validates(command):
    data, _ = cli_outputs.outputs()[command]
    jsonschema.validate(data, schemas.load(command), cls=jsonschema.Draft202012Validator)


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
