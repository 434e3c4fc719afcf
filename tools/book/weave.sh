#!/bin/sh
# weave.sh -- turn the literate book into ONE self-contained HTML page
# (CSS, images and MathML inside; it works offline, no scripts, no CDN).
#
# Usage, from the repository root (figures/... paths are relative to it):
#     tools/book/weave.sh book.md build/book.html chapters/*.md
#
# Exits non-zero if pandoc fails or a resource (an image, the CSS) is
# missing; the output file is only written when all went well.
#
# The weave is two steps, which make runs apart:
#     tools/book/weave.sh --text book.md build/book-refs.html chapters/*.md
# is pandoc alone: the page with its images and CSS named, not inside
# (it needs no figure, and runs while the programs that draw them are
# compiled); then
#     tools/book/weave.sh --embed build/book-refs.html build/book.html
# puts every image named by a relative src="..." in as a data: URL and
# the CSS in as a <style>, in a moment, once the figures are drawn.
#
# WEAVE_PAGE=FILE: FILE's HTML goes before the page's </body> (the book's
# scenes rendered in the page: tools/editions/page.sh makes it).
#     tools/book/weave.sh --page FILE IN_HTML OUT_HTML
# does that alone, to a page woven before (make weaves the text while the
# programs for the page are compiled, and adds them at the end).
set -eu  # plain POSIX sh: the Makefile may run it as 'sh tools/book/weave.sh'

# add_page PAGE IN OUT: IN with PAGE's HTML before its </body>, as OUT.
add_page() {
    awk -v page="$1" '
      /<\/body>/ { while ((getline line < page) > 0) print line }
      { print }' "$2" > "$3.tmp" && mv "$3.tmp" "$3"
}

# embed IN OUT: IN with each image that a relative src="..." names as a
# data: URL of its bytes in base64, and each stylesheet that a <link>
# names as a <style> holding it, as OUT; fails, writing nothing, on a
# file that cannot be read or an image of a kind it does not know.
embed() {
    awk '
      function fail(what) {
          print "weave.sh: " what > "/dev/stderr"
          failed = 1
          exit 1
      }
      function readable(path,    line, status) {
          status = (getline line < path)
          close(path)
          return status >= 0
      }
      # the base64 of the file at path, on one line
      function base64_of(path,    cmd, line, text) {
          if (!readable(path))
              fail("missing resource: " path)
          gsub(/\047/, "\047\\\047\047", path)
          cmd = "base64 < \047" path "\047 | tr -d \"\\n\""
          text = ""
          while ((cmd | getline line) > 0)
              text = text line
          close(cmd)
          return text
      }
      function mime_of(path) {
          if (path ~ /\.png$/) return "image/png"
          if (path ~ /\.svg$/) return "image/svg+xml"
          if (path ~ /\.jpe?g$/) return "image/jpeg"
          if (path ~ /\.gif$/) return "image/gif"
          fail("an image of a kind not known: " path)
      }
      # a line that only names a stylesheet: the stylesheet itself
      /^[ \t]*<link rel="stylesheet" href="[^"]*" \/>[ \t]*$/ {
          path = $0
          sub(/^[^"]*"stylesheet" href="/, "", path)
          sub(/".*$/, "", path)
          if (!readable(path))
              fail("missing resource: " path)
          print "  <style type=\"text/css\">"
          while ((getline line < path) > 0)
              print line
          close(path)
          print "</style>"
          next
      }
      {
          out = ""
          rest = $0
          # src="PATH" with PATH neither a URL, a data: URL nor a fragment
          while (match(rest, /src="[^"#:]+"/)) {
              path = substr(rest, RSTART + 5, RLENGTH - 6)
              out = out substr(rest, 1, RSTART - 1) "src=\"data:" \
                    mime_of(path) ";base64," base64_of(path) "\""
              rest = substr(rest, RSTART + RLENGTH)
          }
          print out rest
      }
      END { exit failed }' "$1" > "$2.tmp" && mv "$2.tmp" "$2" ||
        { rm -f "$2.tmp"; echo "weave.sh: could not embed $1's resources" >&2
          return 1; }
}

mode=both
case "${1:-}" in
--page)
    [ "$#" -eq 4 ] || { echo "usage: $0 --page PAGE_HTML IN_HTML OUT_HTML" >&2; exit 2; }
    [ -r "$2" ] && [ -r "$3" ] || { echo "weave.sh: cannot read $2 or $3" >&2; exit 1; }
    add_page "$2" "$3" "$4"
    echo "weave.sh: wrote $4"
    exit 0 ;;
--embed)
    [ "$#" -eq 3 ] || { echo "usage: $0 --embed IN_HTML OUT_HTML" >&2; exit 2; }
    [ -r "$2" ] || { echo "weave.sh: cannot read $2" >&2; exit 1; }
    embed "$2" "$3" || exit 1
    echo "weave.sh: wrote $3"
    exit 0 ;;
--text)
    mode=text
    shift ;;
esac

if [ "$#" -lt 3 ]; then
    echo "usage: $0 [--text] BOOK_MD OUT_HTML CHAPTER..." >&2
    exit 2
fi
book=$1
out=$2
shift 2

if ! command -v pandoc > /dev/null; then
    echo "weave.sh: pandoc is not installed (apt-get install pandoc)" >&2
    exit 1
fi

tools_dir=$(cd "$(dirname "$0")" && pwd)
work_dir=$(mktemp -d)
trap 'rm -rf "$work_dir"' EXIT

# Defaults the book's own YAML may override (--metadata would win over it).
cat > "$work_dir/defaults.yaml" <<'EOF'
lang: en
toc-title: Contents
EOF

mkdir -p "$(dirname "$out")"
partial="$work_dir/book.html"
log="$work_dir/pandoc.log"

# The images and the CSS are named, not put in: embed puts them in, in a
# moment where pandoc's own --self-contained takes seconds.
if ! pandoc "$book" "$@" \
        --from markdown \
        --to html5 \
        --standalone \
        --toc --toc-depth=2 \
        --number-sections \
        --mathml \
        --resource-path=. \
        --metadata-file="$work_dir/defaults.yaml" \
        --css="$tools_dir/book.css" \
        --lua-filter="$tools_dir/weave.lua" \
        --output="$partial" 2> "$log"; then
    cat "$log" >&2
    echo "weave.sh: pandoc failed" >&2
    exit 1
fi
cat "$log" >&2

if [ "$mode" = both ]; then
    embed "$partial" "$partial" || exit 1
    [ -z "${WEAVE_PAGE:-}" ] || add_page "$WEAVE_PAGE" "$partial" "$partial"
fi
mv "$partial" "$out"
echo "weave.sh: wrote $out"
