#!/bin/sh
# book_code.sh -- the book's code of the exercises, compiled, for a handout.
#
# A handout holds no exercise's code (tools/workbook/handout.sh), yet a student
# should be able to start anywhere: an exercise not started behaves as the
# book's code does, because the book's code is there compiled. The
# Makefile's target book-code (make handout makes it) builds it in two
# steps, which this script does:
#
#   tools/workbook/book_code.sh forms OUT LINE_TANGLE CHAPTER.md...
#       writes OUT/forward/NN-name.md and OUT/export/NN-name.md (shipped
#       in the handout's book/ folder) and OUT/book/NN-name.md (not
#       shipped): each exercise's code in the three forms of
#       tools/book_code.awk. LINE_TANGLE is the last chapter's --line
#       tangle, which says which exercises' code lands in a header.
#       A file is rewritten only when its bytes change.
#   tools/workbook/book_code.sh link OUT.o OBJECT.o...
#       of the objects of a chapter's program built from the chapters and
#       OUT/book/ (compiled without debugging information), links those
#       that define the book's functions (rt_book_...) into one object,
#       OUT.o, in which every other symbol it defines is weak: where the
#       student's program defines it too, the student's program's stands,
#       so that there is one of each table and variable.
#
# In the handout, OUT.o is book/chNN.o, linked into every program of
# chapter NN, and book/MACHINE says what it was compiled for (uname -sm
# and the compiler's target): on another machine it cannot be linked,
# and the Makefile builds the programs from the stubs instead.
set -eu

case ${1:-} in
forms)
    out=$2 tangled=$3
    shift 3
    # the exercises whose code lands in a header: those whose lines the
    # #line directives of a .h file of the tangle point at (one awk for
    # them all: one an exercise and a header took seconds)
    headers=$(awk -f tools/workbook/exercises.awk "$@" | awk -F '\t' '
        # the list: each exercise, its chapter, the line of its fence
        FILENAME == "-" { n++; id[n] = $1; ch[n] = $2; from[n] = $3; next }
        # a chapter: the fence that ends each of its exercises
        FILENAME ~ /\.md$/ && /^```/ {
            for (k = 1; k <= n; k++)
                if (ch[k] == FILENAME && !(k in to) && FNR > from[k])
                    to[k] = FNR
            next
        }
        FILENAME ~ /\.md$/ { next }
        # a header: the chapter and line each of its lines comes from
        FNR == 1 { f = ""; line = 0 }
        /^#line / { line = $0; sub(/^#line /, "", line); f = line
                    sub(/ .*/, "", line); sub(/^[^ ]* /, "", f)
                    gsub(/"/, "", f); line += 0; next }
        {
            for (k = 1; k <= n; k++)
                if (ch[k] == f && line > from[k] && line < to[k])
                    in_header[k] = 1
            line++
        }
        END { for (k = 1; k <= n; k++) if (k in in_header) printf "%s ", id[k] }' \
        - "$@" "$tangled"/*.h)
    mkdir -p "$out/forward" "$out/export" "$out/book"
    for mode in forward export book; do
        for c in "$@"; do
            awk -v mode="$mode" -v headers=" $headers" -f tools/workbook/stub.awk \
                -f tools/workbook/book_code.awk -f tools/workbook/workbook.awk "$c" "$c" \
                > "$out/$mode.tmp"
            f=$out/$mode/$(basename "$c")
            cmp -s "$out/$mode.tmp" "$f" || mv "$out/$mode.tmp" "$f"
            rm -f "$out/$mode.tmp"
        done
    done
    ;;
link)
    out=$2
    shift 2
    tmp=$out.parts
    rm -rf "$tmp" && mkdir -p "$tmp"
    # the objects that define a book's function not defined yet
    : > "$tmp/defined"
    for o in "$@"; do
        nm --defined-only -g "$o" | awk '$3 ~ /^rt_book_/ { print $3 }' |
            sort -u > "$tmp/mine"
        if [ -n "$(comm -23 "$tmp/mine" "$tmp/defined")" ]; then
            echo "$o" >> "$tmp/objects"
            sort -u "$tmp/defined" "$tmp/mine" -o "$tmp/defined"
        fi
    done
    # shellcheck disable=SC2046  # one object a word
    ld -r -o "$tmp/all.o" $(cat "$tmp/objects")
    nm --defined-only -g "$tmp/all.o" | awk '$3 !~ /^rt_book_/ { print $3 }' |
        sort -u > "$tmp/weak"
    objcopy --strip-debug --weaken-symbols="$tmp/weak" "$tmp/all.o" "$out.tmp"
    # every book's function the forms call is there
    missing=$(nm -u "$out.tmp" | awk '$2 ~ /^rt_book_/ { print $2 }' |
        while read -r s; do grep -qx "$s" "$tmp/defined" || echo "$s"; done)
    if [ -n "$missing" ]; then
        echo "book_code.sh: $out: the book's functions missing: $missing" >&2
        exit 1
    fi
    mv "$out.tmp" "$out"
    rm -rf "$tmp"
    ;;
machine)
    # whether book/MACHINE (its first line uname -sm, its second the
    # compiler's target) is this machine, compiler CC
    want_system=$(sed -n 1p "$2") want_target=$(sed -n 2p "$2")
    [ "$(uname -sm)" = "$want_system" ] || exit 1
    target=$($3 -dumpmachine 2> /dev/null) || exit 1
    [ "${target%%-*}" = "${want_target%%-*}" ]
    ;;
record)
    # book/MACHINE for this machine and compiler CC
    { uname -sm; $3 -dumpmachine; } > "$2"
    ;;
*)
    echo "usage: $0 forms OUT LINE_TANGLE CHAPTER.md... | link OUT.o OBJECT.o..." >&2
    exit 2
    ;;
esac
