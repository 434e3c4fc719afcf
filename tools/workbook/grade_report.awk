# grade_report.awk -- the grader's verdict, one line per exercise.
#
#   awk -v built=yes|no -v bad_files=FILE [-v cleared=FILE -v later=FILE] \
#       -f tools/workbook/grade_report.awk \
#       EXERCISES.tsv STATE.tsv TESTS.log
#
# EXERCISES.tsv is tools/workbook/exercises.awk's listing, STATE.tsv tools/workbook/grade.sh's
# (ID, state, workbook file, first and last line of its chunk), TESTS.log
# what the suites printed in Check's verbose mode, one line per test:
#   FILE:LINE:P|F|E:TCASE:TEST:ITERATION: MESSAGE
# An exercise names a test, or one iteration K of a loop test as TEST:K.
# Every suite of the chapters graded ran against the reader's program. An
# exercise is done when every test it names passed and no other test
# failed; otherwise the first of its tests (in the exercise's order) that
# did not pass says why: failing with the test's message, timed out, or
# crashed (signal N). A failing test that the exercise passes alone, the
# book's code in every other exercise (-v cleared=FILE: lines "ID<tab>
# TEST", tools/workbook/grade.sh), does not count against it, nor does a test of a
# later chapter's suites, which did not run (-v later=FILE: one name a
# line). A failing test that no started exercise names, or none that
# fails it alone, is listed after the exercises, as the reader's code
# breaking something elsewhere: every test passes with the book's code
# alone. Prints
# "Progress: D of N exercises" last, and exits 1 unless every started
# exercise is done, no other test failed and no workbook file was left out.

function verdict(id,    names, n, i, t, r, graded) {
    n = split(tests[id], names, " ")
    graded = 0
    for (i = 1; i <= n; i++) {
        t = names[i]
        if ((id SUBSEP t) in clear)
            continue
        if (!(t in result) && bare_name(t) in later_test)
            continue
        graded++
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
    return graded > 0 ? "done" : "not graded: its tests are a later chapter's"
}

# A test's name without the iteration an exercise may give it (TEST:K).
function bare_name(t) {
    sub(/:[0-9]+$/, "", t)
    return t
}

# A message as the test's source spells it: the C library's macros were
# expanded when the assertion was turned into text.
function readable(text) {
    gsub(/\(__builtin_inff ?\(\)\)/, "INFINITY", text)
    gsub(/\(__builtin_nanf ?\(""\)\)/, "NAN", text)
    gsub(/\(\(double\)2\.22044604925031308084726333618164062e-16L\)/, "DBL_EPSILON", text)
    return text
}

BEGIN {
    while (cleared != "" && (getline line < cleared) > 0) {
        split(line, f, "\t")
        clear[f[1], f[2]] = 1
    }
    while (later != "" && (getline line < later) > 0)
        later_test[line] = 1
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
    # a loop test's iteration K is also "TEST:K", which an exercise may name
    # alone (chapter 2's forms: one iteration an exercise); the test's own
    # name stands for its worst iteration
    full = part[5] ":" part[6]
    if (!(full in result)) {
        ran[++ran_count] = full
        shown[full] = part[6] == "0" ? part[5] : full
        bare[full] = part[5]
    }
    record(full, line)
    record(part[5], line)
}

# The result of test key k (a test or one iteration of it): its first
# result that did not pass, or its pass.
function record(k, text) {
    if (!(k in result) || result[k] == "P") {
        result[k] = part[3]
        message[k] = readable(text)
        where[k] = part[1] ":" part[2]
    }
}

# The failing tests that no started exercise names (or none that was not
# cleared of it, passing it alone), in the order they ran, into
# broken[1..]; returns how many.
function broken_elsewhere(    i, j, n, names, count_broken) {
    for (i = 1; i <= count; i++) {
        if (st[order[i]] != "started")
            continue
        n = split(tests[order[i]], names, " ")
        for (j = 1; j <= n; j++)
            if (!((order[i] SUBSEP names[j]) in clear))
                named[names[j]] = 1
    }
    count_broken = 0
    for (i = 1; i <= ran_count; i++)
        if (result[ran[i]] != "P" && !(ran[i] in named) &&
            !(bare[ran[i]] in named))
            broken[++count_broken] = ran[i]
    return count_broken
}

END {
    done = 0
    failed = 0
    elsewhere = built == "yes" ? broken_elsewhere() : 0
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
        if (v == "done" && elsewhere > 0)
            v = "its tests pass, but " elsewhere " other test(s) fail (below)"
        if (v == "done")
            done++
        else if (s == "started" || s == "broken")
            failed++
        printf "  %-5s %-38s %s\n", id, key[id], v
    }
    if (elsewhere > 0) {
        print "Failing, and the fault of no exercise you started alone" \
              " (your code elsewhere, or two exercises together; each" \
              " passes with the book's code):"
        for (i = 1; i <= elsewhere; i++)
            printf "  %s (%s): %s\n", shown[broken[i]], where[broken[i]],
                   message[broken[i]]
        failed++
    }
    printf "Progress: %d of %d exercises\n", done, count
    exit failed > 0
}
