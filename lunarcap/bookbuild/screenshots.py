"""Look at the built book as a reader would: screenshots and an overflow check in Chromium.

Usage::

    python -m lunarcap.bookbuild.screenshots [--widths 1280 1024] [--pages intro generated/table1]
                                          [--html book/_build/html] [--out book/_build/screenshots]
                                          [--no-screenshots] [--chromium chromium]

Each page of the table of contents (or of ``--pages``) is served from the built site on
127.0.0.1 and opened in headless Chromium at each width, every other host unresolvable, so
the book is read offline. For each page and width it takes a full-page screenshot
(``<out>/<width>/<page>.png``) and finds what a reader would miss: a table, display
formula or page whose content is wider than its scroll box (``scrollWidth`` against
``clientWidth``, after ``_static/lunarcap.js`` has run); a figure shown below
:data:`MIN_FIGURE_SCALE` of its natural width, whose 9 pt text would shrink
(:func:`figure_scale`); a formula MathJax left raw or in error; a request to another
host. It exits with 1 if it finds any, 2 on bad usage or without Chromium, else 0, and
writes the measurements to ``<out>/report.json``.

Chromium is driven through its DevTools protocol over a pipe (``--remote-debugging-pipe``),
so no WebSocket client is needed. ``make screenshots`` runs it.
"""

from __future__ import annotations

import argparse
import base64
import contextlib
import functools
import http.server
import json
import os
import queue
import shutil
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from lunarcap.repro import paths

#: Widths (CSS px) a reader's window is checked at.
DEFAULT_WIDTHS = (1280, 1024)
#: Height (CSS px) of the viewport before the full-page capture.
VIEWPORT_HEIGHT = 900
#: A box overflows when its content is wider than it by more than this (px): sub-pixel
#: rounding of fractional widths.
TOLERANCE_PX = 1
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                  "--no-first-run", "--disable-background-networking",
                  "--disable-component-update", "--disable-sync", "--hide-scrollbars",
                  "--mute-audio", "--remote-debugging-pipe")
#: Seconds to wait for one page to load and typeset.
PAGE_TIMEOUT_S = 60.0
#: A figure shown below this fraction of its natural width (96 CSS px per inch) fails.
MIN_FIGURE_SCALE = 0.8
#: CSS px per inch.
CSS_PX_PER_IN = 96.0

# Runs in the page: waits for MathJax and the fonts, then measures. Returns plain JSON.
MEASURE_JS = r"""
(async () => {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
    await MathJax.startup.promise;
  }
  await document.fonts.ready;
  await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));
  const main = document.querySelector('#main-content') || document.querySelector('main')
               || document.body;
  const scrollBox = (el) => {
    for (let a = el; a && a !== document.body; a = a.parentElement) {
      const ox = getComputedStyle(a).overflowX;
      if (ox === 'auto' || ox === 'scroll' || ox === 'hidden' || ox === 'clip') return a;
    }
    return null;
  };
  const measure = (el, label) => {
    const box = scrollBox(el) || el;
    const r = el.getBoundingClientRect();
    return {label: label.replace(/\s+/g, ' ').trim().slice(0, 90),
            scrollWidth: box.scrollWidth, clientWidth: box.clientWidth,
            width: Math.round(r.width), top: Math.round(r.top + window.scrollY),
            bottom: Math.round(r.bottom + window.scrollY)};
  };
  const tables = [...main.querySelectorAll('table')].map((t, i) => {
    const cap = t.querySelector('caption');
    return {...measure(t, `table ${i + 1}` + (cap ? `: ${cap.innerText}` : '')),
            fitted: ['lc-tight', 'lc-wrap'].filter(c => t.classList.contains(c))};
  });
  // code blocks of the prose (not the folded notebook cells) that scroll: reported only
  const code = [...main.querySelectorAll('div.highlight pre')]
    .filter(p => !p.closest('.cell_input'))
    .map((p, i) => measure(p, `code ${i + 1}: ${p.textContent}`));
  // a displayed formula scrolls in its mjx-container, which the theme's div.math clips:
  // the larger overflow of the two
  const over = (x) => x.scrollWidth - x.clientWidth;
  const math = [...main.querySelectorAll('div.math')].map((m, i) => {
    const label = `math ${i + 1}: ${m.textContent}`, outer = measure(m, label);
    const eq = m.querySelector('mjx-container');
    const inner = eq ? measure(eq, label) : outer;
    // scaled down by the book's lunarcap.js to fit: the ratio to its typeset size
    // (MathJax's own font-size, a percentage of the text's, is kept in data-lc-font-size)
    const typeset = eq && eq.dataset.lcFontSize;
    const scale = typeset && typeset.endsWith('%') && eq.style.fontSize !== typeset
      ? parseFloat(getComputedStyle(eq).fontSize) /
        (parseFloat(getComputedStyle(m).fontSize) * parseFloat(typeset) / 100) : null;
    return {...(over(inner) > over(outer) ? inner : outer), scaled: scale};
  });
  const allMath = [...main.querySelectorAll('.math')];
  const raw = allMath.filter(m => !m.querySelector('mjx-container'))
                     .map(m => m.textContent.trim().slice(0, 60));
  const texErrors = [...main.querySelectorAll('mjx-merror')]
                    .map(e => (e.getAttribute('data-mjx-error') || e.textContent).slice(0, 80));
  await Promise.all([...main.querySelectorAll('img')].map(im => im.complete ? 0 :
    new Promise(r => { im.addEventListener('load', r); im.addEventListener('error', r); })));
  const images = [...main.querySelectorAll('img')].map((im, i) => ({
    label: `figure ${i + 1}: ${im.alt || ''}`.replace(/\s+/g, ' ').trim().slice(0, 90),
    src: im.currentSrc || im.src, naturalWidth: im.naturalWidth,
    shownWidth: Math.round(im.getBoundingClientRect().width)}));
  const de = document.documentElement;
  return {tables, math, code, images, nMath: allMath.length, rawTex: raw, texErrors,
          pageScrollWidth: de.scrollWidth, pageClientWidth: de.clientWidth,
          height: Math.ceil(de.scrollHeight), title: document.title};
})()
"""


# Runs in the page before a screenshot: lets the layout settle (lunarcap.js refits after a
# resize within 100 ms), scrolls everything back to its origin, returns the page height.
SETTLE_JS = r"""
(async () => {
  await new Promise(r => setTimeout(r, 250));
  window.scrollTo(0, 0);
  await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));
  return Math.ceil(document.documentElement.scrollHeight);
})()
"""


# Runs in the page: what a reader sees in the first screen (the viewport, before scrolling):
# its text, and the links wholly inside it. Returns plain JSON.
FIRST_SCREEN_JS = r"""
(async () => {
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) {
    await MathJax.startup.promise;
  }
  await document.fonts.ready;
  await new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)));
  window.scrollTo(0, 0);
  const h = window.innerHeight, w = window.innerWidth;
  const inView = (el) => { const r = el.getBoundingClientRect();
    return r.width > 0 && r.height > 0 && r.top >= 0 && r.bottom <= h && r.left < w; };
  // the page's own text: the article, not the navigation or the page's table of contents
  const main = document.querySelector('article.bd-article') || document.querySelector('main')
               || document.body;
  const blocks = [...main.querySelectorAll('p, li, h1, h2, h3, dt, dd, td, th, .admonition-title')]
    .filter(inView).map(e => e.innerText.replace(/\s+/g, ' ').trim()).filter(t => t);
  const links = [...main.querySelectorAll('a[href]')].filter(inView)
    .map(a => ({text: a.innerText.trim(), href: a.getAttribute('href')}));
  const findings = [...main.querySelectorAll('.lc-findings')].map(e => {
    const r = e.getBoundingClientRect(); return {top: r.top, bottom: r.bottom}; });
  return {height: h, width: w, text: blocks, links, findings};
})()
"""


def first_screen(html: Path, page: str, width: int, height: int, out: Path | None = None,
                 chromium: str = "chromium") -> dict:
    """What the first screen of a built page shows at ``width`` x ``height`` CSS px.

    Serves ``html`` on 127.0.0.1 (every other host unresolvable), opens ``page`` (a toc
    file, no extension) in headless Chromium and returns the text blocks and the links
    lying wholly inside the viewport, in the page's article (not the navigation bars or
    the page's table of contents; :data:`FIRST_SCREEN_JS`); with ``out``, also a
    screenshot of that screen there (PNG). Raises :class:`ChromiumError` if Chromium is
    missing or fails.
    """
    with tempfile.TemporaryDirectory(prefix="lunarcap-chromium-") as profile, \
            serve(html) as base:
        rules = "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"
        dt = DevTools(chromium, profile, extra_flags=(rules,))
        try:
            target = dt.send("Target.createTarget", {"url": "about:blank"})["targetId"]
            session = dt.send("Target.attachToTarget", {"targetId": target,
                                                        "flatten": True})["sessionId"]
            dt.send("Page.enable", session=session)
            dt.send("Emulation.setDeviceMetricsOverride",
                    {"width": width, "height": height, "deviceScaleFactor": 1,
                     "mobile": False}, session=session)
            dt.events(session)
            dt.send("Page.navigate", {"url": f"{base}{page}.html"}, session=session)
            dt.wait_event(session, "Page.loadEventFired")
            res = dt.send("Runtime.evaluate", {"expression": FIRST_SCREEN_JS,
                                               "awaitPromise": True, "returnByValue": True},
                          session=session)
            if "exceptionDetails" in res:
                raise ChromiumError(f"{page}: measuring failed: {res['exceptionDetails']}")
            if out is not None:
                shot = dt.send("Page.captureScreenshot", {"format": "png"}, session=session)
                out.parent.mkdir(parents=True, exist_ok=True)
                out.write_bytes(base64.b64decode(shot["data"]))
            return res["result"]["value"]
        finally:
            dt.close()


def png_dpi(path: Path) -> float | None:
    """The resolution a PNG records (its ``pHYs`` chunk), dots per inch; None if absent.

    matplotlib writes the ``dpi`` a figure was saved at there.
    """
    import struct

    try:
        data = Path(path).read_bytes()
    except OSError:
        return None
    pos = 8  # after the signature
    while pos + 8 <= len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        if kind == b"pHYs" and length == 9:
            ppu_x, _, unit = struct.unpack(">IIB", data[pos + 8:pos + 17])
            return ppu_x * 0.0254 if unit == 1 and ppu_x else None
        if kind in (b"IDAT", b"IEND"):
            return None
        pos += 12 + length
    return None


def figure_scale(shown_px: float, natural_px: float, dpi: float | None) -> float:
    """A figure's shown width over its natural width (96 CSS px per inch of the figure).

    >>> figure_scale(700, 1050, 150)   # a 7 in figure in a 700 px column
    1.0416666666666667
    >>> round(figure_scale(700, 1500, 150), 3)   # a 10 in figure: text shrunk to 73 %
    0.729
    """
    natural_css = natural_px * CSS_PX_PER_IN / (dpi or CSS_PX_PER_IN)
    return shown_px / natural_css if natural_css else float("inf")


def figure_reports(images: list, base: str, html: Path | None) -> list:
    """The measured images with their ``dpi`` (from the file served) and ``scale``."""
    from urllib.parse import unquote, urlparse

    out = []
    for im in images:
        if not im.get("naturalWidth"):
            continue
        path = urlparse(im["src"]).path
        dpi = png_dpi(html / unquote(path).lstrip("/")) if html and path.endswith(".png") else None
        out.append({**im, "dpi": dpi,
                    "scale": figure_scale(im["shownWidth"], im["naturalWidth"], dpi)})
    return out


class ChromiumError(RuntimeError):
    """Chromium is missing, died or did not answer."""


class DevTools:
    """A minimal DevTools-protocol client over ``--remote-debugging-pipe``."""

    def __init__(self, chromium: str, user_data_dir: str, extra_flags=()):
        exe = shutil.which(chromium)
        if exe is None:
            raise ChromiumError(f"{chromium!r} not found (Debian: apt-get install chromium)")
        # the pipe ends Chromium reads (fd 3) and writes (fd 4)
        to_chrome_r, to_chrome_w = os.pipe()
        from_chrome_r, from_chrome_w = os.pipe()

        def child_fds():  # in the child, before exec: our pipe ends become fds 3 and 4
            a, b = os.dup(to_chrome_r), os.dup(from_chrome_w)  # away from 3/4 first
            os.dup2(a, 3)
            os.dup2(b, 4)
            for fd in (a, b):
                if fd not in (3, 4):
                    os.close(fd)

        cmd = [exe, *CHROMIUM_FLAGS, f"--user-data-dir={user_data_dir}", *extra_flags,
               "about:blank"]
        self.proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, preexec_fn=child_fds,
                                     close_fds=False)
        os.close(to_chrome_r)
        os.close(from_chrome_w)
        self._out = os.fdopen(to_chrome_w, "wb", buffering=0)
        self._in = os.fdopen(from_chrome_r, "rb", buffering=0)
        self._next_id = 0
        self._replies: dict[int, queue.Queue] = {}
        self._events: dict[str | None, list] = {}
        self._lock = threading.Lock()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        buf = b""
        while True:
            chunk = self._in.read(1 << 16)
            if not chunk:
                break
            buf += chunk
            *messages, buf = buf.split(b"\0")
            for raw in messages:
                msg = json.loads(raw)
                with self._lock:
                    if "id" in msg and msg["id"] in self._replies:
                        self._replies[msg["id"]].put(msg)
                    elif "method" in msg:
                        self._events.setdefault(msg.get("sessionId"), []).append(msg)
        with self._lock:
            for q in self._replies.values():
                q.put({"error": {"message": "Chromium closed the DevTools pipe"}})

    def send(self, method: str, params: dict | None = None, session: str | None = None,
             timeout: float = PAGE_TIMEOUT_S) -> dict:
        """Send one command and return its result (raises ChromiumError on an error)."""
        with self._lock:
            self._next_id += 1
            mid = self._next_id
            self._replies[mid] = q = queue.Queue()
        msg = {"id": mid, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        self._out.write(json.dumps(msg).encode() + b"\0")
        try:
            reply = q.get(timeout=timeout)
        except queue.Empty:
            raise ChromiumError(f"no answer to {method} within {timeout:g} s") from None
        finally:
            with self._lock:
                self._replies.pop(mid, None)
        if "error" in reply:
            raise ChromiumError(f"{method}: {reply['error'].get('message')}")
        return reply.get("result", {})

    def events(self, session: str | None) -> list:
        """Take the events received so far for a session."""
        with self._lock:
            return self._events.pop(session, [])

    def wait_event(self, session: str, method: str, timeout: float = PAGE_TIMEOUT_S) -> list:
        """Wait for an event; return every event of the session received until then."""
        seen, t_end = [], time.monotonic() + timeout
        while time.monotonic() < t_end:
            seen += self.events(session)
            if any(e["method"] == method for e in seen):
                return seen
            if self.proc.poll() is not None:
                raise ChromiumError(f"Chromium exited with status {self.proc.returncode}")
            time.sleep(0.02)
        raise ChromiumError(f"no {method} within {timeout:g} s")

    def close(self) -> None:
        """Close the browser (killed after 10 s) and the pipe."""
        with contextlib.suppress(Exception):
            self.send("Browser.close", timeout=5)
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for f in (self._out, self._in):
            with contextlib.suppress(OSError):
                f.close()


@dataclass
class PageReport:
    """What one page showed at one width."""

    page: str
    width: int
    tables: list = field(default_factory=list)
    math: list = field(default_factory=list)
    n_math: int = 0
    raw_tex: list = field(default_factory=list)
    tex_errors: list = field(default_factory=list)
    page_overflow_px: int = 0
    remote: list = field(default_factory=list)
    screenshot: Path | None = None
    height: int = 0
    code: list = field(default_factory=list)
    figures: list = field(default_factory=list)   # from figure_reports

    @staticmethod
    def _over(items):
        return [t for t in items if t["scrollWidth"] - t["clientWidth"] > TOLERANCE_PX]

    @property
    def table_overflows(self) -> list:
        """The tables whose content is wider than their box."""
        return self._over(self.tables)

    @property
    def math_overflows(self) -> list:
        """The displayed formulas wider than their box."""
        return self._over(self.math)

    @property
    def code_overflows(self) -> list:
        """The code blocks of the prose that scroll sideways (reported, not a failure)."""
        return self._over(self.code)

    @property
    def small_figures(self) -> list:
        """The figures shown below :data:`MIN_FIGURE_SCALE` of their natural width."""
        return [f for f in self.figures if f["scale"] < MIN_FIGURE_SCALE]

    @property
    def ok(self) -> bool:
        """Nothing overflows or is shrunk, every formula is typeset, nothing is remote."""
        return not (self.table_overflows or self.math_overflows or self.raw_tex
                    or self.tex_errors or self.page_overflow_px > TOLERANCE_PX or self.remote
                    or self.small_figures)

    def lines(self) -> list[str]:
        """One summary line, then one indented line per problem."""
        worst = max([t["scrollWidth"] - t["clientWidth"] for t in self.tables] + [0])
        fitted = sum(bool(t.get("fitted")) for t in self.tables)
        scaled = sum(bool(t.get("scaled")) for t in self.math)
        head = (f"{'ok  ' if self.ok else 'FAIL'} {self.width:5d} px  {self.page:32s} "
                f"tables {len(self.tables):2d} (overflowing {len(self.table_overflows)}, "
                f"worst {worst:+d} px, fitted {fitted})  math {self.n_math:3d} "
                f"(raw {len(self.raw_tex)}, errors {len(self.tex_errors)}, overflowing "
                f"{len(self.math_overflows)}, scaled {scaled})  figures {len(self.figures)}"
                + (f" (smallest {min(f['scale'] for f in self.figures):.0%} of natural width, "
                   f"below {MIN_FIGURE_SCALE:.0%}: {len(self.small_figures)})"
                   if self.figures else "")
                + (f"  [{len(self.code_overflows)} code blocks scroll]"
                   if self.code_overflows else ""))
        out = [head]
        for t in self.table_overflows + self.math_overflows:
            out.append(f"       {t['label'][:70]!r}: content {t['scrollWidth']} px in a "
                       f"{t['clientWidth']} px box ({t['scrollWidth'] - t['clientWidth']:+d})")
        out += [f"       {f['label'][:70]!r}: shown {f['shownWidth']} px, natural "
                f"{f['naturalWidth'] * CSS_PX_PER_IN / (f['dpi'] or CSS_PX_PER_IN):.0f} px "
                f"({f['scale']:.0%})" for f in self.small_figures]
        out += [f"       raw TeX: {t!r}" for t in self.raw_tex[:5]]
        out += [f"       TeX error: {t!r}" for t in self.tex_errors[:5]]
        if self.page_overflow_px > TOLERANCE_PX:
            out.append(f"       the page scrolls sideways by {self.page_overflow_px} px")
        out += [f"       remote request: {u}" for u in self.remote[:5]]
        return out


class _QuietHandler(http.server.SimpleHTTPRequestHandler):
    def log_message(self, *args):  # no access log on stderr
        pass


@contextlib.contextmanager
def serve(directory: Path):
    """Serve ``directory`` on 127.0.0.1 (a free port); yields the base URL."""
    handler = functools.partial(_QuietHandler, directory=str(directory))
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), handler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield f"http://127.0.0.1:{server.server_address[1]}/"
    finally:
        server.shutdown()
        server.server_close()


def _local(url: str, base: str) -> bool:
    return url.startswith((base, "data:", "blob:", "about:", "chrome:", "devtools:"))


def check_page(dt: DevTools, base: str, page: str, width: int, out_dir: Path | None,
               html: Path | None = None) -> PageReport:
    """Open ``page`` (a toc file, no extension) at ``width`` px, measure, screenshot.

    ``html``: the directory served, where each figure's PNG is read for its resolution.
    """
    target = dt.send("Target.createTarget", {"url": "about:blank"})["targetId"]
    session = dt.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
    try:
        for domain in ("Page", "Network"):
            dt.send(f"{domain}.enable", session=session)
        dt.send("Emulation.setDeviceMetricsOverride",
                {"width": width, "height": VIEWPORT_HEIGHT, "deviceScaleFactor": 1,
                 "mobile": False}, session=session)
        dt.events(session)
        dt.send("Page.navigate", {"url": f"{base}{page}.html"}, session=session)
        events = dt.wait_event(session, "Page.loadEventFired")
        res = dt.send("Runtime.evaluate", {"expression": MEASURE_JS, "awaitPromise": True,
                                           "returnByValue": True}, session=session)
        if "exceptionDetails" in res:
            raise ChromiumError(f"{page}: measuring failed: {res['exceptionDetails']}")
        m = res["result"]["value"]
        events += dt.events(session)
        remote = sorted({e["params"]["request"]["url"] for e in events
                         if e["method"] == "Network.requestWillBeSent"
                         and not _local(e["params"]["request"]["url"], base)})
        rep = PageReport(page, width, m["tables"], m["math"], m["nMath"], m["rawTex"],
                         m["texErrors"], m["pageScrollWidth"] - m["pageClientWidth"], remote,
                         None, m["height"], m["code"],
                         figure_reports(m.get("images", []), base, html))
        if out_dir is not None:
            # full page: a viewport as tall as the page, then an ordinary capture (Chromium's
            # captureBeyondViewport sometimes shifted the page sideways mid-capture)
            height = m["height"]
            for _ in range(3):  # the page may grow a little in a taller window
                dt.send("Emulation.setDeviceMetricsOverride",
                        {"width": width, "height": height, "deviceScaleFactor": 1,
                         "mobile": False}, session=session)
                now = dt.send("Runtime.evaluate", {"expression": SETTLE_JS, "awaitPromise": True,
                                                   "returnByValue": True},
                              session=session)["result"]["value"]
                if now <= height:
                    break
                height = now
            shot = dt.send("Page.captureScreenshot",
                           {"format": "png", "clip": {"x": 0, "y": 0, "width": width,
                                                      "height": height, "scale": 1}},
                           session=session)
            path = out_dir / str(width) / f"{page}.png"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(base64.b64decode(shot["data"]))
            rep.screenshot = path
        return rep
    finally:
        with contextlib.suppress(ChromiumError):
            dt.send("Target.closeTarget", {"targetId": target}, timeout=10)


def run(pages, widths, html: Path, out_dir: Path | None, chromium: str = "chromium",
        echo=print) -> list[PageReport]:
    """Check every page at every width (see the module docstring); returns the reports."""
    reports = []
    with tempfile.TemporaryDirectory(prefix="lunarcap-chromium-") as profile, serve(html) as base:
        # every host but the book's server is unresolvable: the book is read offline
        rules = "--host-resolver-rules=MAP * ~NOTFOUND, EXCLUDE 127.0.0.1"
        dt = DevTools(chromium, profile, extra_flags=(rules,))
        try:
            for width in widths:
                for page in pages:
                    rep = check_page(dt, base, page, width, out_dir, html)
                    reports.append(rep)
                    for line in rep.lines():
                        echo(line)
        finally:
            dt.close()
    return reports


def main(argv=None) -> int:
    """Command line (see the module docstring); returns the exit status."""
    from lunarcap.bookbuild.build import toc_files

    ap = argparse.ArgumentParser(prog="python -m lunarcap.bookbuild.screenshots",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--widths", type=int, nargs="+", default=list(DEFAULT_WIDTHS),
                    help="window widths, CSS px (default: 1280 1024)")
    ap.add_argument("--pages", nargs="+", help="toc files to check (default: every page)")
    ap.add_argument("--html", type=Path, default=paths.HTML, help="the built site")
    ap.add_argument("--out", type=Path, default=paths.BUILD / "screenshots",
                    help="output folder: <out>/<width>/<page>.png and <out>/report.json")
    ap.add_argument("--no-screenshots", action="store_true", help="measure only")
    ap.add_argument("--chromium", default="chromium", help="Chromium executable")
    args = ap.parse_args(argv)
    prog = ap.prog
    pages = args.pages or toc_files()
    missing = [p for p in pages if not (args.html / f"{p}.html").is_file()]
    if missing:
        print(f"{prog}: error: not built: {', '.join(missing)} (in {args.html}; run "
              "`make book` first)", file=sys.stderr)
        return 2
    if any(w < 320 for w in args.widths):
        print(f"{prog}: error: widths must be at least 320 px", file=sys.stderr)
        return 2
    try:
        reports = run(pages, args.widths, args.html,
                      None if args.no_screenshots else args.out, args.chromium)
    except ChromiumError as e:
        print(f"{prog}: error: {e}", file=sys.stderr)
        return 2
    bad = [r for r in reports if not r.ok]
    args.out.mkdir(parents=True, exist_ok=True)
    summary = args.out / "report.json"
    summary.write_text(json.dumps([dict(vars(r), screenshot=str(r.screenshot or ""), ok=r.ok)
                                   for r in reports], indent=1), encoding="utf-8")
    print(f"{len(reports) - len(bad)} of {len(reports)} page views fit; measurements in "
          f"{summary}" + ("" if args.no_screenshots else ", screenshots beside it"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
