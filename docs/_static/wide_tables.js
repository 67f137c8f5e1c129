// SPDX-FileCopyrightText: 2026 warptrunc developers
// SPDX-License-Identifier: MIT
// Marks every table container that is wider than the text column ("wt-wide"), on load and on
// resize, so that warptrunc.css shows a note above it: the table scrolls sideways.
(function () {
  function mark() {
    document.querySelectorAll(".bd-article .pst-scrollable-table-container, .bd-article .table-wrapper")
      .forEach(function (box) {
        box.classList.toggle("wt-wide", box.scrollWidth > box.clientWidth + 1);
      });
  }
  window.addEventListener("load", mark);
  window.addEventListener("resize", mark);
})();
