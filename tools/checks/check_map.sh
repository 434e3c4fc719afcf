#!/bin/sh
# check_map.sh: chapters/README.md's map must be true of the program.
#
# usage: sh tools/checks/check_map.sh MAP SRC_DIR CHAPTER.md...
#        sh tools/checks/check_map.sh --tools TOOLS_DIR
#        sh tools/checks/check_map.sh --self-test
#
# MAP is chapters/README.md; SRC_DIR the plain tangle of the last chapter
# (src/chNN); the chapters are every chapter's Markdown, in order.
#
# It checks, and prints each failure as "MAP: error: ...", exiting 1:
#  - layers: every .c and .h file of SRC_DIR is named on a line of the
#    "## Layers" block (a line's files come before its first run of three
#    blanks; x.h/.c names x.h and x.c; a * matches any run of characters),
#    and every #include "F" of a file names a file on its own line or on
#    a line above it (bottom-up: nothing includes upwards, so there is
#    no cycle between lines); files of one line include each other
#    without a cycle;
#  - hooks: every chunk of the "## Hooks" table (its first column, commas
#    between names, a parenthesis a comment) is first defined, empty or
#    not, in the chapter of its "left by" column; each chapter named in
#    "filled by" appends to or replaces at least one hook of its row; each
#    hook of the row is filled somewhere; and each hook that holds code in
#    the last chapter starts in one of the files of the "file" column.
# With --tools it checks the folders of TOOLS_DIR (tools/) instead, and
# prints each failure as "TOOLS_DIR: error: ...": at most eight files at
# its top, one of them README.md, which gives each folder a row of its
# table ("| `NAME/` | its job |") and each other file at the top a line
# of its list ("- `FILE`: its job"); every other file in a folder of its
# own, whose README.md gives it a line of its list ("- `FILE`: its job",
# "- `SUB/FILE`: ..." for a file in a folder below); and no such row or
# line for a file or folder that is not there.
# The self-test runs both checks on small examples that are wrong in each
# of these ways and fails unless every mistake is reported.
set -u

check() {
    map=$1 src=$2
    shift 2
    awk -v map="$map" -v src="$src" '
    function fail(msg) { printf "%s: error: %s\n", map, msg; bad = 1 }
    function trim(s) { gsub(/^[ \t`]+|[ \t`]+$/, "", s); return s }
    function glob_to_re(g,   r) {
        r = g; gsub(/\./, "\\.", r); gsub(/\*/, ".*", r)
        return "^" r "$"
    }
    # The line of the layers block that names file f, or 0.
    function layer_of(f,   k) {
        for (k = 1; k <= npat; k++)
            if (f ~ pat_re[k]) return pat_line[k]
        return 0
    }
    FILENAME == map && /^## / { section = $0 }
    FILENAME == map && section == "## Layers" && /^```/ { inblock = !inblock; next }
    FILENAME == map && section == "## Layers" && inblock && /^[^ ]/ {
        layer++
        files = $0; sub(/   .*/, "", files)
        n = split(files, names, /[ \t]+/)
        for (k = 1; k <= n; k++) {
            name = names[k]
            if (name ~ /\.h\/\.c$/) {
                base = name; sub(/\.h\/\.c$/, "", base)
                pat_re[++npat] = glob_to_re(base ".c"); pat_line[npat] = layer
                pat_re[++npat] = glob_to_re(base ".h"); pat_line[npat] = layer
            } else {
                pat_re[++npat] = glob_to_re(name); pat_line[npat] = layer
            }
        }
        next
    }
    FILENAME == map && section ~ /^## Hooks/ && /^\| / && !/^\| hook \(chunk\)|^\|---/ {
        nrow++
        split($0, col, "|")
        hooks = col[2]; gsub(/\([^)]*\)/, "", hooks)
        row_file[nrow] = col[3]; row_left[nrow] = trim(col[4])
        row_filled[nrow] = col[5]
        gsub(/\([^)]*\)/, "", row_filled[nrow]) # what a chapter adds: words
        nh = split(hooks, hs, ",")
        row_count[nrow] = 0
        for (k = 1; k <= nh; k++) {
            h = trim(hs[k]); if (h == "") continue
            row_hook[nrow, ++row_count[nrow]] = h
        }
        next
    }
    FILENAME == map { next }
    # The chapters: chunk fences, with the chapter number of the file.
    FNR == 1 && FILENAME != map && FILENAME !~ /^-$/ {
        chapter = FILENAME; sub(/.*\//, "", chapter); sub(/-.*/, "", chapter)
        if (FILENAME ~ /\.md$/) { kind = "chapter"; chapters_seen[chapter] = 1 }
        else kind = "source"
    }
    kind == "chapter" && /^(```|~~~)/ && /chunk="/ {
        name = $0; sub(/.*chunk="/, "", name); sub(/".*/, "", name)
        if ($0 ~ /\.append|\.replace/) filled[name, chapter] = 1
        else if (!((name) in first)) first[name] = chapter
        next
    }
    # The plain tangle: includes and chunk markers, by file.
    kind == "source" {
        f = FILENAME; sub(/.*\//, "", f)
        seen_file[f] = 1
        if (match($0, /^#include "[^"]+"/)) {
            inc = substr($0, RSTART + 10, RLENGTH - 11)
            includes[f, ++ninc[f]] = inc
        }
        if (match($0, /\/\* <<[^>]+>>/)) {
            m = substr($0, RSTART + 5, RLENGTH - 7)
            if (!index(marker_in[m], " " f " "))
                marker_in[m] = marker_in[m] " " f " "
        }
    }
    END {
        for (f in seen_file)
            if (layer_of(f) == 0) fail("layers: " f " is on no line of the map")
        for (f in seen_file)
            for (k = 1; k <= ninc[f]; k++) {
                g = includes[f, k]
                sub(/.*\//, "", g)
                if (!(g in seen_file)) continue
                if (layer_of(g) > layer_of(f))
                    fail("layers: " f " includes " g ", which is above it")
            }
        # Cycles among includes: a depth-first search from every file.
        for (f in seen_file) state[f] = 0
        for (f in seen_file) if (state[f] == 0) visit(f)
        for (r = 1; r <= nrow; r++) {
            any_filled_somewhere = 0
            listed = row_filled[r]
            nchap = 0
            while (match(listed, /[0-9][0-9]/)) {
                chap[++nchap] = substr(listed, RSTART, 2)
                listed = substr(listed, RSTART + 2)
            }
            for (k = 1; k <= row_count[r]; k++) {
                h = row_hook[r, k]
                if (!(h in first)) { fail("hooks: no chunk <" h ">"); continue }
                if (first[h] != row_left[r])
                    fail("hooks: <" h "> is left by chapter " first[h] ", not " row_left[r])
                was_filled = 0
                for (c in chapters_seen) if ((h, c) in filled) was_filled = 1
                if (!was_filled) fail("hooks: <" h "> is filled by no chapter")
                if (h in marker_in) {
                    ok = 0
                    nf = split(row_file[r], fs, /[ ,]+/)
                    for (j = 1; j <= nf; j++) {
                        spec = trim(fs[j]); if (spec == "") continue
                        if (spec ~ /\.[ch]\/\.[ch]$/) {
                            b = spec; sub(/\.[ch]\/\.[ch]$/, "", b)
                            if (index(marker_in[h], " " b ".h ") || index(marker_in[h], " " b ".c ")) ok = 1
                        } else if (index(marker_in[h], " " spec " ")) ok = 1
                    }
                    if (!ok) fail("hooks: <" h "> is in" marker_in[h] "not in " trim(row_file[r]))
                }
            }
            for (j = 1; j <= nchap; j++) {
                ok = 0
                for (k = 1; k <= row_count[r]; k++)
                    if ((row_hook[r, k], chap[j]) in filled) ok = 1
                if (!ok) fail("hooks: chapter " chap[j] " fills none of " row_hook[r, 1] "...")
            }
        }
        exit bad
    }
    function visit(f,   k, g) {
        state[f] = 1
        for (k = 1; k <= ninc[f]; k++) {
            g = includes[f, k]; sub(/.*\//, "", g)
            if (!(g in seen_file)) continue
            if (state[g] == 1) fail("layers: an include cycle through " f " and " g)
            else if (state[g] == 0) visit(g)
        }
        state[f] = 2
    }
    ' "$map" "$@" $(ls "$src"/*.c "$src"/*.h)
}

# check_tools DIR: the folders of DIR against their README.md files.
check_tools() {
    dir=$1
    (cd "$dir" && find . -type f | sed 's#^\./##' | LC_ALL=C sort) | awk -v dir="$dir" '
    function fail(msg) { printf "%s: error: %s\n", dir, msg; bad = 1 }
    # The names README.md gives a line of their own ("- `FILE`: its job"
    # or a table row "| `NAME/` | ..."), into named[].
    function read_readme(readme, folder,   line) {
        while ((getline line < readme) > 0) {
            if (line !~ /^(- |\| )`[^`]+`/) continue
            sub(/^(- |\| )`/, "", line); sub(/`.*/, "", line)
            named[folder, line] = 1
        }
        close(readme)
    }
    {
        if (index($0, "/") == 0) {
            top++; there["", $0] = 1
            if ($0 == "README.md") top_readme = 1; else top_files[$0] = 1
            next
        }
        folder = $0; sub(/\/.*/, "", folder)
        file = substr($0, length(folder) + 2)
        folders[folder] = 1
        there[folder, file] = 1
        if (file ~ /\//) { sub_dir = file; sub(/\/[^\/]*$/, "/", sub_dir); there[folder, sub_dir] = 1 }
        if (file == "README.md") has_readme[folder] = 1
        else files[++nfiles] = folder SUBSEP file
    }
    END {
        if (top > 8) fail(top " files at the top, more than eight: give each a folder of its job")
        if (!top_readme) fail("no README.md at the top")
        else read_readme(dir "/README.md", "")
        for (f in folders) {
            if (top_readme && !(("", f "/") in named)) fail("README.md does not name " f "/")
            if (!(f in has_readme)) fail(f "/ has no README.md")
            else read_readme(dir "/" f "/README.md", f)
        }
        for (f in top_files)
            if (top_readme && !(("", f) in named)) fail("README.md does not name " f)
        for (k = 1; k <= nfiles; k++) {
            split(files[k], part, SUBSEP)
            if ((part[1] in has_readme) && !((part[1], part[2]) in named))
                fail(part[1] "/README.md does not name " part[2])
        }
        for (key in named) {
            split(key, part, SUBSEP)
            if (part[1] == "" && part[2] ~ /\/$/) {
                if (!(substr(part[2], 1, length(part[2]) - 1) in folders))
                    fail("README.md names " part[2] ", which is not there")
            } else if (!((part[1], part[2]) in there))
                fail((part[1] == "" ? "" : part[1] "/") "README.md names " part[2] ", which is not there")
        }
        exit bad
    }'
}

self_test() {
    dir=$(mktemp -d) || exit 1
    trap 'rm -rf "$dir"' EXIT
    mkdir "$dir/src"
    printf '#include "b.h"\n/* <<hook one>> ch01 */\nint a;\n' >"$dir/src/a.h"
    printf '#include "a.h"\nint b;\n' >"$dir/src/b.h"
    printf '#include "a.h"\n/* <<hook two>> ch02 */\n' >"$dir/src/c.c"
    printf 'int stray;\n' >"$dir/src/stray.c"
    cat >"$dir/01-x.md" <<'EOF'
```{.c chunk="hook one"}
```
```{.c chunk="hook two"}
```
EOF
    cat >"$dir/02-y.md" <<'EOF'
```{.c chunk="hook two" .append}
x;
```
EOF
    cat >"$dir/map.md" <<'EOF'
## Layers

```
a.h          the bottom
b.h          above it
c.c          the top
```

## Hooks

| hook (chunk) | file | left by | filled by |
|---|---|---|---|
| hook one, hook missing | b.h | 01 | 02 |
| hook two | b.h | 02 | 02 |
EOF
    out=$(check "$dir/map.md" "$dir/src" "$dir/01-x.md" "$dir/02-y.md")
    status=0
    for expected in "stray.c is on no line" "a.h includes b.h, which is above it" \
                    "include cycle" "no chunk <hook missing>" \
                    "<hook one> is filled by no chapter" \
                    "<hook two> is left by chapter 01, not 02" \
                    "<hook one> is in a.h not in b.h" "<hook two> is in c.c not in b.h" \
                    "chapter 02 fills none of hook one"; do
        case $out in
        *"$expected"*) ;;
        *) echo "check_map.sh: self-test: not reported: $expected"; status=1 ;;
        esac
    done
    # A tools/ folder wrong in each way, beside a folder that is right.
    t=$dir/tools
    mkdir -p "$t/good/sub" "$t/bare" "$t/hidden" "$t/gone"
    for k in 1 2 3 4 5 6 7 8; do : >"$t/loose$k.sh"; done
    printf '| `good/` | fine |\n| `bare/` | |\n| `gone/` | |\n| `lost/` | |\n' >"$t/README.md"
    printf -- '- `loose1.sh`: named\n- `loose9.sh`: not there\n' >>"$t/README.md"
    : >"$t/good/a.sh"; : >"$t/good/sub/b.js"
    printf -- '- `a.sh`: one\n- `sub/b.js`: two\n' >"$t/good/README.md"
    : >"$t/bare/c.sh"
    : >"$t/hidden/d.awk"; : >"$t/hidden/e.awk"
    printf -- '- `d.awk`: named\n' >"$t/hidden/README.md"
    : >"$t/gone/f.c"
    printf -- '- `f.c`: here\n- `g.c`: no longer\n' >"$t/gone/README.md"
    out=$(check_tools "$t")
    for expected in "9 files at the top, more than eight" \
                    "README.md does not name hidden/" "bare/ has no README.md" \
                    "hidden/README.md does not name e.awk" \
                    "gone/README.md names g.c, which is not there" \
                    "README.md names lost/, which is not there" \
                    "README.md does not name loose2.sh" \
                    "README.md names loose9.sh, which is not there"; do
        case $out in
        *"$expected"*) ;;
        *) echo "check_map.sh: self-test: not reported: $expected"; status=1 ;;
        esac
    done
    case $out in
    *good/*|*"name loose1.sh"*)
        echo "check_map.sh: self-test: a right file reported: $out"; status=1 ;;
    esac
    [ $status = 0 ] && echo "check_map.sh: self-test passed"
    return $status
}

if [ "${1:-}" = --self-test ]; then
    self_test
    exit $?
fi
if [ "${1:-}" = --tools ] && [ $# = 2 ]; then
    if check_tools "$2"; then
        echo "$2: every file is in a folder whose README.md names it: ok"
        exit 0
    fi
    exit 1
fi
[ $# -ge 3 ] || { echo "usage: sh tools/checks/check_map.sh MAP SRC_DIR CHAPTER.md..." >&2; exit 2; }
map=$1 src=$2
shift 2
if check "$map" "$src" "$@"; then
    echo "$map: the layers and hooks are those of $src: ok"
else
    exit 1
fi
