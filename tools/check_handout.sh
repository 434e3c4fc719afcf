#!/bin/sh
# check_handout.sh -- no line of an exercise's solution is in the handout.
#
# Usage: tools/check_handout.sh HANDOUT_DIR   (make check-handout)
# The solution lines are tools/solution_lines.awk's, but for those that the
# book's other code, its tests or its tools also hold; each is looked for, as it is and as HTML escapes it, in every file of the
# handout. The same search in chapters/ must find them all: a search that
# finds nothing anywhere would prove nothing.
set -eu
handout=$1
patterns=$(mktemp)
trap 'rm -f "$patterns" "$patterns.html" "$patterns.common"' EXIT

# Lines that the rest of the book, its tests or its tools also hold give
# nothing away: they are no exercise's secret.
{
    awk -v others=1 -f tools/stub.awk -f tools/solution_lines.awk chapters/[0-9][0-9]-*.md
    cat tests/*.c tests/*.h tools/*.c tools/diagrams/*.c | sed 's/^[ \t]*//; s/[ \t]*$//'
} | sort -u > "$patterns.common"
awk -f tools/stub.awk -f tools/solution_lines.awk chapters/[0-9][0-9]-*.md | sort -u |
    comm -23 - "$patterns.common" > "$patterns"
sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' -e 's/"/\&quot;/g' \
    "$patterns" > "$patterns.html"
count=$(wc -l < "$patterns")
[ "$count" -gt 100 ] || { echo "check-handout: only $count solution lines found"; exit 1; }
missing=$(grep -hoF -f "$patterns" chapters/[0-9][0-9]-*.md | sort -u | wc -l)
[ "$missing" = "$count" ] ||
    { echo "check-handout: the search finds $missing of $count lines in chapters/"; exit 1; }
if found=$(grep -rlF -f "$patterns" -f "$patterns.html" "$handout"); then
    echo "check-handout: solution lines in the handout:"
    echo "$found" | head
    grep -rnoF -f "$patterns" -f "$patterns.html" "$handout" | head -10
    exit 1
fi
echo "check-handout: none of $count solution lines is in $handout"
