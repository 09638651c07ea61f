"""Sphinx extension of the book: author-year citations and references-page labels.

sphinxcontrib-bibtex's ``author_year`` style writes "Song et al. [2011]"; the book (like
the paper) writes "Song et al. (2011)" and "(Song et al. 2011)". This module registers
the referencing style ``author_year_round`` (``bibtex_reference_style`` in
``book/_config.yml``): the same style with round brackets and no comma between author
and year. The references page lists each work under the label the text cites it by
("Song et al. (2011)", not "[1]"): the formatting style :data:`FORMAT_STYLE_NAME`
(``bibtex_default_style``), pybtex's ``plain`` with the labels of
:func:`author_year_label`.

Loaded by ``book/_config.yml`` (``sphinx: extra_extensions``), before
sphinxcontrib-bibtex reads its configuration.
"""

from __future__ import annotations

from dataclasses import dataclass, field

#: Name of the referencing style registered here.
STYLE_NAME = "author_year_round"
#: Name of the formatting style (the references page's labels) registered here.
FORMAT_STYLE_NAME = "lunarcap_author_year"


def author_year_label(last_names: list[str], year: str) -> str:
    """The label a work is cited by, as the text cites it.

    "Robbins (1966)", "Vallado and McClain (2007)", "Song et al. (2011)" (three authors or
    more).

    >>> author_year_label(["Song", "Park", "Kim"], "2009c"), author_year_label(["Betts"], "2010")
    ('Song et al. (2009c)', 'Betts (2010)')
    >>> author_year_label(["Vallado", "McClain"], "2007")
    'Vallado and McClain (2007)'
    """
    names = (last_names[0] if len(last_names) == 1 else
             " and ".join(last_names) if len(last_names) == 2 else f"{last_names[0]} et al.")
    return f"{names} ({year})"


def _entry_label(entry) -> str:
    persons = entry.persons.get("author") or entry.persons.get("editor") or []
    last = [" ".join(p.last_names).replace("{", "").replace("}", "") for p in persons]
    if not last:  # an organisation as author: its name as written
        last = [entry.fields.get("organization", entry.key).strip("{}")]
    return author_year_label(last, entry.fields.get("year", "n.d."))


def format_style_class():
    """The ``plain`` formatting style of pybtex with author-year labels.

    The labels are :func:`author_year_label`'s.
    """
    from pybtex.plugin import register_plugin
    from pybtex.style.formatting.plain import Style as Plain
    from pybtex.style.labels import BaseLabelStyle

    class AuthorYearLabels(BaseLabelStyle):
        def format_labels(self, sorted_entries):
            for entry in sorted_entries:
                yield _entry_label(entry)

    register_plugin("pybtex.style.labels", FORMAT_STYLE_NAME, AuthorYearLabels, force=True)

    class AuthorYearStyle(Plain):
        default_label_style = FORMAT_STYLE_NAME

    return AuthorYearStyle


def _round():
    from sphinxcontrib.bibtex.style.referencing import BracketStyle

    return BracketStyle(left="(", right=")")


def round_style_class():
    """The referencing style class: author-year with round brackets."""
    from sphinxcontrib.bibtex.style.referencing.author_year import AuthorYearReferenceStyle

    @dataclass
    class RoundAuthorYearReferenceStyle(AuthorYearReferenceStyle):
        bracket_parenthetical: object = field(default_factory=_round)
        bracket_textual: object = field(default_factory=_round)
        bracket_author: object = field(default_factory=_round)
        bracket_label: object = field(default_factory=_round)
        bracket_year: object = field(default_factory=_round)
        author_year_sep: object = " "

    return RoundAuthorYearReferenceStyle


def setup(app) -> dict:
    """Register :data:`STYLE_NAME` with sphinxcontrib-bibtex."""
    from sphinxcontrib.bibtex.plugin import register_plugin

    register_plugin("sphinxcontrib.bibtex.style.referencing", STYLE_NAME,
                    round_style_class(), force=True)
    from pybtex.plugin import register_plugin as register_pybtex

    register_pybtex("pybtex.style.formatting", FORMAT_STYLE_NAME, format_style_class(),
                    force=True)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
