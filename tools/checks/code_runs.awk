# code_runs.awk -- runs of three lines of code, compared loosely.
#
#   awk -f tools/checks/code_runs.awk FILE...
#
# prints, for every three lines of code that follow one another in a FILE,
# the file's name, a tab and the three lines joined by blanks (and once
# more with "~" for the middle one, which a restatement may have changed:
# its own names in one expression), each line
# loosened first: comments, blanks and parentheses dropped, `||` written
# `|` and `&&` written `&`, and the names of the floating-point types
# (real, float, double) written T; a line that is then shorter than 6
# characters, part of a block comment or a <<chunk>> line is skipped. So a
# solution restated by other code, with other spacing, comments, types or
# forms of its tests, is found by its runs (tools/checks/check_handout.sh). Code
# is what is in a Markdown file's fenced blocks and all of any other file
# (an HTML file's markup dropped and its escapes undone). A line "<<>>"
# (tools/workbook/solution_lines.awk's, where a stub keeps a line) ends a run.

function loose(line,    out) {
    sub(/\/\/.*$/, "", line)
    gsub(/\/\*([^*]|\*+[^*\/])*\*+\//, "", line)
    sub(/\/\*.*$/, "", line)
    line = " " line " "
    out = ""
    while (match(line, /[^A-Za-z0-9_](real|float|double)[^A-Za-z0-9_]/)) {
        out = out substr(line, 1, RSTART) "T"
        line = substr(line, RSTART + RLENGTH - 1)
    }
    line = out line
    gsub(/[ \t\r\f\v()]/, "", line)
    gsub(/\|\|/, "|", line)
    gsub(/&&/, "\\&", line)
    return line
}

function reset() { n = 0 }

FNR == 1 {
    reset()
    fenced = FILENAME ~ /\.md$/
    html = FILENAME ~ /\.html?$/
    inside = 0
}
$0 == "<<>>" { reset(); next }
fenced && /^(```|~~~)/ {
    if (!inside) { inside = 1; fence = substr($0, 1, 3) }
    else if ($0 ~ "^" fence "[`~]*[ \t]*$") inside = 0
    next
}
fenced && !inside { next }
{
    line = $0
    if (html) {
        gsub(/<[^>]*>/, "", line)
        gsub(/&lt;/, "<", line); gsub(/&gt;/, ">", line)
        gsub(/&quot;/, "\"", line); gsub(/&#39;/, "\047", line)
        gsub(/&amp;/, "\\&", line)
    }
    trimmed = line
    gsub(/^[ \t]+/, "", trimmed)
    if (trimmed ~ /^(\* |\*$|\*\/|\/\*|<<)/)
        next
    line = loose(line)
    if (length(line) < 6)
        next
    last[0] = last[1]; last[1] = last[2]; last[2] = line
    if (++n >= 3) {
        print FILENAME "\t" last[0] " " last[1] " " last[2]
        print FILENAME "\t" last[0] " ~ " last[2] # the middle one changed
    }
}
