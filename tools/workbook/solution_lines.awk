# solution_lines.awk -- the lines of the exercises' solutions.
#
#   awk -f tools/workbook/stub.awk -f tools/workbook/solution_lines.awk CHAPTER.md...
#
# prints every line of an exercise's code (a block whose fence carries
# .exercise) that its stub (tools/workbook/stub.awk) leaves out, without its blanks
# in front and behind, if that leaves at least 20 characters and is not a
# <<chunk>> reference (the book names those in its tasks): the lines a
# handout must not hold (tools/checks/check_handout.sh). With -v others=1 it
# prints instead every line of the other code blocks, trimmed: lines such
# as "return false;" that are no one exercise's secret. With -v runs=1 it
# prints every line that the stub leaves out, whatever its length, and a
# line "<<>>" where the stub keeps lines and where an exercise ends: the
# solutions' runs of lines (tools/checks/code_runs.awk).

function emit(    n, i, stub_lines, body_lines, kept, line) {
    n = split(stub_of(body), stub_lines, "\n")
    for (i = 1; i <= n; i++)
        kept[stub_lines[i]] = 1
    n = split(body, body_lines, "\n")
    for (i = 1; i <= n; i++) {
        line = body_lines[i]
        if (runs && line ~ /^[ \t]*$/)
            continue
        if (line in kept) {
            if (runs)
                print "<<>>"
            continue
        }
        if (runs) {
            print line
            continue
        }
        gsub(/^[ \t]+|[ \t]+$/, "", line)
        if (length(line) >= 20 && line !~ /^<<.*>>$/)
            print line
    }
}

in_code && $0 ~ "^" fence "[`~]*[ \t]*$" {
    if (is_exercise && !others)
        emit()
    if (is_exercise && runs)
        print "<<>>"
    in_code = 0
    next
}
in_code && is_exercise { body = body (body == "" ? "" : "\n") $0; next }
in_code && others { line = $0; gsub(/^[ \t]+|[ \t]+$/, "", line); print line }
in_code { next }
/^(```|~~~)/ {
    in_code = 1
    fence = substr($0, 1, 3)
    is_exercise = $0 ~ /[{ ]\.exercise[ }]/
    body = ""
}
