# committed_figure.sh: sourced by check_figures.sh.
# committed_figure FIG COPY MAKE_TARGET: writes the committed FIG to COPY,
# from git's HEAD when FIG is tracked (so that a figure that `make` has just
# rewritten cannot vouch for itself), else the file as it is; fails, saying
# which make target makes it, when there is no such figure.
committed_figure() {
  if git cat-file -e "HEAD:$1" 2>/dev/null; then
    git show "HEAD:$1" > "$2"
  elif [ -f "$1" ]; then
    cp "$1" "$2"
  else
    echo "$1: error: no committed figure (run make $3 and commit it)"
    return 1
  fi
}
