"""A force term added from outside lunarcap: one file and one registration call.

The toy term below (a constant acceleration along the transverse axis, its magnitude the
plan key ``transverse_kmps2`` in km/s^2) is written into a temporary folder put on
``sys.path``, imported (which registers it), and then has to reach, without another file
changed: a plan's ``dynamics`` mapping (read, checked, written back), the model's label,
the parameter vector and the right-hand side (numpy and CasADi), a propagation, the solve
of ``lunarcap plan``, and the GMAT exporter, which refuses it by name.

The physics is checked against Gauss's variational equation of the semi-major axis,
da/dt = 2 a^2 / h (e sin(nu) a_r + p / r a_t) (Vallado 2013, Eq. 9-24), a relation the
MEE equations do not contain as such.
"""

import importlib
import json
import sys
import textwrap

import numpy as np
import pytest
import yaml

from lunarcap.errors import InputError
from lunarcap.exchange import gmat
from lunarcap.mission.plan import load_plan
from lunarcap.physics import constants as C
from lunarcap.physics import dynamics as dyn
from lunarcap.physics import elements as el
from lunarcap.physics.forces import TERMS, force_model, from_mapping, register
from lunarcap.physics.propagate import propagate

MU = C.MU_MOON
KEY = "transverse_kmps2"
#: The toy's magnitude, km/s^2: 1e-7 moves a 100 km orbit's semi-major axis by 1.6 km a turn.
A_T = 1e-7

TOY = textwrap.dedent(f'''
    """A toy force: a constant acceleration along the transverse axis, km/s^2."""
    from lunarcap.errors import InputError
    from lunarcap.physics.forces import Term, register

    KEY = "{KEY}"


    class Transverse(Term):
        name = "transverse"
        keys = (KEY,)
        params = (KEY,)

        def read(self, d, gravity, base_dir=None):
            if KEY not in d:
                return {{}}
            a = d[KEY]
            if isinstance(a, bool) or not isinstance(a, (int, float)):
                raise InputError(f"dynamics.{{KEY}}: a number of km/s^2, got {{a!r}}")
            return {{KEY: float(a)}}

        def acts(self, forces):
            return forces.setting(KEY) is not None

        def rtn(self, at):
            return (0.0, at.prm_of(KEY), 0.0)

        def values(self, forces, model):
            return {{KEY: forces.setting(KEY)}}

        def words(self, forces):
            return f"transverse {{forces.setting(KEY):g}} km/s^2"

        def to_plan(self, forces):
            a = forces.setting(KEY)
            return {{}} if a is None else {{KEY: a}}


    register(Transverse())
''')


@pytest.fixture
def toy(tmp_path, monkeypatch):
    """The toy term's module, imported from a temporary folder (TERMS restored after)."""
    (tmp_path / "toy_transverse.py").write_text(TOY)
    monkeypatch.syspath_prepend(str(tmp_path))
    saved = dict(TERMS)
    try:
        yield importlib.import_module("toy_transverse")
    finally:
        TERMS.clear()
        TERMS.update(saved)
        sys.modules.pop("toy_transverse", None)


def _toy_plan(tmp_path, a_t: float = A_T):
    """The 450 N paper plan in two burns, two-body plus the toy, as a YAML file."""
    d = load_plan("song2011-450N").to_dict()
    d.update(name="toy-transverse", dynamics={"gravity": "point", "third_bodies": [],
                                              KEY: a_t},
             burns=[{"target_period_h": 8.0, "start_min": "free"},
                    {"target": "circular", "start_min": "free"}])
    f = tmp_path / "toy.yaml"
    f.write_text(yaml.safe_dump(d, sort_keys=False))
    return f


def _da_dt_from_rates(x, xdot):
    """da/dt from the MEE rates: a = p / (1 - f^2 - g^2)."""
    p, f, g = x[:3]
    w = 1.0 - f * f - g * g
    return xdot[0] / w + p * 2.0 * (f * xdot[1] + g * xdot[2]) / w ** 2


def test_toy_term_reaches_the_plan_and_its_label(toy, tmp_path):
    plan = load_plan(_toy_plan(tmp_path))
    forces = plan.dynamics
    assert [t.name for t in forces.terms] == ["point", "transverse"]
    assert forces.label == "point mass, transverse 1e-07 km/s^2"
    assert forces.perturbed and not forces.needs_fit
    assert forces.layout == {"mu": 0, "thrust_kN": 1, "vex_mps": 2, KEY: 3}
    # written back as read, and the same model again
    back = plan.to_dict()["dynamics"]
    assert back == {"gravity": "point", "third_bodies": [], KEY: A_T}
    assert from_mapping(back) == forces and force_model(back).key == forces.key
    # another magnitude is another model (compiled functions are keyed by it)
    assert from_mapping({**back, KEY: 2 * A_T}).key != forces.key
    # its key's errors name the key; without the module the key is unknown
    with pytest.raises(InputError, match=f"dynamics.{KEY}: a number of km/s"):
        from_mapping({"gravity": "point", KEY: "fast"})
    TERMS.pop("transverse")
    with pytest.raises(InputError, match=f"dynamics.{KEY}: unknown key"):
        from_mapping(back)


def test_a_second_term_of_a_name_is_refused(toy):
    with pytest.raises(InputError, match="'transverse': a term needs a name of its own"):
        register(toy.Transverse())


def test_toy_rates_are_gauss_semi_major_axis_equation(toy):
    forces = from_mapping({"gravity": "point", "third_bodies": [], KEY: A_T})
    toy_model, kepler = dyn.Model(forces, thrust_N=0.0), dyn.Model("two-body", thrust_N=0.0)
    f_toy, f_kep = dyn.rhs_function(forces), dyn.rhs_function("two-body")
    rng = np.random.default_rng(35)
    for _ in range(20):
        a, e = rng.uniform(1800.0, 6000.0), rng.uniform(0.0, 0.8)
        coe = (a, e, rng.uniform(0.1, 3.0), *rng.uniform(-3, 3, 3))
        x = np.array([*el.mee_from_coe(*coe), 500.0])
        got = np.asarray(f_toy(x, [0, 0, 0], 0.0, toy_model.params())).ravel()
        # the same rates through numpy (the generic operations)
        np.testing.assert_allclose(dyn.mee_rates(x, [0, 0, 0], 0.0, toy_model.params(), forces),
                                   got, rtol=1e-14, atol=1e-18)
        p, nu = a * (1 - e * e), coe[5]
        r = p / (1 + e * np.cos(nu))
        gauss = 2 * a * a / np.sqrt(MU * p) * (p / r) * A_T
        assert _da_dt_from_rates(x, got) == pytest.approx(gauss, rel=1e-10)
        # the toy adds to the Kepler rates nothing but its own
        kep = np.asarray(f_kep(x, [0, 0, 0], 0.0, kepler.params())).ravel()
        assert _da_dt_from_rates(x, kep) == pytest.approx(0.0, abs=1e-12 * abs(gauss))


def test_toy_propagates_the_orbit_gauss_raises(toy):
    # a 100 km circle, one revolution: da/dt = 2 sqrt(a^3 / mu) a_t on a circle, so
    # a^(-1/2) falls linearly, by a_t t / sqrt(mu) (the orbit stays circular to 1e-4)
    forces = from_mapping({"gravity": "point", "third_bodies": [], KEY: A_T})
    a0 = C.R_MOON + 100.0
    x0 = np.array([*el.mee_from_coe(a0, 0.0, 1.5, 0.3, 0.0, 0.0), 500.0])
    t1 = float(el.period_from_semi_major_axis(a0, MU))
    traj = propagate(dyn.Model(forces, thrust_N=0.0), 0.0, x0, t1)
    p, f, g = traj.x[:3, -1]
    a1 = p / (1 - f * f - g * g)
    expect = (a0 ** -0.5 - A_T * t1 / np.sqrt(MU)) ** -2
    assert a1 - a0 == pytest.approx(expect - a0, rel=1e-3)
    assert a1 - a0 > 1.5   # km: the toy's effect, not rounding


@pytest.mark.slow
def test_lunarcap_plan_solves_in_two_body_plus_toy(toy, tmp_path, capsys):
    from lunarcap import cli

    assert cli.main(["plan", str(_toy_plan(tmp_path)), "--json", "--no-cache", "--quiet",
                     "--no-impulsive"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["complete"] and len(d["burns"]) == 2
    for b in d["burns"]:   # re-flown in the toy's dynamics, the targets are met
        assert b["verification_passed"], b
        assert b["dynamics"] == "point mass, transverse 1e-07 km/s^2"


def test_gmat_export_refuses_the_toy_by_name(toy):
    from lunarcap.capture.export import gmat_gravity

    model = dyn.Model(from_mapping({"gravity": "point", "third_bodies": [], KEY: A_T}))
    with pytest.raises(InputError, match=r"force term 'transverse' \(transverse 1e-07 km/s"
                                         r"\^2\) has no GMAT counterpart"):
        gmat.capture_forces(model, "iau2009-j2000")
    with pytest.raises(InputError, match="'transverse'"):
        gmat_gravity(model, "iau2009-j2000")
    # the same model without the toy exports
    grav, third = gmat.capture_forces(dyn.Model(from_mapping({"gravity": "point",
                                                              "third_bodies": []})),
                                      "iau2009-j2000")
    assert grav.degree == 2 and grav.c[2, 0] == 0.0 and third == ()
