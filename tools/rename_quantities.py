#!/usr/bin/env python3
"""Rename reported quantities (CSV columns, JSON keys) to the names of lunarcap.quantities.

Re-runnable and idempotent: run it after merging a branch that still writes an old name::

    python tools/rename_quantities.py          # rewrite the files, print what changed
    python tools/rename_quantities.py --check  # exit 1 if anything would change

It edits ``lunarcap/``, ``notebooks/``, ``tests/`` and ``book/*.md`` in three passes, each
a regular expression applied to whole files:

1. :data:`CONTEXT`: a name whose meaning depends on what surrounds it (``loss_mps`` of
   Robbins' estimate inside the trade study, which otherwise means the objective loss);
2. :data:`PER_FILE`: a name whose meaning depends on the module (``loss_mps`` is delta-V
   minus our impulsive limit in ``runs/chain.py``, minus the paper's printed impulse in
   ``runs/sweeps.py``, the objective loss in ``runs/study.py``);
3. :data:`GLOBAL`: a name with one meaning everywhere, renamed on word boundaries.

A context rule that finds nothing is listed at the end (already applied, or the code
around it changed: look at it). Names of the glossary never contain an old name on a word
boundary, so a second run changes nothing.
"""

from __future__ import annotations

import argparse
import fnmatch
import io
import re
import sys
import tokenize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCOPE = ("lunarcap/**/*.py", "lunarcap/**/*.yaml", "notebooks/*.ipynb", "tests/**/*.py",
         "book/*.md")
SKIP = ("lunarcap/quantities.py", "tests/test_glossary.py", "tests/test_json_schemas.py")

# ------------------------------------------------------------------ the meanings of "loss"
#: delta-V minus the impulsive limit in the same dynamics
DV_LOSS = {"loss_mps": "delta_v_loss_mps", "loss_percent": "delta_v_loss_percent",
           "total_loss_mps": "total_delta_v_loss_mps",
           "total_loss_percent": "total_delta_v_loss_percent",
           "impulsive_delta_v_mps": "impulsive_limit_mps",
           "total_impulsive_delta_v_mps": "total_impulsive_limit_mps"}
#: delta-V minus the paper's printed impulse; "model" is our impulsive limit
VS_PAPER = {"loss_mps": "loss_vs_paper_impulse_mps",
            "loss_percent": "loss_vs_paper_impulse_percent",
            "total_loss_mps": "total_loss_vs_paper_impulse_mps",
            "total_loss_percent": "total_loss_vs_paper_impulse_percent",
            "model_loss_mps": "delta_v_loss_mps", "model_loss_percent": "delta_v_loss_percent",
            "total_model_loss_mps": "total_delta_v_loss_mps",
            "total_model_loss_percent": "total_delta_v_loss_percent",
            "model_impulsive_delta_v_mps": "impulsive_limit_mps",
            "total_model_impulsive_delta_v_mps": "total_impulsive_limit_mps"}
#: the trade study's loss: by the objective of Eq. (9)
OBJECTIVE = {"loss_mps": "objective_loss_mps", "loss_percent": "objective_loss_percent",
             "loss_mps_sequence": "objective_loss_mps_sequence",
             "loss_percent_sequence": "objective_loss_percent_sequence",
             "loss_percent_loi1": "objective_loss_percent_loi1",
             "loss_percent_loi2": "objective_loss_percent_loi2",
             "loss_percent_loi3": "objective_loss_percent_loi3",
             "impulsive_delta_v_mps": "impulsive_limit_mps"}

#: Pass 2: ``{file glob: {old: new}}`` (the first matching glob of a file wins). A glob
#: ``summary*.py`` also covers the modules a page is split into (``summary_tables.py``,
#: ``summary/notes.py``): a split module keeps the meaning of the module it came from.
PER_FILE = {
    "lunarcap/runs/chain*.py": DV_LOSS, "lunarcap/cli*.py": DV_LOSS,
    "lunarcap/runs/burns*.py": DV_LOSS, "lunarcap/report/pages/capture_plan*.py": DV_LOSS,
    "lunarcap/report/pages/burn_count*.py": DV_LOSS, "tests/test_cli_plan*.py": DV_LOSS,
    "tests/report/pages/test_capture_plan*.py": DV_LOSS, "tests/runs/test_burns*.py": DV_LOSS,
    "tests/report/pages/test_studies_pages*.py": DV_LOSS, "book/rerun.md": DV_LOSS,
    "notebooks/capture_plan.ipynb": DV_LOSS,
    "lunarcap/runs/sweeps*.py": VS_PAPER, "lunarcap/report/pages/other_engines*.py": VS_PAPER,
    "lunarcap/report/pages/summary*.py": VS_PAPER, "lunarcap/report/reproduction*.py": VS_PAPER,
    "tests/runs/test_sweeps*.py": VS_PAPER, "tests/report/pages/test_other_engines*.py": VS_PAPER,
    "tests/report/pages/test_summary*.py": VS_PAPER,
    "tests/report/pages/test_reproduction_report*.py": VS_PAPER,
    "lunarcap/report/pages/sweep*.py": VS_PAPER, "tests/report/pages/test_sweep*.py": VS_PAPER,
    "lunarcap/runs/study*.py": OBJECTIVE, "lunarcap/report/pages/trade_study*.py": OBJECTIVE,
    "tests/runs/test_study*.py": OBJECTIVE, "tests/report/pages/test_trade_study*.py": OBJECTIVE,
}

_ANALYTIC = {"loss_mps": "analytic_loss_mps", "loss_percent": "analytic_loss_percent"}
_PAPER_LOSS = {"loss_mps": "paper_delta_v_loss_mps",
               "loss_percent": "paper_delta_v_loss_percent"}


def _keys(prefix: str, names: dict, quote: str = '"') -> list:
    """Rules renaming ``prefix["old"]`` (or ``prefix.old``) to the new names."""
    out = []
    for old, new in names.items():
        if quote == ".":
            out.append((re.escape(prefix) + r"\." + old + r"\b", f"{prefix}.{new}"))
        else:
            out.append((re.escape(f'{prefix}["{old}"]'), f'{prefix}["{new}"]'))
    return out


#: Pass 1: ``[(file glob, regex, replacement)]``, in order.
CONTEXT = [
    # Robbins' estimate on a grid (study.analytic_curves), before the rules on ``e[...]``
    ("lunarcap/runs/study*.py", r'"loss_mps": e\["loss_mps"\], "loss_percent": e\["loss_percent"\]',
     '"analytic_loss_mps": e["analytic_loss_mps"],\n                             '
     '"analytic_loss_percent": e["analytic_loss_percent"]'),
    # the burn's loss record (lunarcap.runs.chain.burn_loss) read elsewhere
    *[("lunarcap/runs/*.py", p, r) for p, r in _keys("loss", {
        k: DV_LOSS[k] for k in ("loss_mps", "loss_percent", "impulsive_delta_v_mps")})],
    ("lunarcap/report/pages/other_engines*.py", re.escape('res.totals()["total_loss_mps"]'),
     'res.totals()["total_delta_v_loss_mps"]'),
    # the trade study: Robbins' estimate (capture_chain_estimate, analytic_curves) ...
    *[("lunarcap/runs/study*.py", p, r) for p, r in _keys("theory[i]", _ANALYTIC)],
    *[("lunarcap/runs/study*.py", p, r) for pre in ("t", "e") for p, r in _keys(pre, {
        "loss_mps": "analytic_loss_mps", "impulsive_delta_v_mps": "paper_impulsive_delta_v_mps"})],
    ("lunarcap/runs/study*.py", r'"loss_mps": loss,(\s+)"loss_percent": 100\.0 \* loss / dv',
     r'"analytic_loss_mps": loss,\1"analytic_loss_percent": 100.0 * loss / dv'),
    ("lunarcap/runs/study*.py", r'"loss_mps": loss, "loss_percent": 100\.0 \* loss / imp,',
     '"analytic_loss_mps": loss, "analytic_loss_percent": 100.0 * loss / imp,'),
    ("lunarcap/runs/study*.py", r'"impulsive_delta_v_mps": float\(dv\)',
     '"paper_impulsive_delta_v_mps": float(dv)'),
    # ... and the paper's engines as printed (paper_points; Table B1's own columns stay)
    ("lunarcap/runs/study*.py",
     r'"loss_mps": r\.delta_v_mps - r\.impulsive_delta_v_mps,(\s+)"loss_percent": r\.diff',
     r'"paper_delta_v_loss_mps": r.delta_v_mps - r.impulsive_delta_v_mps,\1'
     r'"paper_delta_v_loss_percent": r.diff'),
    ("lunarcap/runs/study*.py", r"\b([rg])\.impulsive_delta_v_mps\b", r"\1.@@B1@@"),
    ("lunarcap/runs/study*.py",
     r'"burn_duration_min": float\(g\.burn_duration_min\.sum\(\)\), "loss_mps": loss,(\s+)'
     r'"loss_percent":', r'"burn_duration_min": float(g.burn_duration_min.sum()), '
     r'"paper_delta_v_loss_mps": loss,\1"paper_delta_v_loss_percent":'),
    ("lunarcap/runs/study*.py", r'``loss_mps``, ``loss_percent``\.',
     '``analytic_loss_mps``, ``analytic_loss_percent``.'),
    ("lunarcap/runs/study*.py", r"part, burn_duration_min, loss_mps,\n(\s+)loss_percent \(",
     r"part, burn_duration_min, paper_delta_v_loss_mps,\n\1paper_delta_v_loss_percent ("),
    ("lunarcap/runs/study*.py", r"part, eq19_duration_min, loss_mps,\n(\s+)loss_percent \(",
     r"part, eq19_duration_min, analytic_loss_mps,\n\1analytic_loss_percent ("),
    ("lunarcap/runs/study*.py", r"(?<!\w)loss_percent_loi1\.\.3", "objective_loss_percent_loi1..3"),
    ("lunarcap/runs/study*.py", r'row\[f"loss_percent_\{p\.lower\(\)\}"\]',
     'row[f"objective_loss_percent_{p.lower()}"]'),
    ("lunarcap/report/pages/trade_study*.py", r'"paper_loss_percent": r\.loss_percent',
     '"paper_loss_percent": r.paper_delta_v_loss_percent'),
    ("lunarcap/report/pages/trade_study*.py", r'robbins\.loc\[r\.part, "loss_percent"\]',
     'robbins.loc[r.part, "analytic_loss_percent"]'),
    ("lunarcap/report/pages/trade_study*.py", r'theory\.groupby\(\["isp_s", "part"\]\)\.loss_',
     'theory.groupby(["isp_s", "part"]).analytic_loss_'),
    ("lunarcap/report/figures*.py", r"(ok|d)\.loss_percent\b", r"\1.objective_loss_percent"),
    ("lunarcap/report/figures*.py", r"th\.loss_percent\b", "th.analytic_loss_percent"),
    ("lunarcap/report/figures*.py", r"r\.loss_percent\b", "r.paper_delta_v_loss_percent"),
    ("lunarcap/report/figures*.py", r"``part``, ``isp_s``, ``thrust_to_weight``,\n(\s+)"
     r"``loss_percent``\)", r"``part``, ``isp_s``, ``thrust_to_weight``,\n\1"
     r"``objective_loss_percent``)"),
    ("lunarcap/report/figures*.py", r"\(same columns\)", "(``analytic_loss_percent``)"),
    ("lunarcap/report/figures*.py", r"``part``, ``loss_percent``\), drawn as stars",
     "``part``, ``paper_delta_v_loss_percent``), drawn as stars"),
    ("lunarcap/report/figures*.py", r"``paper_impulsive_delta_v_mps``, ``loss_mps``,\n(\s+)"
     r"``model_loss_mps``\)", r"``paper_impulsive_delta_v_mps``, "
     r"``loss_vs_paper_impulse_mps``,\n\1``delta_v_loss_mps``)"),
    ("lunarcap/report/figures*.py", r"s\.loss_mps\b", "s.loss_vs_paper_impulse_mps"),
    ("lunarcap/report/figures*.py", r"s\.model_loss_mps\b", "s.delta_v_loss_mps"),
    ("lunarcap/report/figures*.py", r"\btotal_loss_mps\b", "total_delta_v_loss_mps"),
    # the summary page's glued B1 totals are named after the totals' keys
    *[(g, r"(?<![\w@])(b1_)?total_loss_(mps|percent)_(?=\d|\{)",
       r"\1total_loss_vs_paper_impulse_\2_")
      for g in ("lunarcap/report/pages/summary*.py", "notebooks/summary.ipynb",
                "tests/report/pages/test_summary*.py", "book/index.md")],
    *[(g, r"(?<![\w@])total_model_impulsive_delta_v_mps_(?=\d)", "total_impulsive_limit_mps_")
      for g in ("notebooks/summary.ipynb", "tests/report/pages/test_summary*.py",
                "book/index.md")],
    *[(g, r"(?<![\w@])total_model_loss_(mps|percent)_(?=\d)", r"total_delta_v_loss_\1_")
      for g in ("notebooks/summary.ipynb", "tests/report/pages/test_summary*.py",
                "book/index.md")],
    # the index quotes the capture-plan pages' totals (notebooks/capture_plan.ipynb)
    ("book/index.md", r"(plan_lro_like|plan_two_burn)\.ipynb::total_loss_(mps|percent)\b",
     r"\1.ipynb::total_delta_v_loss_\2"),
    # the other-engines test compares with the plan's own table (lunarcap.runs.chain)
    ("tests/report/pages/test_other_engines*.py", r"rows\.loss_mps\b", "rows.delta_v_loss_mps"),
    # tests of the trade study's estimate and of the figures
    ("lunarcap/runs/study*.py", r"One per LOI: ``loi``, ``impulsive_delta_v_mps``",
     "One per LOI: ``loi``, ``paper_impulsive_delta_v_mps``"),
    ("tests/runs/test_study*.py", r'(p\.loc\[\([^)]*\), ")loss_', r"\1paper_delta_v_loss_"),
    ("tests/runs/test_study*.py", r"row\.loss_mps == pytest\.approx\(sum\(e",
     "row.analytic_loss_mps == pytest.approx(sum(e"),
    ("tests/runs/test_study*.py", r'e\["loss_mps"\]', 'e["analytic_loss_mps"]'),
    ("tests/runs/test_study*.py", r'e\["impulsive_delta_v_mps"\]',
     'e["paper_impulsive_delta_v_mps"]'),
    ("tests/runs/test_study*.py", r'r\["loss_mps"\] for r in study\.capture_chain_estimate',
     'r["analytic_loss_mps"] for r in study.capture_chain_estimate'),
    ("tests/report/pages/test_trade_study*.py", r'e\["loss_mps"\]', 'e["analytic_loss_mps"]'),
    ("tests/report/pages/test_trade_study*.py", r'e\["impulsive_delta_v_mps"\]',
     'e["paper_impulsive_delta_v_mps"]'),
    ("tests/report/pages/test_trade_study*.py",
     r'capture_chain_estimate\(thrust_N, 250\.0\)\[loi - 1\]\["loss_mps"\]',
     'capture_chain_estimate(thrust_N, 250.0)[loi - 1]["analytic_loss_mps"]'),
    # one frame drawn as the study's rows, Robbins' curves and the paper's engines
    ("tests/report/test_figure_legibility*.py", r"(\s+)(?<!_)loss_percent=1 / t / 10,",
     r"\1objective_loss_percent=1 / t / 10, analytic_loss_percent=1 / t / 10,"
     r"\1paper_delta_v_loss_percent=1 / t / 10,"),
    ("tests/report/test_figure_legibility*.py", r"loss_mps=\[15\.0, 4\.0, 3\.0\], "
     r"model_loss_mps=", "loss_vs_paper_impulse_mps=[15.0, 4.0, 3.0], delta_v_loss_mps="),
    ("tests/report/test_figure_legibility*.py", r"\bloss_mps=\[20\.0", "delta_v_loss_mps=[20.0"),
    ("tests/report/test_figure_legibility*.py", r'totals, "loss_mps"',
     'totals, "delta_v_loss_mps"'),
    ("tests/report/test_figure_legibility*.py", r"\btotal_loss_mps=", "total_delta_v_loss_mps="),
    ("tests/report/test_figures*.py", r'"loss_percent": p\.diff_percent \+ 0\.1',
     '"loss_vs_paper_impulse_percent": p.diff_percent + 0.1'),
    ("tests/report/test_figures*.py", r'\{"loss_mps": b\["delta_v_mps"\] - imp,',
     '{"loss_vs_paper_impulse_mps": b["delta_v_mps"] - imp,'),
    ("tests/report/test_figures*.py", r'"loss_percent": 100 \* \(b\["delta_v_mps"\] - imp\)',
     '"loss_vs_paper_impulse_percent": 100 * (b["delta_v_mps"] - imp)'),
    # the impulsive command: its delta-V is the two-body impulse, its duration Eq. (19)'s
    ("lunarcap/cli*.py", r'"delta_v_mps": b\.delta_v_mps', '"impulsive_delta_v_two_body_mps": '
     'b.delta_v_mps'),
    ("lunarcap/cli*.py", r"""sum\(r\["delta_v_mps"\] for r in rows\)""",
     'sum(r["impulsive_delta_v_two_body_mps"] for r in rows)'),
    ("lunarcap/cli*.py", r"""sum\(r\['delta_v_mps'\] for r in rows\)""",
     "sum(r['impulsive_delta_v_two_body_mps'] for r in rows)"),
    ("lunarcap/cli*.py", r'"total_delta_v_mps": sum\(r\["impulsive_delta_v_two_body_mps"\]',
     '"total_impulsive_delta_v_two_body_mps": sum(r["impulsive_delta_v_two_body_mps"]'),
    ("lunarcap/cli*.py", r"\{r\['delta_v_mps'\]:9\.3f\} \{r\['period_after_h'\]",
     "{r['impulsive_delta_v_two_body_mps']:9.3f} {r['period_after_h']"),
    # a count of the burns study: its propellant and IPOPT iterations are totals
    ("lunarcap/runs/burns*.py", r"(?<![\w.])fuel_kg=rows\[0\]", "total_fuel_kg=rows[0]"),
    ("lunarcap/runs/burns*.py", r'"fuel_kg", "final_mass_kg"', '"total_fuel_kg", "final_mass_kg"'),
    ("lunarcap/runs/burns*.py", r"r\['fuel_kg'\]:\.2f\} kg; final",
     "r['total_fuel_kg']:.2f} kg; final"),
    ("lunarcap/runs/burns*.py", r"``fuel_kg``, ``final_mass_kg``",
     "``total_fuel_kg``, ``final_mass_kg``"),
    ("lunarcap/runs/burns*.py", r"(?<![\w.])iterations=res\.iterations",
     "total_ipopt_iterations=res.iterations"),
    ("lunarcap/runs/burns*.py", r'"iterations": None', '"total_ipopt_iterations": None'),
    ("lunarcap/runs/burns*.py", r'"ipopt_status", "iterations", "burns_json"',
     '"ipopt_status", "total_ipopt_iterations", "burns_json"'),
    ("lunarcap/runs/burns*.py", r"``ipopt_status``, ``iterations``",
     "``ipopt_status``, ``total_ipopt_iterations``"),
    ("lunarcap/report/pages/burn_count*.py", r'("total_(?:delta_v_)?loss_mps"), "fuel_kg"',
     r'\1, "total_fuel_kg"'),
    # ... and its test
    ("tests/test_cli.py", r'(burns\[0\]|\bb)\["delta_v_mps"\]',
     r'\1["impulsive_delta_v_two_body_mps"]'),
    ("tests/test_cli.py", r'out\["total_delta_v_mps"\]',
     'out["total_impulsive_delta_v_two_body_mps"]'),
    ("tests/runs/test_campaign*.py", r'"total_impulsive_delta_v_mps", "fuel_kg",',
     '"total_impulsive_limit_mps", "total_fuel_kg",'),
    # the solution's target kind (the plan's orbit in words is target_orbit)
    ("lunarcap/optim/solution*.py", r'"target": prob\.target\.kind', '"target_kind": '
     'prob.target.kind'),
    *[(g, r'"target"(?=[:,\]])', '"target_orbit"') for g in (
        "lunarcap/runs/burns*.py", "lunarcap/runs/missed*.py",
        "lunarcap/report/pages/burn_count*.py", "lunarcap/report/pages/missed_thrust*.py")],
    # the verification's branch: e cos(nu) at the end of the coast
    ("lunarcap/optim/verify*.py", r"\bbranch: float \| None = None",
     "end_e_cos_nu: float | None = None"),
    ("lunarcap/optim/verify*.py", r"self\.branch\b", "self.end_e_cos_nu"),
    ("tests/optim/test_gate*.py", r"\bbranch=None if circular", "end_e_cos_nu=None if circular"),
    ("tests/optim/test_gate*.py", r'\("branch", -0\.01, "apolune"\)',
     '("end_e_cos_nu", -0.01, "apolune")'),
]

#: Pass 3: names with one meaning everywhere.
GLOBAL = {
    "impulsive_two_body_mps": "impulsive_delta_v_two_body_mps",
    "two_body_impulsive_total_mps": "total_impulsive_delta_v_two_body_mps",
    "objective_mps": "objective_j_mps",
    "verification_branch": "verification_end_e_cos_nu",
    "eq19_burn_duration_min": "eq19_duration_min",
    "paper_loss_percent": "paper_delta_v_loss_percent",
    "paper_loss_mps": "paper_delta_v_loss_mps",
}

#: Placeholders of pass 1 for names that must keep their old spelling (a column of the
#: paper's printed tables, which are not renamed), restored after pass 3.
PLACEHOLDERS = {"@@B1@@": "impulsive_delta_v_mps"}


def _files(root: Path) -> list:
    out = set()
    for pattern in SCOPE:
        out.update(p for p in root.glob(pattern) if p.is_file())
    return sorted(p for p in out if p.relative_to(root).as_posix() not in SKIP)


def _word(old: str) -> str:
    return r"(?<![\w@])" + re.escape(old) + r"(?![\w@])"


def rename_text(rel: str, text: str, hits: dict | None = None) -> str:
    """``text`` of the file at ``rel`` (POSIX path from the root) with every rule applied."""
    for i, (glob, pattern, repl) in enumerate(CONTEXT):
        if fnmatch.fnmatch(rel, glob):
            text, n = re.subn(pattern, repl, text)
            if hits is not None:
                hits[i] = hits.get(i, 0) + n
    for glob, names in PER_FILE.items():
        if fnmatch.fnmatch(rel, glob):
            for old, new in sorted(names.items(), key=lambda kv: -len(kv[0])):
                text = re.sub(_word(old), new, text)
            break
    for old, new in GLOBAL.items():
        text = re.sub(_word(old), new, text)
    for mark, name in PLACEHOLDERS.items():
        text = text.replace(mark, name)
    return text


LIMIT = 100  # ruff's line length (pyproject.toml)


def _split_at(line: str, lineno: int, tokens: list) -> str | None:
    """``line`` broken after its last top-level-enough comma before the limit, or None."""
    depth, opener = 0, []
    best = None
    for tok in tokens:
        if tok.start[0] > lineno:
            break
        if tok.type != tokenize.OP:
            continue
        if tok.string in "([{":
            opener.append(tok.start)
        elif tok.string in ")]}":
            opener.pop() if opener else None
        elif tok.string == "," and tok.start[0] == lineno and opener and tok.end[1] < LIMIT:
            row, col = opener[-1]
            indent = col + 1 if row == lineno else len(line) - len(line.lstrip())
            if tok.end[1] + 1 < len(line.rstrip()):
                best = (tok.end[1], indent)
    del depth
    if best is None:
        return None
    cut, indent = best
    return line[:cut] + "\n" + " " * indent + line[cut:].lstrip()


def _split_string(line: str, lineno: int, tokens: list) -> str | None:
    """A one-line string literal inside brackets broken in two at a space (outside ``{}``)."""
    depth = 0
    for tok in tokens:
        if tok.start[0] > lineno:
            break
        if tok.type == tokenize.OP and tok.string in "([{":
            depth += 1
        elif tok.type == tokenize.OP and tok.string in ")]}":
            depth -= 1
        elif tok.type == tokenize.STRING and tok.start[0] == lineno == tok.end[0] \
                and tok.end[1] > LIMIT and depth > 0:
            text, col = tok.string, tok.start[1]
            m = re.match(r"[a-zA-Z]*", text)
            prefix, quote = m.group(0), text[m.end()]
            if text[m.end():m.end() + 3] == quote * 3:
                return None
            braces = 0
            cut = None
            for k, ch in enumerate(text[m.end() + 1:-1], m.end() + 1):
                braces += (ch == "{") - (ch == "}") if "f" in prefix.lower() else 0
                if ch == " " and braces == 0 and col + k + 2 < LIMIT:
                    cut = k
            if cut is None:
                return None
            first = text[:cut + 1] + quote
            second = prefix + quote + text[cut + 1:]
            return line[:col] + first + "\n" + " " * col + second + line[tok.end[1]:]
    return None


def _split_prose(line: str) -> str | None:
    """A docstring or comment line broken at its last space before the limit."""
    body = line.rstrip("\n")
    indent = len(body) - len(body.lstrip())
    lead = "# " if body.lstrip().startswith("#") else ""
    cut = body.rfind(" ", indent + len(lead) + 1, LIMIT)
    if cut <= indent + len(lead):
        return None
    return body[:cut] + "\n" + " " * indent + lead + body[cut + 1:]


def wrap_long_lines(text: str) -> str:
    """Python source with the lines over :data:`LIMIT` broken (what a rename lengthened).

    Code breaks after a comma inside brackets, aligned with the bracket; docstring and
    comment lines break at a space. A line that cannot be broken so is left as it is.
    """
    for _ in range(200):
        lines = text.split("\n")
        long = [i for i, ln in enumerate(lines, 1) if len(ln) > LIMIT]
        if not long:
            return text
        tokens = list(tokenize.generate_tokens(io.StringIO(text).readline))
        prose = set()
        for tok in tokens:
            if tok.type == tokenize.STRING and tok.start[0] != tok.end[0]:
                prose.update(range(tok.start[0] + 1, tok.end[0] + 1))
            if tok.type == tokenize.COMMENT and tok.start[1] == \
                    len(lines[tok.start[0] - 1]) - len(lines[tok.start[0] - 1].lstrip()):
                prose.add(tok.start[0])
        for i in long:
            new = _split_prose(lines[i - 1]) if i in prose else \
                _split_at(lines[i - 1], i, tokens) or _split_string(lines[i - 1], i, tokens)
            if new is not None:
                lines[i - 1] = new
                break
        else:
            return text
        text = "\n".join(lines)
    return text


def main(argv=None) -> int:
    """Rewrite the files (or ``--check``); print the changed files and unused context rules."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="change nothing; exit 1 if needed")
    ap.add_argument("--root", type=Path, default=ROOT)
    args = ap.parse_args(argv)
    hits, changed = {}, []
    for path in _files(args.root):
        rel = path.relative_to(args.root).as_posix()
        old = path.read_text(encoding="utf-8")
        new = rename_text(rel, old, hits)
        if new != old and rel.endswith(".py"):
            new = wrap_long_lines(new)
        if new != old:
            changed.append(rel)
            if not args.check:
                path.write_text(new, encoding="utf-8")
    for rel in changed:
        print(("would change " if args.check else "changed ") + rel)
    unused = [CONTEXT[i] for i in range(len(CONTEXT)) if not hits.get(i)]
    for glob, pattern, _ in unused:
        print(f"context rule found nothing (applied already?): {glob}: {pattern}",
              file=sys.stderr)
    return 1 if args.check and changed else 0


if __name__ == "__main__":
    raise SystemExit(main())
