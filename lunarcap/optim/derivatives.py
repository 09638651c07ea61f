"""Exact derivatives of a collocation NLP, assembled from one node's, in C where it pays.

Every NLP of :mod:`lunarcap.optim.transcription` evaluates the dynamics at each collocation
point through a map of one right-hand side over the points of a phase
(:func:`lunarcap.optim.collocation.collocation_defects`). CasADi's own exact derivatives
differentiate every copy of the right-hand side inside the expanded NLP: 1.5-2.8 s per
shape to build, and a Hessian of the Lagrangian of 588,818 instructions in the SX virtual
machine (the 8x16 LGR-5 full-dynamics shape). Here the chain rule is applied once instead.
With Y = F(Z) the node outputs (each column of a map one node: Y_k = F(z_k)), their inputs
Z affine in the NLP variables w, and the Lagrangian written with the node outputs as free
symbols, L~(w, Y) = sigma f(w) + lambda^T G(w, Y) (G is g with each map call replaced by
its output symbol, so g(w) = G(w, F(Z(w)))),

    dg/dw      = G_w + G_Y J Z_w,
    d2L/dw2    = L~_ww + C + C^T + Z_w^T (H + J^T L~_YY J) Z_w,      C = L~_wY J Z_w,

where J = blockdiag_k dF/dz (z_k) and H = blockdiag_k d2(mu_k^T F)/dz2 (z_k) with
mu = dL~/dY (Z_ww = 0 since Z is affine). The small functions of w and Y (L~'s
derivatives: the target conditions, the unit controls, the linear defect algebra) are
differentiated by CasADi in SX; the node's Jacobian and Hessian, J_k and H_k, are one
function of one node's inputs, differentiated once and mapped over the nodes.

That node function is the part every node repeats, so it is the part compiled: its C
(CasADi's code generator, gcc -O1: 0.5-2 s per right-hand side, once per machine, the
library kept in the NLP store) is never compiled whole, only per node. Measured on the
first burn of ``song2011-150N`` (8x16 LGR-5, full dynamics, 2 cores at load 5, medians of
three ``lunarcap bench --studies`` runs): the NLP builds in 0.2-0.5 s against CasADi's 2-3 s
and loads in 0.1 s; its Hessian takes 0.76 ms of CPU compiled, 4.2 ms in the virtual
machine, 4.0 ms as CasADi's expanded SX; the Jacobian 0.50, 1.7 and 1.2 ms; an IPOPT
iteration 5.7, 11.6 and 8.2 ms (MUMPS and IPOPT's own work are the rest), the same 14
iterations to the same optimum. The all-burns NLPs, whose CasADi derivatives ran
unexpanded (their Hessian 19-124 ms for 1-5 legs), take 6-36 ms in the virtual machine.
Without a compiler (or a store to keep the library in) the node function runs in the
virtual machine: builds stay fast, a single burn's iterations are slower than CasADi's
expanded SX. The two give the same bits (checked on every library loaded), so a result
never depends on whether a compiler was found. The whole NLP is never compiled: its C
took 242 s at -O1, 35 s of CPU at -O0.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
from dataclasses import dataclass

import casadi as ca
import numpy as np

#: gcc flags of a node function's library: -O1 (the 8x16 Hessian 1.2 ms, its node functions
#: compiled in 3.8 s; -O0 2.2 ms in 1.7 s; -O2 1.1 ms in 5.4 s: measured at load ~20).
CFLAGS = ("-O1", "-fPIC", "-shared")

#: Environment variable naming the C compiler (default: ``cc`` or ``gcc`` on the PATH);
#: ``LUNARCAP_CC=none`` keeps every node function in CasADi's virtual machine.
CC_ENV = "LUNARCAP_CC"


def compiler() -> str | None:
    """The C compiler used for node functions, or None (:data:`CC_ENV`, else cc or gcc)."""
    cc = os.environ.get(CC_ENV, "").strip()
    if cc.lower() in ("none", "0", "no", "off"):
        return None
    return shutil.which(cc) if cc else (shutil.which("cc") or shutil.which("gcc"))


def node_calls(g) -> list:
    """The calls in ``g`` (MX) of single-output maps of an SX function, in graph order."""
    probe = ca.Function("probe", ca.symvar(g), [g], {"allow_free": True})
    out = []
    for k in range(probe.n_instructions()):
        if probe.instruction_id(k) != ca.OP_CALL:
            continue
        node = probe.instruction_MX(k)
        fun = node.which_function()
        if fun.class_name() == "Map" and fun.n_out() == 1 and \
                fun.info()["f"].class_name() == "SXFunction":
            out.append(node)
    return out


@dataclass
class _Block:
    """One map of nodes: its inputs, the node derivatives mapped, and dZ/dw."""

    deps: list          # the map's inputs (MX), each (rows, N)
    d_full: ca.Function  # map of (inputs..., mu) -> (J, triu H)
    d_jac: ca.Function   # map of inputs -> J
    zw: ca.MX            # d vec(Z_var) / dw, (nz N, nw)
    n: int               # nodes
    ny: int              # outputs per node
    sp_j: ca.Sparsity    # one node's J
    sp_h: ca.Sparsity    # one node's triu H


#: Node derivative functions made in this process: {(digest of F, variable inputs, compiler):
#: (D, DJ)}.
_NODE_FUNS: dict = {}


def node_functions(base: ca.Function, var: tuple, compile_fn=None) -> tuple:
    """(D, DJ) of one node of ``base``: D(inputs, mu) -> (J, triu H), DJ(inputs) -> J.

    J = dF/dz and H = d2(mu^T F)/dz2 with z the inputs listed in ``var`` (those that depend
    on the NLP's variables). ``compile_fn(Function) -> Function`` (a library of the same
    function) or None for the virtual machine. Made once per process.
    """
    key = (hashlib.sha256(base.serialize().encode()).hexdigest(), var, compile_fn)
    if key not in _NODE_FUNS:
        xin = [ca.SX.sym(f"i{i}", base.size1_in(i), base.size2_in(i))
               for i in range(base.n_in())]
        mu = ca.SX.sym("mu", base.size1_out(0))
        out = base(*xin)
        z = ca.vertcat(*[xin[i] for i in var])
        jac = ca.jacobian(out, z)
        hess = ca.triu(ca.hessian(ca.dot(mu, out), z)[0])
        # common subexpressions of the two merged: 16 % fewer instructions (full dynamics:
        # 6,012 against 7,144), the same operations on the same values
        nz = ca.cse(ca.vertcat(*jac.nonzeros(), *hess.nonzeros()))
        jac = ca.SX(jac.sparsity(), nz[:jac.nnz()])
        hess = ca.SX(hess.sparsity(), nz[jac.nnz():])
        tag = f"{base.name()}_v{''.join(map(str, var))}"
        funs = (ca.Function(f"d_{tag}", xin + [mu], [jac, hess]),
                ca.Function(f"j_{tag}", xin, [jac]))
        if compile_fn is not None:
            funs = tuple(compile_fn(f) for f in funs)
        _NODE_FUNS[key] = funs
    return _NODE_FUNS[key]


def _blocks(w, calls, compile_fn) -> list | None:
    """The node block of each of ``calls`` (None where no input depends on ``w``).

    None if a node input is not affine in ``w``.
    """
    blocks = []
    for call in calls:
        info = call.which_function().info()
        base, n = info["f"], int(info["n"])
        deps = [call.dep(i) for i in range(call.n_dep())]
        var = tuple(i for i, d in enumerate(deps) if ca.depends_on(d, w))
        if not var:
            blocks.append(None)
            continue
        zw = ca.jacobian(ca.vec(ca.vertcat(*[deps[i] for i in var])), w)
        if ca.depends_on(zw, w):
            return None
        d_full, d_jac = node_functions(base, var, compile_fn)
        blocks.append(_Block(deps, d_full.map(n), d_jac.map(n), zw, n, base.size1_out(0),
                             d_full.sparsity_out(0), d_full.sparsity_out(1)))
    return blocks


def _outer_parts(w, p, f, g, calls):
    """L~'s derivatives and G's Jacobians (SX functions of w, p, Y[, sigma, lambda]).

    ``(lagrangian, constraints)``: lagrangian(w, p, Y, sigma, lambda) -> (L~_ww, L~_wY,
    L~_YY, dL~/dY); constraints(w, p, Y) -> (G_w, G_Y). Y is every map output, stacked
    column by column (each map's ``vec``) in the order of ``calls``.
    """
    outs = [c.get_output(0) for c in calls]
    ys = [ca.MX.sym(f"y{k}", o.shape[0], o.shape[1]) for k, o in enumerate(outs)]
    G = ca.graph_substitute(g, outs, ys)
    y_all = ca.vertcat(*[ca.vec(y) for y in ys])
    gm = ca.Function("G", [w, p, y_all], [f, G]).expand()
    ws, ps, yv = (ca.SX.sym(n, v.shape[0]) for n, v in (("w", w), ("p", p), ("y", y_all)))
    sig, lam = ca.SX.sym("sigma"), ca.SX.sym("lam", g.shape[0])
    fs, gs = gm(ws, ps, yv)
    lag = sig * fs + ca.dot(lam, gs)
    l_y = ca.gradient(lag, yv)
    lagrangian = ca.Function("lagrangian_parts", [ws, ps, yv, sig, lam],
                             [ca.hessian(lag, ws)[0], ca.jacobian(l_y, ws).T,
                              ca.jacobian(l_y, yv), l_y])
    constraints = ca.Function("constraint_parts", [ws, ps, yv],
                              [ca.jacobian(gs, ws), ca.jacobian(gs, yv)])
    return lagrangian, constraints, ca.vertcat(*[ca.vec(o) for o in outs])


def exact_derivatives(w, p, f, g, compile_fn=None) -> tuple | None:
    """IPOPT's ``(hess_lag, jac_g)`` of the NLP (w, p, f, g) by the chain rule (see module).

    ``compile_fn``: turns a node function into its compiled library (None: the virtual
    machine). None when the constraints call no map of nodes, a node's inputs are not
    affine in the variables, or what is left of the constraints does not expand to SX:
    CasADi's own derivatives are then the ones to use.
    """
    calls = node_calls(g)
    if not calls:
        return None
    try:
        lagrangian, constraints, y_all = _outer_parts(w, p, f, g, calls)
    except RuntimeError:   # a call that does not expand (an external function)
        return None
    blocks = _blocks(w, calls, compile_fn)
    if blocks is None or not any(blocks):
        return None
    sig, lam = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", g.shape[0])
    l_ww, l_wy, l_yy, l_y = lagrangian(w, p, y_all, sig, lam)
    g_w, g_y = constraints(w, p, y_all)
    hess, jac, bjz_all, offset = l_ww, g_w, [], 0
    for call, b in zip(calls, blocks):
        size = call.get_output(0).numel()
        rows, offset = slice(offset, offset + size), offset + size
        if b is None:   # its nodes depend on parameters only
            bjz_all.append(ca.MX(size, w.shape[0]))
            continue
        sp_j = ca.diagcat(*[b.sp_j] * b.n)
        jn, hn = b.d_full(*b.deps, ca.reshape(l_y[rows], b.ny, b.n))
        bjz = ca.mtimes(ca.MX(sp_j, jn.nz[:]), b.zw)
        jac = jac + ca.mtimes(g_y[:, rows], ca.mtimes(ca.MX(sp_j, b.d_jac(*b.deps).nz[:]), b.zw))
        c = ca.mtimes(l_wy[:, rows], bjz)
        hu = ca.MX(ca.diagcat(*[b.sp_h] * b.n), hn.nz[:])
        hess = hess + c + c.T + ca.mtimes(b.zw.T, ca.mtimes(hu + ca.tril(hu.T, False), b.zw))
        bjz_all.append(bjz)
    if l_yy.nnz():   # node outputs entering nonlinearly (none in lunarcap's NLPs)
        bjz = ca.vertcat(*bjz_all)
        hess = hess + ca.mtimes(bjz.T, ca.mtimes(l_yy, bjz))
    return (ca.Function("nlp_hess_l", [w, p, sig, lam], [ca.triu(hess)],
                        ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"]),
            ca.Function("nlp_jac_g", [w, p], [g, jac], ["x", "p"], ["g", "jac_g_x"]))


# ====================================================================== compiled nodes
class NodeCompiler:
    """Turns node functions into compiled libraries kept in a store (see the module).

    ``store``: where libraries live (:meth:`file` and :meth:`locked` of
    :class:`lunarcap.repro.cache.NLPStore`); ``cc``: the compiler. A library is named by the
    SHA-256 of its C source, the compiler and the flags: built once per machine (one process
    compiles while any other asking for it waits), loaded by every later process. A library
    that cannot be built or loaded, or that does not reproduce the virtual machine's bits at
    a random point, leaves the function in the virtual machine (one line on stderr).
    """

    def __init__(self, store, cc: str):
        self.store, self.cc = store, cc
        self.compiled = 0   # libraries compiled by this process
        self._arcs: dict = {}   # propagators' right-hand sides, by digest

    @property
    def tag(self) -> str:
        """What the NLPs built with this compiler are keyed by (the compiler and flags)."""
        return f"c:{os.path.basename(self.cc)}:{' '.join(CFLAGS)}"

    def __call__(self, fun: ca.Function, opts: dict | None = None) -> ca.Function:
        """The library of ``fun`` (compiled here or loaded), or ``fun`` itself if none.

        ``opts``: options of the loaded function (CasADi's ``external``).
        """
        name = f"lc_{fun.name()}"
        gen = ca.CodeGenerator(name)
        gen.add(fun)
        source = gen.dump()
        key = hashlib.sha256("\0".join([source, self.cc, *CFLAGS, ca.__version__])
                             .encode()).hexdigest()[:32]
        lib = self.store.file(f"node-{key}", ".so")
        try:
            loaded = self._load(fun.name(), source, lib, key, opts)
        except (OSError, RuntimeError):   # a damaged library: compiled again, once
            lib.unlink(missing_ok=True)
            try:
                loaded = self._load(fun.name(), source, lib, key, opts)
            except (OSError, RuntimeError, subprocess.CalledProcessError) as exc:
                _warn(f"node function {fun.name()} not compiled ({_first_line(exc)}); it "
                      f"runs in CasADi's virtual machine")
                return fun
        except subprocess.CalledProcessError as exc:
            _warn(f"node function {fun.name()} not compiled ({_first_line(exc)}); it runs "
                  f"in CasADi's virtual machine")
            return fun
        if not _same_bits(fun, loaded):
            _warn(f"the compiled {fun.name()} ({lib}) differs from CasADi's virtual machine; "
                  f"the virtual machine is used")
            return fun
        return loaded

    def arc(self, dae: dict):
        """A propagator's DAE (x, t, p, ode) as a compiled function, or ``dae`` itself.

        :data:`lunarcap.physics.propagate.ARC_COMPILER`: CVODES (Adams, functional
        iteration) calls only the right-hand side, which compiled runs a 12 h coast in
        full dynamics 2.1x faster (2.8 ms against 5.8 ms of CPU, 618 evaluations, the same
        bits); its derivatives, never asked for, are left to finite differences.
        """
        ins = {"t": dae["t"], "x": dae["x"], "z": ca.SX(0, 1), "p": dae["p"],
               "u": ca.SX(0, 1)}
        outs = {"ode": dae["ode"]}
        fun = ca.Function(f"arc_{len(self._arcs)}", [ins[k] for k in ca.dyn_in()],
                          [outs.get(k, ca.SX(0, 1)) for k in ca.dyn_out()],
                          ca.dyn_in(), ca.dyn_out())
        key = hashlib.sha256(fun.serialize().encode()).hexdigest()
        if key not in self._arcs:
            self._arcs[key] = self(fun, {"enable_fd": True})
        got = self._arcs[key]
        return dae if got is fun else got

    def _load(self, name: str, source: str, lib, key: str, opts=None) -> ca.Function:
        """The library ``lib`` of ``source`` loaded, compiled first if absent (locked)."""
        if not lib.is_file():
            with self.store.locked(f"node-{key}"):
                if not lib.is_file():
                    self._compile(source, lib)
        return ca.external(name, str(lib), opts or {})

    def _compile(self, source: str, lib) -> None:
        """Gcc ``source`` into ``lib`` (written under a temporary name, then moved)."""
        tmp_c = lib.with_name(f".{lib.stem}.{os.getpid()}.c")
        tmp_so = lib.with_name(f".{lib.stem}.{os.getpid()}.so")
        try:
            tmp_c.write_text(source)
            subprocess.run([self.cc, *CFLAGS, str(tmp_c), "-o", str(tmp_so), "-lm"],
                           check=True, capture_output=True, text=True)
            os.replace(tmp_so, lib)
            self.compiled += 1
        finally:
            for t in (tmp_c, tmp_so):
                t.unlink(missing_ok=True)


def _same_bits(a: ca.Function, b: ca.Function) -> bool:
    """Whether two functions give the same outputs, bit for bit, at a random point."""
    rng = np.random.default_rng(2011)
    args = [rng.uniform(0.5, 1.5, a.sparsity_in(i).shape) for i in range(a.n_in())]
    ra, rb = a(*args), b(*args)
    ra, rb = (ra, rb) if isinstance(ra, (list, tuple)) else ([ra], [rb])
    return all(np.array_equal(np.asarray(x.nonzeros()), np.asarray(y.nonzeros()),
                              equal_nan=True)
               for x, y in zip(ra, rb))


def _first_line(exc) -> str:
    text = getattr(exc, "stderr", None) or str(exc)
    return (text.strip().splitlines() or [type(exc).__name__])[0][:200]


def _warn(msg: str) -> None:
    print(f"lunarcap: {msg}", file=sys.__stderr__ or sys.stderr, flush=True)
