# fences.awk -- the exercises of one chapter as its workbook file holds
# them (tools/workbook/grade.sh, one process a file).
#
#   awk -v chapter=C -v wb=W -v state=S -v lost=L -v bad_files=B \
#       -f tools/workbook/fences.awk LIST C W
#
# LIST is exercises.awk's list, C the chapter's Markdown, W its workbook
# file. For each exercise of C, in order, it appends to S "ID STATE W
# FIRST LAST" (tab-separated): STATE started (no "// NOT DONE" line in its
# fence), not-started, or broken (its fence lost: reported at the place
# it belongs). A started exercise whose fence has lost one of the
# <<chunk>> lines of the book's code is reported at its first line and
# appended to L, "ID MESSAGE". W is appended to B (once) when either is
# found. Messages go to the standard error.

FILENAME == ARGV[1] {
    split($0, f, "\t")
    if (f[2] == chapter)
        ids[++n] = f[1]
    next
}
FILENAME == ARGV[2] { book[++book_lines] = $0; next }
{ text[++lines] = $0 }

# The fence of exercise id: sets first, last and started; 0 if lost.
function find_fence(id,    i, open) {
    open = 0
    started = 0
    for (i = 1; i <= lines; i++) {
        if (!open && text[i] ~ /^```/ && index(text[i], "ex=\"" id "\"")) {
            open = i
            started = 1
            continue
        }
        if (open && text[i] ~ /^[ \t]*\/\/ NOT DONE/)
            started = 0
        if (open && text[i] ~ /^```[ \t]*$/) {
            first = open
            last = i
            return 1
        }
    }
    return 0
}

# Where exercise id's fence belongs: the first line after its hint (the
# heading's line if there is none; 1 if there is no heading).
function fence_place(id,    i, heading, hint_done) {
    heading = hint_done = 0
    for (i = 1; i <= lines; i++) {
        if (index(text[i], "## Exercise " id ":") == 1) {
            heading = i
            continue
        }
        if (heading && !hint_done && text[i] ~ /^<\/details>/) {
            hint_done = 1
            continue
        }
        if (hint_done && text[i] ~ /[^ \t]/)
            return i
        if (heading && text[i] ~ /^## Exercise /)
            break
    }
    return heading ? heading : 1
}

# The <<chunk>> lines of the book's code of exercise id (the k-th fence
# marked .exercise in the chapter), trimmed, into want[1..]; their count.
function book_chunk_lines(id,    k, i, code, count, mine, line, m) {
    k = substr(id, index(id, ".") + 1) + 0
    code = count = mine = m = 0
    for (i = 1; i <= book_lines; i++) {
        line = book[i]
        if (line ~ /^(```|~~~)/ && !code) {
            code = 1
            count += line ~ /[{ ]\.exercise[ }]/
            mine = count == k && line ~ /\.exercise/
            continue
        }
        if (code && line ~ /^(```|~~~)[ \t]*$/) {
            code = mine = 0
            continue
        }
        if (mine && line ~ /^[ \t]*<<[^>]+>>[ \t]*$/) {
            gsub(/^[ \t]+|[ \t]+$/, "", line)
            want[++m] = line
        }
    }
    return m
}

# Whether line want is among lines first..last of the workbook, trimmed.
function holds(want,    i, line) {
    for (i = first; i <= last; i++) {
        line = text[i]
        gsub(/^[ \t]+|[ \t]+$/, "", line)
        if (line == want)
            return 1
    }
    return 0
}

function left_out() {
    if (!is_bad) {
        print wb >> bad_files
        close(bad_files)
        is_bad = 1
    }
}

END {
    while ((getline line < bad_files) > 0)
        if (line == wb)
            is_bad = 1
    close(bad_files)
    for (e = 1; e <= n; e++) {
        id = ids[e]
        if (!find_fence(id)) {
            print wb ":" fence_place(id) ": error: exercise " id " has lost its" \
                  " chunk fence (a line ```{.c ... .exercise ex=\"" id "\"})" > "/dev/stderr"
            left_out()
            printf "%s\tbroken\t%s\t0\t0\n", id, wb >> state
            continue
        }
        printf "%s\t%s\t%s\t%s\t%s\n", id, started ? "started" : "not-started",
               wb, first, last >> state
        if (!started)
            continue
        m = book_chunk_lines(id)
        for (j = 1; j <= m; j++) {
            if (holds(want[j]))
                continue
            message = "lost its line " want[j] ": the book's other chunks and" \
                      " later chapters put their code there; put it back where" \
                      " the stub had it"
            print wb ":" first ": error: exercise " id " " message > "/dev/stderr"
            left_out()
            printf "%s\t%s\n", id, message >> lost
        }
    }
}
