#!/bin/sh
# check_handout_programs.sh -- an untouched handout's programs pass the book's
# suites.
#
# Usage: tools/checks/check_handout_programs.sh TARBALL NN
#        (make check-handout-programs, in CI)
# Unpacks the handout's tarball in an empty folder, as a student has it,
# and runs make test-chNN there: the suites of chapters 1 to NN against
# the handout's program of chapter NN, every exercise not started, so the
# book's compiled code (book/chNN.o) stands in for each of them. Its
# programs must behave as the book's: an exercise through which the
# compiled code cannot stand in (a part of a function's body), or a
# function outside an exercise that reads the statics its functions write
# (two copies of them, the book's and the handout's), fails here.
set -u
tarball=$1
chapter=$2
[ -f "$tarball" ] || { echo "$0: no $tarball (make handout)" >&2; exit 2; }
tarball=$(cd "$(dirname "$tarball")" && pwd)/$(basename "$tarball")
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
cd "$dir" && tar -xzf "$tarball" || exit 1
cd "$(ls -d */ | head -n 1)" || exit 1
# the compiled code serves only the system it was compiled for
built_for=$(head -n 1 book/MACHINE)
if [ "$built_for" != "$(uname -s) $(uname -m)" ]; then
    echo "check-handout-programs: skipped: book/ compiled for $built_for"
    exit 0
fi
# (the handout's make alone: none of the calling make's flags or jobs)
if env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL \
    make -s --no-print-directory "test-ch$chapter" > "$dir/test.log" 2>&1; then
    echo "check-handout-programs: an untouched handout passes make test-ch$chapter"
    exit 0
fi
grep -E ':[FE]:|: error:|\*\*\*' "$dir/test.log" | head -20
echo "check-handout-programs: an untouched handout fails make test-ch$chapter" \
     "(its exercises not started, the book's compiled code standing in)"
exit 1
