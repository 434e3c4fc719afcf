#!/bin/sh
# check_figures.sh [--made-by TARGET] PNGDIFF RENDER_DIR FIGURE...
# Compares each figure as the program draws it now, RENDER_DIR/NAME.png
# (make renders it there once, for figures/ and for this check), with the
# committed copy: the version in git's HEAD when there is one, so that a
# figure rewritten by `make` cannot vouch for itself. TARGET (default
# figures) is the make target a missing committed figure is made by.
# check-failures uses it too, with --made-by failures.
set -u
. "$(dirname "$0")/committed_figure.sh"
target=figures
if [ "$1" = --made-by ]; then target=$2; shift 2; fi
pngdiff=$1 renders=$2
shift 2
out=build/figcheck
mkdir -p "$out"
status=0
for fig in "$@"; do
  name=$(basename "$fig" .png)
  committed="$out/$name.committed.png"
  committed_figure "$fig" "$committed" "$target" || { status=1; continue; }
  [ -f "$renders/$name.png" ] ||
    { echo "$fig: error: no render $renders/$name.png"; status=1; continue; }
  # Two 8-bit codes of slack absorb libm differences between machines.
  "$pngdiff" --tolerance 2 "$committed" "$renders/$name.png" || status=1
done
exit $status
