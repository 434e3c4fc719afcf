#!/bin/sh
# check_quotes.sh [QUOTES]: are the numbers the chapters quote still the
# numbers their benchmarks measured?
#
# Each line of QUOTES (default bench/quotes.txt) names a chapter, a CSV made
# by `make charts`, one row of it (method, param, error_kind) and how the
# chapter prints that row's error column: divided by SCALE, through a printf
# FORMAT (SCALE "log10" prints the decimal logarithm instead). The chapter,
# with its lines joined, must contain the printed text. Fields are separated
# by '|'; blank lines and lines starting with '#' are skipped:
#   CHAPTER | CSV | METHOD | PARAM | KIND | SCALE | FORMAT
# Only deterministic errors are quoted this way; times vary by machine.
quotes=${1:-bench/quotes.txt}
status=0
checked=0
while IFS='|' read -r chapter csv method param kind scale format; do
  chapter=$(echo $chapter) csv=$(echo $csv) method=$(echo $method)
  param=$(echo $param) kind=$(echo $kind) scale=$(echo $scale)
  format=$(printf '%s\n' "$format" | sed 's/^ *//; s/ *$//') # dash's echo eats backslashes
  case "$chapter" in ''|'#'*) continue ;; esac
  value=$(awk -F, -v m="$method" -v p="$param" -v k="$kind" \
    '$1 == m && $2 == p && $5 == k { print $4; exit }' "$csv")
  if [ -z "$value" ]; then
    echo "$quotes: error: no row $method,$param,$kind in $csv"; status=1; continue
  fi
  # The format travels through the environment: awk -v would eat its backslashes.
  text=$(FORMAT="$format" awk -v v="$value" -v s="$scale" 'BEGIN {
    f = ENVIRON["FORMAT"]
    if (s == "log10") printf f, log(v) / log(10); else printf f, v / s }')
  checked=$((checked + 1))
  if ! tr '\n' ' ' < "$chapter" | tr -s ' ' | grep -qF -- "$text"; then
    echo "$chapter: error: quotes '$text' for $method,$param,$kind of $csv ($value): not found"
    status=1
  fi
done < "$quotes"
[ $status = 0 ] && echo "check_quotes: $checked numbers in the chapters match their CSV files"
exit $status
