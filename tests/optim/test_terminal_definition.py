"""One terminal-condition definition: the single-burn NLP, the all-burns NLP and the
verification evaluate the same function on the same state.

The NLPs' constraint functions are evaluated at a point whose final coast state is a
chosen state; the rows of the target kinds must equal, to round-off, what
:meth:`lunarcap.mission.targets.Target.conditions` gives for that state (in lunar units,
as the NLP sees it) and what the verification's :meth:`Target.errors` reports (in km).
"""

import numpy as np
import pytest

from lunarcap.mission.targets import CIRCULAR, PERILUNE, Target
from lunarcap.optim.collocation import LU, Mesh
from lunarcap.optim.joint import build_joint_nlp
from lunarcap.optim.nlp import build_burn_nlp
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mee_from_coe

MESH = Mesh(2, 3, 3)
RP = C.R_MOON + 100.0


def _state_km(kind):
    """A state near (not on) the target: r_p 40 m high, i 90.01 deg, 0.3 deg past apse."""
    e = 0.62 if kind == PERILUNE else 0.002
    a = (RP + 0.04) / (1 - e)
    mee = mee_from_coe(a, e, np.radians(90.01), 0.4, 1.1, np.radians(0.3))
    return np.array([*mee, 500.0])


def _point(layout, prefix, x_scaled):
    """An NLP point whose every state is x_scaled (so the last coast state is x_scaled)."""
    w = np.zeros(layout.nv)
    for name, (rows, cols) in layout.var_shapes.items():
        if not name.startswith(prefix):
            continue
        part = name[len(prefix):]
        if part in ("Xb", "Xc", "X0"):
            layout.put(w, name, np.tile(x_scaled[:, None], cols))
        elif part == "Ub":
            layout.put(w, name, np.tile([[0.0], [-1.0], [0.0]], cols))
        elif part == "t1":
            layout.put(w, name, 0.5)
    return w


def _rows(g, layout, prefix, names):
    return np.array([g[layout.rows(prefix + n)][0] for n in names])


@pytest.mark.parametrize("kind", [PERILUNE, CIRCULAR])
def test_single_nlp_joint_nlp_and_verification_share_the_target_function(kind):
    target = Target(kind, RP, 90.0)
    x_km = _state_km(kind)
    scale = np.array([LU, 1, 1, 1, 1, 1, 500.0])
    xs = x_km / scale
    names = target.equality_names + target.inequality_names
    prm = Model(mode="two-body", thrust_N=100.0, isp_s=300.0).params()
    expected = np.array(sum(target.conditions(xs[:6], target.values(LU)), []))

    # the single-burn NLP
    single = build_burn_nlp(MESH, kind, False, "optimal", "two-body").compiled
    lay = single.layout
    p = lay.params(x_start=x_km, t_ref=0.0, t_end=3600.0, dynamics=prm,
                   mesh_burn=np.linspace(0, 1, MESH.n_burn + 1),
                   mesh_coast=np.linspace(0, 1, MESH.n_coast + 1), target=target.values(LU))
    g1 = np.asarray(single.g(_point(lay, "", xs), p)).ravel()
    np.testing.assert_allclose(_rows(g1, lay, "", names), expected, rtol=1e-12, atol=1e-15)

    # the all-burns NLP: the same target on the last of two legs
    joint = build_joint_nlp(MESH, (PERILUNE, kind), "two-body").compiled
    lay = joint.layout
    params = {"x_start": x_km, "t_ref": [0.0, 3600.0, 7200.0]}
    for k in (0, 1):
        params.update({f"leg{k}.dynamics": prm,
                       f"leg{k}.mesh_burn": np.linspace(0, 1, MESH.n_burn + 1),
                       f"leg{k}.mesh_coast": np.linspace(0, 1, MESH.n_coast + 1),
                       f"leg{k}.target": target.values(LU)})
    w = _point(lay, "leg0.", xs) + _point(lay, "leg1.", xs)
    g2 = np.asarray(joint.g(w, lay.params(**params))).ravel()
    np.testing.assert_allclose(_rows(g2, lay, "leg1.", names), expected, rtol=1e-12,
                               atol=1e-15)

    # the verification: Target.errors on the state in km; its residuals are the same
    # function in km (lengths scale by LU, the rest is dimensionless)
    res = target.errors(x_km[:6])["residuals"]
    length = {"rp", "p"}
    got = np.array([res[n] / (LU if n in length else 1.0) for n in names])
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-15)
    # and the state is genuinely off target, so the comparison is not of zeros
    assert np.all(np.abs(expected[:2]) > 1e-7)
