#!/bin/sh
# check_line_directives.sh TANGLE CHAPTER.md PATTERN
# Types a syntax error into a copy of CHAPTER.md just above the first line
# that contains PATTERN, tangles it with --line, compiles every C file, and
# checks that the compiler blames CHAPTER.md at exactly that line: the
# promise that errors point at the Markdown a reader edits.
set -eu
tangle=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
chapter=$2 pattern=$3
work=build/linecheck
rm -rf "$work"
mkdir -p "$work/$(dirname "$chapter")"
line=$(grep -n -F -- "$pattern" "$chapter" | head -n 1 | cut -d: -f1)
[ -n "$line" ] || { echo "$chapter: error: no line contains '$pattern'"; exit 1; }
awk -v n="$line" 'NR == n { print "    this is not C;" } { print }' "$chapter" > "$work/$chapter"
(cd "$work" && "$tangle" --line -o out "$chapter")
status=0
for c in "$work"/out/*.c; do
  cc -std=c11 -fsyntax-only -I"$work/out" $(pkg-config --cflags libpng) "$c" 2>> "$work/errors.txt" || status=1
done
if [ $status = 0 ]; then
  echo "$chapter: error: the compiler accepted a syntax error"; exit 1
fi
if grep -q "^$chapter:$line:[0-9]*: error" "$work/errors.txt"; then
  echo "$chapter: a syntax error typed at line $line is reported at line $line"
else
  echo "$chapter: error: expected the compiler to report $chapter:$line, it said:"
  cat "$work/errors.txt"; exit 1
fi
