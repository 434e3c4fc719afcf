#!/bin/sh
# check_failures.sh PNGDIFF RENDER_DIR FIGURE...
# Compares each failure figure figures/chNN-failure-NAME.png as its program
# in failures/ draws it now, RENDER_DIR/chNN-failure-NAME.png (make draws it
# there once; a program whose naive half no longer shows the failure exits
# non-zero and fails that step), with the committed copy: git's HEAD when
# there is one, so that a figure rewritten by `make` cannot vouch for itself.
set -u
. "$(dirname "$0")/committed_figure.sh"
pngdiff=$1 renders=$2
shift 2
out=build/failcheck
mkdir -p "$out"
status=0
for fig in "$@"; do
  name=$(basename "$fig" .png)
  committed="$out/$name.committed.png"
  committed_figure "$fig" "$committed" failures || { status=1; continue; }
  [ -f "$renders/$name.png" ] ||
    { echo "$fig: error: no render $renders/$name.png"; status=1; continue; }
  # Two 8-bit codes of slack absorb libm differences between machines.
  "$pngdiff" --tolerance 2 "$committed" "$renders/$name.png" || status=1
done
[ $status = 0 ] && echo "check-failures: $# failure figures up to date"
exit $status
