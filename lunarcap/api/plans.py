"""Plans in code: load one (a file, a packaged name, a mapping) and change its fields.

A plan is a :class:`~lunarcap.mission.plan.CapturePlan`: immutable, validated whenever it
is built or changed, every error naming the field as a plan file would
(``arrival.mass_kg: ...``). :func:`load_plan` reads one and applies the changes a user
asks for in one call, in the order the command line applies its options (engine, arrival,
dynamics, ephemeris, pole, ignitions; then targets, formulation, name), so a plan changed
here and one changed by ``lunarcap plan PLAN --thrust ... --mass ...`` are the same plan.
Each change is also a method of the plan (``with_engine``, ``with_mass``,
``with_dynamics``, ``with_targets``, ``with_starts``, ``with_lunar_pole``) for one field.
"""

from __future__ import annotations

import os
from dataclasses import replace
from pathlib import Path

from lunarcap.errors import InputError, number
from lunarcap.mission.plan import CapturePlan, available_plans
from lunarcap.mission.plan import load_plan as _read_plan
from lunarcap.mission.plan import paper_plan as _paper_plan


def load_plan(source, *, thrust_N=None, isp_s=None, mass_kg=None, hemisphere=None,
              dynamics=None, ephemeris=None, lunar_pole=None, starts=None, targets=None,
              formulation=None, name=None) -> CapturePlan:
    """A capture plan from a file, a packaged name, a mapping or a plan, with changes.

    Parameters
    ----------
    source : str, path, dict or CapturePlan
        A plan file (YAML), the name of a packaged plan (``available()["plans"]``), a
        mapping with a plan file's keys, or a plan (then only changed).
    thrust_N, isp_s : float, optional
        The engine's thrust (N) and specific impulse (s); the plan keeps its name.
    mass_kg : float, optional
        Mass at the arrival perilune, kg.
    hemisphere : {"north", "south"}, optional
        Lunar hemisphere of the arrival perilune.
    dynamics : str, dict or ForceModel, optional
        ``"full"``, ``"j2"``, ``"two-body"``, or a plan file's ``dynamics`` mapping
        (``{"gravity": "LP165P", "degree": 8}``: the registered force terms' keys).
    ephemeris : path, optional
        An SPK file (.bsp) instead of the plan's (default DE405).
    lunar_pole : {"iau2009-j2000", "iau-constant", "of-date"}, optional
        The pole fixing the plan's M-MME2000 frame.
    starts : sequence, optional
        Every burn's ignition, min from its nominal perilune (negative: before), or
        ``"free"`` (optimised).
    targets : sequence, optional
        Every burn's target as in a plan file (:meth:`CapturePlan.with_targets`), None
        keeping one.
    formulation : {"orbit", "song2011"}, optional
        How a period is met: the orbit as asked, or the paper's fixed timeline (Eq. 17).
    name : str, optional
        The plan's new name.

    Returns
    -------
    CapturePlan

    Raises
    ------
    lunarcap.PlanError
        A file that cannot be read, or a value the plan refuses: the message names the
        file and the field (an InputError, whose exit status is 2 on the command line).

    Examples
    --------
    >>> import lunarcap
    >>> plan = lunarcap.load_plan("two-burn-8h", thrust_N=440, isp_s=321, mass_kg=900,
    ...                           dynamics="two-body")
    >>> plan.name, plan.engine.thrust_N, plan.arrival.mass_kg, plan.dynamics
    ('two-burn-8h', 440.0, 900.0, 'two-body')
    >>> lunarcap.load_plan(plan, targets=[{"target_period_h": 6}, None]).burns[0].describe()
    'ellipse, 6 h'
    >>> lunarcap.load_plan("two-burn-8h", mass_kg=-5)
    Traceback (most recent call last):
    ...
    lunarcap.mission.plan_checks.PlanError: arrival.mass_kg: must be positive (kg), got -5
    """
    plan = _source(source)
    if thrust_N is not None or isp_s is not None:
        plan = plan.with_engine(
            plan.engine.thrust_N if thrust_N is None else number("engine.thrust_N", thrust_N,
                                                                 "N"),
            plan.engine.isp_s if isp_s is None else number("engine.isp_s", isp_s, "s"),
            name=plan.name)
    arrival = plan.arrival
    if mass_kg is not None:
        arrival = replace(arrival, mass_kg=mass_kg)
    if hemisphere is not None:
        arrival = replace(arrival, hemisphere=hemisphere)
    if arrival != plan.arrival:
        plan = replace(plan, arrival=arrival)
    if dynamics is not None:
        plan = plan.with_dynamics(dynamics)
    if ephemeris is not None:
        plan = replace(plan, ephemeris=str(Path(ephemeris).expanduser().resolve()))
    if lunar_pole is not None:
        plan = plan.with_lunar_pole(lunar_pole)
    if starts is not None:
        plan = plan.with_starts(starts)
    if targets is not None:
        plan = plan.with_targets(targets)
    if formulation is not None and formulation != plan.formulation:
        plan = replace(plan, formulation=formulation)
    if name is not None:
        plan = replace(plan, name=name)
    return plan


def _source(source) -> CapturePlan:
    """The plan ``source`` names (see :func:`load_plan`)."""
    if isinstance(source, CapturePlan):
        return source
    if isinstance(source, dict):
        return CapturePlan.from_dict(source)
    if isinstance(source, (str, os.PathLike)):
        return _read_plan(source)
    raise InputError(f"plan: a file, a packaged plan ({', '.join(available_plans())}), a "
                     f"mapping or a CapturePlan, got {type(source).__name__}")


def paper_plan(thrust_N: float = 150.0, isp_s: float = 200.0, starts=None,
               dynamics: str = "full") -> CapturePlan:
    """Song et al. (2011)'s capture (their Section 3.2.1) with any engine.

    For the paper's engines (150 N / 200 s, 300 N / 250 s, 450 N / 300 s) the packaged plan
    with the ignitions of its Table B1; for another engine the 150 N plan with that engine
    and every ignition free. ``starts`` (min from perilune, or "free") replaces them;
    ``dynamics``: ``"full"`` (the paper's), ``"j2"`` or ``"two-body"``.

    Examples
    --------
    >>> import lunarcap
    >>> p = lunarcap.paper_plan(300, 250)
    >>> p.name, [b.start_min for b in p.burns]
    ('song2011-300N', [-4.0, -3.0, -2.0])
    >>> lunarcap.paper_plan(200, 230).burns[0].start_min
    'free'
    """
    return _paper_plan(thrust_N, isp_s, starts=starts, dynamics=dynamics)


def available() -> dict:
    """What lunarcap offers by name, from its registries.

    ``plans``: the packaged plans; ``studies``: the registered studies
    (:data:`lunarcap.studies.registry.STUDIES`, the names :func:`lunarcap.run_study`
    takes); ``export_formats``: the registered writers
    (:data:`lunarcap.capture.writers.WRITERS`, the names
    :meth:`lunarcap.CaptureResult.export` takes); ``dynamics``: the preset words and the
    keys of a ``dynamics`` mapping (the registered force terms',
    :data:`lunarcap.physics.forces.TERMS`).

    Examples
    --------
    >>> import lunarcap
    >>> a = lunarcap.available()
    >>> a["studies"], a["export_formats"][:2], a["dynamics"]["presets"]
    (['study', 'burns', 'missed', 'dispersions'], ['oem', 'spk'], ['full', 'j2', 'two-body'])
    >>> "two-burn-8h" in a["plans"], "degree" in a["dynamics"]["keys"]
    (True, True)
    """
    from lunarcap.capture.writers import WRITERS
    from lunarcap.physics.forces import PRESETS, plan_keys
    from lunarcap.studies.registry import studies

    return {"plans": available_plans(), "studies": list(studies()),
            "export_formats": list(WRITERS),
            "dynamics": {"presets": list(PRESETS), "keys": list(plan_keys())}}
