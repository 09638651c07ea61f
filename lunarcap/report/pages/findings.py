"""The findings page (notebooks/findings.ipynb) and the landing page's first screen.

Run after every other page of the book (its ``BOOK`` depends on every page), :func:`build`
reads what each executed page glued (:mod:`lunarcap.report.landing`): its finding
(``headline``) for the list of every page's finding, in the order of the table of
contents, and the numbers of a few pages for the landing page's first screen
(:func:`first_screen`): the paper reproduced within x %, the finite-burn losses of the
paper's three engines, the paper's inconsistencies, what lunarcap adds (the pages of the
"Beyond the paper" part, whatever they are), and how to cite. The landing page
(``book/index.md``) includes the Markdown files this page writes below
``book/generated``: :data:`LANDING`, :data:`BY_PAGE` and :data:`CITATION`.
"""

from __future__ import annotations

import pandas as pd

from lunarcap.mission.scenario import paper_engine_pairs
from lunarcap.report import contents
from lunarcap.report import landing as F
from lunarcap.report.contents import EVERY_PAGE, BookPage, Execution, table_files
from lunarcap.report.page import Page, listing
from lunarcap.repro import paths

NOTEBOOK = "notebooks/findings.ipynb"
#: Files below book/generated that book/index.md includes.
LANDING, BY_PAGE, CITATION = "findings_landing.md", "findings_by_page.md", "citation.md"
#: The archive of all the book's data (below book/generated), linked from the landing page.
ARCHIVE = "lunarcap-book-data.zip"
#: It reads what every other page glued, so it runs after all of them.
BOOK = BookPage(NOTEBOOK, "Results", 10, (
    Execution(
        "findings", "Findings, page by page",
        depends_on=(EVERY_PAGE,),
        outputs=(LANDING, BY_PAGE, CITATION, ARCHIVE) + table_files("findings", "pages")),
))
#: The part of the table of contents whose pages are "what lunarcap adds".
BEYOND_CAPTION = "Beyond the paper"
#: The paper's engines, as the landing page names them (thrust N, Isp s).
PAPER_ENGINES = tuple((int(t), int(i)) for t, i in paper_engine_pairs())
#: The label of the landing page's "How to cite" section (book/index.md).
CITE_LABEL = "how-to-cite"


#: What a value no page glued is shown as (a page left out of a partial build).
F_MISSING = "lunarcap-missing:not in this build"


def _losses(summary: dict) -> str:
    return listing({k: summary.get(k, F_MISSING) for k in
                    (f"total_delta_v_loss_mps_{t}N" for t, _ in PAPER_ENGINES)},
                   [(f"total_delta_v_loss_mps_{t}N", f"{t} N / {i} s")
                    for t, i in PAPER_ENGINES], ".2f", " m/s")


def first_screen(values: dict, items: list, beyond: list[str], cite: dict | None = None) -> str:
    """The landing page's first screen (MyST Markdown, links from ``book/index.md``).

    Parameters
    ----------
    values : dict
        ``{entry name: glued values}`` of the executed pages
        (:func:`lunarcap.report.landing.glued`).
    items : list of :class:`lunarcap.report.landing.Headline`
        Every page's finding (for the titles of the pages listed).
    beyond : list of str
        The toc files of the "Beyond the paper" part.
    cite : dict, optional
        :func:`lunarcap.report.landing.citation` (the version and date named first).
    """
    def v(page, name):
        return values.get(page, {}).get(name, F_MISSING)

    rr, ver, summ = (values.get(k, {}) for k in ("reproduction_report", "verification",
                                                 "summary"))
    title = {h.page: h.title.split(":")[0].strip() for h in items}
    added = [f"{{doc}}`{title[f]} </{f}>`" for f in beyond if f in title]
    version = (f"lunarcap {cite['version']}" + (f" of {cite['date']}" if cite.get("date") else "")
               if cite else "lunarcap")
    return (
        ":::{admonition} What this book found\n:class: lc-findings\n\n"
        f"{version}: {{ref}}`how to cite it <{CITE_LABEL}>` (BibTeX, licence); all the "
        f"book's data in one archive, {{download}}`{ARCHIVE} <generated/{ARCHIVE}>`.\n\n"
        f"- **The paper, reproduced.** Solved again with an independent optimiser, the "
        f"delta-Vs of the paper's best burns (Table B1) agree with the printed ones within "
        f"{F.shown(v('reproduction_report', 'b1_max_dv_diff_percent'), '.2f', ' %')}; "
        f"{F.shown(v('verification', 'n_passed'), '.0f')} of "
        f"{F.shown(v('verification', 'n_cases'), '.0f')} solutions of its Tables 1–5 pass an "
        f"independent re-propagation check ({{doc}}`reproduction report "
        f"</generated/reproduction_report>`).\n"
        f"- **Finite-burn losses.** Over the whole three-burn capture (*the paper's fixed "
        f"timings*, full dynamics) the paper's engines need {_losses(summ)} more than impulses "
        f"in the same dynamics ({{doc}}`Table B1 and totals </generated/summary>`).\n"
        f"- **The paper against itself.** {F.shown(rr.get('n_inconsistent', F_MISSING), 'd')} "
        f"of {F.shown(rr.get('n_findings', F_MISSING), 'd')} checks of its printed numbers "
        f"against one another fail beyond print resolution; among them the Sun's "
        f"gravitational parameter, printed "
        f"{F.shown(rr.get('sun_ratio', F_MISSING), '.0f')} times too small.\n"
        f"- **What lunarcap adds.** {len(added)} pages beyond the paper: "
        f"{', '.join(added)}.\n:::\n")


def build(output_name: str = "findings", quick: bool = False) -> Page:
    """The findings page (see the module docstring); writes the landing page's includes."""
    pages = contents.registered()
    entries = [x for x in contents.executions(pages) if x.name != output_name]
    page = Page(NOTEBOOK, {}, output_name, quick)
    items = F.headlines(entries, paths.GENERATED, contents.toc_files(pages))
    values = {x.name: F.glued(x.output) for x in entries if x.output.is_file()}
    beyond = next((files for cap, files in contents.toc_parts(pages)
                   if cap == BEYOND_CAPTION), [])
    c = F.citation(paths.ROOT / "CITATION.cff")
    landing = first_screen(values, items, beyond, c)
    by_page = F.by_page_markdown(items, link_prefix="/")
    cite = F.citation_markdown(c)
    for name, text in ((LANDING, landing), (BY_PAGE, by_page), (CITATION, cite)):
        paths.write_text_atomic(paths.GENERATED / name, text)
    archive, n_files = F.write_archive(paths.GENERATED, ARCHIVE)
    page.value("n_archive_files", n_files)
    page.value("archive_kB", archive.stat().st_size / 1e3)
    page.note("archive", f"{{download}}`{ARCHIVE} <{paths.relative_to_page(archive)}>`")
    page.note("by_page", by_page)
    page.note("landing", landing)
    page.table("pages", pd.DataFrame(
        [{"page": h.page, "title": h.title, "finding": " ".join((h.markdown or "").split())}
         for h in items]),
        caption="Every page's finding, as the page computed it (the CSV for a reader's own "
                "use; the list above shows the same).", show_columns=["title", "page"])
    page.value("n_pages", len(items))
    page.expect("every page of the book glues its finding (Page.headline)",
                all(h.markdown for h in items),
                ", ".join(h.page for h in items if not h.markdown))
    page.data.update(items=items, values=values)
    return page
