# check_brackets.awk CHAPTER.md...: every paragraph of prose (outside code
# fences, inline code and $...$ math) closes each '[' it opens. Pandoc 2.17
# looks for the close of an unmatched '[' through the rest of the book, and
# one such paragraph made the book take 100 s to weave instead of 4: write
# an interval such as [0, 1) as \[0, 1) or in math. Prints FILE:LINE: error
# for each paragraph that does not balance and exits 1; 0 otherwise.
function finish() {
    if (open != 0) {
        printf "%s:%d: error: a paragraph opens %d more '[' than it closes" \
               " (write \\[ for a bracket that is not a link)\n",
               file, start, open
        bad = 1
    }
    open = 0; start = 0
}
FNR == 1 { finish(); file = FILENAME; fence = 0 }
/^(```|~~~)/ { finish(); fence = !fence; next }
fence { next }
/^[ \t]*$/ { finish(); next }
{
    if (!start) start = FNR
    line = $0
    gsub(/\\[][]/, "", line)        # escaped brackets are text
    gsub(/`[^`]*`/, "", line)       # inline code
    gsub(/\$[^$]*\$/, "", line)     # inline math
    open += gsub(/\[/, "[", line) - gsub(/\]/, "]", line)
}
END { finish(); exit bad }
