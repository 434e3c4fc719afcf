# epub_links.awk -- points every link to an id at the file that holds it.
#
# Usage: awk -f tools/editions/epub_links.awk A.xhtml B.xhtml ...   (tools/editions/epub.sh)
# The weaver writes its links as raw HTML, href="#id" (chunk references,
# "used in", the index, the chapter navigation): right in the one-page
# book, wrong in an EPUB split into one file per chapter, where pandoc
# rewrites only the links it made itself. This reads every file once to
# learn which file holds each id, then writes FILE.new for each FILE with
# href="#id" made href="other.xhtml#id" wherever the id is in another
# file. The files must be in one folder (as pandoc's EPUB/text/ is). An
# id that no file holds is left as it was, for epubcheck to report.

function base(path) {
    sub(/.*\//, "", path)
    return path
}

# Every file twice: first to learn the ids, then to write.
BEGIN {
    files = ARGC - 1
    for (i = 1; i <= files; i++) ARGV[ARGC++] = ARGV[i]
}

FNR == 1 {
    if (++opened > files) {
        pass = 2
        if (previous != "") close(previous ".new")
        previous = FILENAME
    } else pass = 1
}

pass == 1 {
    line = $0
    while (match(line, /(^|[ \t])id="[^"]*"/)) {
        found = substr(line, RSTART, RLENGTH)
        sub(/^[ \t]*id="/, "", found)
        sub(/"$/, "", found)
        if (!(found in owner)) owner[found] = base(FILENAME)
        line = substr(line, RSTART + RLENGTH)
    }
    next
}

{
    here = base(FILENAME)
    line = $0
    out = ""
    while (match(line, /href="#[^"]*"/)) {
        id = substr(line, RSTART + 7, RLENGTH - 8)
        target = (id in owner && owner[id] != here) ? owner[id] : ""
        out = out substr(line, 1, RSTART - 1) "href=\"" target "#" id "\""
        line = substr(line, RSTART + RLENGTH)
    }
    print out line > (FILENAME ".new")
}
