"""JSON Schemas of the command line's ``--json`` outputs, generated from the glossary.

One schema per command with a ``--json`` output (``lunarcap/schemas/<command>.schema.json``,
package data): lunarcap's own (:data:`OWN`: impulsive, solve, plan) and each registered
study that declares records (:mod:`lunarcap.studies.registry`). Each record lists its keys
(:data:`RECORDS`, and the studies' own); the type, unit and description of every key come
from :mod:`lunarcap.quantities`, so a key that is not in the glossary cannot be written
here, and a record with a key not listed fails validation (``additionalProperties``
false). :func:`schemas` builds them; :func:`write` stores them (``python -m
lunarcap.schemas``); the tests check that the stored files are the generated ones and that
real outputs validate.

The schemas sit above the studies (they read the registry) rather than the studies
handing their records down: a schema describes a command's output, which the studies
define, and reading the registry when a schema is asked for needs no order of imports.

Examples
--------
>>> s = schemas()["solve"]
>>> s["properties"]["delta_v_loss_mps"]["x-unit"]
'm/s'
"""

from __future__ import annotations

import json
from pathlib import Path

from lunarcap import quantities as Q
from lunarcap.studies.registry import merge_quantities, studies

HERE = Path(__file__).resolve().parent
DRAFT = "https://json-schema.org/draft/2020-12/schema"

#: The keys of each kind of record (object) of lunarcap's own outputs and the records the
#: studies share; a nested record is named by ``{"key": "record"}`` instead of a key, a key
#: whose JSON type is not its glossary kind by ``(key, kind)``. A study's own records are
#: declared in its folder (:class:`lunarcap.studies.registry.StudyCommand`).
_SUMMARY = ["burn", "thrust_N", "isp_s", "dynamics", "steering", "target_kind", "free_start",
            "start_min", "ignition_epoch", "end_epoch", "burn_duration_min", "delta_v_mps",
            "impulsive_delta_v_two_body_mps", "m_start_kg", "m_end_kg", "fuel_kg", "v_end_kmps",
            "rp_end_km", "ra_end_km", "inc_end_deg", "period_end_h", "eq19_duration_min",
            "objective_j_mps", "ipopt_status", "ipopt_iterations", "mesh", "nlp_solve_s",
            "solve_wall_s"]
_LOSSES = ["impulsive_limit_mps", "delta_v_loss_mps", "delta_v_loss_percent",
           "objective_loss_mps", "objective_loss_percent"]
_VERIFICATION = ["delta_v_mps", "delta_v_diff_mps", "objective_diff_mps", "rp_error_m",
                 "ra_error_m", "inc_error_deg", "gamma_error_deg", "final_position_diff_m",
                 "passed", "nfev", "released", "end_e_cos_nu", "end_speed_diff_mps",
                 "period_error_s", "ellipse"]

#: The run record of every study (:func:`lunarcap.studies.campaign.run_campaign`'s keys and
#: those the packaged studies describe their runs with); a study's further keys are its
#: ``run_keys`` (:class:`lunarcap.studies.registry.StudyCommand`).
RUN = ["study", "started_utc", "wall_s", "cluster_start_s", "scheduler", "workers",
       ("cases", "integer"), "computed", "reused", "failed_computed", "interrupted", "table",
       "cache", "code_version", "host", "cpu_count", "load_avg_1min_start", "load_avg_1min_end",
       "counts", "grid", "burn", "fractions", "delays_min", ("late_min", "array"),
       "max_period_h", "max_days", "seed", ("samples", "integer"), ("error_model", "string")]

RECORDS = {
    "impulsive": ["plan", "thrust_N", "isp_s", "mass_kg", "v_inf_kmps",
                  "total_impulsive_delta_v_two_body_mps", {"burns": "impulsive_burn"}],
    "impulsive_burn": ["burn", "impulsive_delta_v_two_body_mps", "period_before_h",
                       "period_after_h", "v_perilune_before_kmps", "v_perilune_after_kmps",
                       "m_before_kg", "m_after_kg", "fuel_kg", "eq19_duration_min"],
    "solve": [*_SUMMARY, "target_orbit", "u_inertial", {"verification": "verification"},
              {"attempts": "attempt"},
              *_LOSSES, "plan", ("previous_starts_min", "starts")],
    "verification": _VERIFICATION,
    "attempt": ["mesh", "ipopt_status", "iterations", "nlp_solve_s", "delta_v_mps", "verified",
                "rp_error_m", "inc_error_deg", "gamma_error_deg", "delta_v_diff_mps",
                "failures"],
    "plan": [{"plan": "plan_file"}, "complete", {"burns": "plan_burn"},
             {"totals": "totals"}, {"after": "after"}],
    "after": ["after_days", "after_dynamics", "after_start_epoch", "after_revolutions",
              "after_min_perilune_altitude_km", "after_max_apolune_altitude_km",
              "after_last_perilune_altitude_km", "after_last_apolune_altitude_km",
              "after_inclination_change_deg", {"revolutions": "revolution"}],
    "revolution": ["perilune_epoch", "perilune_altitude_km", "apolune_altitude_km",
                   "mean_inclination_deg"],
    "plan_burn": [*_SUMMARY, "target_orbit", *_LOSSES, "impulsive_verified",
                  "impulsive_limit_reason",
                  *[f"verification_{k}" for k in _VERIFICATION]],
    "totals": ["total_delta_v_mps", "total_impulsive_limit_mps", "total_delta_v_loss_mps",
               "total_delta_v_loss_percent", "total_fuel_kg", "total_burn_duration_min",
               "final_mass_kg", "final_rp_km", "final_ra_km", "final_inc_deg",
               "final_perilune_epoch", "final_orbit_epoch", "time_to_final_orbit_h",
               "all_verified"],
    "plan_file": ["name", "description", {"arrival": "plan_arrival"},
                  {"engine": "plan_engine"}, ("dynamics", "string|object"), "ephemeris",
                  "lunar_pole", {"burns": "plan_file_burn"}, "formulation",
                  {"start": "plan_start"}],
    "plan_arrival": ["epoch", "perilune_altitude_km", "inclination_deg", "impulsive_loi1_mps",
                     "v_inf_kmps", "hemisphere", "approach_dir", "mass_kg", "frame",
                     "position_km", "velocity_kmps", "opm", "b_r_km", "b_t_km",
                     "bplane_reference"],
    "plan_engine": ["thrust_N", "isp_s"],
    "plan_file_burn": [("target", "target"), "target_period_h", "target_apolune_altitude_km",
                       "coast_min", ("start_min", "number or free"), "steering",
                       "start_bounds_min"],
    "plan_start": ["epoch", "mee", "mass_kg", "first_coast_min"],
    "run": RUN,
}

#: Shared records that are arrays of records where they appear.
ARRAYS = {"attempt", "impulsive_burn", "plan_burn", "plan_file_burn", "revolution"}

#: lunarcap's own commands with a ``--json`` output; each one's document is its record.
OWN = ("impulsive", "solve", "plan")


#: What a plan file writes where one JSON type is not enough (see
#: :mod:`lunarcap.mission.plan_io`): an ignition offset is minutes or ``"free"``; a target
#: is ``"circular"``, ``"perilune"`` (an ellipse of the plan's perilune given by a period
#: or an apolune beside it) or an ellipse given by both altitudes.
_FREE = {"anyOf": [{"type": "number"}, {"const": "free"}]}
_ALTITUDES = ["perilune_altitude_km", "apolune_altitude_km"]


def _types(kind: str) -> dict:
    """The JSON type of a leaf of ``kind`` (a glossary kind, or one of the plan file's)."""
    if kind == "number or free":
        return dict(_FREE)
    if kind == "starts":
        return {"type": ["array", "null"], "items": _FREE}
    if kind == "target":
        both = {"type": "object", "properties": {k: _leaf(k) for k in _ALTITUDES},
                "required": _ALTITUDES, "additionalProperties": False}
        return {"anyOf": [{"enum": ["circular", "perilune"]}, both]}
    if kind == "string|object":   # a plan's dynamics: a word or a mapping of forces
        return {"type": ["string", "object", "null"]}
    return {"type": [kind, "null"]}


def _leaf(name: str, kind: str | None = None) -> dict:
    q = Q.lookup(name)
    out = _types(kind or q.kind) | {"title": q.header, "description": q.definition}
    if q.unit:
        out["x-unit"] = q.unit
    return out


def _leaf(name: str, kind: str | None = None) -> dict:
    q = Q.lookup(name)
    out = _types(kind or q.kind) | {"title": q.header, "description": q.definition}
    if q.unit:
        out["x-unit"] = q.unit
    return out


def all_records() -> tuple:
    """``(records, arrays)``: :data:`RECORDS` and :data:`ARRAYS` with every study's own.

    ValueError if a study declares a record that is already declared (shared or another
    study's): a record is declared once.
    """
    records, arrays = dict(RECORDS), set(ARRAYS)
    for study in studies().values():
        twice = sorted(set(study.records) & set(records))
        if twice:
            raise ValueError(f"study {study.name!r} declares records already declared: "
                             f"{', '.join(twice)}")
        records |= study.records
        arrays |= set(study.arrays)
    return records, arrays


def record_schema(record: str, records: dict | None = None, arrays=None) -> dict:
    """The schema of one kind of record (its keys from ``records``, default all of them)."""
    if records is None:
        records, arrays = all_records()
    props = {}
    for item in records[record]:
        if isinstance(item, dict):
            (key, sub), = item.items()
            inner = record_schema(sub, records, arrays)
            if sub in arrays:
                props[key] = {"type": "array", "items": inner}
            else:
                props[key] = inner | {"type": ["object", "null"]}
            props[key]["description"] = Q.lookup(key).definition
        elif isinstance(item, tuple):
            props[item[0]] = _leaf(*item)
        else:
            props[item] = _leaf(item)
    return {"type": "object", "properties": props, "additionalProperties": False}


def commands() -> dict:
    """``{command: its document's record}`` of every ``--json`` output with a schema.

    :data:`OWN`, then the registered studies that declare a record named as their command,
    in the registry's order.
    """
    return {**{c: c for c in OWN},
            **{name: name for name, s in studies().items() if name in s.records}}


def __getattr__(name: str):
    """``COMMANDS``: :func:`commands`, read from the registry when asked."""
    if name == "COMMANDS":
        return commands()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def schemas() -> dict:
    """``{command: JSON Schema}`` of every ``--json`` output.

    A study's document sees the shared run record with its own ``run_keys`` added.
    """
    merge_quantities()
    records, arrays = all_records()
    run_keys = {name: s.run_keys for name, s in studies().items()}
    out = {}
    for cmd, rec in commands().items():
        extra = [k for k in run_keys.get(cmd, ()) if k not in RUN]
        s = record_schema(rec, records | {"run": RUN + extra} if extra else records, arrays)
        out[cmd] = {"$schema": DRAFT, "$id": f"lunarcap/schemas/{cmd}.schema.json",
                    "title": f"lunarcap {cmd} --json", **s}
    return out


def path(command: str) -> Path:
    """The stored schema file of ``command``."""
    return HERE / f"{command}.schema.json"


def text(schema: dict) -> str:
    """The stored text of a schema (sorted keys kept in insertion order, 2-space indent)."""
    return json.dumps(schema, indent=2, ensure_ascii=False) + "\n"


def load(command: str) -> dict:
    """The stored schema of ``command``."""
    return json.loads(path(command).read_text(encoding="utf-8"))


def write() -> list:
    """Write every schema file; the paths written."""
    out = []
    for cmd, s in schemas().items():
        path(cmd).write_text(text(s), encoding="utf-8")
        out.append(path(cmd))
    return out
