# workbook.awk -- write a chapter's workbook file: its exercises to do.
#
#   awk -f tools/workbook/stub.awk -f tools/workbook/workbook.awk [-v solved=1] CHAPTER.md CHAPTER.md
#
# (the chapter twice: the first reading collects every chunk's pieces)
# prints, for the exercises of CHAPTER.md (see tools/workbook/exercises.awk for how
# a chapter marks them), a Markdown file in the book's chunk syntax: for
# each exercise its task, the tests that grade it, its hint, and a chunk
# that replaces the book's (.replace) holding a stub from tools/workbook/stub.awk
# and the line "// NOT DONE". The tangler leaves such a chunk out until its
# reader deletes that line (tangle --skip-not-done); tools/workbook/grade.sh grades
# it then. With solved=1 the chunk holds the book's own code instead, and
# no "// NOT DONE" line: a workbook with every exercise done.
#
# An exercise may mark an .append piece of a chunk that the chapter builds
# in several pieces (and that no other chapter writes to): the workbook's
# chunk then replaces all of them, and holds the book's other pieces as
# they are, around the stub of the exercise's piece.

function chapter_number(path,    name) {
    name = path
    sub(/.*\//, "", name)
    match(name, /^[0-9]+/)
    return substr(name, RSTART, RLENGTH) + 0
}

function attribute(line, key) {
    if (!match(line, key "=\"[^\"]*\""))
        return ""
    return substr(line, RSTART + length(key) + 2, RLENGTH - length(key) - 3)
}

# TeX of inline math ($...$) as plain text, for a file read as it is:
# $2^{-53}$ is 2^-53, $t_\text{max}$ t_max, $\lceil n/W \rceil$ ceil(n/W).
function plain_math(tex) {
    gsub(/\\text\{/, "{", tex)
    gsub(/\\lceil */, "ceil(", tex)
    gsub(/ *\\rceil/, ")", tex)
    gsub(/\\lfloor */, "floor(", tex)
    gsub(/ *\\rfloor/, ")", tex)
    gsub(/\\times/, "x", tex)
    gsub(/\\cdot/, "*", tex)
    gsub(/\\le(q)?/, "<=", tex)
    gsub(/\\ge(q)?/, ">=", tex)
    gsub(/\\/, "", tex)
    gsub(/[{}]/, "", tex)
    return tex
}

function plain_line(line,    out) {
    out = ""
    while (match(line, /\$[^$]+\$/)) {
        out = out substr(line, 1, RSTART - 1) \
              plain_math(substr(line, RSTART + 1, RLENGTH - 2))
        line = substr(line, RSTART + RLENGTH)
    }
    return out line
}

# The notes' text so far, joined into paragraphs.
function add_note(line) {
    line = plain_line(line)
    if (section == "task")
        task = task line "\n"
    else if (section == "hint")
        hint = hint line "\n"
}

function trim_end(text) {
    sub(/\n+$/, "", text)
    return text
}

# The <<chunk>> lines of TEXT, one a line, in their order.
function chunk_lines(text,    lines, n, i, found) {
    n = split(text, lines, "\n")
    found = ""
    for (i = 1; i <= n; i++)
        if (lines[i] ~ /^[ \t]*<<[^>]+>>[ \t]*$/) {
            sub(/^[ \t]+/, "", lines[i])
            found = found lines[i] "\n"
        }
    return found
}

# A stub keeps every <<chunk>> line of the book's code: later chapters add
# to those chunks, and a stub without one would silently lose their code.
function check_stub_keeps_chunks(    book, stub) {
    book = chunk_lines(body)
    stub = chunk_lines(stub_of(body))
    if (book == stub)
        return
    printf "%s:%d: error: the stub of exercise %s does not keep the " \
           "chunk lines of its code:\n%s", FILENAME, fence_line, id, book \
           > "/dev/stderr"
    stub_errors++
}

function write_exercise(    code, tests_list, fence_attr) {
    if (!solved)
        check_stub_keeps_chunks()
    tests_list = tests
    gsub(/ +/, "`\n- `", tests_list)
    printf "## Exercise %s: %s \"%s\"\n\n", id, kind, key
    printf "%s\n\n", trim_end(task)
    printf "Graded by `make grade-ch%02d`, with the tests:\n\n- `%s`\n\n", \
        number, tests_list
    printf "<details><summary>Hint (also: make hint EX=%s)</summary>\n\n", id
    printf "%s\n\n</details>\n\n", trim_end(hint)
    code = exercise_code(key)
    fence_attr = kind "=\"" key "\" .replace .exercise ex=\"" id "\""
    printf "```{.c %s}\n%s\n", fence_attr, code
    if (!solved)
        print "// NOT DONE: delete this line to have your code graded"
    printf "```\n\n"
}

# The first reading: every piece of every chunk, an exercise's stubbed.
NR == FNR && in_code && $0 ~ "^" fence "[`~]*[ \t]*$" {
    in_code = 0
    if (name != "")
        piece[name, pieces[name]] = stubbing ? stub_of(text) : text
    next
}
NR == FNR && in_code { text = (text_lines++ ? text "\n" : "") $0; next }
NR == FNR && /^(```|~~~)/ {
    in_code = 1
    fence = substr($0, 1, 3)
    name = attribute($0, "chunk")
    stubbing = !solved && $0 ~ /[{ ]\.exercise[ }]/
    text = ""
    text_lines = 0 # a first line that is blank is kept
    if (name != "")
        pieces[name]++
    next
}
NR == FNR { next }

# The code of an exercise's chunk K: all its pieces, or the file's one.
function exercise_code(k,    i, code) {
    if (kind == "file" || pieces[k] < 2)
        return solved ? body : stub_of(body)
    code = ""
    # the book's code joined as the tangler joins it (a piece brings its
    # own blank line), the stubs a blank line apart
    for (i = 1; i <= pieces[k]; i++)
        if (piece[k, i] != "")
            code = code (code == "" ? "" : solved ? "\n" : "\n\n") piece[k, i]
    return code
}

FNR == 1 {
    number = chapter_number(FILENAME)
    k = 0
    in_code = 0
}

!title && /^# / {
    title = $0
    sub(/^# */, "", title)
    sub(/ *\{.*\}[ \t]*$/, "", title)
    printf "# Workbook, chapter %d: %s\n\n", number, title
    printf "Written by `make workbook` from %s; yours to edit (`make\n", FILENAME
    print "workbook` never overwrites it). Each exercise holds a stub of one of"
    print "the chapter's chunks. Write your own code in its place, then delete"
    print "its line `// NOT DONE` to have it graded; until then the book's code"
    printf "stands in for it. `make grade-ch%02d` grades chapters 1 to %d.\n\n", \
        number, number
}

in_code && $0 ~ "^" fence "[`~]*[ \t]*$" {
    in_code = 0
    if (is_exercise)
        want_notes = 1
    next
}
in_code && is_exercise { body = (body_lines++ ? body "\n" : "") $0; next }
in_code { next }

/^(```|~~~)/ {
    in_code = 1
    fence = substr($0, 1, 3)
    is_exercise = $0 ~ /[{ ]\.exercise[ }]/
    if (is_exercise) {
        k++
        id = number "." k
        fence_line = FNR
        kind = attribute($0, "chunk") != "" ? "chunk" : "file"
        key = attribute($0, kind)
        tests = attribute($0, "tests")
        body = ""
        body_lines = 0 # a first line that is blank is kept
        task = hint = ""
    }
    next
}

want_notes && /^:::+ *\{\.exercise-notes\}/ { in_notes = 1; want_notes = 0; next }
in_notes && /^:::+[ \t]*$/ { in_notes = 0; write_exercise(); next }
in_notes && /^\*\*Your task\.\*\*/ { section = "task" }
in_notes && /^\*\*Hint\.\*\*/ { section = "hint"; sub(/^\*\*Hint\.\*\* */, "") }
in_notes { add_note($0) }

END { exit stub_errors > 0 }
