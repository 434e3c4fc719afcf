/*
 * book_check.js -- measures the woven book in a browser; tools/checks/book_check.sh
 * puts it at the end of a copy of build/book.html and runs headless Chromium.
 *
 * Once the page has loaded it writes its findings into the page itself, in
 * a pre element with the id book-check-report: one line per problem, each
 * starting "book-check: problem: ", and the line starting "book-check:
 * done, " last, which tells how many elements were measured.  A problem is
 *   - a <pre> (a code box) or display <math> whose content is wider than
 *     its box (scrollWidth > clientWidth: the reader has to scroll);
 *   - a code box, table, image, figure, formula or paragraph whose right
 *     edge lies beyond the text column (the body's content box).
 * Each line says what it is and where: the chunk (with its chapter) or
 * the nearest heading above it.
 */
(function () {
  "use strict";

  var SELECTOR = "pre, table, img, svg, figure, math, p, .chunk, blockquote, ul, ol";

  function chunkOf(element) {
    var chunk = element.closest(".chunk");
    if (!chunk) return null;
    var name = chunk.dataset.file ? "file " + chunk.dataset.file
                                  : "chunk <<" + chunk.dataset.chunk + ">>";
    return name + " (" + chunk.dataset.chapter + ")";
  }

  // The text of the nearest h1..h3 before element in document order.
  function headingBefore(element) {
    var headings = document.querySelectorAll("h1, h2, h3");
    var found = null;
    for (var i = 0; i < headings.length; i++) {
      var relation = headings[i].compareDocumentPosition(element);
      if (relation & Node.DOCUMENT_POSITION_FOLLOWING) found = headings[i];
      else break;
    }
    return found ? "section \"" + found.textContent.replace(/\s+/g, " ").trim() + "\""
                 : "the top of the page";
  }

  function describe(element) {
    var tag = element.tagName.toLowerCase();
    return tag + " in " + (chunkOf(element) || headingBefore(element));
  }

  // The longest line of a code box, shortened, to show what to fix.
  function longestLine(element) {
    var lines = element.textContent.split("\n");
    var longest = "";
    for (var i = 0; i < lines.length; i++)
      if (lines[i].length > longest.length) longest = lines[i];
    return longest.length > 100 ? longest.slice(0, 97) + "..." : longest;
  }

  function scrolls(element) {
    var tag = element.tagName.toLowerCase();
    if (tag !== "pre" && !(tag === "math" && element.getAttribute("display") === "block"))
      return null;
    if (element.scrollWidth <= element.clientWidth + 1) return null;
    return describe(element) + ": content " + element.scrollWidth + " px wide in a "
      + element.clientWidth + " px box: " + longestLine(element);
  }

  function sticksOut(element, columnRight) {
    var right = element.getBoundingClientRect().right;
    if (right <= columnRight + 1) return null;
    return describe(element) + ": right edge at " + Math.round(right)
      + " px, the text column ends at " + Math.round(columnRight) + " px";
  }

  function measure() {
    var body = document.body;
    var style = getComputedStyle(body);
    var columnRight = body.getBoundingClientRect().right - parseFloat(style.paddingRight);
    var problems = [];
    var elements = document.querySelectorAll(SELECTOR);
    var measured = 0;
    for (var i = 0; i < elements.length; i++) {
      var element = elements[i];
      if (element.closest("nav#TOC")) continue;  // the side bar is outside the column
      measured++;
      var problem = scrolls(element) || sticksOut(element, columnRight);
      if (problem) problems.push("book-check: problem: " + problem);
    }
    problems.push("book-check: done, " + measured + " elements measured");
    var report = document.createElement("pre");
    report.id = "book-check-report";
    report.textContent = "\n" + problems.join("\n") + "\n";
    body.appendChild(report);
  }

  if (document.readyState === "complete") measure();
  else window.addEventListener("load", measure);
})();
