#!/bin/sh
# book_check.sh -- look at the woven book in a real browser (headless
# Chromium) at a 1280 x 900 window, as a reader on a laptop meets it.
#
# Usage: sh tools/checks/book_check.sh [--no-install] BOOK.html SCREENSHOT.png|-
#
# It runs tools/checks/book_check.js in a copy of BOOK.html and prints one line per
# element wider than its place: a code box or display formula whose content
# needs scrolling, or a box, table, image or paragraph whose right edge is
# beyond the text column. Exits 1 if there is any, 0 if none. It also saves
# the top of the page as SCREENSHOT.png, to look at; with SCREENSHOT "-"
# (make test), none: the book loaded once more costs Chromium about ten
# seconds of a core.
#
# Chromium is installed with apt-get when missing (as root, through
# tools/book/deps.sh, with fonts-dejavu-extra for the math font); if it cannot
# be, or with --no-install (how `make test` calls it), the check says so and
# is skipped with status 0.
set -u

install=yes
if [ "${1:-}" = "--no-install" ]; then install=no; shift; fi
if [ "$#" -ne 2 ]; then
  echo "usage: $0 [--no-install] BOOK.html SCREENSHOT.png|-" >&2
  exit 2
fi
book=$1
screenshot=$2
tools_dir=$(cd "$(dirname "$0")" && pwd)

. "$tools_dir/../editions/find_chromium.sh"

browser=$(find_chromium)
if [ -z "$browser" ] && [ "$install" = yes ]; then
  sh "$tools_dir/../book/deps.sh" chromium fonts-dejavu-extra >&2
  browser=$(find_chromium)
fi
if [ -z "$browser" ]; then
  echo "book-check: skipped: no chromium (run 'make book-check' as root to install it)"
  exit 0
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# run_browser OPTION... URL: headless, a 1280 x 900 window, quiet.
run_browser() {
  sandbox=""
  [ "$(id -u)" = 0 ] && sandbox="--no-sandbox"  # Chromium refuses root otherwise
  # shellcheck disable=SC2086  # $sandbox is one word or none
  timeout 120 "$browser" --headless $sandbox --disable-gpu --disable-dev-shm-usage \
    --hide-scrollbars --window-size=1280,900 --user-data-dir="$work/profile" "$@" \
    2>"$work/browser.log"
}

# The page with the measuring script before its last </body>.
awk -v script="$tools_dir/book_check.js" '
  /<\/body>/ { sub(/<\/body>/, ""); print; print "<script>";
               while ((getline line < script) > 0) print line;
               print "</script></body>"; next }
  { print }' "$book" > "$work/page.html"

run_browser --virtual-time-budget=20000 --dump-dom "file://$work/page.html" > "$work/dom.html"
# The report, as text: the lines the script wrote (the script's own source
# holds these words too, but never at the start of a line).
grep -E '^book-check: (problem|done)' "$work/dom.html" |
  sed -e 's/<[^>]*>//g' -e 's/&lt;/</g' -e 's/&gt;/>/g' -e 's/&quot;/"/g' \
      -e 's/&amp;/\&/g' > "$work/report.txt"

if ! grep -q '^book-check: done' "$work/report.txt"; then
  echo "book-check: error: the measuring script did not finish; browser said:" >&2
  tail -n 5 "$work/browser.log" >&2
  exit 1
fi

if [ "$screenshot" != - ]; then
  mkdir -p "$(dirname "$screenshot")"
  run_browser --screenshot="$screenshot" "file://$(cd "$(dirname "$book")" && pwd)/$(basename "$book")" \
    >/dev/null || echo "book-check: warning: no screenshot" >&2
fi

problems=$(grep -c '^book-check: problem: ' "$work/report.txt")
grep '^book-check: problem: ' "$work/report.txt" | sed "s|^book-check: problem: |$book: error: |" >&2
summary=$(grep '^book-check: done' "$work/report.txt" | sed 's/^book-check: done, //')
if [ "$problems" -gt 0 ]; then
  echo "book-check: $problems element(s) wider than their place at 1280 px ($summary)" >&2
  exit 1
fi
shot="; screenshot $screenshot"
[ "$screenshot" != - ] || shot=""
echo "book-check: $summary at 1280 x 900, none wider than its place$shot"
