#!/bin/sh
# charts_check.sh BENCH...: can the charts' speed axes be trusted?
#
# Runs every benchmark twice, one after the other (never two at once), into
# build/charts-check/run1 and run2, and reports:
#   - per chart, the largest ratio between the two runs' median times of the
#     same method and param (1.00: the runs agree), and the method;
#   - for every RATIO line of bench/quotes.txt and bench/quotes-ratios.txt
#     (tools/checks/check_quotes.sh), the ratio in each run and whether it is within
#     its band in both; and whether an ordering a claim relies on (A faster
#     than B, or slower) flipped between the runs.
# Exits 1 if an ordering flipped. make charts-check runs it on every bench.
# BENCH is a benchmark binary, build/rel/bench/chNN_topic; its CSV is named
# like figures/chNN-topic.csv. Runs from the repository's root.
out=build/charts-check
rm -rf "$out"
mkdir -p "$out/run1" "$out/run2"
echo "charts-check: every benchmark run twice; times are medians over interleaved rounds"
for run in 1 2; do
  for bench in "$@"; do
    name=$(basename "$bench" | tr _ -)
    "$bench" > "$out/run$run/$name.csv" 2> "$out/run$run/$name.log" || {
      echo "charts-check: $bench failed: see $out/run$run/$name.log"; exit 1; }
  done
done

echo
printf '%-20s %-10s %s\n' "chart" "largest" "run-to-run ratio of a method's median time (method,param: run 1, run 2 ns)"
for bench in "$@"; do
  name=$(basename "$bench" | tr _ -)
  # A method's timing is repeated on every row of its error kinds: the first
  # row of each method and time stands for the rest.
  awk -F, -v name="$name" '
    /^#/ || $3 == "" || $3 + 0 == 0 || $3 == "ns_per_op" || (FILENAME SUBSEP $1 SUBSEP $3 SUBSEP $6) in timed { next }
    { timed[FILENAME, $1, $3, $6] = 1 }
    FNR == NR { a[$1 "," $2] = $3; next }
    ($1 "," $2) in a {
      r = a[$1 "," $2] / $3; if (r < 1) r = 1 / r
      if (r > worst) { worst = r; which = $1 "," $2 ": " a[$1 "," $2] ", " $3 }
    }
    END { if (which == "") printf "%-20s %-10s %s\n", name, "-", "(no timed rows)"
          else printf "%-20s %-10.3f %s\n", name, worst, which }' \
    "$out/run1/$name.csv" "$out/run2/$name.csv"
done

quotes=""
for q in bench/quotes.txt bench/quotes-ratios.txt; do [ -f "$q" ] && quotes="$quotes $q"; done
sh tools/checks/check_quotes.sh --report --csv-dir "$out/run1" $quotes 2>/dev/null | grep '^ratio ' > "$out/ratios1"
sh tools/checks/check_quotes.sh --report --csv-dir "$out/run2" $quotes 2>/dev/null | grep '^ratio ' > "$out/ratios2"
echo
echo "quoted speed ratios (A/B: run 1 median (quartile interval), run 2; band; verdicts):"
paste -d' ' "$out/ratios1" "$out/ratios2" | awk '
  { where = $2; ab = $3; band = $7
    flip = band !~ /^(same|within)/ && (($4 > 1) != ($12 > 1))
    flips += flip
    printf "  %s %s\n      run 1 %.3f (%.3f..%.3f)  run 2 %.3f (%.3f..%.3f)  band %s  %s, %s%s\n",
      where, ab, $4, $5, $6, $12, $13, $14, band, $8, $16, flip ? "  ORDER FLIPPED" : "" }
  END { printf "\norderings flipped between the runs: %d of %d quoted ratios\n", flips, NR
        exit flips > 0 }'
