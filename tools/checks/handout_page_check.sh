#!/bin/sh
# handout_page_check.sh -- the handout's book renders its scenes as the
# book's page does, for a student who has the tarball alone:
#
#     sh tools/checks/handout_page_check.sh HANDOUT.tar.gz BOOK.html BIN_DIR SIZE NN:SCENE...
#
# Unpacks HANDOUT.tar.gz in an empty folder. Its book.html must hold the
# page's part of BOOK.html (the checkout's book), programs, meshes and
# scripts, byte for byte: check-page renders every scene of that page
# against bin/chNN. Every chapter with a playground in the handout's page
# must have its program there. Then, with the handout's book opened from
# file:// in headless Chromium, the network off, the scenes named must
# render within 1 code of BIN_DIR/chNN's pictures (tools/checks/page_check.sh
# --scenes, skipped where Chromium or node is not installed). When BOOK.html
# has no programs (no clang for wasm32-wasi), the handout's must have none
# either, and nothing is rendered.
set -u
if [ "$#" -lt 5 ]; then
  echo "usage: $0 HANDOUT.tar.gz BOOK.html BIN_DIR SIZE NN:SCENE..." >&2
  exit 2
fi
tarball=$1 book=$2
shift 2
tools_dir=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "handout-page-check: error: $1"; exit 1; }

mkdir "$work/student"
tar -xzf "$tarball" -C "$work/student" || fail "$tarball does not unpack"
handout_book=$(find "$work/student" -maxdepth 2 -name book.html | head -n 1)
[ -n "$handout_book" ] || fail "no book.html in $tarball"

# page_part HTML: what tools/editions/page.sh put before </body>, from the
# first program (or mesh) to the page's script.
page_part() {
  awk '/^<script type="application\/octet-stream"/ { on = 1 }
       /<\/body>/ { on = 0 }
       on' "$1"
}
page_part "$book" > "$work/book.part"
page_part "$handout_book" > "$work/handout.part"
if ! grep -q 'id="rt-program-' "$work/book.part"; then
  [ ! -s "$work/handout.part" ] ||
    fail "the handout's book holds programs that $book does not"
  echo "handout-page-check: skipped: $book has no programs (no clang for wasm32-wasi)"
  exit 0
fi
cmp -s "$work/book.part" "$work/handout.part" ||
  fail "the handout's page does not hold $book's programs and scripts as they are"
programs=$(grep -c '^<script type="application/octet-stream" id="rt-program-' "$work/handout.part")
bytes=$(wc -c < "$work/handout.part")

# Every chapter a playground of the handout's page renders with.
grep -o '<div class="playground" data-chapter="[0-9]*"' "$handout_book" |
  sed 's/.*data-chapter="\([0-9]*\)"/\1/' | awk '{ printf "%02d\n", $0 }' |
  sort -u > "$work/chapters"
[ -s "$work/chapters" ] || fail "the handout's book has no playground"
while read -r n; do
  grep -q "^<script type=\"application/octet-stream\" id=\"rt-program-$n\">" \
      "$work/handout.part" ||
    fail "chapter $n's playgrounds in the handout's book have no program"
done < "$work/chapters"
echo "handout-page-check: the handout's book holds $book's $programs programs, meshes and scripts" \
  "($bytes bytes, the same), one for each of the $(wc -l < "$work/chapters") chapters with a playground"

sh "$tools_dir/page_check.sh" --scenes "$handout_book" "$@"
