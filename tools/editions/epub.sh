#!/bin/sh
# epub.sh -- the book as an EPUB 3 for tablets and readers.
#
# Usage: tools/editions/epub.sh BOOK_MD OUT_EPUB CHAPTER...   (make epub)
# pandoc with the book's filter (tools/book/weave.lua: chunk boxes, exercise
# labels, cross-references) and stylesheet, math as MathML, one EPUB
# chapter per chapter of the book, figures embedded. Then, in the EPUB's
# own copies, what pandoc leaves for an EPUB reader to refuse:
# tools/editions/epub_links.awk points the weaver's links at the chapter file that
# holds their target, tools/editions/epub_svg.awk makes each SVG figure valid SVG
# 1.1 (the figures themselves are not changed). The parts are zipped again
# (zip), mimetype first and stored, as EPUB asks. The file is written only
# when all of this succeeded; make test checks it with epubcheck
# (tools/checks/check_epub.sh). EPUB_PLAYGROUNDS=yes: the HTML edition
# renders the scenes in the page, and each scene is followed by a note
# that says so (tools/book/weave.lua's playgrounds).
set -eu
if [ "$#" -lt 3 ]; then
    echo "usage: $0 BOOK_MD OUT_EPUB CHAPTER..." >&2
    exit 2
fi
book=$1 out=$2
shift 2
tools_dir=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$(dirname "$out")"
out_abs=$(cd "$(dirname "$out")" && pwd)/$(basename "$out")
playgrounds=false
[ "${EPUB_PLAYGROUNDS:-}" != yes ] || playgrounds=true
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pandoc "$book" "$@" --from markdown --to epub3 --mathml --toc --toc-depth=2 \
    --number-sections --epub-chapter-level=1 --resource-path=. \
    --metadata lang=en --metadata playgrounds="$playgrounds" --css="$tools_dir/../book/book.css" \
    --lua-filter="$tools_dir/../book/weave.lua" --output="$work/pandoc.epub" 2> "$work/log" ||
    { cat "$work/log" >&2; exit 1; }
cat "$work/log" >&2

mkdir "$work/parts"
cd "$work/parts"
unzip -q ../pandoc.epub
set -- EPUB/text/*.xhtml
awk -f "$tools_dir/epub_links.awk" "$@"
for page in "$@"; do mv "$page.new" "$page"; done
for figure in EPUB/media/*.svg; do
    [ -f "$figure" ] || continue
    awk -f "$tools_dir/epub_svg.awk" "$figure" > "$figure.new"
    mv "$figure.new" "$figure"
done
# -X: no extra file attributes; -D: no entries for folders.
zip -q -X -0 ../book.epub mimetype
zip -q -X -D -r -9 ../book.epub . -x mimetype
mv ../book.epub "$out_abs"
echo "epub.sh: wrote $out"
