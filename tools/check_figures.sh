#!/bin/sh
# check_figures.sh BIN PNGDIFF TANGLE_DIR FIGURE...
# Renders each figure again with the chapter's binary and compares it with the
# committed copy (the version in git's HEAD when there is one, so that a
# figure rewritten by `make` cannot vouch for itself). A figure
# figures/chNN-default.png is the binary's embedded scene; any other
# figures/chNN-NAME.png is TANGLE_DIR/scenes/chNN-NAME.scene.
set -u
. "$(dirname "$0")/committed_figure.sh"
bin=$1 pngdiff=$2 tangled=$3
shift 3
out=build/figcheck
mkdir -p "$out"
status=0
for fig in "$@"; do
  name=$(basename "$fig" .png)
  committed="$out/$name.committed.png"
  committed_figure "$fig" "$committed" figures || { status=1; continue; }
  case "$name" in
    *-default) "$bin" -o "$out/$name.png" ;;
    *) "$bin" "$tangled/scenes/$name.scene" -o "$out/$name.png" ;;
  esac || { echo "$fig: error: $bin failed to render it"; status=1; continue; }
  # Two 8-bit codes of slack absorb libm differences between machines.
  "$pngdiff" --tolerance 2 "$committed" "$out/$name.png" || status=1
done
exit $status
