"""One module per book page: each builds the page's :class:`lunarcap.report.page.Page`.

The notebooks in ``notebooks/`` call these with their parameters and only show the
result, so everything a page computes is library code, tested in ``tests/report/pages``.
"""
