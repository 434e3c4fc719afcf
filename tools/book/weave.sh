#!/bin/sh
# weave.sh -- turn the literate book into ONE self-contained HTML page
# (CSS, images and MathML inside; it works offline, no scripts, no CDN).
#
# Usage, from the repository root (figures/... paths are relative to it):
#     tools/book/weave.sh book.md build/book.html chapters/*.md
#
# Exits non-zero if pandoc fails or warns that a resource (an image, the
# CSS) is missing; the output file is only written when all went well.
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

if [ "${1:-}" = "--page" ]; then
    [ "$#" -eq 4 ] || { echo "usage: $0 --page PAGE_HTML IN_HTML OUT_HTML" >&2; exit 2; }
    [ -r "$2" ] && [ -r "$3" ] || { echo "weave.sh: cannot read $2 or $3" >&2; exit 1; }
    add_page "$2" "$3" "$4"
    echo "weave.sh: wrote $4"
    exit 0
fi

if [ "$#" -lt 3 ]; then
    echo "usage: $0 BOOK_MD OUT_HTML CHAPTER..." >&2
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

# pandoc 2.19 replaced --self-contained by --embed-resources (the old
# option is deprecated since), so pick the option by pandoc's version.
embed_options() {
    version=$(pandoc --version | head -n 1 | sed 's/^[^0-9]*//')
    major=${version%%.*}
    minor=${version#*.}
    minor=${minor%%.*}
    if [ "$major" -gt 2 ] || { [ "$major" -eq 2 ] && [ "$minor" -ge 19 ]; }; then
        echo "--embed-resources"  # --standalone is passed anyway
    else
        echo "--self-contained"
    fi
}

# Defaults the book's own YAML may override (--metadata would win over it).
cat > "$work_dir/defaults.yaml" <<'EOF'
lang: en
toc-title: Contents
EOF

mkdir -p "$(dirname "$out")"
partial="$work_dir/book.html"
log="$work_dir/pandoc.log"

# shellcheck disable=SC2046  # embed_options is meant to split into words
if ! pandoc "$book" "$@" \
        --from markdown \
        --to html5 \
        --standalone $(embed_options) \
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

# Newer pandoc only warns about a missing image and writes a page without
# it; for the book that is an error.  (Our filter's own warnings may name
# chunks freely, so they are left out of the search.)
missing_resources() {
    grep -Ei 'could not fetch|not found' "$log" | grep -v '^weave\.lua: '
}
if missing_resources > /dev/null; then
    echo "weave.sh: missing resources:" >&2
    missing_resources >&2
    exit 1
fi

[ -z "${WEAVE_PAGE:-}" ] || add_page "$WEAVE_PAGE" "$partial" "$partial"
mv "$partial" "$out"
echo "weave.sh: wrote $out"
