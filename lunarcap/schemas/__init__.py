"""JSON Schemas of the command line's ``--json`` outputs, generated from the glossary.

One schema per command (``lunarcap/schemas/<command>.schema.json``, package data). Each
record lists its keys (:data:`RECORDS`); the type, unit and description of every key come
from :mod:`lunarcap.quantities`, so a key that is not in the glossary cannot be written
here, and a record with a key not listed fails validation (``additionalProperties``
false). :func:`schemas` builds them; :func:`write` stores them (``python -m
lunarcap.schemas``); the tests check that the stored files are the generated ones and that
real outputs validate.

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

HERE = Path(__file__).resolve().parent
DRAFT = "https://json-schema.org/draft/2020-12/schema"

#: The keys of each kind of record (object) of the outputs; a nested record is named by
#: ``{"key": "record"}`` instead of a key.
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
                     "position_km", "velocity_kmps", "opm", "b_r_km", "b_t_km"],
    "plan_engine": ["thrust_N", "isp_s"],
    "plan_file_burn": [("target", "target"), "target_period_h", "target_apolune_altitude_km",
                       "coast_min", ("start_min", "number or free"), "steering",
                       "start_bounds_min"],
    "plan_start": ["epoch", "mee", "mass_kg", "first_coast_min"],
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
    "run": ["study", "started_utc", "wall_s", "cluster_start_s", "scheduler", "workers",
            ("cases", "integer"), "computed", "reused", "failed_computed", "interrupted",
            "table", "cache", "code_version", "host", "cpu_count", "load_avg_1min_start",
            "load_avg_1min_end", "counts", "grid", "burn", "fractions", "delays_min",
            ("late_min", "array"), "max_period_h", "max_days", "seed", ("samples", "integer"),
            ("error_model", "string")],
    "missed": [{"plan": "plan_file"}, "burn", "max_period_h", "table", {"run": "run"},
               {"cases": "missed_case"}],
    "missed_case": ["plan", "plan_id", "thrust_N", "isp_s", "dynamics", "burn", "contingency",
                    "fraction", "delay_min", "late_min", "max_period_h", "status", "reason",
                    "captured", "cutoff_orbit", "cutoff_epoch", "cutoff_min_after_ignition",
                    "nominal_burn_duration_min", "partial_delta_v_mps",
                    "nominal_burn_delta_v_mps", "cutoff_energy_km2ps2", "cutoff_e",
                    "cutoff_rp_km", "cutoff_ra_km", "cutoff_period_h", "cutoff_soi_radius_km",
                    "recovery_start_e", "recovery_delta_v_mps", "total_delta_v_mps",
                    "nominal_remaining_delta_v_mps", "penalty_mps", "make_up_delta_v_mps",
                    "make_up_estimate_mps", "make_up_period_h", "nominal_period_after_burn_h",
                    "first_coast_h", "make_up_estimate_h", "time_to_final_orbit_h",
                    "nominal_time_to_final_orbit_h", "all_verified", "ipopt_status",
                    "task_wall_s", "worker", "code_version", "completed_utc", "error",
                    {"recovery_burns": "recovery_burn"}],
    "recovery_burn": ["burn", "target_orbit", "ignition_epoch", "ignition_min_after_fault",
                      "burn_duration_min", "delta_v_mps", "verified"],
    "dispersions": [{"plan": "plan_file"}, {"error_model": "error_model"}, "seed", "table",
                    {"run": "run"}, {"summary": "dispersions_summary"},
                    {"samples": "dispersions_sample"}],
    "error_model": ["thrust_sigma_pct", "isp_sigma_pct", "pointing_sigma_deg",
                    "ignition_sigma_s", "arrival_sigma_km", "arrival_sigma_mps", "arrival_cov",
                    "knowledge_sigma_km", "knowledge_sigma_mps", "knowledge_cov",
                    "gates_magnitude_pct", "gates_magnitude_mps", "gates_pointing_deg",
                    "gates_pointing_mps", "bplane_cov", "description"],
    "dispersions_summary": [
        ("samples", "integer"), "captured_and_corrected", "nominal_delta_v_mps",
        "nominal_propellant_kg", *[f"{q}_p{p}_{u}" for p in (50, 90, 95, 99)
                                   for q, u in (("delta_v", "mps"), ("propellant", "kg"))],
        *[f"{k}_p{p}{u}" for p in (50, 90, 95, 99)
          for k, u in (("delta_v", "_ci_mps"), ("samples_needed", ""))],
        "mean_above_nominal_mps", "mean_above_nominal_se_mps",
        "budget_p99_above_nominal_mps", "budget_p99_ci_mps", "budget_p99_ci_ranks",
        "ci_level", "p_not_captured", "p_not_captured_upper95", "p_correction_failed",
        "p_correction_failed_upper95", {"failures": "failed_sample"},
        *[f"final_{s}_{e}" for e in ("rp_error_km", "ra_error_km", "inc_error_deg")
          for s in ("rms", "max_abs")]],
    "failed_sample": ["sample", "status", "reason"],
    "dispersions_sample": ["plan", "plan_id", "thrust_N", "isp_s", "dynamics", "seed",
                           "sample", "antithetic", "thrust_sigma_pct", "isp_sigma_pct",
                           "pointing_sigma_deg", "ignition_sigma_s", "arrival_sigma_km",
                           "arrival_sigma_mps", "arrival_cov", "status", "reason",
                           "burns_flown", "total_delta_v_mps", "propellant_kg",
                           "nominal_delta_v_mps", "nominal_propellant_kg",
                           "delta_v_above_nominal_mps", "final_rp_error_km",
                           "final_ra_error_km", "final_inc_error_deg", "final_rp_altitude_km",
                           "final_ra_altitude_km", "arrival_dr_km", "arrival_dv_mps",
                           "task_wall_s", "task_cpu_s", "worker", "code_version",
                           "completed_utc", "error", "knowledge_sigma_km",
                           "knowledge_sigma_mps", "knowledge_cov", "gates_magnitude_pct",
                           "gates_magnitude_mps", "gates_pointing_deg", "gates_pointing_mps",
                           "bplane_cov", "arrival_db_km", "arrival_dt_s",
                           {"burns": "dispersed_burn"}],
    "dispersed_burn": ["burn", "delta_v_mps", "planned_delta_v_mps", "ignition_min",
                       "duration_min", "thrust_error_pct", "isp_error_pct",
                       "pointing_error_deg", "ignition_error_s", "knowledge_dr_km",
                       "knowledge_dv_mps"],
}

#: Records that are arrays of records where they appear.
ARRAYS = {"attempt", "impulsive_burn", "plan_burn", "plan_file_burn", "burns_count",
          "burns_count_burn",
          "missed_case", "recovery_burn", "dispersions_sample", "dispersed_burn",
          "failed_sample", "revolution"}


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


def record_schema(record: str) -> dict:
    """The schema of one kind of record (its keys from :data:`RECORDS`)."""
    props = {}
    for item in RECORDS[record]:
        if isinstance(item, dict):
            (key, sub), = item.items()
            inner = record_schema(sub)
            if sub in ARRAYS:
                props[key] = {"type": "array", "items": inner}
            else:
                props[key] = inner | {"type": ["object", "null"]}
            props[key]["description"] = Q.lookup(key).definition
        elif isinstance(item, tuple):
            props[item[0]] = _leaf(*item)
        else:
            props[item] = _leaf(item)
    return {"type": "object", "properties": props, "additionalProperties": False}


#: The commands with a ``--json`` output and their top-level record.
COMMANDS = {"impulsive": "impulsive", "solve": "solve", "plan": "plan", "burns": "burns",
            "missed": "missed", "dispersions": "dispersions"}


def schemas() -> dict:
    """``{command: JSON Schema}`` of every ``--json`` output."""
    out = {}
    for cmd, rec in COMMANDS.items():
        s = record_schema(rec)
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
