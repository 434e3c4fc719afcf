#!/bin/sh
# build_speed.sh [--ci] [--runs N] [--out FILE]: how fast the book builds
# and tests itself, measured as a student meets it: each step in a fresh
# clone of this repository's HEAD (the packages already installed), timed
# as a whole, wall clock. A benchmark like the charts, never a test:
#
#   make               a fresh clone, everything built
#   make test          after that make, every check
#   make check-editions  after that, the PDF and the EPUB made and checked
#                      (CI runs it beside make test; it has no target)
#   make test-ch04     a fresh clone of its own, one chapter's suites
#   make grade-ch02    after a graded workbook, exercise 2.1's chunk edited
#   make grade-ch08    the same, exercise 8.1's chunk edited
#   make grade-ch13    the same, exercise 13.1's chunk edited (each grade
#                      after a grade of its chapter with the edits before,
#                      so that one chunk is new to it)
#   .ci/run            a fresh clone of its own, CI=true (with --ci only:
#                      it takes minutes)
#
# Each step runs N times (--runs, default 1); the table gives the median
# and, with N > 1, the smallest and largest. A step that fails is reported
# as failed. The table, with the machine on its first line, goes to FILE
# (default figures/build-speed.md, which the README quotes) and to stdout.
set -u
runs=1 ci="" out=figures/build-speed.md
while [ $# -gt 0 ]; do
  case "$1" in
    --ci) ci=1; shift ;;
    --runs) runs=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    *) echo "usage: $0 [--ci] [--runs N] [--out FILE]" >&2; exit 2 ;;
  esac
done
repo=$(pwd)
scratch=$(mktemp -d) || exit 1
trap 'rm -rf "$scratch"' EXIT
times=$scratch/times

now() { date +%s.%N; }

# clone NAME: a fresh clone of HEAD in the scratch folder; prints its path.
clone() {
  rm -rf "$scratch/$1"
  git clone -q "$repo" "$scratch/$1" && echo "$scratch/$1"
}

# timed STEP DIR COMMAND...: runs COMMAND in DIR, appends "STEP SECONDS"
# (or "STEP failed") to the times file; its output goes to STEP's log.
timed() {
  step=$1 dir=$2
  shift 2
  log="$scratch/$(echo "$step" | tr ' /' '__').log"
  start=$(now)
  if (cd "$dir" && "$@") >> "$log" 2>&1; then
    echo "$step	$(echo "$(now) - $start" | bc)" >> "$times"
  else
    echo "$step	failed" >> "$times"
    echo "build_speed: '$step' failed; its log:" >&2
    tail -20 "$log" >&2
  fi
}

# edit_one_chunk EX NN: exercise EX's code in chapter NN's workbook file
# gets a comment line; fails when there is no such exercise.
edit_one_chunk() {
  f=$(ls workbook/"$2"-*.md 2>/dev/null | head -n 1)
  [ -n "$f" ] && grep -q "ex=\"$1\"" "$f" ||
    { echo "build_speed: no exercise $1 in workbook/$2-*.md" >&2; return 1; }
  awk -v ex="ex=\"$1\"" 'index($0, ex) { print; print "/* edited */"; next } { print }' \
    "$f" > "$f.new" && mv "$f.new" "$f"
}

k=0
while [ "$k" -lt "$runs" ]; do
  k=$((k + 1))
  d=$(clone build) || exit 1
  timed "make" "$d" make
  timed "make test" "$d" make test
  timed "make check-editions, after make test" "$d" make check-editions
  d=$(clone chapter) || exit 1
  timed "make test-ch04, fresh clone" "$d" make test-ch04
  # A solved workbook, graded once; then one chunk edited and graded again.
  (cd "$d" && make -s workbook SOLVED=1 && sed -i '/^\/\/ NOT DONE/d' workbook/*.md &&
     make -s grade-ch02 grade-ch08 grade-ch13) > "$scratch/grade-setup.log" 2>&1
  for edit in "02 2.1" "08 8.1" "13 13.1"; do
    set -- $edit
    # graded again first, untimed: the edits of the chapters before are
    # in its program too, and only this one chunk is new to it
    (cd "$d" && make -s grade-ch$1) >> "$scratch/grade-setup.log" 2>&1
    (cd "$d" && edit_one_chunk "$2" "$1") || exit 1
    timed "make grade-ch$1, one chunk edited" "$d" make grade-ch$1
  done
  if [ -n "$ci" ]; then
    d=$(clone ci) || exit 1
    timed ".ci/run, fresh clone" "$d" env CI=true bash .ci/run
  fi
done

# The machine, as the charts' CSVs name it.
cpu=$(sed -n 's/^model name[ 	]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
# Machines of one name differ: their family and model, and widest vectors.
family=$(sed -n 's/^cpu family[ 	]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
model=$(sed -n 's/^model[ 	]*: //p' /proc/cpuinfo 2>/dev/null | head -n 1)
vectors=$(grep -qw avx512f /proc/cpuinfo 2>/dev/null && echo AVX-512 ||
          { grep -qw avx2 /proc/cpuinfo 2>/dev/null && echo AVX2 || echo "no AVX2"; })
[ -z "$family" ] || cpu="$cpu (family $family, model $model, $vectors)"
cores=$(nproc 2>/dev/null || echo "?")
cc_version=$(cc --version 2>/dev/null | head -n 1)
load=$(cut -d ' ' -f 1 /proc/loadavg 2>/dev/null || echo "?")
{
  echo "Machine: ${cpu:-unknown}, $cores cores (load $load at the end);" \
       "$cc_version; $(date -u '+%Y-%m-%d %H:%M UTC'); $runs run(s) a step."
  echo
  echo "| step | seconds, median | smallest | largest | target |"
  echo "|---|---|---|---|---|"
  awk -F '\t' '
    { step[$1] = step[$1] " " $2; if (!($1 in seen)) { seen[$1] = 1; order[++n] = $1 } }
    END {
      target["make"] = "60"; target["make test"] = "150"
      target["make test-ch04, fresh clone"] = "20"
      target["make grade-ch02, one chunk edited"] = "5"
      target["make grade-ch08, one chunk edited"] = "5"
      target["make grade-ch13, one chunk edited"] = "10"
      target[".ci/run, fresh clone"] = "420"
      target["make check-editions, after make test"] = "none"
      for (i = 1; i <= n; i++) {
        s = order[i]; m = split(substr(step[s], 2), v, " ")
        failed = 0
        for (j = 1; j <= m; j++) if (v[j] == "failed") failed = 1
        if (failed) { printf "| `%s` | failed | | | %s |\n", s, target[s]; continue }
        for (a = 1; a <= m; a++) for (b = a + 1; b <= m; b++)
          if (v[b] + 0 < v[a] + 0) { t = v[a]; v[a] = v[b]; v[b] = t }
        med = (m % 2) ? v[(m + 1) / 2] : (v[m / 2] + v[m / 2 + 1]) / 2
        printf "| `%s` | %.0f | %.0f | %.0f | %s |\n", s, med, v[1], v[m], target[s]
      }
    }' "$times"
} > "$scratch/table"
mkdir -p "$(dirname "$out")"
cp "$scratch/table" "$out"
cat "$out"
