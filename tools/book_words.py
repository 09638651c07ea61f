"""Count the words of the built book as a reader sees them, page by page.

Usage (from the repository root)::

    .venv/bin/python tools/book_words.py [--html book/_build/html] [--limit 45000]

A word is a whitespace-separated token of the text a reader sees on a built HTML page:
prose, headings, tables, captions and cell outputs, without the notebooks' code cells,
code blocks, scripts and styles (:func:`lunarcap.bookbuild.bookcheck.page_words`), and
without the theme's navigation (the sidebar, the header bar, the page's table of contents
and the previous/next links), which a reader skips. Only the pages of the table of contents
count (``index``, ``model``, ``rerun``, ``references`` and ``generated/*``); Sphinx's
``search`` and ``genindex`` pages are left out. It prints one line per page, largest first,
and the total; it exits with 1 when the total is above ``--limit`` (issue 36 item 5: the
book under 45,000 words, from about 73,000). ``--captions`` lists instead every table or
figure caption longer than :data:`CAPTION_CHARS` characters (about 3 lines at 1280 px).
``--split`` prints each page's words in three parts: tables (their cells and captions),
equations (the TeX source MathJax renders, one "word" per token) and the rest, its prose.
A table's cells are looked up, not read through, and the full book's tables have more rows
than the quick book's; an equation is not words at all; so the three answer different
questions.
"""

from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

from lunarcap.bookbuild.bookcheck import page_words

#: Sphinx pages that are not the book's pages.
NOT_PAGES = {"search", "genindex", "py-modindex"}
#: Where the theme (sphinx-book-theme 1.x) puts a page's own content.
MAIN_OPEN = '<main id="main-content"'
MAIN_CLOSE = "</main>"
#: The theme's navigation inside <main>: the page's own table of contents and the
#: previous/next links, not part of what the page says.
NAV_MARKERS = ('<div class="bd-sidebar-secondary', '<footer class="prev-next-footer',
               '<div class="prev-next-area', '<nav class="bd-toc-nav')


#: A caption longer than this many characters of text takes more than about 3 lines of the
#: book's text column at 1280 px (measured: about 100 characters a line).
CAPTION_CHARS = 300
#: A table's or figure's caption as Sphinx writes it.
CAPTION = re.compile(r"<(figcaption|caption)\b.*?</\1>", re.S)
#: A table as Sphinx and pandas write it (the book's tables are not nested).
TABLE = re.compile(r"<table\b.*?</table>", re.S)
#: An equation as Sphinx writes it for MathJax (inline or display), outside tables.
MATH = re.compile(r'<(span|div) class="math\b[^"]*"[^>]*>.*?</\1>', re.S)


def long_captions(html: str, limit: int = CAPTION_CHARS) -> list[str]:
    """The captions of a built page whose text is longer than ``limit`` characters.

    >>> long_captions('<caption>' + 'x' * 301 + '</caption><figcaption>ok</figcaption>')[0][:5]
    'xxxxx'
    """
    return [text for m in CAPTION.finditer(html)
            if len(text := page_words(m.group(0))) > limit]


def main_html(html: str) -> str:
    """The part of a built page that is its content (<main>, its navigation cut off).

    >>> main_html('<nav>x</nav><main id="main-content" class="a"><p>y</p>'
    ...           '<footer class="prev-next-footer">next</footer></main>')
    '<main id="main-content" class="a"><p>y</p>'
    """
    start = html.find(MAIN_OPEN)
    if start < 0:
        return html
    body = html[start:]
    end = body.find(MAIN_CLOSE)
    body = body if end < 0 else body[:end]
    cuts = [i for i in (body.find(m) for m in NAV_MARKERS) if i > 0]
    return body[:min(cuts)] if cuts else body


def count_words(html: str) -> int:
    """Words a reader reads on one built page.

    >>> count_words('<main id="main-content"><p>lose <b>20.35</b> m/s</p>'
    ...             '<pre>x = 1</pre></main>')
    3
    """
    return len(page_words(main_html(html)).split())


def _words(html: str) -> int:
    return len(page_words(html).split())


def split_words(html: str) -> tuple[int, int, int]:
    r"""``(prose, tables, math)``: the words of one built page outside tables and equations,
    inside its tables, and in its equations outside tables.

    The three add up to :func:`count_words`.

    >>> split_words('<main id="main-content"><p>We lose 13.39 m/s, '
    ...             '<span class="math notranslate">\\(J_2\\)</span>.</p>'
    ...             '<table><caption>LOI 1</caption><tr><td>13.39</td></tr></table></main>')
    (5, 3, 1)
    """
    main = main_html(html)
    tables = sum(_words(m.group(0)) for m in TABLE.finditer(main))
    rest = TABLE.sub(" ", main)
    math = sum(_words(m.group(0)) for m in MATH.finditer(rest))
    return _words(MATH.sub(" ", rest)), tables, math


def _pages(html_dir: Path):
    """``(page, path)`` of every page of the table of contents built below ``html_dir``."""
    for path in sorted(Path(html_dir).rglob("*.html")):
        page = path.relative_to(html_dir).with_suffix("").as_posix()
        if page in NOT_PAGES or page.startswith(("_", "jupyter_execute")):
            continue
        yield page, path


def book_words(html_dir: Path) -> dict[str, int]:
    """``{page: words}`` for every page of the built book below ``html_dir``."""
    return {page: count_words(path.read_text(encoding="utf-8"))
            for page, path in _pages(html_dir)}


def book_split(html_dir: Path) -> dict[str, tuple[int, int, int]]:
    """``{page: (prose, tables, math)}`` for every page of the built book
    (:func:`split_words`)."""
    return {page: split_words(path.read_text(encoding="utf-8"))
            for page, path in _pages(html_dir)}


def _print_split(html_dir: Path) -> int:
    split = book_split(html_dir)
    print(f"{'prose':>7} {'tables':>7} {'math':>7} {'total':>7}  page")
    rows = sorted(split.items(), key=lambda kv: -sum(kv[1]))
    rows.append((f"total ({len(split)} pages)",
                 tuple(sum(v[i] for v in split.values()) for i in range(3))))
    for page, parts in rows:
        print("".join(f"{n:7d} " for n in parts) + f"{sum(parts):7d}  {page}")
    return 0


def main(argv=None) -> int:
    """Print the words per page and the total; 1 if the total exceeds ``--limit``."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--html", type=Path, default=Path("book/_build/html"))
    ap.add_argument("--limit", type=int, default=45000)
    ap.add_argument("--captions", action="store_true",
                    help=f"list the captions longer than {CAPTION_CHARS} characters")
    ap.add_argument("--split", action="store_true",
                    help="print each page's words in prose and in tables apart")
    args = ap.parse_args(argv)
    if args.split:
        return _print_split(args.html)
    if args.captions:
        found = [(path, c) for path in sorted(Path(args.html).rglob("*.html"))
                 for c in long_captions(path.read_text(encoding="utf-8"))]
        for path, c in found:
            print(f"{len(c):5d}  {path.relative_to(args.html)}: {c[:90]}")
        print(f"{len(found)} captions over {CAPTION_CHARS} characters")
        return 0 if not found else 1
    words = book_words(args.html)
    if not words:
        print(f"no built pages under {args.html}", file=sys.stderr)
        return 2
    for page, n in sorted(words.items(), key=lambda kv: -kv[1]):
        print(f"{n:7d}  {page}")
    total = sum(words.values())
    print(f"{total:7d}  total ({len(words)} pages; limit {args.limit})")
    return 0 if total <= args.limit else 1


if __name__ == "__main__":
    sys.exit(main())
