# grade_report.awk -- the grader's verdict, one line per exercise.
#
#   awk -v built=yes|no -v bad_files=FILE [-v later=FILE -v laid=FILE \
#       -v cleared=FILE -v lost=FILE -v warned=FILE -v races=FILE \
#       -v index_file=FILE -v multiplier=M -v load=L -v cores=C \
#       -v only=ID -v junit=FILE -v chapter=NN -v stubs=yes \
#       -v stubbed="ID ..." -v stubs_fail=FILE -v fragments_waiting="ID ..."] \
#       -f tools/workbook/grade_report.awk EXERCISES.tsv STATE.tsv TESTS.log
#
# EXERCISES.tsv is tools/workbook/exercises.awk's listing, STATE.tsv tools/workbook/grade.sh's
# (ID, state, workbook file, first and last line of its chunk), TESTS.log
# what the suites printed in Check's verbose mode, one line per test:
#   FILE:LINE:P|F|E:TCASE:TEST:ITERATION: MESSAGE
# An exercise names a test, or one iteration K of a loop test as TEST:K.
# tools/workbook/grade.sh ran the failing tests again with some exercises alone in
# place of the book's code: laid holds "ID<tab>TEST:K" for a test that
# fails with exercise ID alone started, cleared the same for a test that
# ID names and passes alone. lost, warned and races hold "ID<tab>MESSAGE":
# a <<chunk>> line the exercise lost, the compiler's warning at its lines,
# and a data race ThreadSanitizer saw in its code (ID "-": in no
# exercise's). index_file is tools/workbook/test_index.awk's listing (where each
# test is, and its own time limit), multiplier what limits were
# multiplied by, load and cores the machine's when the tests ran. A test
# of a later chapter's suites, which did not run, is not held against an
# exercise that names it (later: one name a line).
#
# An exercise is done when every test it names passed (or failed with
# another exercise alone to blame, or passed with it alone), no other test
# was laid on it, the compiler did not warn at its lines, no data race
# was seen in them and it kept its <<chunk>> lines; otherwise the first
# of these that did not hold says why: failing with the test's message,
# timed out (after how long, and the machine's load), or crashed (signal
# N). The failing tests that no one exercise causes are listed after the
# exercises. Prints "Progress: D of N exercises" last, writes junit (a
# JUnit report, a test case an exercise), and exits 1 unless every
# started exercise is done, no other test failed and no workbook file was
# left out; with only=ID, 0 exactly when that exercise is done.
#
# With stubs=yes (a handout whose compiled book's code this machine cannot
# link) the exercises not started are stubs, not the book's code, and
# nothing was laid on an exercise: a failing test that a not-started
# exercise names, or that no started exercise names, waits for the
# exercises not started; it is listed as waiting and fails nothing.
# stubbed lists the exercises whose stubs stand in though the book's code
# is linked (in a handout, a part of a function's body, which has no
# function to call the book's code through): a test that one of them
# names, not started, waits for it in the same way, and so does a test
# listed in the file stubs_fail (TEST:K a line: it fails with none of the
# reader's exercises, the stubs of fragments_waiting standing in).

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

# What went wrong with failing test key k (TEST:K, or TEST).
function describe(k,    t, limit, shown_k) {
    t = bare_name(k)
    shown_k = (k in shown) ? shown[k] : k
    if (message[k] ~ /Test timeout expired/) {
        limit = (t in own_limit && own_limit[t] > 0 ? own_limit[t] : 10) * multiplier
        return "timed out after " limit " s (its limit; the machine's load was " \
               load " on " cores " cores as the grade began): " shown_k " (" located(t) ")"
    }
    if (match(message[k], /Received signal [0-9]+/))
        return "crashed (signal " substr(message[k], RSTART + 16, RLENGTH - 16) \
               "): " shown_k " (" located(t) ")"
    return "failing: " shown_k ": " message[k]
}

function located(t) {
    return (t in test_file) ? test_file[t] ":" test_line[t] : "its suite"
}

# The failing keys of test name t as an exercise names it: t itself
# (TEST:K), or every failing iteration of TEST, into keys[1..]; how many.
function failing_keys(t, keys,    i, n) {
    n = 0
    if (t ~ /:[0-9]+$/) {
        if ((t in result) && result[t] != "P")
            keys[++n] = t
        return n
    }
    for (i = 1; i <= ran_count; i++)
        if (bare[ran[i]] == t && result[ran[i]] != "P")
            keys[++n] = ran[i]
    return n
}

# Does failing test k wait for the stub of an exercise not started?
function waits_for_stub(k) {
    return bare[k] in named_by_waiting || k in named_by_waiting
}

function verdict(id,    names, n, i, t, graded, keys, m, j, k) {
    if (id in lost_line)
        return "failing: " lost_line[id]
    if (id in warning)
        return "failing: the compiler warns at your line: " warning[id]
    n = split(tests[id], names, " ")
    graded = 0
    for (i = 1; i <= n; i++) {
        t = names[i]
        if (!(t in result) && bare_name(t) in later_test)
            continue
        graded++
        if (!(t in result))
            return "failing: " t " did not run (did an earlier test stop the suites?)"
        m = failing_keys(t, keys)
        for (j = 1; j <= m; j++) {
            k = keys[j]
            # a stub's test fails whoever is laid on it: it waits first
            if (waits_for_stub(k))
                return "waiting for " named_by_waiting[k in named_by_waiting ? k : bare[k]] \
                       " (not started): " shown[k]
            if ((id SUBSEP k) in laid_on)
                return describe(k)
            if ((k in laid_any) || ((id SUBSEP k) in clear))
                continue
            claimed[k] = 1
            return describe(k)
        }
    }
    for (j = 1; j <= ran_count; j++) {
        k = ran[j]
        # laid on it with a stub standing in: the stub's failure, not its
        if ((id SUBSEP k) in laid_on && result[k] != "P" && !waits_for_stub(k))
            return describe(k) " (" located(bare[k]) "; it fails with your " \
                   id " alone in place of the book's code)"
    }
    if (id in race)
        return "failing: " race[id]
    return graded > 0 ? "done" : "not graded: its tests are a later chapter's"
}

function xml(text) {
    gsub(/&/, "\\&amp;", text)
    gsub(/</, "\\&lt;", text)
    gsub(/>/, "\\&gt;", text)
    gsub(/"/, "\\&quot;", text)
    gsub(/[\001-\010\013\014\016-\037]/, "", text)
    return text
}

function read_pairs(file, into,    line, f) {
    while (file != "" && (getline line < file) > 0) {
        split(line, f, "\t")
        into[f[1], f[2]] = 1
    }
}

BEGIN {
    # the tests that fail with none of the reader's exercises started,
    # the stubs of fragments_waiting standing in: they wait for those
    waited = fragments_waiting
    gsub(/^ +| +$/, "", waited)
    gsub(/ +/, ", ", waited)
    while (stubs_fail != "" && (getline line < stubs_fail) > 0)
        named_by_waiting[line] = waited
    read_pairs(laid, laid_on)
    read_pairs(cleared, clear)
    for (p in laid_on) {
        split(p, f, SUBSEP)
        laid_any[f[2]] = 1
    }
    while (later != "" && (getline line < later) > 0)
        later_test[line] = 1
    while (lost != "" && (getline line < lost) > 0) {
        split(line, f, "\t")
        if (!(f[1] in lost_line))
            lost_line[f[1]] = f[2]
    }
    while (warned != "" && (getline line < warned) > 0) {
        p = index(line, "\t")
        warning[substr(line, 1, p - 1)] = substr(line, p + 1)
    }
    while (races != "" && (getline line < races) > 0) {
        p = index(line, "\t")
        id = substr(line, 1, p - 1)
        if (id == "-")
            loose_race[++loose_races] = substr(line, p + 1)
        else if (!(id in race))
            race[id] = substr(line, p + 1)
    }
    while (index_file != "" && (getline line < index_file) > 0) {
        split(line, f, "\t")
        test_file[f[1]] = f[2]
        test_line[f[1]] = f[3]
        own_limit[f[1]] = f[4] + 0
    }
    if (multiplier == "")
        multiplier = 1
}

FILENAME == ARGV[1] { split($0, f, "\t"); order[++count] = f[1]; key[f[1]] = f[5]
                      tests[f[1]] = f[6]; next }
FILENAME == ARGV[2] {
    split($0, f, "\t"); st[f[1]] = f[2]; file_of[f[1]] = f[3]
    # its tests wait for it, where it is a stub: every exercise not
    # started with stubs=yes, those listed in stubbed otherwise
    if (f[2] != "started" &&
        (stubs == "yes" || index(" " stubbed " ", " " f[1] " ") > 0)) {
        n = split(tests[f[1]], names, " ")
        for (i = 1; i <= n; i++)
            if (!(names[i] in named_by_waiting))
                named_by_waiting[names[i]] = f[1]
    }
    next
}
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
        if (s == "started" && (id in lost_line))
            v = "failing: " lost_line[id]
        else if (s == "started" && (file_of[id] in left_out))
            v = "not graded: " file_of[id] " was left out (see above)"
        else if (s == "started")
            v = built == "yes" ? verdict(id) : "not graded: the build failed (see above)"
        else if (s == "not-started")
            v = "not started"
        else if (s == "absent")
            v = "not started (no workbook file: make workbook)"
        else
            v = "not graded: its workbook file has an error (see above)"
        verdicts[id] = v
        if (v == "done")
            done++
        else if (s == "started" || s == "broken")
            failed++
        printf "  %-5s %-38s %s\n", id, key[id], v
    }
    # the failing tests that no one exercise causes, nor names
    elsewhere = waits = 0
    for (i = 1; built == "yes" && i <= ran_count; i++) {
        k = ran[i]
        if (result[k] == "P" || (k in claimed))
            continue
        if (stubs == "yes" || waits_for_stub(k))
            waiting[++waits] = k
        else if (!(k in laid_any))
            other[++elsewhere] = k
    }
    if (waits > 0)
        printf "Waiting for the exercises you have not started (their stubs" \
               " stand in; %s): %d test(s)\n", stubs == "yes" ? \
               "book/ is not for this machine" : \
               "a part of a function has no book's code to call", waits
    if (elsewhere + loose_races > 0) {
        print "Failing, and laid on no one exercise of yours (each test passes" \
              " with the book's code, and with each of your exercises alone;" \
              " yours together make it fail, or the machine was too busy):"
        for (i = 1; i <= elsewhere; i++) {
            k = other[i]
            if (message[k] ~ /Test timeout expired/)
                printf "  %s\n", describe(k)
            else
                printf "  %s (%s): %s\n", shown[k], located(bare[k]), message[k]
        }
        for (i = 1; i <= loose_races; i++)
            printf "  %s\n", loose_race[i]
        failed++
    }
    printf "Progress: %d of %d exercises\n", done, count
    if (junit != "")
        write_junit()
    if (only != "") {
        if (!(only in verdicts)) {
            printf "no exercise %s in chapters 1 to %d\n", only, chapter
            exit 2
        }
        printf "Exercise %s: %s\n", only, verdicts[only]
        exit verdicts[only] != "done"
    }
    exit failed > 0
}

function write_junit(    i, id, v, failures, skipped) {
    failures = skipped = 0
    for (i = 1; i <= count; i++) {
        v = verdicts[order[i]]
        if (v ~ /^not started/)
            skipped++
        else if (v != "done")
            failures++
    }
    printf "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" > junit
    printf "<testsuites>\n<testsuite name=\"workbook, chapters 1 to %d\" " \
           "tests=\"%d\" failures=\"%d\" errors=\"0\" skipped=\"%d\">\n",
           chapter, count + (elsewhere > 0), failures + (elsewhere > 0),
           skipped > junit
    for (i = 1; i <= count; i++) {
        id = order[i]
        v = verdicts[id]
        printf "  <testcase classname=\"chapter %d\" name=\"%s %s\"", \
               id + 0, xml(id), xml(key[id]) > junit
        if (v == "done")
            printf "/>\n" > junit
        else if (v ~ /^not started/)
            printf "><skipped message=\"%s\"/></testcase>\n", xml(v) > junit
        else
            printf "><failure message=\"%s\">%s</failure></testcase>\n",
                   xml(v), xml(v) > junit
    }
    if (elsewhere > 0) {
        printf "  <testcase classname=\"chapter %d\" name=\"tests laid on no " \
               "one exercise\"><failure message=\"%d test(s)\">", chapter,
               elsewhere > junit
        for (i = 1; i <= elsewhere; i++)
            printf "%s: %s\n", xml(shown[other[i]]), xml(message[other[i]]) > junit
        printf "</failure></testcase>\n" > junit
    }
    printf "</testsuite>\n</testsuites>\n" > junit
    close(junit)
}
