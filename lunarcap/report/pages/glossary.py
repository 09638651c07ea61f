"""The glossary page (notebooks/glossary.ipynb): every reported quantity, its unit and meaning.

Generated from :mod:`lunarcap.quantities`, the one list the CSV columns, the JSON keys of
the command line (and their schemas, :mod:`lunarcap.schemas`), the tables' headers and the
axis labels read. :func:`losses_table` sets the quantities that are easily confused side
by side (the two impulsive references and the four losses); :func:`glossary_table` lists
them all; :func:`composition_table` gives the prefixes and suffixes that name a family
(``paper_delta_v_mps``, ``total_fuel_kg``, ``objective_loss_percent_loi1``).
"""

from __future__ import annotations

import pandas as pd

from lunarcap import quantities as Q
from lunarcap import schemas
from lunarcap.report.contents import BookPage, Execution, table_files
from lunarcap.report.page import Page

NOTEBOOK = "notebooks/glossary.ipynb"
BOOK = BookPage(NOTEBOOK, "Reproduce", 10, (
    Execution(
        "glossary", "Glossary of quantities",
        outputs=table_files("glossary", "losses", "quantities", "composition", "captures")),
))

#: The quantities a reader confuses most easily, in the order the page explains them.
CONFUSABLE = ("impulsive_delta_v_two_body_mps", "impulsive_limit_mps",
              "paper_impulsive_delta_v_mps", "delta_v_mps", "delta_v_loss_mps",
              "objective_j_mps", "objective_loss_mps", "loss_vs_paper_impulse_mps",
              "analytic_loss_mps", "time_to_final_orbit_h", "target_kind", "target_orbit")


def _rows(names) -> list:
    return [{"name": q.name, "unit": q.unit or "—", "label": q.label,
             "json_type": q.kind, "definition": q.definition}
            for q in (Q.lookup(n) for n in names)]


def losses_table() -> pd.DataFrame:
    """The impulsive references, the losses and the time to the final orbit."""
    return pd.DataFrame(_rows(CONFUSABLE))


def glossary_table() -> pd.DataFrame:
    """Every quantity of the glossary, sorted by name."""
    return pd.DataFrame(_rows(sorted(Q.GLOSSARY)))


def composition_table() -> pd.DataFrame:
    """The prefixes and suffixes composing a name from a glossary name."""
    rows = [{"part": f"{p}…", "label": (before + "…" + after).strip(),
             "definition": text.format("…"), "example": f"{p}delta_v_mps"}
            for p, (before, after, text) in Q.PREFIXES.items()]
    rows += [{"part": f"…{s}", "label": "…" + lab, "definition": text.format("…"),
              "example": f"objective_loss_percent{s}"} for s, (lab, text) in Q.SUFFIXES.items()]
    return pd.DataFrame(rows)


def captures_table() -> pd.DataFrame:
    """The captures of the paper's arrival the pages compare, by the name they use."""
    return pd.DataFrame([{"key": k, "capture": name, "definition": text}
                         for k, (name, text) in Q.CAPTURES.items()])


def build(output_name: str = "glossary", quick: bool = False) -> Page:
    """The glossary page (see the module docstring)."""
    page = Page(NOTEBOOK, {}, output_name, quick, ephemeris=False)
    page.table("losses", losses_table(),
               caption=("The quantities most easily confused: the impulsive references and "
                        "the losses measured against them."),
               show_columns=["name", "unit", "definition"])
    page.table("quantities", glossary_table(),
               caption=("Every quantity lunarcap reports: name (CSV column, JSON key), unit, "
                        "definition; the CSV adds the label of tables and axes."),
               show_columns=["name", "unit", "definition"])
    page.table("composition", composition_table(),
               caption="Names composed from a glossary name by a prefix or a suffix.",
               show_columns=["part", "definition", "example"])
    page.table("captures", captures_table(),
               caption="The captures of the paper's arrival the book compares.",
               show_columns=["capture", "definition"])
    page.value("n_quantities", len(Q.GLOSSARY))
    page.headline(f"{len(Q.GLOSSARY)} quantities, each with one name (CSV column and JSON "
                  f"key), unit and definition; {len(Q.CAPTURES)} captures named apart.")
    page.value("n_schemas", len(schemas.COMMANDS))
    page.value("schema_commands", ", ".join(schemas.COMMANDS))
    page.expect("every confusable name resolves", all(Q.is_known(n) for n in CONFUSABLE))
    page.expect("no retired name is in the glossary",
                not any(Q.is_known(n) for n in Q.RETIRED))
    page.expect("every definition is one sentence ending with a full stop",
                all(q.definition.endswith(".") for q in Q.GLOSSARY.values()))
    return page
