"""Sphinx extension of the book: the paper's tables and figures get no book number.

(Also: link addresses with ``&`` are mended, :func:`unescape_link_ampersands`; a glued
value a page marks as missing is printed as its reason, :func:`format_glued_text`.)

Sphinx numbers every captioned table and figure, here "Book table N" and "Book figure N"
(``numfig_format`` in ``book/_config.yml``). A table or figure that regenerates one of the
paper's carries the paper's number in its caption instead ("Song et al. (2011) Table 1",
:func:`lunarcap.report.display.paper_caption`) and the class :data:`PAPER_CLASS`. This
extension notes the ids of those while the documents are read, and once Sphinx has
numbered every table and figure (``assign_figure_numbers``, at the ``env-get-updated``
event) it takes their numbers back and numbers the book's own ones again without them,
in the same order: the paper's items show no book number and the book's run on without
gaps. The paper's items keep their ids, so their permalinks work.

Loaded by ``book/_config.yml`` (``sphinx: extra_extensions``).
"""

from __future__ import annotations

from docutils import nodes
from sphinx.transforms import AutoNumbering, SphinxTransform

#: Class of the tables and figures that are the paper's: the one
#: :data:`lunarcap.report.display.PAPER_CLASS` sets (not imported from there, which would
#: bring matplotlib into Sphinx; a test checks they are the same).
PAPER_CLASS = "lc-paper"
#: Head of a missing value's glued text: :data:`lunarcap.report.page.MISSING_PREFIX` (not
#: imported, for the same reason; a test checks they are the same).
MISSING_PREFIX = "lunarcap-missing:"
_ENV_KEY = "lunarcap_paper_ids"   # attribute of the build environment: docname -> ids


class NotePaperItems(SphinxTransform):
    """Note the ids (given by ``AutoNumbering``) of the paper's tables and figures."""

    default_priority = AutoNumbering.default_priority + 1

    def apply(self, **kwargs) -> None:
        """Record the ids of every table or figure of class :data:`PAPER_CLASS`."""
        ids = {node["ids"][0] for node in self.document.findall(nodes.Element)
               if isinstance(node, (nodes.table, nodes.figure))
               and PAPER_CLASS in node["classes"] and node["ids"]}
        store = getattr(self.env, _ENV_KEY, None)
        if store is None:
            store = {}
            setattr(self.env, _ENV_KEY, store)
        store[self.env.docname] = ids


def renumber(fignumbers: dict, paper_ids: dict) -> dict:
    """``env.toc_fignumbers`` without the paper's items, the others numbered again.

    Parameters
    ----------
    fignumbers : dict
        docname -> figtype -> id -> number (a tuple: section numbers, then the count).
    paper_ids : dict
        docname -> set of ids of the paper's tables and figures.

    Returns
    -------
    dict
        The same mapping with the paper's ids left out and, per figtype and section
        prefix, the last component renumbered 1, 2, ... in the original order.

    Examples
    --------
    >>> renumber({"a": {"table": {"t1": (1,), "p": (2,)}}, "b": {"table": {"t2": (3,)}}},
    ...          {"a": {"p"}})
    {'a': {'table': {'t1': (1,)}}, 'b': {'table': {'t2': (2,)}}}
    """
    kept = sorted((num, doc, figtype, fid)
                  for doc, types in fignumbers.items()
                  for figtype, ids in types.items()
                  for fid, num in ids.items()
                  if fid not in paper_ids.get(doc, ()))
    out: dict = {doc: {figtype: {} for figtype in types} for doc, types in fignumbers.items()}
    counters: dict = {}
    for num, doc, figtype, fid in kept:
        key = (figtype, tuple(num[:-1]))
        counters[key] = counters.get(key, 0) + 1
        out[doc][figtype][fid] = (*num[:-1], counters[key])
    return out


def _renumber_env(app, env) -> None:
    env.toc_fignumbers = renumber(env.toc_fignumbers, getattr(env, _ENV_KEY, {}))


def _purge(app, env, docname) -> None:
    getattr(env, _ENV_KEY, {}).pop(docname, None)


def _merge(app, env, docnames, other) -> None:
    store = getattr(env, _ENV_KEY, None)
    if store is None:
        store = {}
        setattr(env, _ENV_KEY, store)
    for doc in docnames:
        if doc in getattr(other, _ENV_KEY, {}):
            store[doc] = getattr(other, _ENV_KEY)[doc]


def unescape_link_ampersands(doctree) -> int:
    """Undo MyST's escaping of ``&`` in link addresses; returns the links mended.

    myst-parser (3.0) stores a Markdown link's address HTML-escaped (``a?b=1&amp;c=2``)
    and the HTML writer escapes it again, so the page's ``href`` reads ``&amp;amp;`` and
    the link is broken (four source links of the real-missions page). Run on every
    resolved document (``doctree-resolved``).

    >>> from docutils import nodes
    >>> ref = nodes.reference("", "x", refuri="http://a.org/?b=1&amp;c=2")
    >>> unescape_link_ampersands(nodes.paragraph("", "", ref)), ref["refuri"]
    (1, 'http://a.org/?b=1&c=2')
    """
    n = 0
    for ref in doctree.findall(nodes.reference):
        uri = ref.get("refuri", "")
        if "&amp;" in uri:
            ref["refuri"] = uri.replace("&amp;", "&")
            n += 1
    return n


def _mend_links(app, doctree, docname) -> None:
    unescape_link_ampersands(doctree)


def format_glued_text(original):
    """myst-nb's ``format_plain_text`` that prints a missing value as its reason.

    A page glues a value it could not compute as ``MISSING_PREFIX + reason``
    (:meth:`lunarcap.report.page.Page.value`); the prose pastes it with a number format
    (``{glue:text}`x:.2f```), which myst-nb cannot apply to a text. Whatever the format, such
    a value reads "— (reason)"; every other value is formatted by ``original``.

    >>> fmt = format_glued_text(lambda text, spec: format(float(text), spec))
    >>> fmt("12.345", ".1f"), fmt("'lunarcap-missing:not run in the quick book'", ".2f")
    ('12.3', '— (not run in the quick book)')
    """
    import ast

    def fmt(text: str, fmt_spec: str) -> str:
        try:
            value = ast.literal_eval(text)
        except (SyntaxError, ValueError):
            value = text
        if isinstance(value, str) and value.startswith(MISSING_PREFIX):
            return f"— ({value[len(MISSING_PREFIX):]})"
        return original(text, fmt_spec)

    fmt.lunarcap = True
    return fmt


def _patch_glue_formatting() -> None:
    """Route myst-nb's glue text formatting (same page and other pages) through ours."""
    from myst_nb.ext.glue import crossref, roles

    for mod in (roles, crossref):
        if not getattr(mod.format_plain_text, "lunarcap", False):
            mod.format_plain_text = format_glued_text(mod.format_plain_text)


def setup(app):
    """Register the transform and the renumbering (Sphinx extension entry point)."""
    _patch_glue_formatting()
    app.add_transform(NotePaperItems)
    app.connect("doctree-resolved", _mend_links)
    app.connect("env-purge-doc", _purge)
    app.connect("env-merge-info", _merge)
    # after the toctree collector's assign_figure_numbers (env-get-updated), before writing
    app.connect("env-check-consistency", _renumber_env)
    return {"version": "1", "env_version": 1, "parallel_read_safe": True,
            "parallel_write_safe": True}
