#!/bin/sh
# handout.sh -- the book for students: no exercise's solution in it.
#
# Usage: tools/workbook/handout.sh OUTDIR [--no-book]   (make handout, make check-handout)
# Writes OUTDIR, a folder in which a student can `make workbook` and `make
# grade`: the Makefile, README.md, book.md, the chapters with every exercise's
# code replaced by its stub (tools/workbook/handout.awk), the workbook made from them
# (workbook/, stubs and "// NOT DONE" lines), tests/, tools/, meshes/ and
# figures/, and the book woven from the handout's chapters (book.html)
# unless --no-book. Left out: src/ (the tangle of the book's solutions),
# bench/ and failures/ (programs that use them), fuzz/, .git.
set -eu
out=$1
book=${2:-}
rm -rf "$out"
mkdir -p "$out/chapters"
cp -R Makefile README.md book.md tools tests meshes figures "$out/"
printf 'build/\nbin/\n' > "$out/.gitignore"
cp chapters/README.md "$out/chapters/"
rm -rf "$out/tests/data/workbook"  # the workbook's own tests: wrong answers
for c in chapters/[0-9][0-9]-*.md; do
    awk -f tools/workbook/stub.awk -f tools/workbook/handout.awk "$c" > "$out/$c"
done
(cd "$out" && make -s --no-print-directory workbook > /dev/null)
if [ "$book" != "--no-book" ]; then
    (cd "$out" && sh tools/book/weave.sh book.md book.html chapters/[0-9][0-9]-*.md) > /dev/null
fi
echo "handout.sh: wrote $out"
