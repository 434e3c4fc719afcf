#!/bin/sh
# pdf.sh -- the book for printing: headless Chromium's print of the page.
#
# Usage: tools/editions/pdf.sh BOOK.html OUT.pdf   (make pdf)
# Prints BOOK.html with its print stylesheet (tools/book/book.css, @media print:
# a page break before every chapter, no side bar, code boxes and figures
# kept whole) to OUT.pdf, A4, without the browser's headers and footers.
# Chromium is installed with apt-get when missing (as root, through
# tools/book/deps.sh); without it the script says so and exits 1.
set -u
if [ "$#" -ne 2 ]; then
    echo "usage: $0 BOOK.html OUT.pdf" >&2
    exit 2
fi
book=$1 out=$2
tools_dir=$(cd "$(dirname "$0")" && pwd)

. "$tools_dir/find_chromium.sh"
browser=$(find_chromium)
[ -n "$browser" ] || { sh "$tools_dir/../book/deps.sh" chromium fonts-dejavu-extra >&2; browser=$(find_chromium); }
[ -n "$browser" ] || { echo "pdf: no chromium: run make pdf as root to install it" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sandbox=""
[ "$(id -u)" = 0 ] && sandbox="--no-sandbox"  # Chromium refuses root otherwise
mkdir -p "$(dirname "$out")"
# shellcheck disable=SC2086  # $sandbox is one word or none
timeout 300 "$browser" --headless $sandbox --disable-gpu --disable-dev-shm-usage \
    --user-data-dir="$work/profile" --no-pdf-header-footer \
    --print-to-pdf="$work/book.pdf" \
    "file://$(cd "$(dirname "$book")" && pwd)/$(basename "$book")" 2> "$work/log"
if [ ! -s "$work/book.pdf" ]; then
    echo "pdf: Chromium printed nothing:" >&2
    tail -n 5 "$work/log" >&2
    exit 1
fi
mv "$work/book.pdf" "$out"
echo "pdf.sh: wrote $out"
