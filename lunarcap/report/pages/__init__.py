"""One module per book page: each builds the page's :class:`lunarcap.report.page.Page`.

A notebook computes its result with lunarcap's public API (``import lunarcap``) and hands
it to its page module, which only formats it (tables, figures, glued values, captions,
provenance, checks); the few pages with no public call yet are built from their
parameters (``tests/report/test_notebooks_public_api.py`` lists them). Everything a page
computes is library code, tested in ``tests/report/pages``.
Each page module declares its notebook, the executions of it the book makes and its place
in the table of contents (``BOOK``, a :class:`lunarcap.report.contents.BookPage`);
:data:`PAGES` registers it, which is all the book's build reads
(:mod:`lunarcap.report.contents`). A new page ``x`` is ``pages/x.py`` (``NOTEBOOK``,
``BOOK``, ``build``), ``notebooks/x.ipynb`` (a parameters cell, the public calls,
``x.build(...)``, the ``show`` calls) and the line ``"x",`` below; a figure only it draws goes in
``lunarcap/report/figures/x.py``.
"""

#: The book's page modules, one line each; their executions are listed to the build in
#: this order (which breaks ties when it chooses what to run next).
PAGES = (
    "fig1_geometry",
    "impulsive_baseline",
    "lunar_pole",
    "sweep",
    "summary",
    "verification",
    "trade_study",
    "capture_sequence",
    "reproduction_report",
    "free_ignition",
    "steering_laws",
    "joint_capture",
    "other_engines",
    "real_missions",
    "burn_count",
    "missed_thrust",
    "dispersions",
    "capture_plan",
    "kplo_capture",
    "exchange",
    "real_moon",
    "gmat_flight",
    "findings",
    "tutorial",
    "glossary",
)
