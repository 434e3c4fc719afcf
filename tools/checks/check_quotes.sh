#!/bin/sh
# check_quotes.sh [--csv-dir DIR] [--report] [QUOTES...]: are the numbers
# the chapters quote still the numbers their benchmarks measured?
#
# Each QUOTES file (default bench/quotes.txt) has one claim a line, fields
# separated by '|', spaces and tabs around them ignored; blank lines and
# lines starting with '#' are skipped. The seventh field (FORMAT, or a
# RATIO's TEXT) runs to the end of the line and may itself contain '|'.
# CSV files are those `make charts` writes;
# their '#' lines (the machine line) are skipped. A chapter is searched for
# a fixed string in its text with its lines joined by spaces and every run
# of spaces squeezed to one. Three kinds of line:
#
# Errors, deterministic numbers printed by the chapter:
#   CHAPTER | CSV | METHOD | PARAM | KIND | SCALE | FORMAT
#   The row METHOD,PARAM,KIND of CSV has an error column; divided by SCALE
#   (SCALE "log10": its decimal logarithm) and printed through the printf
#   FORMAT, it must appear in CHAPTER (with the chapter's lines joined).
#   FORMAT has at most one conversion (%% prints a '%').
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
#   must say that the two cannot be told apart. tools/checks/charts_check.sh
#   reports whether the order of an ordered claim flips between runs.
#
# Absolute times, true only of the machine named on the CSV's first line:
#   TIME | CHAPTER | CSV | METHOD,PARAM | LO..HI [per N] | TEXT
#   CHAPTER must contain TEXT, and the interval [ns_q1, ns_q3] of the row
#   (divided by N when "per N" is given: "some 15 ns per triangle") must
#   lie inside [LO, HI] nanoseconds.
#
# Each failed check prints one line "WHERE: error: WHAT" on standard output;
# WHERE is the chapter when the chapter's text or numbers are wrong, and
# QUOTES:LINE when the claim itself is (no such row, a bad band or format,
# a CSV that cannot be read). A QUOTES file that cannot be read is an error
# too. With no error, a summary line (on standard error under --report) and
# exit status 0; else exit status 1.
#
# --csv-dir DIR reads every CSV from DIR (same file name) instead: how
# `make charts-check` checks its reruns. --report prints, for each RATIO
# line, "ratio QUOTES:LINE A/B MEDIAN LO HI BAND VERDICT" on standard output
# (VERDICT: ok, or what is wrong with the numbers; the text is not looked
# at), for tools/checks/charts_check.sh.
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

# All the work is one awk program (forks are slow: a few processes a line
# took a minute), which reads every QUOTES file, CSV and chapter once. The
# options travel through the environment: awk -v would eat backslashes.
# The file names are awk operands, only ever opened with getline.
export CHECK_QUOTES_CSV_DIR="$csv_dir" CHECK_QUOTES_REPORT="$report"
exec awk '
# sq(S): S between single quotes.
function sq(s) { return "\047" s "\047" }

# fail(MESSAGE): one error line.
function fail(m) { print m; status = 1 }

# slurp(F): the bytes of file F (RS is a byte no text file holds, so one
# record is normally the whole file); sets unreadable to 1 if F cannot be
# opened or is a directory. getline < "-" would read standard input: "-"
# is a file here.
function slurp(f,   g, s, r, n, rc) {
  if (f in DIRECTORY) { unreadable = 1; return "" }
  g = f == "-" ? "./-" : f
  s = ""; n = 0
  while ((rc = (getline r < g)) > 0) s = s (n++ ? RS : "") r
  close(g)
  unreadable = rc < 0
  return s
}

# find_directories(PATHS): put in DIRECTORY those of the files PATHS (each
# after a space) that are directories, which awk would stop at: one shell
# for them all.
function find_directories(paths,   cmd, s, r, n, D, i) {
  if (paths == "") return
  cmd = "for f in" paths "; do [ -d \"$f\" ] && printf \"%s\\n\" \"$f\"; done"
  s = ""; n = 0
  while ((cmd | getline r) > 0) s = s (n++ ? RS : "") r
  close(cmd)
  n = lines(s, D)
  for (i = 1; i <= n; i++) DIRECTORY[D[i]] = 1
}

# shell_word(S): S quoted for the shell.
function shell_word(s) {
  gsub(/\047/, "\047\\\\\047\047", s)
  return " \047" s "\047"
}

# lines(S, L): the lines of text S in L[1..n] (the last one may lack its
# newline); returns n.
function lines(s, L,   n) {
  n = split(s, L, "\n")
  if (n > 0 && L[n] == "") n--
  return n
}

# strnum(S): S as awk -v or a field would hold it: compared as a number
# with a field that looks numeric too ("2.0" is the param "2"), else as a
# string.
function strnum(s,   T) {
  if (s == "") return ""
  split(s, T, "\n")
  return T[1]
}

# csv_path(F): F, or its file name in --csv-dir.
function csv_path(f) {
  if (csv_dir == "") return f
  if (f != "") {
    while (f ~ /.\/$/) sub(/\/$/, "", f)
    if (f != "/") sub(/.*\//, "", f)
  }
  return csv_dir "/" f
}

# csv(F): read CSV F once, its rows but the # lines in CELL[F, ROW, 1..7]
# and their number in ROWS[F]; 0 if F cannot be read.
function csv(f,   s, L, n, i, k, j, C) {
  if (!(f in ROWS)) {
    s = slurp(f)
    if (unreadable) { ROWS[f] = -1; return 0 }
    n = lines(s, L)
    k = 0
    for (i = 1; i <= n; i++) {
      if (L[i] ~ /^#/) continue
      split(L[i], C, ",")
      k++
      for (j = 1; j <= 7; j++) CELL[f, k, j] = C[j]
    }
    ROWS[f] = k
  }
  return ROWS[f] >= 0
}

# error_of(F, M, P, K): the error column of the first row M,P,K of CSV F,
# "" if none.
function error_of(f, m, p, k,   i) {
  for (i = 1; i <= ROWS[f]; i++)
    if (CELL[f, i, 1] == m && CELL[f, i, 2] == p && CELL[f, i, 5] == k)
      return CELL[f, i, 4]
  return ""
}

# timing_of(F, METHOD,PARAM): "median q1 q3" of the first timed row of that
# method and param in CSV F, "" if none.
function timing_of(f, a,   c, m, p, i) {
  c = index(a, ",")
  if (c) { m = strnum(substr(a, 1, c - 1)); p = strnum(substr(a, c + 1)) }
  else m = p = strnum(a)
  for (i = 1; i <= ROWS[f]; i++)
    if (CELL[f, i, 1] == m && CELL[f, i, 2] == p && CELL[f, i, 3] != "")
      return CELL[f, i, 3] " " CELL[f, i, 6] " " CELL[f, i, 7]
  return ""
}

# found(CHAPTER, TEXT): does the chapter, lines joined with single spaces
# and runs of spaces squeezed, contain the fixed string TEXT? (What
# tr "\n" " " | tr -s " " | grep -qF did: an empty TEXT is in any chapter
# but an empty one.)
function found(ch, t,   s) {
  if (!(ch in TEXT)) {
    s = slurp(ch)
    if (unreadable) {
      fflush()
      printf "check_quotes: cannot read %s\n", ch > "/dev/stderr"
    }
    gsub(/\n/, " ", s)
    gsub(/  +/, " ", s)
    TEXT[ch] = s
  }
  if (t == "") return TEXT[ch] != ""
  return index(TEXT[ch], t) > 0
}

# bad_format(F): is F not a printf format of at most one conversion that
# awk can apply to one number? (awk would stop with a run-time error.)
function bad_format(f,   i, n, rest) {
  n = 0
  while ((i = index(f, "%")) > 0) {
    rest = substr(f, i)
    if (substr(rest, 2, 1) == "%") { f = substr(rest, 3); continue }
    if (!match(rest, /^%[-+ #0]*[0-9]*(\.[0-9]*)?([hl]?[diouxX]|[cseEfgG])/))
      return 1
    if (++n > 1) return 1
    f = substr(rest, RLENGTH + 1)
  }
  return 0
}

# ratio_verdict(BAND, X): "MEDIAN LO HI VERDICT" of the ratio of A to B,
# X[1..6] being "median q1 q3" of A then of B.
function ratio_verdict(band, X,   r, lo, hi, out, within, b, has1) {
  if (X[4] <= 0 || X[5] <= 0) return "0 0 0 badrow"
  r = X[1] / X[4]; lo = X[2] / X[6]; hi = X[3] / X[5]
  out = sprintf("%.3f %.3f %.3f ", r, lo, hi)
  if (band == "same") return out ((lo <= 1 && 1 <= hi) ? "ok" : "ordered")
  within = sub(/^within +/, "", band)
  if (split(band, b, /\.\./) != 2 || b[1] !~ /^[0-9.]+$/ || b[2] !~ /^[0-9.]+$/ || b[1] + 0 > b[2] + 0)
    return out "badband"
  has1 = b[1] <= 1 && 1 <= b[2]
  if (within != has1) return out (within ? "withoutside1" : "bandhas1")
  if (!within && lo <= 1 && 1 <= hi) return out "includes1"
  return out ((b[1] <= lo && hi <= b[2]) ? "ok" : "outside")
}

# time_verdict(BAND, X): "MEDIAN Q1 Q3 VERDICT", X[1..3] being "median q1 q3".
function time_verdict(band, X,   per, b, lo, hi) {
  per = 1
  if (band ~ / per /) { per = band; sub(/.* per /, "", per); sub(/ per .*/, "", band) }
  if (split(band, b, /\.\./) != 2) return "- - - badband"
  lo = X[2] / per; hi = X[3] / per
  return sprintf("%.4g %.4g %.4g %s", X[1] / per, lo, hi, (b[1] <= lo && hi <= b[2]) ? "ok" : "outside")
}

# parse(LINE): its fields in F[1..7], split at the first six "|" (F[7]
# runs to the end of the line, less a last "|" if it has only that one,
# as IFS="|" read f1 ... f7 splits), spaces and tabs around them trimmed.
function parse(line,   n, c, i) {
  for (i = 1; i <= 7; i++) F[i] = ""
  n = 0
  while (n < 6 && (c = index(line, "|")) > 0) {
    F[++n] = substr(line, 1, c - 1)
    line = substr(line, c + 1)
  }
  if (n < 6) F[n + 1] = line
  else {
    if (line ~ /^[^|]*[|]$/) line = substr(line, 1, length(line) - 1)
    F[7] = line
  }
  for (i = 1; i <= 7; i++) { sub(/^[ \t]+/, "", F[i]); sub(/[ \t]+$/, "", F[i]) }
}

# check_error(WHERE): CHAPTER | CSV | METHOD | PARAM | KIND | SCALE | FORMAT
function check_error(where,   ch, path, v, s, text) {
  ch = F[1]; path = csv_path(F[2])
  if (!csv(path)) { fail(where ": error: cannot read " path); return }
  v = error_of(path, strnum(F[3]), strnum(F[4]), strnum(F[5]))
  if (v == "") { fail(where ": error: no row " F[3] "," F[4] "," F[5] " in " path); return }
  checked++
  if (bad_format(F[7])) {
    fail(where ": error: format " sq(F[7]) " is not a printf format with at most one conversion")
    return
  }
  s = strnum(F[6])
  if (s == "log10") text = sprintf(F[7], log(v) / log(10)); else text = sprintf(F[7], v / s)
  sub(/\n+$/, "", text)
  if (!found(ch, text))
    fail(ch ": error: quotes " sq(text) " for " F[3] "," F[4] "," F[5] " of " path " (" v "): not found")
}

# check_ratio(WHERE): RATIO | CHAPTER | CSV | A | B | BAND | TEXT
function check_ratio(where,   ch, path, a, b, X, W, ab, bd, what) {
  ch = F[2]; path = csv_path(F[3])
  if (!csv(path)) { fail(where ": error: cannot read " path); return }
  a = timing_of(path, F[4]); b = timing_of(path, F[5])
  if (a == "") { fail(where ": error: no timed row " F[4] " in " path); return }
  if (b == "") { fail(where ": error: no timed row " F[5] " in " path); return }
  split(a " " b, X, " ")
  split(ratio_verdict(F[6], X), W, " ")
  ratios++
  if (report != "") {
    ab = F[4] "/" F[5]; gsub(/ /, "_", ab)
    bd = F[6]; gsub(/ /, "_", bd)
    print "ratio " where " " ab " " W[1] " " W[2] " " W[3] " " bd " " W[4]
  }
  what = sq(F[7]) ": " F[4] " / " F[5] " = " W[1] " (" W[2] ".." W[3] ")"
  if (W[4] == "badband") fail(where ": error: band " sq(F[6]) " is not LO..HI, within LO..HI or same")
  else if (W[4] == "bandhas1") fail(where ": error: band " F[6] " contains 1: it orders nothing; write " sq("within " F[6]) " or " sq("same"))
  else if (W[4] == "withoutside1") fail(where ": error: band " sq(F[6]) " does not contain 1: an ordered claim is just LO..HI")
  else if (W[4] == "badrow") fail(where ": error: " F[4] " or " F[5] " has no positive time in " path)
  else if (W[4] == "includes1") fail(ch ": error: " what " includes 1: state it as indistinguishable (band " sq("same") ")")
  else if (W[4] == "ordered") fail(ch ": error: " what " says one is faster: not indistinguishable")
  else if (W[4] == "outside") fail(ch ": error: " what " is not within the band " F[6])
  if (!found(ch, F[7])) fail(ch ": error: " sq(F[7]) " (" F[4] " / " F[5] " in " F[6] "): not found")
}

# check_time(WHERE): TIME | CHAPTER | CSV | A | BAND | TEXT
function check_time(where,   ch, path, t, X, W) {
  ch = F[2]; path = csv_path(F[3])
  if (!csv(path)) { fail(where ": error: cannot read " path); return }
  t = timing_of(path, F[4])
  if (t == "") { fail(where ": error: no timed row " F[4] " in " path); return }
  split(t, X, " ")
  split(time_verdict(F[5], X), W, " ")
  checked++
  if (W[4] == "badband") fail(where ": error: band " sq(F[5]) " is not LO..HI [per N]")
  else if (W[4] != "ok") fail(ch ": error: " sq(F[6]) ": " F[4] " takes " W[1] " ns (" W[2] ".." W[3] "), not within " F[5])
  if (!found(ch, F[6])) fail(ch ": error: " sq(F[6]) " (" F[4] " in " F[5] "): not found")
}

BEGIN {
  RS = "\001"
  csv_dir = ENVIRON["CHECK_QUOTES_CSV_DIR"]
  report = ENVIRON["CHECK_QUOTES_REPORT"]
  status = 0; checked = 0; ratios = 0
  # Every claim of every QUOTES file in CLAIM[1..n], WHERE it is, and the
  # files it names in paths, so that all directories are found at once.
  paths = ""
  for (q = 1; q < ARGC; q++) paths = paths shell_word(ARGV[q])
  find_directories(paths)
  n = 0; paths = ""
  for (q = 1; q < ARGC; q++) {
    s = slurp(ARGV[q])
    if (unreadable) { CLAIM[++n] = ""; WHERE[n] = ARGV[q]; continue }
    m = lines(s, L)
    for (i = 1; i <= m; i++) {
      parse(L[i])
      if (F[1] == "" || F[1] ~ /^#/) continue
      CLAIM[++n] = L[i]; WHERE[n] = ARGV[q] ":" i
      if (F[1] == "RATIO" || F[1] == "TIME") { ch = F[2]; path = csv_path(F[3]) }
      else { ch = F[1]; path = csv_path(F[2]) }
      if (!(ch in NAMED)) { NAMED[ch] = 1; paths = paths shell_word(ch) }
      if (!(path in NAMED)) { NAMED[path] = 1; paths = paths shell_word(path) }
    }
  }
  find_directories(paths)
  for (i = 1; i <= n; i++) {
    if (CLAIM[i] == "") { fail(WHERE[i] ": error: cannot read this quotes file"); continue }
    parse(CLAIM[i])
    if (F[1] == "RATIO") check_ratio(WHERE[i])
    else if (F[1] == "TIME") check_time(WHERE[i])
    else check_error(WHERE[i])
  }
  summary = "check_quotes: " checked " numbers and " ratios " speed ratios in the chapters match their CSV files"
  if (status == 0) {
    if (report != "") { fflush(); print summary > "/dev/stderr" }
    else print summary
  }
  exit status
}' "$@"
