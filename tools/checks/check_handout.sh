#!/bin/sh
# check_handout.sh -- no line of an exercise's solution is in the handout.
#
# Usage: tools/checks/check_handout.sh HANDOUT_DIR   (make check-handout)
# The solution lines are tools/workbook/solution_lines.awk's, but for those that the
# book's other code, its tests or its tools also hold. Lines are compared
# normalised, so that a solution respaced, recommented or highlighted is
# found all the same: an HTML file's tags dropped and its escapes undone, a
# comment that ends the line dropped, and every blank removed. The same
# search in chapters/ must find them all: a search that finds nothing
# anywhere would prove nothing; and a solution line planted respaced and
# with a comment of its own must be found.
#
# Code that restates a solution in lines that are each common (a later
# chapter's loop written again, its tests written with | for ||, double
# for real) is found by its runs: every three lines of a solution, compared
# loosely (tools/checks/code_runs.awk), must not follow one another in the
# handout's code, unless a chapter before the exercise's holds them too
# (the exercise then repeats the book, not the other way round). The same
# search in chapters/ must find every run, and a chapter's solutions
# planted in disguise (respaced, commented, in other parentheses, with
# double for real and | for ||) must show all of that chapter's runs.
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
        if (FILENAME ~ /\.html?$/)
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
    awk -v others=1 -f tools/workbook/stub.awk -f tools/workbook/solution_lines.awk chapters/[0-9][0-9]-*.md
    cat tests/*.c tests/*.h tools/*/*.c
} | normalise | sort -u > "$patterns.common"
awk -f tools/workbook/stub.awk -f tools/workbook/solution_lines.awk chapters/[0-9][0-9]-*.md |
    normalise | awk 'length($0) >= 12' | sort -u |
    comm -23 - "$patterns.common" > "$patterns"
count=$(wc -l < "$patterns")
[ "$count" -gt 100 ] || { echo "check-handout: only $count solution lines found"; exit 1; }

# search DIR: the text files under DIR whose normalised text holds a
# pattern.
search() {
    text_files "$1"
    set --
    while IFS= read -r file; do set -- "$@" "$file"; done < "$patterns.files"
    [ "$#" -eq 0 ] || normalise "$@" | grep -F -f "$patterns" | cut -f 1 | uniq
}

# text_files DIR: the text files under DIR, sorted, one a line, into
# $patterns.files, for one awk to read them all (one a file took most of
# the check's time: a process each of a thousand files, three times).
text_files() {
    find "$1" -type f -exec grep -lI '' {} + | sort > "$patterns.files"
}
missing=$(cat chapters/[0-9][0-9]-*.md | normalise | grep -oF -f "$patterns" |
    sort -u | wc -l)
[ "$missing" = "$count" ] ||
    { echo "check-handout: the search finds $missing of $count lines in chapters/"; exit 1; }
mkdir "$patterns.planted"
head -n 1 "$patterns" | sed 's/./& /g; s|$|// mine|' > "$patterns.planted/x.c"
[ -n "$(search "$patterns.planted")" ] ||
    { echo "check-handout: a solution line respaced is not found"; exit 1; }
# The runs: CHAPTER TAB RUN for the solutions' and for the other code's.
for chapter in chapters/[0-9][0-9]-*.md; do
    number=$(basename "$chapter" | cut -d - -f 1)
    awk -v runs=1 -f tools/workbook/stub.awk -f tools/workbook/solution_lines.awk "$chapter" \
        > "$patterns.code"
    awk -f tools/checks/code_runs.awk "$patterns.code" |
        sed "s/^[^	]*/$number/" >> "$patterns.solution-runs"
    awk -v others=1 -f tools/workbook/stub.awk -f tools/workbook/solution_lines.awk "$chapter" \
        > "$patterns.code"
    awk -f tools/checks/code_runs.awk "$patterns.code" |
        sed "s/^[^	]*/$number/" >> "$patterns.other-runs"
done
# A run stays unless a chapter before its own holds it in other code.
awk -F '\t' 'FILENAME == ARGV[1] {
        if (!($2 in first) || $1 < first[$2]) first[$2] = $1
        next
    }
    !($2 in first) || first[$2] >= $1 { print $1 "\t" $2 }' \
    "$patterns.other-runs" "$patterns.solution-runs" | sort -u > "$patterns.runs"
cut -f 2 "$patterns.runs" | sort -u > "$patterns.run-set"
runs=$(wc -l < "$patterns.run-set")
[ "$runs" -gt 100 ] || { echo "check-handout: only $runs solution runs found"; exit 1; }

# runs_in FILE...: the solutions' runs that the files' code holds, each
# after its file's name and a tab.
runs_in() {
    awk -f tools/checks/code_runs.awk "$@" |
        awk -F '\t' 'FILENAME == ARGV[1] { want[$0] = 1; next }
            ($2 in want) && !seen[$0]++' "$patterns.run-set" -
}
found=$(runs_in chapters/[0-9][0-9]-*.md | cut -f 2 | sort -u | wc -l)
[ "$found" = "$runs" ] ||
    { echo "check-handout: the search finds $found of $runs runs in chapters/"; exit 1; }
awk -v runs=1 -f tools/workbook/stub.awk -f tools/workbook/solution_lines.awk chapters/04-*.md |
    sed -E 's/(^|[^A-Za-z0-9_])real([^A-Za-z0-9_]|$)/\1double\2/g;
            s/[|][|]/|/g; s/&&/\&/g; s/[(]/((/g; s/[)]/))/g; s/ /   /g;
            s|$| // mine|' > "$patterns.planted/disguised.c"
want=$(awk -F '\t' '$1 == "04"' "$patterns.runs" | wc -l)
found=$(runs_in "$patterns.planted/disguised.c" | wc -l)
[ "$want" -gt 0 ] && [ "$found" = "$want" ] ||
    { echo "check-handout: $found of chapter 4's $want runs found in disguise"; exit 1; }

text_files "$handout"
set --
while IFS= read -r file; do set -- "$@" "$file"; done < "$patterns.files"
found=$([ "$#" -eq 0 ] || runs_in "$@")
if [ -n "$found" ]; then
    echo "check-handout: a solution restated in the handout (three lines of it, loosely):"
    echo "$found" | head -6
    exit 1
fi
found=$(search "$handout")
if [ -n "$found" ]; then
    echo "check-handout: solution lines in the handout:"
    echo "$found" | head
    echo "$found" | head -3 | while read -r file; do
        normalise < "$file" | grep -noF -f "$patterns" | head -3 | sed "s|^|$file:|"
    done
    exit 1
fi
echo "check-handout: none of $count solution lines, nor of $runs runs of three, is in $handout (compared without blanks and comments)"
