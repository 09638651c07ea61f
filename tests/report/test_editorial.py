"""Editorial checks of the book (issue 36 item 5): provenance once per page, words counted.

The notebook and parameters that made a page are named once, in its provenance block
(:meth:`lunarcap.report.page.Page.header`), not under each of its tables and figures; the
book's words are counted as a reader sees them (``tools/book_words.py``).
"""

import importlib.util
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

from lunarcap.report.page import Page
from lunarcap.repro import paths

ROOT = Path(__file__).resolve().parents[2]


def _tool(name):
    spec = importlib.util.spec_from_file_location(name, ROOT / "tools" / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_a_pages_tables_and_figures_do_not_repeat_its_provenance(tmp_path, monkeypatch):
    gen = tmp_path / "generated"
    monkeypatch.setattr(paths, "GENERATED", gen)
    monkeypatch.setattr(paths, "TABLES", gen / "tables")
    monkeypatch.setattr(paths, "FIGURES", gen / "figures")
    page = Page("notebooks/x.ipynb", {"plans": ["song2011-150N"], "sigmas": {"a": 1}}, "x")
    page.table("t", pd.DataFrame({"dv_mps": [1.0]}), "Delta-V (m/s).")
    fig, ax = plt.subplots()
    ax.plot([0, 1], [0, 1])
    page.figure("f", fig, "A line (km).")
    shown = page.show("t", display=False) + page.show("f", display=False)
    assert "Made by" not in shown and "song2011-150N" not in shown
    assert "{download}`x_t.csv" in shown and "{download}`PNG" in shown  # the data stay
    header = page.header(display=False)
    assert header.count("notebooks/x.ipynb") == 1 and "song2011-150N" in header


def test_words_are_counted_in_the_pages_content_only(tmp_path):
    words = _tool("book_words")
    html = ('<html><nav class="bd-sidebar">Home Table 1 Table 2</nav>'
            '<main id="main-content" class="bd-main"><h1>LOI 1</h1>'
            '<p>We lose <b>13.39</b> m/s.</p><div class="cell_input"><pre>x = 1</pre></div>'
            '<footer class="prev-next-footer">previous next</footer></main></html>')
    assert words.count_words(html) == 6           # "LOI 1 We lose 13.39 m/s."
    (tmp_path / "generated").mkdir()
    (tmp_path / "generated" / "a.html").write_text(html, encoding="utf-8")
    (tmp_path / "search.html").write_text(html, encoding="utf-8")
    assert words.book_words(tmp_path) == {"generated/a": 6}
    assert words.main(["--html", str(tmp_path), "--limit", "6"]) == 0
    assert words.main(["--html", str(tmp_path), "--limit", "5"]) == 1


def test_the_exchange_captions_burn_colours_are_the_ones_drawn():
    import numpy as np
    from matplotlib.colors import to_hex

    from lunarcap.report.figstyle import colour_name
    from lunarcap.report.figures import exchange as draw

    t = np.linspace(0.0, 1.0, 5)
    arc = np.vstack([2000 * np.cos(t), 2000 * np.sin(t), 0 * t])
    arcs = [("approach", arc, False)]
    for n in (1, 2, 3):
        arcs += [(f"burn {n}", arc, True), (f"coast {n}", arc, False)]
    fig = draw.plot_exported_trajectory(arcs, 1738.2)
    drawn = [colour_name(to_hex(line.get_color())) for line in fig.axes[0].lines
             if line.get_linewidth() == 3.0]
    plt.close(fig)
    assert len(drawn) == 3
    assert draw.burn_colour_words(3).endswith(f"in {drawn[0]}, {drawn[1]} and {drawn[2]}")


def test_captions_over_three_lines_are_listed(tmp_path):
    words = _tool("book_words")
    long, short = "Delta-V (m/s) " * 25, "Delta-V (m/s)."
    page = (f'<main id="main-content"><figure><figcaption><p>{long}</p></figcaption></figure>'
            f'<table><caption>{short}</caption></table></main>')
    assert [len(c) for c in words.long_captions(page)] == [len(long.strip())]
    (tmp_path / "a.html").write_text(page, encoding="utf-8")
    assert words.main(["--html", str(tmp_path), "--captions"]) == 1
    (tmp_path / "a.html").write_text(page.replace(long, short), encoding="utf-8")
    assert words.main(["--html", str(tmp_path), "--captions"]) == 0


def test_words_in_tables_and_equations_are_counted_apart_from_the_prose(tmp_path, capsys):
    words = _tool("book_words")
    html = ('<main id="main-content"><h1>LOI 1</h1><p>We lose 13.39 m/s.</p>'
            '<table><caption>Losses (m/s).</caption><tr><th>LOI</th><th>loss</th></tr>'
            '<tr><td>1</td><td>13.39</td></tr></table><p>Then LOI 2 under '
            '<span class="math notranslate nohighlight">\\(J_2 + \\mu\\)</span>.</p>'
            '<div class="math notranslate nohighlight">\\[ J = \\Delta V \\]</div></main>')
    # prose: "LOI 1 We lose 13.39 m/s. Then LOI 2 under ."; math: "\\(J_2 + \\mu\\)" and
    # "\\[ J = \\Delta V \\]", delimiters included
    assert words.split_words(html) == (11, 6, 9)
    assert sum(words.split_words(html)) == words.count_words(html)
    (tmp_path / "a.html").write_text(html, encoding="utf-8")
    assert words.main(["--html", str(tmp_path), "--split"]) == 0
    assert capsys.readouterr().out.splitlines()[-1].split()[:4] == ["11", "6", "9", "26"]
