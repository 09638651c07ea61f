"""Song 2011's scenario and engines, read from the packaged plans (their one source).

The packaged plans ``song2011-150N``, ``song2011-300N`` and ``song2011-450N``
(:data:`PAPER_PLANS`, in :data:`PLAN_DIR`) are the paper's capture (Song, Park, Kim, Lee &
Sim 2011, J. Astron. Space Sci. 28(3) 203-216, Sec. 3.1-3.2): the arrival (epoch,
perilune altitude, inclination, mass, the impulsive LOI 1 that sets v_inf), the capture
orbits' periods and the three engines. Everything else in lunarcap that needs one of
these reads it here, so editing a plan file changes it everywhere (the paper's printed
numbers, compared against ours, stay in :mod:`lunarcap.paper.printed`).

The files are read raw (a plain YAML mapping, no plan validation: that is
:meth:`lunarcap.mission.plan.CapturePlan.from_dict`'s), once per process. The three plans
must agree on the scenario; a disagreement raises ValueError naming the field.

Examples
--------
>>> paper_engines()
{150.0: 200.0, 300.0: 250.0, 450.0: 300.0}
>>> paper_engine_pairs()[0]
(150.0, 200.0)
>>> paper_scenario().mass_kg
524.895
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

#: The packaged plans' folder.
PLAN_DIR = Path(__file__).resolve().parent / "plans"

#: The packaged plans of the paper's capture, one per engine.
PAPER_PLANS = ("song2011-150N", "song2011-300N", "song2011-450N")

#: Scenario fields of a plan's ``arrival`` section (every paper plan gives each).
_ARRIVAL_FIELDS = ("epoch", "perilune_altitude_km", "inclination_deg", "impulsive_loi1_mps",
                   "hemisphere", "mass_kg")


@dataclass(frozen=True)
class PaperScenario:
    """The paper's capture, as its packaged plans give it (units in the names)."""

    #: Epoch of the first perilune, TDB (Sec. 3.2.1).
    epoch_tdb: str
    #: Target altitude of every capture orbit's perilune, km (Sec. 1 and 3.2.1).
    perilune_altitude_km: float
    #: Inclination of the arrival hyperbola and the capture orbits, deg (M-MME2000).
    inclination_deg: float
    #: The two-body impulsive LOI 1 the hyperbolic excess speed is derived from, m/s.
    impulsive_loi1_mps: float
    #: Hemisphere of the arrival's approach (not printed in the paper).
    hemisphere: str
    #: Spacecraft mass at the first perilune, kg (Sec. 3.2.1).
    mass_kg: float
    #: Periods of the capture orbits after LOI 1, 2 and 3, s (Sec. 3.1; the last is the
    #: final coast, 117.848 min).
    capture_periods_s: tuple

    @property
    def loi_count(self) -> int:
        """Number of burns of the capture (one per capture orbit)."""
        return len(self.capture_periods_s)


@lru_cache(maxsize=None)
def _raw(name: str) -> dict:
    import yaml

    return yaml.safe_load((PLAN_DIR / f"{name}.yaml").read_text(encoding="utf-8"))


def _periods_s(plan: dict, name: str) -> tuple:
    out = []
    for n, b in enumerate(plan["burns"], 1):
        if "target_period_h" in b:
            out.append(float(b["target_period_h"]) * 3600.0)
        elif "coast_min" in b:
            out.append(float(b["coast_min"]) * 60.0)
        else:
            raise ValueError(f"packaged plan {name}: burn {n} gives neither target_period_h "
                             f"nor coast_min (the capture orbit's period)")
    return tuple(out)


@lru_cache(maxsize=1)
def paper_engines() -> dict:
    """The paper's engines, thrust N -> Isp s, in the order of :data:`PAPER_PLANS`."""
    return {float(_raw(n)["engine"]["thrust_N"]): float(_raw(n)["engine"]["isp_s"])
            for n in PAPER_PLANS}


def paper_engine_pairs() -> tuple:
    """The paper's engines as ((thrust N, Isp s), ...): the default of the book's pages."""
    return tuple(paper_engines().items())


def paper_plan_name(thrust_N: float, isp_s: float) -> str | None:
    """The packaged plan of the paper's engine (thrust N, Isp s), or None for another."""
    for name in PAPER_PLANS:
        e = _raw(name)["engine"]
        if (float(e["thrust_N"]), float(e["isp_s"])) == (float(thrust_N), float(isp_s)):
            return name
    return None


@lru_cache(maxsize=1)
def paper_scenario() -> PaperScenario:
    """The paper's scenario from its packaged plans (ValueError if they disagree)."""
    first = _raw(PAPER_PLANS[0])
    for name in PAPER_PLANS[1:]:
        other = _raw(name)
        for f in _ARRIVAL_FIELDS:
            if other["arrival"][f] != first["arrival"][f]:
                raise ValueError(f"packaged plans {PAPER_PLANS[0]} and {name} disagree on "
                                 f"arrival.{f}: {first['arrival'][f]!r} vs "
                                 f"{other['arrival'][f]!r}")
        if _periods_s(other, name) != _periods_s(first, PAPER_PLANS[0]):
            raise ValueError(f"packaged plans {PAPER_PLANS[0]} and {name} disagree on the "
                             f"capture orbits' periods")
    a = first["arrival"]
    return PaperScenario(
        epoch_tdb=str(a["epoch"]), perilune_altitude_km=float(a["perilune_altitude_km"]),
        inclination_deg=float(a["inclination_deg"]),
        impulsive_loi1_mps=float(a["impulsive_loi1_mps"]), hemisphere=str(a["hemisphere"]),
        mass_kg=float(a["mass_kg"]), capture_periods_s=_periods_s(first, PAPER_PLANS[0]))
