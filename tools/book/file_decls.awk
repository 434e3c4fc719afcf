# file_decls.awk -- the files that chapters declare on a fence's line.
#
#   awk -f tools/book/file_decls.awk chapters/NN-name.md...
#
# prints NN:FILE for each line that opens a fence (three or more backticks
# or tildes) and holds file="FILE" (the last such, as a greedy sed would
# take it); the Makefile's c_files and scene_files read them.
FNR == 1 {
    chapter = FILENAME
    sub(/.*\//, "", chapter)
    chapter = substr(chapter, 1, 2)
}
/^[`~][`~][`~]/ {
    rest = $0
    name = ""
    while (match(rest, /file="[^"]*"/)) {
        name = substr(rest, RSTART + 6, RLENGTH - 7)
        rest = substr(rest, RSTART + 1)
    }
    if (name != "")
        print chapter ":" name
}
