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

  function fitTables() {
    document.querySelectorAll("table.table").forEach(function (table) {
      var box = table.closest(".pst-scrollable-table-container") || table.parentElement;
      table.classList.remove("lc-tight", "lc-wrap");
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
  document.addEventListener("DOMContentLoaded", function () {
    fit();
    if (document.fonts && document.fonts.ready) document.fonts.ready.then(fit);
  });
  window.addEventListener("load", fit);
})();
