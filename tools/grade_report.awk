# grade_report.awk -- the grader's verdict, one line per exercise.
#
#   awk -v built=yes|no -v bad_files=FILE -f tools/grade_report.awk \
#       EXERCISES.tsv STATE.tsv TESTS.log
#
# EXERCISES.tsv is tools/exercises.awk's listing, STATE.tsv tools/grade.sh's
# (ID, state, workbook file, first and last line of its chunk), TESTS.log
# what the suites printed in Check's verbose mode, one line per test:
#   FILE:LINE:P|F|E:TCASE:TEST:ITERATION: MESSAGE
# An exercise is done when every test it names passed; otherwise the first
# of them (in the exercise's order) that did not pass says why: failing
# with the test's message, timed out, or crashed (signal N). Prints
# "Progress: D of N exercises" last, and exits 1 unless every started
# exercise is done and no workbook file was left out.

function verdict(id,    names, n, i, t, r) {
    n = split(tests[id], names, " ")
    for (i = 1; i <= n; i++) {
        t = names[i]
        if (!(t in result))
            return "failing: " t " did not run (did an earlier test stop the suites?)"
        r = result[t]
        if (r == "P")
            continue
        if (message[t] ~ /Test timeout expired/)
            return "timed out: " t
        if (match(message[t], /Received signal [0-9]+/))
            return "crashed (signal " substr(message[t], RSTART + 16, RLENGTH - 16) "): " t
        return "failing: " t ": " message[t]
    }
    return "done"
}

FILENAME == ARGV[1] { split($0, f, "\t"); order[++count] = f[1]; key[f[1]] = f[5]
                      tests[f[1]] = f[6]; next }
FILENAME == ARGV[2] { split($0, f, "\t"); st[f[1]] = f[2]; file_of[f[1]] = f[3]; next }
{
    # FILE:LINE:R:TCASE:TEST:ITER: MESSAGE (the message may hold colons)
    line = $0
    for (i = 1; i <= 6; i++) {
        p = index(line, ":")
        if (p == 0)
            next
        part[i] = substr(line, 1, p - 1)
        line = substr(line, p + 1)
    }
    if (part[3] !~ /^[PFE]$/)
        next
    sub(/^ /, "", line)
    sub(/^\(after this point\) /, "", line)
    if (!(part[5] in result) || result[part[5]] == "P") {
        result[part[5]] = part[3]
        message[part[5]] = line
    }
}

END {
    done = 0
    failed = 0
    while ((getline line < bad_files) > 0) {
        left_out[line] = 1
        failed++
    }
    for (i = 1; i <= count; i++) {
        id = order[i]
        s = st[id]
        if (s == "started" && (file_of[id] in left_out))
            v = "not graded: " file_of[id] " was left out (see above)"
        else if (s == "started")
            v = built == "yes" ? verdict(id) : "not graded: the build failed (see above)"
        else if (s == "not-started")
            v = "not started"
        else if (s == "absent")
            v = "not started (no workbook file: make workbook)"
        else
            v = "not graded: its workbook file has an error (see above)"
        if (v == "done")
            done++
        else if (s == "started" || s == "broken")
            failed++
        printf "  %-5s %-38s %s\n", id, key[id], v
    }
    printf "Progress: %d of %d exercises\n", done, count
    exit failed > 0
}
