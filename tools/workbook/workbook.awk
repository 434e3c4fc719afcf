# workbook.awk -- write a chapter's workbook file: its exercises to do.
#
#   awk -f tools/workbook/stub.awk -f tools/workbook/book_code.awk -f tools/workbook/workbook.awk \
#       [-v solved=1] [-v types=TYPES.tsv] CHAPTER.md CHAPTER.md
#   awk ... -v mode=forward|export|book [-v headers=" ID..."] CHAPTER.md CHAPTER.md
#
# (the chapter twice: the first reading collects every chunk's pieces)
# prints, for the exercises of CHAPTER.md (see tools/workbook/exercises.awk for how
# a chapter marks them), a Markdown file in the book's chunk syntax: for
# each exercise its task, the tests that grade it, its hint, and a chunk
# that replaces the book's (.replace) holding a stub from tools/workbook/stub.awk
# and the line "// NOT DONE". The tangler leaves such a chunk out until its
# reader deletes that line (tangle --skip-not-done); tools/workbook/grade.sh grades
# it then. With solved=1 the chunk holds the book's own code instead, and
# no "// NOT DONE" line: a workbook with every exercise done. After each
# task come the <<chunk>> lines its code must keep (later chapters put
# their code there) and, with types=TYPES.tsv (tools/workbook/types.awk's listing),
# where the types its code uses are defined.
#
# With mode=forward, export or book it prints instead, for each exercise,
# only a chunk that replaces the book's (forward, book) or adds to it
# (export), in the form tools/workbook/book_code.awk makes for a handout; headers
# lists the exercises whose code lands in a header.
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
    gsub(/\\[,;:!]/, "", tex)
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

# The notes' text so far, joined into paragraphs (their math made plain
# when written: a formula may span lines).
function add_note(line) {
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

# "Keep ..." for the <<chunk>> lines of the exercise's code, or "".
function keep_note(    lines, n, i, list) {
    n = split(chunk_lines(body), lines, "\n")
    list = ""
    for (i = 1; i <= n; i++)
        if (lines[i] != "")
            list = list (list == "" ? "" : ", ") "`" lines[i] "`"
    if (list == "")
        return ""
    return "Keep the line" (n > 2 ? "s " : " ") list " of the stub where " \
           (n > 2 ? "they stand" : "it stands") ": the book's other " \
           "chunks and later chapters put their code there, and the " \
           "grade fails an exercise that loses one."
}

# "Its types: ..." for the book's types that the exercise's code uses
# (those it defines itself aside), in the order they first appear.
function types_note(    rest, word, list, mine, done) {
    rest = stub_code_part_all(body)
    while (match(rest, /\}[ \t]*[A-Za-z_][A-Za-z_0-9]*[ \t]*;/)) {
        word = substr(rest, RSTART + 1, RLENGTH - 2)
        gsub(/[ \t]/, "", word)
        mine[word] = 1
        rest = substr(rest, RSTART + RLENGTH)
    }
    list = ""
    rest = stub_code_part_all(body)
    while (match(rest, /[A-Za-z_][A-Za-z_0-9]*/)) {
        word = substr(rest, RSTART, RLENGTH)
        rest = substr(rest, RSTART + RLENGTH)
        if (!(word in type_chapter) || (word in mine) || (word in done))
            continue
        done[word] = 1
        list = list (list == "" ? "" : ", ") "`" word "` (" \
               (type_where[word] ~ /^</ ? "" : type_where[word] ", ") \
               "chapter " type_chapter[word] \
               (type_where[word] ~ /^</ ? ", " chunk_shown(type_where[word]) : "") ")"
    }
    return list == "" ? "" : "Its types are defined in the book: " list "."
}

# <name> as the book shows a chunk's name, in angle brackets.
function chunk_shown(where) {
    sub(/^</, "\342\237\250", where)
    sub(/>$/, "\342\237\251", where)
    return where
}

# TEXT without its comments and strings, line by line.
function stub_code_part_all(text,    lines, n, i, out, in_comment, line) {
    n = split(text, lines, "\n")
    out = ""
    for (i = 1; i <= n; i++) {
        line = lines[i]
        if (in_comment) {
            if (!sub(/^([^*]|\*[^\/])*\*\//, "", line))
                continue
            in_comment = 0
        }
        line = stub_code_part(line)
        if (sub(/\/\*.*/, "", line))
            in_comment = 1
        out = out line "\n"
    }
    return out
}

# TEXT in lines of at most 75 columns, broken at blanks.
function wrapped(text,    words, n, i, out, line) {
    n = split(text, words, " ")
    out = line = ""
    for (i = 1; i <= n; i++) {
        if (line != "" && length(line) + 1 + length(words[i]) > 75) {
            out = out line "\n"
            line = ""
        }
        line = line (line == "" ? "" : " ") words[i]
    }
    return out line
}

function write_exercise(    code, tests_list, fence_attr, note) {
    if (!solved && mode == "")
        check_stub_keeps_chunks()
    tests_list = tests
    gsub(/ +/, "`\n- `", tests_list)
    printf "## Exercise %s: %s \"%s\"\n\n", id, kind, key
    printf "%s\n\n", plain_line(trim_end(task))
    note = keep_note()
    if (note != "")
        printf "%s\n\n", wrapped(note)
    note = types_note()
    if (note != "")
        printf "%s\n\n", wrapped(note)
    printf "Graded by `make grade-ch%02d`, with the tests:\n\n- `%s`\n\n", \
        number, tests_list
    printf "<details><summary>Hint (also: make hint EX=%s)</summary>\n\n", id
    printf "%s\n\n</details>\n\n", plain_line(trim_end(hint))
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
        piece[name, pieces[name]] = stubbing ? exercise_form(text, first_id) : text
    next
}
NR == FNR && in_code { text = (text_lines++ ? text "\n" : "") $0; next }
NR == FNR && /^(```|~~~)/ {
    in_code = 1
    fence = substr($0, 1, 3)
    name = attribute($0, "chunk")
    stubbing = (!solved || mode != "") && $0 ~ /[{ ]\.exercise[ }]/
    if ($0 ~ /[{ ]\.exercise[ }]/)
        first_id = chapter_number(FILENAME) "." ++first_count
    text = ""
    text_lines = 0 # a first line that is blank is kept
    if (name != "")
        pieces[name]++
    next
}
NR == FNR { next }

# An exercise's code TEXT as the workbook or the mode shows it: the
# book's (solved), its stub, or the handout's form of exercise ID.
function exercise_form(text, id) {
    if (mode != "")
        return book_form(text, mode, index(headers " ", " " id " ") > 0)
    return solved ? text : stub_of(text)
}

# The code of an exercise's chunk K: all its pieces, or the file's one.
function exercise_code(k,    i, code, joined) {
    if (kind == "file" || pieces[k] < 2 || mode == "export")
        return exercise_form(body, id)
    code = ""
    # the book's code joined as the tangler joins it (a piece brings its
    # own blank line), the stubs a blank line apart
    joined = solved || mode != ""
    for (i = 1; i <= pieces[k]; i++)
        if (piece[k, i] != "")
            code = code (code == "" ? "" : joined ? "\n" : "\n\n") piece[k, i]
    return code
}

# The chunk of the handout's form (mode) of the exercise just read.
function write_form(    attr) {
    attr = kind "=\"" key "\" ." (mode == "export" ? "append" : "replace")
    printf "```{.c %s}\n%s\n```\n\n", attr, exercise_code(key)
}

BEGIN {
    while (types != "" && (getline line < types) > 0) {
        split(line, f, "\t")
        type_chapter[f[1]] = f[2]
        type_where[f[1]] = f[3]
    }
}

FNR == 1 {
    number = chapter_number(FILENAME)
    k = 0
    in_code = 0
}

!title && mode != "" && /^# / {
    title = $0
    printf "# The exercises of %s, %s\n\n", FILENAME, mode
    print "Made by tools/workbook/book_code.sh for a handout (see tools/workbook/book_code.awk):"
    print "no exercise's code, only its functions' names and arguments.\n"
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
    if (number == 1)
        printf "stands in for it. `make grade-ch01` grades chapter 1.\n\n"
    else
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
in_notes && /^:::+[ \t]*$/ {
    in_notes = 0
    if (mode != "")
        write_form()
    else
        write_exercise()
    next
}
in_notes && /^\*\*Your task\.\*\*/ { section = "task" }
in_notes && /^\*\*Hint\.\*\*/ { section = "hint"; sub(/^\*\*Hint\.\*\* */, "") }
in_notes { add_note($0) }

END { exit stub_errors > 0 }
