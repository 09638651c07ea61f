"""What the book found, read from its executed pages: the landing page's findings, how to cite.

Every page module glues its finding in one or two sentences with its numbers
(:meth:`lunarcap.report.page.Page.headline`), and every number its prose quotes
(:meth:`~lunarcap.report.page.Page.value`). This module reads them back from the executed
notebooks of a build (:func:`glued`), in the order of the table of contents
(:func:`headlines`), so the findings page lists every page without a hand-kept list, and
composes the first screen of the landing page (:func:`first_screen`): the paper reproduced
within x %, the finite-burn losses of the paper's three engines, the paper's
inconsistencies found, what lunarcap adds, and a link to how to cite, whose BibTeX entry,
licence, version and date come from ``CITATION.cff`` alone (:func:`citation`).

A value a quick build did not compute is glued as missing with its reason
(:func:`lunarcap.report.page.missing`) and is printed as that reason here too.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

from lunarcap.report.page import missing_text

#: The name of the glued finding of each page (:meth:`lunarcap.report.page.Page.headline`).
HEADLINE = "headline"


def glued(notebook: Path) -> dict:
    """``{name: value}`` of everything an executed notebook glued.

    A Markdown note is its Markdown text; a number or text its value (the ``text/plain``
    of the glue, read back with :func:`ast.literal_eval`).
    """
    import nbformat

    nb = nbformat.read(str(notebook), as_version=4)
    out = {}
    for cell in nb.cells:
        for o in cell.get("outputs", []):
            book = o.get("metadata", {}).get("scrapbook", {})
            name = book.get("name")
            if not name:
                continue
            prefix = book.get("mime_prefix", "")
            data = {k[len(prefix):]: v for k, v in o.get("data", {}).items()
                    if k.startswith(prefix)}
            if "text/markdown" in data:
                out[name] = data["text/markdown"]
            elif "text/plain" in data:
                try:
                    out[name] = ast.literal_eval(data["text/plain"])
                except (SyntaxError, ValueError):
                    out[name] = data["text/plain"]
    return out


def shown(v, spec: str = "", unit: str = "") -> str:
    """A glued value as prose prints it: formatted with its unit, or its missing reason.

    >>> shown(20.345, ".1f", " m/s"), shown("lunarcap-missing:not run in the quick book", ".1f")
    ('20.3 m/s', '— (not run in the quick book)')
    """
    gone = missing_text(v)
    return gone if gone is not None else f"{format(v, spec)}{unit}"


@dataclass(frozen=True)
class Headline:
    """The finding of one page: its toc file, title and Markdown (None if it glued none)."""

    page: str
    title: str
    markdown: str | None


def headlines(entries, generated: Path, toc: list[str]) -> list[Headline]:
    """The finding each executed page glued, in the order of the table of contents.

    ``entries``: the book's executions (each with a ``name`` and a ``title``,
    :class:`lunarcap.report.contents.Execution`); ``generated``: the directory of the
    executed notebooks; ``toc``: the toc files (:func:`lunarcap.report.contents.toc_files`).
    A page without an executed notebook or a headline has ``markdown`` None (the findings
    page says so, and its check fails).
    """
    by_name = {e.name: e for e in entries}
    out = []
    for f in toc:
        if not f.startswith("generated/"):
            continue
        e = by_name.get(f.split("/", 1)[1])
        if e is None:
            continue
        nb = Path(generated) / f"{e.name}.ipynb"
        md = glued(nb).get(HEADLINE) if nb.is_file() else None
        out.append(Headline(f, e.title, md))
    return out


def by_page_markdown(items: list[Headline], link_prefix: str = "") -> str:
    """A bullet list: each page's title as a link, then its finding."""
    lines = []
    for h in items:
        text = h.markdown if h.markdown else "*(no finding glued: the page sets none)*"
        text = " ".join(text.split())
        lines.append(f"- {{doc}}`{h.title} <{link_prefix}{h.page}>`: {text}")
    return "\n".join(lines)


# ====================================================================== how to cite
def citation(cff_path: Path) -> dict:
    """The package's citation, read from ``CITATION.cff`` alone.

    Title, authors, version, date, licence, repository address (None if the file names
    none) and DOI (likewise).
    """
    import yaml

    cff = yaml.safe_load(Path(cff_path).read_text(encoding="utf-8"))
    authors = " and ".join(a.get("name") or f"{a.get('family-names', '')}, "
                           f"{a.get('given-names', '')}".strip(", ")
                           for a in cff.get("authors", []))
    date = cff.get("date-released")
    return {"title": cff["title"], "authors": authors, "version": str(cff["version"]),
            "date": str(date) if date else None, "license": cff.get("license"),
            "repository": cff.get("repository-code") or cff.get("url"),
            "doi": cff.get("doi")}


def bibtex(c: dict, key: str = "lunarcap") -> str:
    """A BibTeX ``@software`` entry of :func:`citation`.

    >>> print(bibtex({"title": "t", "authors": "A", "version": "1", "date": "2026-01-02",
    ...               "license": "MIT", "repository": None, "doi": None}))
    @software{lunarcap,
      author  = {{A}},
      title   = {t},
      version = {1},
      year    = {2026},
      date    = {2026-01-02},
      license = {MIT},
    }
    """
    fields = [("author", f"{{{c['authors']}}}"), ("title", c["title"]),
              ("version", c["version"]),
              ("year", c["date"][:4] if c.get("date") else None), ("date", c.get("date")),
              ("license", c.get("license")), ("url", c.get("repository")),
              ("doi", c.get("doi"))]
    body = "".join(f"  {k:<7} = {{{v}}},\n" for k, v in fields if v)
    return f"@software{{{key},\n{body}}}"


def citation_markdown(c: dict, paper_key: str = "song2011") -> str:
    """The "How to cite" section's body: version and date, licence, repository, BibTeX."""
    repo = (f"<{c['repository']}>" if c.get("repository") else
            "not recorded: `CITATION.cff` names no public address yet (each page's "
            "provenance names the git commit it was built from)")
    when = f", released {c['date']}" if c.get("date") else ""
    return (f"Version\n: lunarcap {c['version']}{when} (from `CITATION.cff`, the one source "
            f"of these details).\n\n"
            f"Licence\n: {c.get('license') or 'not stated'} (the `LICENSE` file).\n\n"
            f"Repository\n: {repo}.\n\n"
            + (f"DOI\n: {c['doi']}\n\n" if c.get("doi") else "")
            + f"The paper it reproduces\n: {{cite:t}}`{paper_key}`.\n\n"
            f"BibTeX\n: \n\n```bibtex\n{bibtex(c)}\n```\n")


# ====================================================================== the data archive
#: The folders below book/generated whose files are the book's data (not its figures).
DATA_DIRS = ("tables", "data", "export")
#: A fixed timestamp for every member, so the archive depends on its content only.
_ZIP_TIME = (2011, 1, 1, 0, 0, 0)


def write_archive(generated: Path, name: str) -> tuple[Path, int]:
    """One zip of all the book's data: every file below :data:`DATA_DIRS` of ``generated``.

    The tables (one CSV per table of every page), the study tables and other data the
    pages link (``data/``), the exported files of the plan (``export/``). Members are
    sorted and dated :data:`_ZIP_TIME`, so the archive changes only with its content.
    Returns (path, number of files).
    """
    import zipfile

    from lunarcap.repro import paths

    generated = Path(generated)
    files = sorted(f for d in DATA_DIRS if (generated / d).is_dir()
                   for f in (generated / d).rglob("*")
                   if f.is_file() and not f.name.startswith("."))
    out = generated / name
    with paths.atomic_path(out) as tmp:
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            for f in files:
                info = zipfile.ZipInfo(f.relative_to(generated).as_posix(), _ZIP_TIME)
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = 0o644 << 16
                z.writestr(info, f.read_bytes())
    return out, len(files)
