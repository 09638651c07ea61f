"""The NLPs' derivatives assembled node by node equal CasADi's AD of the expanded NLP.

Two formulations of the same exact derivatives: :mod:`lunarcap.optim.derivatives` (the chain
rule through the node outputs, one node's Jacobian and Hessian mapped over the nodes) and
CasADi's symbolic differentiation of the whole NLP expanded to SX (what every NLP used
before). They must agree to rounding at random points (variables, parameters, multipliers)
for every kind of leg the transcription writes: fixed and free ignition, free perilune
epoch, closed-form steering laws, outer corrections, every dynamics, and the all-burns NLP
with free coasts and period rows. The node function compiled to C must give the virtual
machine's bits.
"""

import casadi as ca
import numpy as np
import pytest

from lunarcap.mission.scenario import paper_scenario
from lunarcap.optim import derivatives as D
from lunarcap.optim.collocation import Mesh
from lunarcap.optim.correction import nlp_forces
from lunarcap.optim.joint import build_joint_nlp
from lunarcap.optim.nlp import build_burn_nlp, clear_nlps
from lunarcap.physics.dynamics import Model, fit_for
from lunarcap.physics.ephemeris import default_ephemeris
from lunarcap.physics.epochs import seconds_from_calendar
from lunarcap.physics.forces import force_model

MESH = Mesh(2, 3, 3)
T_ARRIVAL_S = seconds_from_calendar(paper_scenario().epoch_tdb)
FIELD = {"gravity": "LP165P", "degree": 8, "order": 8}


def _reference(solver: ca.Function):
    """CasADi's own (hess triu, jac_g) of a solver's NLP, from its expanded oracle."""
    oracle = solver.oracle().expand()
    x = ca.SX.sym("x", oracle.size1_in(0))
    p = ca.SX.sym("p", oracle.size1_in(1))
    sig, lam = ca.SX.sym("s"), ca.SX.sym("l", oracle.size1_out(1))
    f, g = oracle(x, p)
    hess = ca.triu(ca.hessian(sig * f + ca.dot(lam, g), x)[0])
    return (ca.Function("h", [x, p, sig, lam], [hess]),
            ca.Function("j", [x, p], [ca.jacobian(g, x)]))


def _point(lay, mode, rng):
    """Random variables about a scaled lunar orbit; the model's parameters; multipliers.

    The variables: p 1-2 LU, f, g, h, k within 0.3, L 0-2 rad, mass 0.8-1, times 0.2-1.2 TU;
    the dynamics parameters those of a 300 N, 300 s engine in ``mode`` over the paper's
    capture; the other parameters (accelerations, targets) of order one.
    """
    w = rng.uniform(0.2, 1.2, lay.nv)
    for name in lay.var_slices:
        if name.endswith(("Xb", "Xc", "X0")):
            x = lay.get(w, name)
            x[0] = rng.uniform(1.0, 2.0, x.shape[1])
            x[1:5] = rng.uniform(-0.3, 0.3, (4, x.shape[1]))
            x[5] = rng.uniform(0.0, 2.0, x.shape[1])
            x[6] = rng.uniform(0.8, 1.0, x.shape[1])
            lay.put(w, name, x)
    p = rng.uniform(0.5, 1.5, lay.np_) * 1e-3
    t0 = T_ARRIVAL_S
    model = Model(mode, 300.0, 300.0, fit_for(mode, default_ephemeris(), t0 - 6 * 3600.0,
                                                t0 + 24 * 3600.0))
    for name, sl in lay.par_slices.items():
        if name.endswith("x_start"):
            p[sl] = [3000.0, 0.1, 0.05, 0.1, -0.05, 1.0, 500.0]
        elif name.endswith(("mesh_burn", "mesh_coast")):
            p[sl] = np.linspace(0.0, 1.0, sl.stop - sl.start)
        elif name.endswith("dynamics"):
            p[sl] = model.params()
        elif name.endswith(("t_ref", "t_end")):
            p[sl] = t0 + 3600.0 * np.arange(sl.stop - sl.start)
    return w, p, rng.standard_normal(lay.ng)


def _agree(compiled, mode, seed=0):
    """Compare the solver's derivatives with the reference at one random point."""
    rng = np.random.default_rng(seed)
    w, p, lam = _point(compiled.layout, mode, rng)
    h_ref, j_ref = _reference(compiled.solver)
    s = compiled.solver
    h = s.get_function("nlp_hess_l")(w, p, 0.7, lam)
    _, j = s.get_function("nlp_jac_g")(w, p)
    for got, ref in ((h, h_ref(w, p, 0.7, lam)), (j, j_ref(w, p))):
        got, ref = np.array(ca.densify(got)), np.array(ca.densify(ref))
        scale = np.abs(ref).max()
        assert np.isfinite(ref).all() and scale > 0
        np.testing.assert_allclose(got, ref, rtol=0, atol=1e-12 * scale)


@pytest.mark.parametrize("shape", [
    ("perilune", False, "optimal", "full", False, False),
    ("circular", False, "optimal", "full", False, False),
    ("perilune", True, "optimal", "full", True, False),     # free ignition and perilune
    ("perilune", False, "inertial", "j2", False, False),
    ("circular", True, "antivelocity", "two-body", False, False),
    ("perilune", True, "optimal", "field", False, True),    # a field's NLP with corrections
])
def test_node_derivatives_equal_casadis(shape):
    kind, free, steering, mode, free_end, corr = shape
    if mode == "field":
        mode = nlp_forces(FIELD)
    nlp = build_burn_nlp(MESH, kind, free, steering, mode, free_end, corr)
    assert nlp.compiled.derivatives != "CasADi's"
    _agree(nlp.compiled, mode)


def test_joint_derivatives_equal_casadis():
    # three legs, the middle one's coast free, with the period rows
    nlp = build_joint_nlp(MESH, ("perilune", "perilune", "circular"), "full",
                          (False, True, False), True)
    assert nlp.compiled.derivatives != "CasADi's"
    _agree(nlp.compiled, "full", seed=3)


def test_compiled_node_functions_give_the_virtual_machines_bits(tmp_path):
    """The same solver's Hessian with the node function in C and in the VM: equal bits."""
    from lunarcap.repro.cache import NLPStore

    cc = D.compiler()
    if cc is None:
        pytest.skip("no C compiler")
    comp = D.NodeCompiler(NLPStore(tmp_path), cc)
    base = force_model("full")
    from lunarcap.physics.dynamics import rhs_function

    f = rhs_function(base, True)
    vm = D.node_functions(f, (0, 1, 2))
    c = D.node_functions(f, (0, 1, 2), comp)
    assert comp.compiled == 2 and all(fun.class_name() == "External" for fun in c)
    rng = np.random.default_rng(7)
    for _ in range(5):
        args = [rng.uniform(0.5, 1.5, vm[0].sparsity_in(i).shape) for i in range(5)]
        args[0][0] *= 3000.0
        for a, b in zip(vm[0](*args), c[0](*args)):
            assert np.array_equal(np.asarray(a.nonzeros()), np.asarray(b.nonzeros()))
    clear_nlps()


def test_compiled_propagators_give_the_virtual_machines_bits(tmp_path, paper_arrival):
    """CVODES with each arc's right-hand side compiled (the store's ARC_COMPILER) flies a
    burn (constant direction, delta-V quadrature, outputs at given epochs) and a dense
    half-day coast in full dynamics to the same bits as with CasADi's virtual machine."""
    from lunarcap.physics import propagate as prop
    from lunarcap.repro.cache import NLPStore

    cc = D.compiler()
    if cc is None:
        pytest.skip("no C compiler")
    t0 = T_ARRIVAL_S
    x0 = np.asarray(paper_arrival.state, float)
    model = Model("full", 300.0, 300.0, fit_for("full", default_ephemeris(), t0 - 6 * 3600.0,
                                                 t0 + 24 * 3600.0))

    def fly():
        prop._integrator.cache_clear()
        burn = prop.propagate(model, t0, x0, t0 + 600.0, u=np.array([0.0, -1.0, 0.0]),
                              delta_v=True, t_eval=t0 + np.linspace(60.0, 600.0, 10))
        coast = prop.propagate(model, t0 + 600.0, burn.x[:7, -1], t0 + 12 * 3600.0,
                               dense=True)
        return burn.x, coast.x, coast(t0 + 3 * 3600.0)

    old = prop.ARC_COMPILER
    try:
        prop.ARC_COMPILER = None
        vm = fly()
        comp = D.NodeCompiler(NLPStore(tmp_path), cc)
        prop.ARC_COMPILER = comp.arc
        compiled = fly()
    finally:
        prop.ARC_COMPILER = old
        prop._integrator.cache_clear()
    assert comp.compiled == 2   # the burn's and the coast's right-hand sides
    assert vm[0][6, -1] < x0[6] and vm[0][7, -1] > 0.05   # a real burn: mass, delta-V
    for a, b in zip(vm, compiled):
        assert np.array_equal(a, b)
