"""Checks of the built book as a reader reads it: the words of every page, no "nan" in them.

:func:`page_words` returns the text a reader of a built HTML page sees (prose, tables,
captions, cell outputs), without the code of the notebooks' cells, literal code blocks,
scripts and styles. :func:`nan_mentions` finds a "nan" (any case, as a word) in it: a
number a page failed to compute, printed instead of the reason it is missing (a page
glues such a value as missing with its reason, :meth:`lunarcap.report.page.Page.value`).
:func:`check_pages` runs it on every page of a built book; ``python -m
lunarcap.bookbuild.build build`` fails when a page of the quick or the full book says
"nan" (:func:`lunarcap.bookbuild.build.build_book`).
"""

from __future__ import annotations

import re
from html.parser import HTMLParser
from pathlib import Path

#: "nan" as a word, any case ("nan", "NaN", "-nan"); not inside "nanometre" or "Nanjing".
NAN_WORD = re.compile(r"(?<![\w.])[-+]?nan(?![\w])", re.IGNORECASE)
#: Elements whose text is not prose: code, scripts, styles; and the notebooks' code cells.
_SKIP_TAGS = {"script", "style", "pre", "code", "noscript", "template"}
_SKIP_CLASSES = {"cell_input", "highlight"}
_VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta",
         "source", "track", "wbr"}


class _Words(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.stack: list[bool] = []      # per open element: is it skipped?
        self.parts: list[str] = []
        self.in_main = 0

    def handle_starttag(self, tag, attrs):
        if tag in _VOID:
            return
        cls = set((dict(attrs).get("class") or "").split())
        skipped = tag in _SKIP_TAGS or bool(cls & _SKIP_CLASSES)
        self.stack.append(skipped)

    def handle_endtag(self, tag):
        if tag not in _VOID and self.stack:
            self.stack.pop()

    def handle_data(self, data):
        if not any(self.stack):
            self.parts.append(data)


def page_words(html: str) -> str:
    """The text a reader sees on a built page (code cells and code blocks left out).

    >>> page_words('<p>lose <b>20.35</b> m/s</p><pre>x = np.nan</pre>')
    'lose 20.35 m/s'
    """
    w = _Words()
    w.feed(html)
    return " ".join(" ".join(w.parts).split())


def nan_mentions(text: str, context: int = 60) -> list[str]:
    """Each "nan" word in ``text`` with ``context`` characters either side.

    >>> nan_mentions("lose 20.35, nan and NaN m/s; Nanjing, a nanometre", context=4)
    ['35, nan and', 'and NaN m/s']
    >>> nan_mentions("the nominal (12.2 h)")
    []
    """
    return [text[max(m.start() - context, 0): m.end() + context]
            for m in NAN_WORD.finditer(text)]


def check_pages(html_dir: Path, pages) -> dict[str, list[str]]:
    """``{page: [context of each "nan"]}`` of the built pages that say "nan".

    ``pages``: toc files (no extension) below ``html_dir``; a page not built is skipped.
    """
    out = {}
    for page in pages:
        path = Path(html_dir) / f"{page}.html"
        if not path.is_file():
            continue
        found = nan_mentions(page_words(path.read_text(encoding="utf-8")))
        if found:
            out[page] = found
    return out
