"""Every notebook computes its result through lunarcap's public API (issue 38, item 2).

A notebook is a worked example: a reader copies its cells into their own session and runs
their own plan, so the cells may import only :mod:`lunarcap` and the names of its
``__all__`` (``lunarcap.load_plan``, ``lunarcap.missed``, ...). What only formats the book
(glue, captions, provenance, checks) stays in the page module, and a notebook may use a page
module for exactly the display helpers named in :data:`DISPLAY_HELPERS`.

The notebooks not converted yet are listed in :data:`NOT_CONVERTED`, each with why: the
list may only shrink (a listed notebook that no longer breaks the rule fails the test until
it is removed from the list), and any other notebook that reaches inside the package fails.
Fast: the notebooks are parsed (:mod:`ast`), not run.
"""

from __future__ import annotations

import ast
import importlib
import json
from pathlib import Path

import pytest

import lunarcap

NOTEBOOKS = Path(__file__).resolve().parents[2] / "notebooks"

#: The public API: ``import lunarcap`` and the names of its ``__all__``.
PUBLIC = frozenset(lunarcap.__all__)

#: The book's display helpers: a page module a converted notebook may import, and the only
#: names it may use from it. Each takes what the public API computed and formats the page
#: (``build``: the page's tables, figures, glued values, captions, provenance and checks
#: from the study's result) or names where the book keeps a study's table (``table_file``:
#: the study's ``out``, so the book resumes its own table; ``export_dir``: where the book
#: keeps the files it links to), or what the page sets beside what (``beside_paper``: the
#: plans it compares with the paper's capture; ``engine_rows``: its engines and their
#: labels, cited first; ``paper_engines``: the paper's engines it solves beside a grid).
DISPLAY_HELPERS = {
    "lunarcap.report.pages.missed_thrust": frozenset({"build", "table_file"}),
    "lunarcap.report.pages.burn_count": frozenset({"build", "table_file"}),
    "lunarcap.report.pages.exchange": frozenset({"build", "export_dir"}),
    "lunarcap.report.pages.gmat_flight": frozenset({"build", "export_dir"}),
    "lunarcap.report.pages.capture_plan": frozenset({"build", "beside_paper"}),
    "lunarcap.report.pages.kplo_capture": frozenset({"build", "table_file", "export_dir"}),
    "lunarcap.report.pages.other_engines": frozenset({"build", "engine_rows"}),
    "lunarcap.report.pages.dispersions": frozenset({"build", "table_file"}),
    "lunarcap.report.pages.free_ignition": frozenset({"build", "grid_starts",
                                                      "best_grid_starts"}),
    # the ignition sweep's page shapes the burns the notebook solved (lunarcap.solve_burn
    # per offset) like the paper's Tables 1-5, beside the paper's rows
    "lunarcap.report.pages.sweep": frozenset({"build"}),
    # the capture sequence's page draws the paper's Figs. 2-5 from the capture the notebook
    # solved (lunarcap.solve) and its Fig. 2 (CaptureResult.plot)
    "lunarcap.report.pages.capture_sequence": frozenset({"build"}),
    # the steering laws' page sets the burns the notebook solved with each law
    # (lunarcap.solve_burn(..., steering=...)) beside the optimal steering's
    "lunarcap.report.pages.steering_laws": frozenset({"build"}),
    # the impulsive baseline's page sets the chain the notebook computed
    # (CapturePlan.impulsive) beside the paper's printed values (build; eq19_masses: the
    # masses the paper prints for its finite-burn chain, which its Eq. (19) used)
    "lunarcap.report.pages.impulsive_baseline": frozenset({"build", "eq19_masses"}),
    # the tutorial's page opens (provenance) and closes (glued numbers, checks) around the
    # reader's own calls, which are public
    "lunarcap.report.pages.tutorial": frozenset({"start", "finish"}),
    # the joint optimum (lunarcap.solve_joint) beside the one-at-a-time chain
    # (lunarcap.solve), per engine, set side by side by the page
    "lunarcap.report.pages.joint_capture": frozenset({"build"}),
    # the study (lunarcap.engine_trade) and the paper's engines it sets beside the grid
    # (paper_engines: Table B1's engines of the grid's Isps), each solved with
    # lunarcap.solve, a SolveError kept and shown by build as a failed row
    "lunarcap.report.pages.trade_study": frozenset({"build", "paper_engines"}),
    # the published captures' page sets the free-ignition chains the notebook solved
    # (lunarcap.solve of lunarcap.paper_plan, one per engine) beside the missions' figures,
    # our delta-Vs flown at the missions' masses (Eq. 19) and KPLO's design
    "lunarcap.report.pages.real_missions": frozenset({"build"}),
    # the lunar pole's page tabulates both poles and sets the chains the notebook solved
    # with each (lunarcap.solve of lunarcap.load_plan(lunarcap.paper_plan(...),
    # lunar_pole=...)) side by side (paper_engines: the paper's engines it compares)
    "lunarcap.report.pages.lunar_pole": frozenset({"build", "paper_engines"}),
    # the real Moon's page sets out what the notebook computed: the J2 design and its
    # re-design in the field (lunarcap.solve, lunarcap.load_plan(..., dynamics=field(n))),
    # the design flown open loop (CaptureResult.fly_open_loop) and its final orbit flown
    # for days (CaptureResult.fly_final_orbit) in each field (field: the plan dynamics of
    # LP165P cut to a degree, with the Earth and the Sun)
    "lunarcap.report.pages.real_moon": frozenset({"build", "field"}),
    # the verification page tabulates the residuals each burn the notebook solved carries
    # (lunarcap.solve_burn of lunarcap.paper_plan per case: paper_case's cached solves) and
    # the impulsive limits of each engine's chain (lunarcap.solve), beside the gates
    # (cases_of: the paper's 37 cases of Tables 1-5, or the list given); build also runs
    # the mesh-convergence study, which no public call offers (meshes other than the solver's)
    "lunarcap.report.pages.verification": frozenset({"build", "cases_of"}),
    # the summary page sets the best chains the notebook solved (lunarcap.solve of
    # lunarcap.paper_plan, one per engine, with the impulsive limits) beside Table B1 and
    # the totals the paper prints
    "lunarcap.report.pages.summary": frozenset({"build"}),
    # the reproduction report sets the solves the notebook made (lunarcap.solve_burn of
    # lunarcap.paper_plan at each ignition the paper prints, paper_starts: Tables 1-5's
    # offsets; lunarcap.solve of lunarcap.paper_plan for paper_engines: the paper's three
    # engines, whose chains its prose quotes) beside every printed number, and the audit
    "lunarcap.report.pages.reproduction_report": frozenset({"build", "paper_starts",
                                                           "paper_engines"}),
}

#: Notebooks whose computation still goes through an internal module, and why. Shrink it.
NOT_CONVERTED = {
    "fig1_geometry": "a figure of constants: the RTN frame and Eq. (14)'s angles of an "
                     "illustrative thrust direction on the paper's first ellipse (12.235 h, "
                     "lunarcap.paper_plan's burn 1 target); no plan is solved, and the "
                     "frame and angles are no public call",
    "findings": "reads the other pages' glued numbers: a book page, nothing to compute",
    "glossary": "renders the glossary: a book page, nothing to compute",
}


def _code_cells(path: Path) -> list[str]:
    """The sources of a notebook's code cells."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    return ["".join(c["source"]) for c in nb["cells"] if c["cell_type"] == "code"]


def _helpers_of(module: str) -> frozenset | None:
    """The display helpers a notebook may use from ``module`` (None: none; not a helper)."""
    return DISPLAY_HELPERS.get(module)


def _imports(tree: ast.AST, aliases: dict) -> list[str]:
    """The imports of one cell that leave the public API; fills ``aliases`` (name -> allowed).

    ``aliases[name]`` is :data:`PUBLIC` for ``lunarcap`` itself, a page's display helpers
    for a page module imported as a display helper.
    """
    bad = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name == "lunarcap":
                    aliases[a.asname or "lunarcap"] = PUBLIC
                elif a.name.startswith("lunarcap."):
                    if _helpers_of(a.name) is not None and a.asname:
                        aliases[a.asname] = _helpers_of(a.name)
                    else:
                        bad.append(f"line {node.lineno}: import {a.name}")
        elif isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "lunarcap":
            for a in node.names:
                whole = f"{node.module}.{a.name}"
                if node.module == "lunarcap" and a.name in PUBLIC:
                    continue
                if _helpers_of(whole) is not None:
                    aliases[a.asname or a.name] = _helpers_of(whole)
                elif a.name in (_helpers_of(node.module) or ()):
                    continue
                else:
                    bad.append(f"line {node.lineno}: from {node.module} import {a.name}")
    return bad


def _dynamic_imports(tree: ast.AST) -> list[str]:
    """``importlib.import_module("lunarcap.x")`` or ``__import__("lunarcap.x")``."""
    bad = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and node.args \
                and isinstance(node.args[0], ast.Constant) \
                and isinstance(node.args[0].value, str) \
                and node.args[0].value.startswith("lunarcap."):
            f = node.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            if name in ("import_module", "__import__"):
                bad.append(f"line {node.lineno}: {name}({node.args[0].value!r})")
    return bad


def _uses(tree: ast.AST, aliases: dict) -> list[str]:
    """Attributes of ``lunarcap`` outside ``__all__``, and a page module's non-helpers."""
    bad, as_value = [], set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                and node.value.id in aliases:
            as_value.add(id(node.value))
            if node.attr not in aliases[node.value.id]:
                bad.append(f"line {node.lineno}: {node.value.id}.{node.attr}")
    for node in ast.walk(tree):   # a page module passed around is a way round the list
        if isinstance(node, ast.Name) and aliases.get(node.id) not in (None, PUBLIC) \
                and id(node) not in as_value and isinstance(node.ctx, ast.Load):
            bad.append(f"line {node.lineno}: {node.id} used other than for its helpers")
    return bad


def violations(cells: list[str]) -> list[str]:
    """Where a notebook's cells leave the public API (empty: a worked example).

    The cells are read in order, as a kernel runs them: a name imported in one cell is
    known in the next.
    """
    aliases, bad = {}, []
    for i, src in enumerate(cells):
        tree = ast.parse(src)
        found = _imports(tree, aliases) + _dynamic_imports(tree) + _uses(tree, aliases)
        bad += [f"code cell {i}, {b}" for b in found]
    return bad


ALL = sorted(p.stem for p in NOTEBOOKS.glob("*.ipynb"))


@pytest.mark.parametrize("name", [n for n in ALL if n not in NOT_CONVERTED])
def test_a_converted_notebook_computes_through_the_public_api(name):
    bad = violations(_code_cells(NOTEBOOKS / f"{name}.ipynb"))
    assert not bad, (f"notebooks/{name}.ipynb reaches inside lunarcap (use the public API, "
                     f"lunarcap.__all__, or a display helper of DISPLAY_HELPERS): "
                     + "; ".join(bad))


@pytest.mark.parametrize("name", sorted(NOT_CONVERTED))
def test_the_list_of_notebooks_not_converted_only_shrinks(name):
    path = NOTEBOOKS / f"{name}.ipynb"
    assert path.exists(), f"{name}: no such notebook; remove it from NOT_CONVERTED"
    assert violations(_code_cells(path)), (f"notebooks/{name}.ipynb now computes through the "
                                           f"public API: remove it from NOT_CONVERTED")


def test_every_display_helper_exists():
    for module, names in DISPLAY_HELPERS.items():
        mod = importlib.import_module(module)
        for n in names:
            assert callable(getattr(mod, n, None)), f"{module}.{n}: not a function"
    assert PUBLIC >= {"load_plan", "missed", "burns"}


@pytest.mark.parametrize("src, caught", [
    ("import lunarcap\np = lunarcap.load_plan('x')\nr = lunarcap.missed(p)", None),
    ("from lunarcap import solve, load_plan", None),
    ("from lunarcap.report.pages import missed_thrust as book\nbook.build(1, 2, 3)", None),
    ("from lunarcap.mission.plan import load_plan", "from lunarcap.mission.plan import"),
    ("import lunarcap.studies.missed.cases as m", "import lunarcap.studies.missed.cases"),
    ("import lunarcap\nlunarcap.api.capture.solve(1)", "lunarcap.api"),
    ("from lunarcap import _MODULE", "from lunarcap import _MODULE"),
    ("from lunarcap.report.pages import findings", "from lunarcap.report.pages import"),
    ("from lunarcap.report.pages import missed_thrust as b\nb.missed.run_missed()", "b.missed"),
    ("from lunarcap.report.pages import burn_count as b\nf = b\nf.draw", "b used other"),
    ("import importlib\nimportlib.import_module('lunarcap.mission.plan')", "import_module"),
])
def test_the_checker_names_what_leaves_the_public_api(src, caught):
    bad = violations([src])
    if caught is None:
        assert bad == []
    else:
        assert bad and caught in bad[0], bad


def public_calls(cells: list[str]) -> list[str]:
    """The public API calls of a notebook's cells (``lunarcap.<name>(...)`` or a name
    imported from ``lunarcap``), in order: a worked example computes through them."""
    names, calls = set(), []
    for src in cells:
        tree = ast.parse(src)
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names |= {a.asname or a.name for a in node.names if a.name == "lunarcap"}
            elif isinstance(node, ast.ImportFrom) and node.module == "lunarcap":
                names |= {a.asname or a.name for a in node.names if a.name in PUBLIC}
        for node in ast.walk(tree):
            f = node.func if isinstance(node, ast.Call) else None
            if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) \
                    and f.value.id in names and f.attr in PUBLIC:
                calls.append(f.attr)
            elif isinstance(f, ast.Name) and f.id in names and f.id in PUBLIC:
                calls.append(f.id)
    return calls


@pytest.mark.parametrize("name", [n for n in ALL if n not in NOT_CONVERTED])
def test_a_converted_notebook_makes_its_own_public_calls(name):
    """A notebook that hands its parameters to a display helper, which then computes,
    keeps clear of internal imports yet is no worked example: each converted notebook
    calls the public API itself (the page then only formats what it was given)."""
    calls = public_calls(_code_cells(NOTEBOOKS / f"{name}.ipynb"))
    assert calls, (f"notebooks/{name}.ipynb makes no call of lunarcap's public API: its "
                   f"result is computed out of the reader's sight")
