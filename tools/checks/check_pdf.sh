#!/bin/sh
# check_pdf.sh -- every chapter of the printed book starts a page.
#
# Usage: tools/checks/check_pdf.sh BOOK.pdf CHAPTER.md...   (make check-pdf)
# With pdftotext (poppler-utils), looks for each chapter N a page whose
# first line of text is "CHAPTER N" and whose next is the chapter's title
# (its first "# " line). Prints the chapters that do not, and exits 1.
set -u
pdf=$1
shift
text=$(mktemp)
trap 'rm -f "$text"' EXIT
pdftotext -layout "$pdf" "$text" || { echo "check-pdf: pdftotext cannot read $pdf"; exit 1; }
bad=0
for chapter in "$@"; do
    number=$(basename "$chapter" | sed 's/^0*\([0-9][0-9]*\)-.*/\1/')
    title=$(sed -n '1,/^# /s/^# \(.*\)$/\1/p' "$chapter" | head -n 1 | sed 's/ *{.*}[ \t]*$//')
    if ! awk -v head="CHAPTER $number" -v title="$title" '
        BEGIN { RS = "\f" }
        {
            n = split($0, lines, "\n"); k = 0
            for (i = 1; i <= n && k < 2; i++) {
                line = lines[i]
                gsub(/^[ \t]+|[ \t]+$/, "", line)
                if (line != "") seen[++k] = line
            }
            if (seen[1] == head && seen[2] == title) { found = 1; exit }
            delete seen
        }
        END { exit !found }' "$text"; then
        echo "check-pdf: $pdf: chapter $number ($title) does not start a page"
        bad=1
    fi
done
[ "$bad" = 0 ] && echo "check-pdf: $pdf: each of $# chapters starts a page"
exit "$bad"
