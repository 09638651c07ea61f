"""Missed thrust and late ignition on generated plans, not the paper's (two-body, no cache).

From a seeded family of generated plans (lunarcap.studies.families: 2-5 burns, 100-600 N,
400-2,000 kg, 20-170 deg) the first plan of each kind of final orbit and formulation: the
paper's (Eq. 17 targets, ending on a circle), orbits as asked ending on a circle, orbits
as asked ending on an ellipse. Burn 1 is cut off after 0.25, 0.5, 0.9 and 1.0 of its
duration with 0 and 30 min to clear the fault, and ignited 1 and 5 min late; the last
burn (whose target is the final orbit) is cut off at its end, and half-way with 0 and 30
min to clear the fault.

* Every case is answered: recovered and verified, or "no recovery" with its reason.
* A recovery has the nominal's freedoms: its penalty is >= -0.05 m/s. A make-up at the
  next perilune (a cut-off of the last burn after a delay: the final orbit passes only
  through radii between its perilune and apolune) splits the burn over two perilunes,
  which the nominal does not; it still cannot beat the two-body impulses (finite burns
  lose).
* A full burn (fraction 1, 0 min) costs nothing (< 0.05 m/s): the make-up vanishes. Of
  the last burn, whose target is the final orbit, nothing is left to re-plan (the
  recovery has no burn).
* A late ignition: the recovered burn ignites the given minutes after the nominal's.
* The last burn cut off half-way with no delay is resumed at once at no cost.

tools/missed_family.py runs a bigger family (and full dynamics) outside the tests.
"""

import pytest

from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.repro.cache import caching
from lunarcap.studies.families import plan_family
from lunarcap.studies.missed.cases import case_result
from lunarcap.studies.missed.nominal import DEFAULT_MAX_PERIOD_H, nominal_of

pytestmark = pytest.mark.slow

CUT_OFFS = [(f, d) for f in (0.25, 0.5, 0.9, 1.0) for d in (0.0, 30.0)]
LATE_MIN = (1.0, 5.0)
LAST_BURN_CUT_OFFS = [(1.0, 0.0), (0.5, 0.0), (0.5, 30.0)]
MAX_PERIOD_S = DEFAULT_MAX_PERIOD_H * 3600.0


def _kind(plan):
    return (plan.formulation, plan.targets[-1].kind)


@pytest.fixture(scope="module")
def plans():
    """The first plan of each (formulation, final orbit) of the seeded family."""
    family, _ = plan_family(seed=24, count=8, mass_kg=(400, 2000),
                            formulations=("orbit", "song2011"))
    firsts = {}
    for p in family:
        firsts.setdefault(_kind(p), p)
    assert set(firsts) == {("song2011", "circular"), ("orbit", "circular"),
                           ("orbit", "ellipse")}
    return list(firsts.values())


@pytest.fixture(scope="module")
def nominals(plans):
    """{(plan name, burn): nominal} of burn 1 and the last burn of each plan, solved once."""
    with caching(False):
        return {(p.name, burn): nominal_of(p, burn, MAX_PERIOD_S)
                for p in plans for burn in (1, p.n_burns)}


@pytest.fixture(scope="module")
def cases(plans, nominals):
    """{(plan name, burn, fraction, delay, late): row} of every case, computed once."""
    out = {}
    with caching(False):
        for p in plans:
            first, last = nominals[(p.name, 1)], nominals[(p.name, p.n_burns)]
            for f, d in CUT_OFFS:
                out[(p.name, 1, f, d, None)] = case_result(p, 1, f, d, nominal=first)
            for m in LATE_MIN:
                out[(p.name, 1, None, 0.0, m)] = case_result(p, 1, late_min=m, nominal=first)
            for f, d in LAST_BURN_CUT_OFFS:
                out[(p.name, p.n_burns, f, d, None)] = case_result(p, p.n_burns, f, d,
                                                                   nominal=last)
    return out


def test_every_case_is_recovered_and_verified_or_refused_with_a_reason(cases):
    for key, r in cases.items():
        assert r["status"] in ("recovered", "no recovery"), (key, r["status"], r["reason"])
        if r["status"] == "recovered":
            assert r["all_verified"], key
        else:
            assert r["reason"], key


def test_no_recovery_beats_the_nominal_with_its_freedoms(plans, cases, nominals):
    by_name = {p.name: p for p in plans}
    for (name, burn, f, d, late), r in cases.items():
        if r["status"] != "recovered":
            continue
        if not r["reason"].startswith("make-up burn at"):   # not in the window
            assert r["penalty_mps"] >= -0.05, (name, burn, f, d, late, r["penalty_mps"])
            continue
        # two burns where the nominal had one: not below the two-body impulses from the
        # orbit before the burn to the final orbit (tangential at perilune)
        nplan = nominals[(by_name[name].name, burn)]["plan"]
        impulses = sum(b.delta_v_mps for b in nplan.impulsive()[burn - 1:])
        assert r["total_delta_v_mps"] >= impulses - 0.05, (name, burn, f, d)


def test_a_full_burn_costs_nothing_and_leaves_nothing_to_make_up(plans, cases):
    for p in plans:
        for burn in (1, p.n_burns):
            r = cases[(p.name, burn, 1.0, 0.0, None)]
            assert r["status"] == "recovered", (p.name, burn, r["reason"])
            assert abs(r["penalty_mps"]) < 0.05, (p.name, burn, r["penalty_mps"])
            assert r["make_up_delta_v_mps"] < 0.05, (p.name, burn)
        # the last burn's target is the final orbit: no burn is left to fly
        assert cases[(p.name, p.n_burns, 1.0, 0.0, None)]["recovery_burns"] == [], p.name


def test_a_late_ignition_ignites_that_many_minutes_after_the_nominal(plans, cases, nominals):
    for p in plans:
        t_nominal = nominals[(p.name, 1)]["legs"][0].problem.t_ign_s
        for m in LATE_MIN:
            r = cases[(p.name, 1, None, 0.0, m)]
            assert r["status"] == "recovered", (p.name, m, r["reason"])
            t_ign = seconds_from_calendar(r["recovery_burns"][0]["ignition_epoch"])
            assert t_ign - t_nominal == pytest.approx(60.0 * m, abs=2e-3), (p.name, m)



def test_the_last_burn_cut_off_half_way_with_no_delay_resumes_at_no_cost(plans, cases):
    # the make-up flies the rest of the nominal burn at once: the next perilune is tried
    # only for a window's make-up dearer than the burn itself (not for a few m/s that
    # splitting the burn over two perilunes would save)
    for p in plans:
        r = cases[(p.name, p.n_burns, 0.5, 0.0, None)]
        assert r["status"] == "recovered" and not r["reason"], (p.name, r["reason"])
        assert abs(r["penalty_mps"]) < 0.05, (p.name, r["penalty_mps"])


#: Long faults: burn 1 cut off late in the burn, 12 h to clear the fault (as the book's
#: 0.9 / 720 min case).
LONG_FAULTS = ((0.75, 720.0), (0.9, 720.0))
#: What may decide a case without recovery: the bound on the make-up orbit, the deadline,
#: an orbit that does not come back, the Moon's sphere of influence.
DECIDERS = ("--max-period-h", "--max-days", "open orbit", "sphere of influence")


@pytest.fixture(scope="module")
def long_faults(plans, nominals):
    """{(plan name, fraction, delay): row} of the long faults, computed once."""
    with caching(False):
        return {(p.name, f, d): case_result(p, 1, f, d, nominal=nominals[(p.name, 1)])
                for p in plans for f, d in LONG_FAULTS}


def test_a_long_fault_waits_for_a_perilune_or_names_what_decides_it(long_faults):
    """Every long fault is recovered and verified within the 3 days, or refused with a
    reason naming what decides each place (before issue 37 a captured spacecraft whose
    window the bound refused was "no recovery" although its next perilune was within
    reach). A make-up that waited ignites about the perilune of the orbit the cut-off
    left: 12 h of fault plus the wait is that orbit's period, give or take the window
    about the perilune (at most 1 h each way) and the burn flown before the cut-off."""
    waited = 0
    for key, r in long_faults.items():
        assert r["status"] in ("recovered", "no recovery"), (key, r["status"], r["reason"])
        if r["status"] == "no recovery":
            assert any(d in r["reason"] for d in DECIDERS), (key, r["reason"])
            continue
        assert r["all_verified"] and r["time_to_final_orbit_h"] <= 72.0, key
        if r["reason"].startswith("make-up burn at the next perilune"):
            waited += 1
            wait_h = r["recovery_burns"][0]["ignition_min_after_fault"] / 60.0
            assert abs(wait_h + key[2] / 60.0 - r["cutoff_period_h"]) < 1.5, (key, wait_h)
    assert waited, "no long fault waited for a perilune"


def test_the_seed_24_family_is_drawn_again_as_the_histories_name_it():
    """The case histories in these tests' docstrings name plans of the seed-24 family
    (``plan_family(24, 12, mass_kg=(400, 2000), formulations=("orbit", "song2011"))``):
    drawn again anywhere (tests, tools/missed_family.py), family-k must be the same plan.
    Its engines, masses and burns as those histories give them; plan 9 is refused at load."""
    family, refused = plan_family(24, 12, mass_kg=(400, 2000),
                                  formulations=("orbit", "song2011"))
    by_name = {p.name: p for p in family}
    assert len(family) == 11 and len(refused) == 1 and "family-9" not in by_name
    drawn = {name: (p.engine.thrust_N, p.arrival.mass_kg, p.n_burns, p.formulation)
             for name, p in by_name.items()}
    assert drawn["family-0"] == (537.0, 538.0, 3, "song2011")
    assert drawn["family-2"] == (141.0, 1145.0, 4, "song2011")
    assert drawn["family-3"] == (194.0, 744.0, 3, "orbit")
    assert drawn["family-4"] == (201.0, 1685.0, 2, "song2011")
    assert drawn["family-5"] == (444.0, 802.0, 4, "orbit")
    assert drawn["family-11"] == (239.0, 1453.0, 4, "orbit")
    # the last target of the song2011 plans is a circle, as the paper's formulation needs
    assert all(p.targets[-1].kind == "circular" for p in family if p.formulation == "song2011")
