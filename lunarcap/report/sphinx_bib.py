"""Sphinx extension of the book: author-year citations in round brackets.

sphinxcontrib-bibtex's ``author_year`` style writes "Song et al. [2011]"; the book (like
the paper) writes "Song et al. (2011)" and "(Song et al. 2011)". This module registers
the referencing style ``author_year_round`` (``bibtex_reference_style`` in
``book/_config.yml``): the same style with round brackets and no comma between author
and year.

Loaded by ``book/_config.yml`` (``sphinx: extra_extensions``), before
sphinxcontrib-bibtex reads its configuration.
"""

from __future__ import annotations

from dataclasses import dataclass, field

#: Name of the referencing style registered here.
STYLE_NAME = "author_year_round"


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
    return {"parallel_read_safe": True, "parallel_write_safe": True}
