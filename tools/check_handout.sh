#!/bin/sh
# check_handout.sh -- no line of an exercise's solution is in the handout.
#
# Usage: tools/check_handout.sh HANDOUT_DIR   (make check-handout)
# The solution lines are tools/solution_lines.awk's, but for those that the
# book's other code, its tests or its tools also hold. Lines are compared
# normalised, so that a solution respaced, recommented or highlighted is
# found all the same: HTML's tags dropped and its escapes undone, a
# comment that ends the line dropped, and every blank removed. The same
# search in chapters/ must find them all: a search that finds nothing
# anywhere would prove nothing; and a solution line planted respaced and
# with a comment of its own must be found.
set -eu
handout=$1
patterns=$(mktemp)
trap 'rm -rf "$patterns" "$patterns".*' EXIT

# normalise [FILE...]: each line of the files (the standard input without
# one) as the search compares it; with files, each after its file's name
# and a tab.
normalise() {
    awk -v named=$# '{
        line = $0
        gsub(/<[^>]*>/, "", line)
        gsub(/&lt;/, "<", line); gsub(/&gt;/, ">", line)
        gsub(/&quot;/, "\"", line); gsub(/&#39;/, "\047", line)
        gsub(/&amp;/, "\\&", line)
        sub(/\/\/.*$/, "", line); gsub(/\/\*.*\*\//, "", line)
        gsub(/[ \t\r\f\v]/, "", line)
        print (named ? FILENAME "\t" : "") line
    }' "$@"
}

# Lines that the rest of the book, its tests or its tools also hold give
# nothing away: they are no exercise's secret.
{
    awk -v others=1 -f tools/stub.awk -f tools/solution_lines.awk chapters/[0-9][0-9]-*.md
    cat tests/*.c tests/*.h tools/*.c tools/diagrams/*.c
} | normalise | sort -u > "$patterns.common"
awk -f tools/stub.awk -f tools/solution_lines.awk chapters/[0-9][0-9]-*.md |
    normalise | awk 'length($0) >= 12' | sort -u |
    comm -23 - "$patterns.common" > "$patterns"
count=$(wc -l < "$patterns")
[ "$count" -gt 100 ] || { echo "check-handout: only $count solution lines found"; exit 1; }

# search DIR: the text files under DIR whose normalised text holds a
# pattern.
search() {
    find "$1" -type f -exec grep -lI '' {} + | sort |
        while read -r file; do normalise "$file"; done |
        grep -F -f "$patterns" | cut -f 1 | uniq
}
missing=$(cat chapters/[0-9][0-9]-*.md | normalise | grep -oF -f "$patterns" |
    sort -u | wc -l)
[ "$missing" = "$count" ] ||
    { echo "check-handout: the search finds $missing of $count lines in chapters/"; exit 1; }
mkdir "$patterns.planted"
head -n 1 "$patterns" | sed 's/./& /g; s|$|// mine|' > "$patterns.planted/x.c"
[ -n "$(search "$patterns.planted")" ] ||
    { echo "check-handout: a solution line respaced is not found"; exit 1; }
found=$(search "$handout")
if [ -n "$found" ]; then
    echo "check-handout: solution lines in the handout:"
    echo "$found" | head
    echo "$found" | head -3 | while read -r file; do
        normalise < "$file" | grep -noF -f "$patterns" | head -3 | sed "s|^|$file:|"
    done
    exit 1
fi
echo "check-handout: none of $count solution lines is in $handout (compared without blanks and comments)"
