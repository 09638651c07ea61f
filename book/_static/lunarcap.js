/* lunarcap book: make wide tables and displayed equations fit the text column.
 *
 * Loaded on every page by jupyter-book (every .js file of book/_static is). Without it
 * (no JavaScript) a wide table or equation scrolls sideways, as the theme makes it.
 *
 * A table wider than its scroll box (the theme's .pst-scrollable-table-container) first
 * gets tighter cells and a smaller font (class lc-tight), then, if still too wide, lets
 * long words of its text cells break (class lc-wrap); tables that fit are left alone.
 * A displayed equation wider than the column is scaled down, to no less than
 * MIN_MATH_SCALE of its size; beyond that it scrolls. Run once the page, its fonts and
 * MathJax's typesetting are ready, and again when the window is resized.
 * `make screenshots` (lunarcap.report.screenshots) measures the result in Chromium.
 */
(function () {
  "use strict";
  var MIN_MATH_SCALE = 0.8;

  function overflows(el) {
    return el.scrollWidth > el.clientWidth + 1;
  }

  // a cell that holds a number (digits, signs, separators, a unit or two): it never
  // breaks, even in a table whose text cells may (lc-wrap)
  var NUMBER = /^[\s\u2212+\-]*[\d.,\u2009]+[\d.,\s%\u00b3\u00b2a-zA-Z\/\u2212+\-]{0,12}$/;

  function markNumbers(table) {
    table.querySelectorAll("td").forEach(function (td) {
      if (NUMBER.test(td.textContent.trim())) td.classList.add("lc-num");
    });
  }

  function fitTables() {
    document.querySelectorAll("table.table").forEach(function (table) {
      var box = table.closest(".pst-scrollable-table-container") || table.parentElement;
      table.classList.remove("lc-tight", "lc-wrap");
      markNumbers(table);
      if (overflows(box)) table.classList.add("lc-tight");
      if (overflows(box)) table.classList.add("lc-wrap");
    });
  }

  function fitMath() {
    document.querySelectorAll("div.math > mjx-container").forEach(function (eq) {
      if (eq.dataset.lcFontSize === undefined) eq.dataset.lcFontSize = eq.style.fontSize;
      eq.style.fontSize = eq.dataset.lcFontSize;
      // a tagged equation has a min-width (in em) wider than the block, which clips it
      // (div.math); an untagged one scrolls inside its mjx-container
      var box = eq.parentElement;
      var full = parseFloat(getComputedStyle(eq).fontSize);
      for (var i = 0; i < 4 && (overflows(box) || overflows(eq)); i++) {
        var size = parseFloat(getComputedStyle(eq).fontSize);
        var room = Math.min(box.clientWidth / box.scrollWidth, eq.clientWidth / eq.scrollWidth);
        var next = Math.max(MIN_MATH_SCALE * full, size * room);
        if (!(next < size)) break;
        eq.style.fontSize = next + "px";
      }
    });
  }

  function fit() {
    fitTables();
    fitMath();
  }

  var pending = null;
  window.addEventListener("resize", function () {
    clearTimeout(pending);
    pending = setTimeout(fit, 100);
  });
  // MathJax (loaded deferred, after this script) reads window.MathJax as its
  // configuration: fit again once it has typeset the page.
  var config = (window.MathJax = window.MathJax || {});
  config.startup = config.startup || {};
  config.startup.pageReady = function () {
    return window.MathJax.startup.defaultPageReady().then(fit);
  };
  // The search page's summaries are cut from each page's text, where a formula is still
  // its TeX source (\(\Delta V\), \begin{aligned} ...): shown as plain text instead.
  var SYMBOLS = {Delta: "Δ", delta: "δ", mu: "μ", omega: "ω", Omega: "Ω", alpha: "α",
                 beta: "β", gamma: "γ", nu: "ν", theta: "θ", pi: "π", sum: "Σ", le: "≤",
                 ge: "≥", leq: "≤", geq: "≥", times: "×", cdot: "·", mp: "∓", pm: "±",
                 infty: "∞", approx: "≈", lVert: "‖", rVert: "‖", imath: "i", sqrt: "√",
                 partial: "∂", quad: " ", qquad: " "};

  function plainTex(s) {
    return s.replace(/\\[()\[\]]/g, "")
      .replace(/\\(begin|end|tag|label)\{[^{}]*\}/g, " ")
      .replace(/\\\\/g, " ")
      .replace(/\\([A-Za-z]+)/g, function (m, name) {
        return SYMBOLS[name] !== undefined ? SYMBOLS[name] : "";
      })
      .replace(/[{}&]/g, "")
      .replace(/\s+/g, " ");
  }

  function plainSearchSummaries() {
    var box = document.getElementById("search-results");
    if (!box || !window.MutationObserver) return;
    var clean = function () {
      box.querySelectorAll("p.context").forEach(function (p) {
        if (p.dataset.lcPlain) return;
        p.dataset.lcPlain = "1";
        var walk = document.createTreeWalker(p, NodeFilter.SHOW_TEXT);
        for (var n = walk.nextNode(); n; n = walk.nextNode()) n.nodeValue = plainTex(n.nodeValue);
      });
    };
    new MutationObserver(clean).observe(box, {childList: true, subtree: true});
  }

  document.addEventListener("DOMContentLoaded", function () {
    plainSearchSummaries();
    fit();
    if (document.fonts && document.fonts.ready) document.fonts.ready.then(fit);
  });
  window.addEventListener("load", fit);
})();
