# types.awk -- where the book's types are defined, for the workbook's tasks.
#
#   awk -f tools/workbook/types.awk chapters/NN-*.md...
#
# prints one line per type that a code block of the chapters defines with
# typedef (a struct, enum or union written over several lines, or a
# typedef on one line, a function pointer's too), at its first definition:
#   NAME  CHAPTER  WHERE
# tab-separated: CHAPTER the chapter's number (02-spheres.md: 2), WHERE the
# file the block is (file="hit.h": hit.h) or, for a named chunk, the chunk
# written as the book shows it, <chunk name>. tools/workbook/workbook.awk names them
# in each exercise's task.

function attribute(line, key) {
    if (!match(line, key "=\"[^\"]*\""))
        return ""
    return substr(line, RSTART + length(key) + 2, RLENGTH - length(key) - 3)
}

function found(name) {
    if (name == "" || (name in seen))
        return
    seen[name] = 1
    printf "%s\t%d\t%s\n", name, chapter, where
}

FNR == 1 {
    chapter = FILENAME
    sub(/.*\//, "", chapter)
    chapter = substr(chapter, 1, match(chapter, /[^0-9]/) - 1) + 0
    in_code = 0
}

in_code && $0 ~ "^" fence "[`~]*[ \t]*$" { in_code = 0; next }
in_code && open_typedef && /^\}[ \t]*[A-Za-z_][A-Za-z_0-9]*[ \t]*;/ {
    name = $0
    sub(/^\}[ \t]*/, "", name)
    sub(/[ \t]*;.*/, "", name)
    found(name)
    open_typedef = 0
    next
}
in_code && /^typedef[ \t].*\{[^}]*$/ { open_typedef = 1; next }
in_code && /^typedef[ \t]/ {
    line = $0
    while (line !~ /;/ && (getline more) > 0)   # a typedef over two lines
        line = line " " more
    if (match(line, /\(\*[ \t]*[A-Za-z_][A-Za-z_0-9]*[ \t]*\)/)) {
        name = substr(line, RSTART + 2, RLENGTH - 3)
        gsub(/[ \t]/, "", name)
    } else {
        name = line
        sub(/[ \t]*;.*/, "", name)
        sub(/.*[^A-Za-z_0-9]/, "", name)
    }
    found(name)
    next
}
in_code { next }
/^(```|~~~)/ {
    fence = substr($0, 1, 3)
    in_code = 1
    open_typedef = 0
    where = attribute($0, "file")
    if (where == "")
        where = "<" attribute($0, "chunk") ">"
    if (where == "<>")
        in_code = 2   # an illustration: its types are not the program's
}
in_code == 2 && /^typedef/ { next }
