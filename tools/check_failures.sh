#!/bin/sh
# check_failures.sh PNGDIFF PROGRAM_DIR FIGURE...
# Renders each failure figure figures/chNN-failure-NAME.png again with its
# program PROGRAM_DIR/chNN_NAME (NAME with _ for -) into build/failcheck and
# compares it with the committed copy (git's HEAD when there is one, so that a
# figure rewritten by `make` cannot vouch for itself), as check_figures.sh
# does for the scenes. A program that exits non-zero, because its naive half
# no longer shows the failure, fails the check too.
set -u
. "$(dirname "$0")/committed_figure.sh"
pngdiff=$1 programs=$2
shift 2
out=build/failcheck
mkdir -p "$out"
status=0
for fig in "$@"; do
  name=$(basename "$fig" .png)
  chapter=${name%%-failure-*}
  program="$programs/${chapter}_$(echo "${name#*-failure-}" | tr - _)"
  committed="$out/$name.committed.png"
  committed_figure "$fig" "$committed" failures || { status=1; continue; }
  "$program" "$out/$name.png" >/dev/null ||
    { echo "$fig: error: $program failed"; status=1; continue; }
  # Two 8-bit codes of slack absorb libm differences between machines.
  "$pngdiff" --tolerance 2 "$committed" "$out/$name.png" || status=1
done
[ $status = 0 ] && echo "check-failures: $# failure figures up to date"
exit $status
