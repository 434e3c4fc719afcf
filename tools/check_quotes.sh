#!/bin/sh
# check_quotes.sh [--csv-dir DIR] [--report] [QUOTES...]: are the numbers
# the chapters quote still the numbers their benchmarks measured?
#
# Each QUOTES file (default bench/quotes.txt) has one claim a line, fields
# separated by '|', spaces around them ignored; blank lines and lines
# starting with '#' are skipped. CSV files are those `make charts` writes;
# their '#' lines (the machine line) are skipped. Three kinds of line:
#
# Errors, deterministic numbers printed by the chapter:
#   CHAPTER | CSV | METHOD | PARAM | KIND | SCALE | FORMAT
#   The row METHOD,PARAM,KIND of CSV has an error column; divided by SCALE
#   (SCALE "log10": its decimal logarithm) and printed through the printf
#   FORMAT, it must appear in CHAPTER (with the chapter's lines joined).
#
# Speed ratios, what the chapter says of one time against another:
#   RATIO | CHAPTER | CSV | METHOD_A,PARAM_A | METHOD_B,PARAM_B | BAND | TEXT
#   CHAPTER must contain TEXT (as above), and the ratio of A's time to B's,
#   ns_A / ns_B, must agree with BAND. The ratio's interval runs from
#   q1_A / q3_B to q3_A / q1_B (the CSV's ns_q1 and ns_q3 columns: the
#   quartiles of interleaved rounds, with 21 rounds also the 95% confidence
#   interval of each median). BAND is one of
#     LO..HI         A is faster, or slower, than B: A takes LO to HI times
#                    B's time ("a quarter faster" is about 0.72..0.88,
#                    "twice as slow" 1.7..2.4). The whole interval must lie
#                    inside [LO, HI], and [LO, HI] must not contain 1.
#     within LO..HI  A costs about as much as B, to within the band, which
#                    contains 1 ("as much as": within 0.9..1.1): the whole
#                    interval must lie inside [LO, HI]. No order is claimed.
#     same           A and B are indistinguishable: the interval contains 1.
#   An ordered claim (LO..HI) whose interval contains 1 fails: the chapter
#   must say that the two cannot be told apart. tools/charts_check.sh
#   reports whether the order of an ordered claim flips between runs.
#
# Absolute times, true only of the machine named on the CSV's first line:
#   TIME | CHAPTER | CSV | METHOD,PARAM | LO..HI [per N] | TEXT
#   CHAPTER must contain TEXT, and the interval [ns_q1, ns_q3] of the row
#   (divided by N when "per N" is given: "some 15 ns per triangle") must
#   lie inside [LO, HI] nanoseconds.
#
# --csv-dir DIR reads every CSV from DIR (same file name) instead: how
# `make charts-check` checks its reruns. --report prints, for each RATIO
# line, "ratio QUOTES:LINE A/B MEDIAN LO HI BAND VERDICT" on standard output
# (VERDICT: ok, or what is wrong with the numbers; the text is not looked
# at), for tools/charts_check.sh.
csv_dir=""
report=""
while [ $# -gt 0 ]; do
  case "$1" in
    --csv-dir) csv_dir=$2; shift 2 ;;
    --report) report=1; shift ;;
    *) break ;;
  esac
done
[ $# -eq 0 ] && set -- bench/quotes.txt

status=0
checked=0
ratios=0
trim() { printf '%s\n' "$1" | sed 's/^[ 	]*//; s/[ 	]*$//'; } # dash's echo eats backslashes
csv_path() { if [ -n "$csv_dir" ]; then echo "$csv_dir/$(basename "$1")"; else echo "$1"; fi; }
fail() { echo "$1"; status=1; }

# in_chapter CHAPTER TEXT: does the chapter, lines joined, contain TEXT?
in_chapter() { tr '\n' ' ' < "$1" | tr -s ' ' | grep -qF -- "$2"; }

# timing_of CSV METHOD,PARAM: "median q1 q3" of the first timed row of that method and param.
timing_of() {
  awk -F, -v m="${2%%,*}" -v p="${2#*,}" \
    '/^#/ { next } $1 == m && $2 == p && $3 != "" { print $3, $6, $7; exit }' "$1"
}

# check_error QUOTES:LINE CHAPTER CSV METHOD PARAM KIND SCALE FORMAT
check_error() {
  value=$(awk -F, -v m="$4" -v p="$5" -v k="$6" \
    '/^#/ { next } $1 == m && $2 == p && $5 == k { print $4; exit }' "$3")
  if [ -z "$value" ]; then
    fail "$1: error: no row $4,$5,$6 in $3"; return
  fi
  # The format travels through the environment: awk -v would eat its backslashes.
  text=$(FORMAT="$8" awk -v v="$value" -v s="$7" 'BEGIN {
    f = ENVIRON["FORMAT"]
    if (s == "log10") printf f, log(v) / log(10); else printf f, v / s }')
  checked=$((checked + 1))
  in_chapter "$2" "$text" ||
    fail "$2: error: quotes '$text' for $4,$5,$6 of $3 ($value): not found"
}

# check_ratio QUOTES:LINE CHAPTER CSV A B BAND TEXT
check_ratio() {
  a=$(timing_of "$3" "$4") b=$(timing_of "$3" "$5")
  [ -n "$a" ] || { fail "$1: error: no timed row $4 in $3"; return; }
  [ -n "$b" ] || { fail "$1: error: no timed row $5 in $3"; return; }
  verdict=$(echo "$a $b" | awk -v band="$6" '{
    if ($4 <= 0 || $5 <= 0) { print "0 0 0 badrow"; exit }
    r = $1 / $4; lo = $2 / $6; hi = $3 / $5
    printf "%.3f %.3f %.3f ", r, lo, hi
    if (band == "same") { print (lo <= 1 && 1 <= hi) ? "ok" : "ordered"; exit }
    within = sub(/^within +/, "", band)
    if (split(band, b, /\.\./) != 2 || b[1] !~ /^[0-9.]+$/ || b[2] !~ /^[0-9.]+$/ || b[1] + 0 > b[2] + 0) {
      print "badband"; exit }
    has1 = b[1] <= 1 && 1 <= b[2]
    if (within != has1) { print within ? "withoutside1" : "bandhas1"; exit }
    if (!within && lo <= 1 && 1 <= hi) { print "includes1"; exit }
    print (b[1] <= lo && hi <= b[2]) ? "ok" : "outside" }')
  set -- "$@" $verdict # $8 median, $9 lo, $10 hi, $11 verdict
  ratios=$((ratios + 1))
  [ -n "$report" ] && echo "ratio $1 $(echo "$4/$5" | tr ' ' _) $8 $9 ${10} $(echo "$6" | tr ' ' _) ${11}"
  what="'$7': $4 / $5 = $8 ($9..${10})"
  case "${11}" in
    ok) ;;
    badband) fail "$1: error: band '$6' is not LO..HI, within LO..HI or same" ;;
    bandhas1) fail "$1: error: band $6 contains 1: it orders nothing; write 'within $6' or 'same'" ;;
    withoutside1) fail "$1: error: band '$6' does not contain 1: an ordered claim is just LO..HI" ;;
    badrow) fail "$1: error: $4 or $5 has no positive time in $3" ;;
    includes1) fail "$2: error: $what includes 1: state it as indistinguishable (band 'same')" ;;
    ordered) fail "$2: error: $what says one is faster: not indistinguishable" ;;
    outside) fail "$2: error: $what is not within the band $6" ;;
  esac
  in_chapter "$2" "$7" || fail "$2: error: '$7' ($4 / $5 in $6): not found"
}

# check_time QUOTES:LINE CHAPTER CSV A BAND TEXT
check_time() {
  t=$(timing_of "$3" "$4")
  [ -n "$t" ] || { fail "$1: error: no timed row $4 in $3"; return; }
  verdict=$(echo "$t" | awk -v band="$5" '{
    per = 1
    if (band ~ / per /) { per = band; sub(/.* per /, "", per); sub(/ per .*/, "", band) }
    if (split(band, b, /\.\./) != 2) { print "- - - badband"; exit }
    lo = $2 / per; hi = $3 / per
    printf "%.4g %.4g %.4g %s\n", $1 / per, lo, hi, (b[1] <= lo && hi <= b[2]) ? "ok" : "outside" }')
  set -- "$@" $verdict # $7 median, $8 q1, $9 q3, $10 verdict
  checked=$((checked + 1))
  case "${10}" in
    ok) ;;
    badband) fail "$1: error: band '$5' is not LO..HI [per N]" ;;
    *) fail "$2: error: '$6': $4 takes $7 ns ($8..$9), not within $5" ;;
  esac
  in_chapter "$2" "$6" || fail "$2: error: '$6' ($4 in $5): not found"
}

for quotes in "$@"; do
  n=0
  while IFS='|' read -r f1 f2 f3 f4 f5 f6 f7; do
    n=$((n + 1))
    f1=$(trim "$f1")
    case "$f1" in ''|'#'*) continue ;; esac
    f2=$(trim "$f2") f3=$(trim "$f3") f4=$(trim "$f4") f5=$(trim "$f5") f6=$(trim "$f6") f7=$(trim "$f7")
    case "$f1" in
      RATIO) check_ratio "$quotes:$n" "$f2" "$(csv_path "$f3")" "$f4" "$f5" "$f6" "$f7" ;;
      TIME) check_time "$quotes:$n" "$f2" "$(csv_path "$f3")" "$f4" "$f5" "$f6" ;;
      *) check_error "$quotes:$n" "$f1" "$(csv_path "$f2")" "$f3" "$f4" "$f5" "$f6" "$f7" ;;
    esac
  done < "$quotes"
done
summary="check_quotes: $checked numbers and $ratios speed ratios in the chapters match their CSV files"
if [ $status = 0 ]; then
  if [ -n "$report" ]; then echo "$summary" >&2; else echo "$summary"; fi
fi
exit $status
