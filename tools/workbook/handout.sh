#!/bin/sh
# handout.sh -- the book for students: no exercise's solution in it.
#
# Usage: tools/workbook/handout.sh OUTDIR [--no-book | --no-objects]
#        (make handout, make check-handout, make check-handout-page)
# Writes OUTDIR, a folder in which a student can `make`, `make workbook`
# and `make grade`: the Makefile, a README.md written for the student
# (tools/workbook/handout_readme.md), book.md, the chapters with every exercise's
# code replaced by its stub (tools/workbook/handout.awk), the workbook made from
# them (workbook/, stubs and "// NOT DONE" lines), tests/, tools/ (but the
# diagrams' programs, whose figures are in figures/, and the workbook's
# own checks, which quote the book's code), meshes/ and
# figures/, the book's code of the exercises compiled (book/chNN.o, with
# book/forward/, book/export/ and book/MACHINE: tools/workbook/book_code.sh, made
# by make book-code in build/bookcode), so that an exercise not started
# behaves as the book's code does, and the book woven from the handout's
# chapters (book.html), with WEAVE_PAGE's HTML when it is set: the page's
# programs, the book's own compiled for WebAssembly and in base64, as
# the checkout's build/book.html holds them (tools/editions/page.sh), so
# that its scenes render in the handout's page as in the book's.
# --no-book leaves out book.html and the compiled
# objects (make check-handout: it reads the text); --no-objects the
# objects alone (make check-handout-page: it opens the book, and needs
# no build of the book's code). Left out: src/ (the
# tangle of the book's solutions), bench/ and failures/ (programs that use
# them), fuzz/, .git.
set -eu
out=$1
book=${2:-}
page=${WEAVE_PAGE:-}
# the weave runs in $out: the page's HTML by its absolute path
[ -z "$page" ] || page=$(cd "$(dirname "$page")" && pwd)/$(basename "$page")
rm -rf "$out"
mkdir -p "$out/chapters" "$out/book"
cp -R Makefile book.md tools tests meshes figures "$out/"
cp tools/workbook/handout_readme.md "$out/README.md"
printf 'build/\nbin/\n' > "$out/.gitignore"
cp chapters/README.md "$out/chapters/"
# the workbook's own tests: wrong answers, and plants that quote the
# book's code to edit it
rm -rf "$out/tests/data/workbook" "$out/tools/checks/check_workbook.sh" \
    "$out/tools/checks/check_stubs.sh"
rm -rf "$out/tools/diagrams"       # draws 7.1 and 7.2 in two dimensions
for c in chapters/[0-9][0-9]-*.md; do
    awk -f tools/workbook/stub.awk -f tools/workbook/handout.awk "$c" > "$out/$c"
done
cp -R build/bookcode/forward build/bookcode/export "$out/book/"
if [ "$book" != "--no-book" ] && [ "$book" != "--no-objects" ]; then
    cp build/bookcode/ch[0-9][0-9].o "$out/book/"
    sh tools/workbook/book_code.sh record "$out/book/MACHINE" "${CC:-cc}"
fi
(cd "$out" && make -s --no-print-directory workbook > /dev/null)
if [ "$book" != "--no-book" ]; then
    (cd "$out" && WEAVE_PAGE=$page sh tools/book/weave.sh book.md book.html \
        chapters/[0-9][0-9]-*.md) > /dev/null
fi
echo "handout.sh: wrote $out"
