#!/bin/sh
# epub.sh -- the book as an EPUB 3 for tablets and readers.
#
# Usage: tools/epub.sh BOOK_MD OUT_EPUB CHAPTER...   (make epub)
# pandoc with the book's filter (tools/weave.lua: chunk boxes, exercise
# labels, cross-references) and stylesheet, math as MathML, one EPUB
# chapter per chapter of the book, figures embedded. The file is written
# only when pandoc succeeded.
set -eu
if [ "$#" -lt 3 ]; then
    echo "usage: $0 BOOK_MD OUT_EPUB CHAPTER..." >&2
    exit 2
fi
book=$1 out=$2
shift 2
tools_dir=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$(dirname "$out")"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
pandoc "$book" "$@" --from markdown --to epub3 --mathml --toc --toc-depth=2 \
    --number-sections --epub-chapter-level=1 --resource-path=. \
    --metadata lang=en --css="$tools_dir/book.css" \
    --lua-filter="$tools_dir/weave.lua" --output="$out.tmp" 2> "$log" ||
    { cat "$log" >&2; rm -f "$out.tmp"; exit 1; }
cat "$log" >&2
mv "$out.tmp" "$out"
echo "epub.sh: wrote $out"
