# handout.awk -- a chapter as a student's handout prints it: every exercise's
# code replaced by its stub.
#
#   awk -f tools/workbook/stub.awk -f tools/workbook/handout.awk CHAPTER.md > HANDOUT/CHAPTER.md
#
# Copies CHAPTER.md line for line, except the body of each code block whose
# fence carries .exercise (see tools/workbook/exercises.awk), which becomes
# tools/workbook/stub.awk's stub of it: the same declarations, every function body a
# return of zero. The tangle of the handout's chapters builds (and fails the
# exercises' tests) until the student's workbook replaces the stubs.

function flush_exercise(    stub) {
    stub = stub_of(body)
    if (stub != "")
        print stub
}

in_code && $0 ~ "^" fence "[`~]*[ \t]*$" {
    if (is_exercise)
        flush_exercise()
    in_code = 0
    print
    next
}
in_code && is_exercise { body = body (body == "" ? "" : "\n") $0; next }
in_code { print; next }
/^(```|~~~)/ {
    in_code = 1
    fence = substr($0, 1, 3)
    is_exercise = $0 ~ /[{ ]\.exercise[ }]/
    body = ""
}
{ print }
