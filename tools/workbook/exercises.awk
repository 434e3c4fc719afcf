# exercises.awk -- the workbook's exercises, read from the chapters.
#
#   awk -f tools/workbook/exercises.awk chapters/*.md            one line per exercise
#   awk -v hint=02.1 -f tools/workbook/exercises.awk chapters/*.md   that one's hint
#
# An exercise is a code block of the book whose fence carries the class
# .exercise and the tests that grade it, followed (after blank lines) by a
# div of class exercise-notes holding two paragraphs, "**Your task.**" and
# "**Hint.**":
#
#   ```{.c chunk="robust form" .exercise tests="test_a test_b"}
#   ...the book's code...
#   ```
#
#   ::: {.exercise-notes}
#   **Your task.** What the code must compute, in the reader's terms.
#
#   **Hint.** Where to start.
#   :::
#
# Exercises are numbered N.k, k counting from 1 in each chapter (N is the
# chapter file's number, 02-spheres.md: 2). The listing is tab-separated:
#   ID  CHAPTER  FENCE_LINE  KIND  KEY  TESTS
# ID "2.1", KIND "chunk" or "file", KEY the chunk's name or the file's path,
# TESTS the test names separated by blanks. A malformed exercise is reported
# as "CHAPTER:LINE: error: ..." on stderr, and the exit status is 1.

function fail(line, message) {
    printf "%s:%d: error: %s\n", FILENAME, line, message > "/dev/stderr"
    errors++
}

# The value of KEY="..." in the fence line LINE, or "".
function attribute(line, key,    rest) {
    if (!match(line, key "=\"[^\"]*\""))
        return ""
    rest = substr(line, RSTART + length(key) + 2, RLENGTH - length(key) - 3)
    return rest
}

function chapter_number(path,    name) {
    name = path
    sub(/.*\//, "", name)
    match(name, /^[0-9]+/)
    return substr(name, RSTART, RLENGTH) + 0
}

FNR == 1 { k = 0; in_code = 0; want_notes = 0; in_notes = 0 }

# Fences: an exercise's opening fence, and every closing fence.
/^(```|~~~)/ {
    if (in_code) {
        if ($0 ~ "^" fence "[`~]*[ \t]*$") {
            in_code = 0
            if (is_exercise)
                want_notes = fence_line
        }
        next
    }
    in_code = 1
    fence = substr($0, 1, 3)
    fence_line = FNR
    is_exercise = $0 ~ /[{ ]\.exercise[ }]/
    if (is_exercise)
        start_exercise($0)
    next
}
in_code { next }

function start_exercise(line,    key, kind) {
    if (want_notes)
        fail(want_notes, "exercise " id " has no exercise-notes div after it")
    k++
    id = chapter_number(FILENAME) "." k
    kind = "chunk"
    key = attribute(line, "chunk")
    if (key == "") {
        kind = "file"
        key = attribute(line, "file")
    }
    tests = attribute(line, "tests")
    if (key == "" || tests == "")
        fail(FNR, "an exercise needs chunk= or file= and tests=\"...\"")
    if (!hint)
        printf "%s\t%s\t%d\t%s\t%s\t%s\n", id, FILENAME, FNR, kind, key, tests
}

# The notes: the next block after the exercise's code must be them.
want_notes && /^[ \t]*$/ { next }
want_notes && /^:::+ *\{\.exercise-notes\}/ {
    want_notes = 0
    in_notes = 1
    section = ""
    next
}
want_notes {
    fail(want_notes, "exercise " id " has no exercise-notes div after it")
    want_notes = 0
}
in_notes && /^:::+[ \t]*$/ { in_notes = 0; next }
in_notes && /^\*\*Hint\.\*\*/ { section = "hint"; sub(/^\*\*Hint\.\*\* */, "") }
in_notes && /^\*\*Your task\.\*\*/ { section = "task" }
in_notes && section == "hint" && (id == hint || "0" id == hint) {
    print
    shown_hint = 1
}

END {
    if (want_notes)
        fail(want_notes, "exercise " id " has no exercise-notes div after it")
    if (hint && !shown_hint) {
        print "no exercise " hint " (they are numbered like 2.1 or 02.1)" > "/dev/stderr"
        errors++
    }
    exit errors > 0
}
