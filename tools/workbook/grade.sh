#!/bin/sh
# grade.sh -- grade the reader's workbook against the chapters' tests.
#
# Usage (the Makefile's grade and grade-chNN targets run it):
#     tools/workbook/grade.sh NN CHAPTER.md...     (the chapters 01..NN, in order)
# Environment: TANGLE (the tangler), MAKE, WB_DIR (the workbook, default
# workbook), WB_BUILD (where it is built, default build/workbook),
# GRADE_TIMEOUT (seconds a test may take, default 10; a quarter of its own
# limit for a test that sets one, as the heavy ones do), GRADE_TANGLE_ONLY
# (1: check and tangle the workbook, build and run nothing), GRADE_ALONE
# (the most failing exercises graded alone as below, default 8; 0: none),
# BOOK_BUILD and BOOK_BIN (the book's build and programs: their logged
# results stand for a workbook that builds the very same programs).
#
# For every chapter its workbook file WB_DIR/NN-name.md (make workbook
# writes them) is checked alone first: one the tangler rejects (a fence
# deleted, a chunk renamed) is reported at its file and line and left out,
# and its chapter is graded with the book's code. The chapters and the good
# workbook files are then tangled together, the reader's started exercises
# (no "// NOT DONE" line) replacing the book's chunks (tangle
# --skip-not-done), so that #line directives send every compiler message to
# the workbook line the reader typed. A workbook file that does not compile
# is left out the same way. The program and the suites of chapters 01..NN,
# and the program of the chapter before (some suites compare the two), are
# built under WB_BUILD (make, incrementally) and every suite runs in
# Check's fork mode with a time limit per test. When a few exercises fail,
# each is built and its failing tests run again with the book's code in
# every other exercise, so that a mistake is laid at one exercise's door,
# where it is, and not at the others' that share its tests. One line per
# exercise follows: done, failing (its first failing test, in the order the
# exercise names them, and the test's message), timed out, crashed (signal
# N), not started, or "its tests pass, but" when other tests fail; then
# the failing tests that no started exercise names (tools/workbook/grade_report.awk)
# and "Progress: D of N exercises". The exit status is 0 only when every
# started exercise is done, no test fails and every workbook file is good.
set -u

if [ "$#" -lt 2 ]; then
    echo "usage: $0 NN CHAPTER.md..." >&2
    exit 2
fi
target=$1
shift
TANGLE=${TANGLE:-build/rel/tools/book/tangle}
MAKE=${MAKE:-make}
WB_DIR=${WB_DIR:-workbook}
WB_BUILD=${WB_BUILD:-build/workbook}
GRADE_TIMEOUT=${GRADE_TIMEOUT:-10}
tools_dir=$(dirname "$0")
work=$WB_BUILD/ch$target
previous=""
[ "$#" -gt 1 ] && previous=$(printf '%02d' "$(expr "$target" - 1)")
mkdir -p "$work"
list=$work/exercises.tsv     # ID CHAPTER LINE KIND KEY TESTS
state=$work/state.tsv        # ID STATE WORKBOOK FIRST LAST
bad_files=$work/bad-files    # workbook files left out
: > "$state"
: > "$bad_files"

awk -f "$tools_dir/exercises.awk" "$@" > "$list" || exit 1

workbook_of() { echo "$WB_DIR/$(basename "$1")"; }

# The fence of exercise ID in FILE: "FIRST LAST STARTED", or nothing.
find_fence() {
    awk -v id="$2" '
        !open && /^```/ && index($0, "ex=\"" id "\"") { open = NR; started = 1; next }
        open && /^[ \t]*\/\/ NOT DONE/ { started = 0 }
        open && /^```[ \t]*$/ { print open, NR, started; exit }' "$1"
}

# Where exercise ID's fence belongs in FILE: the first line after its hint
# (the heading's line if there is none; 1 if there is no heading).
fence_place() {
    awk -v id="$2" '
        index($0, "## Exercise " id ":") == 1 { heading = NR; next }
        heading && !hint_done && /^<\/details>/ { hint_done = 1; next }
        hint_done && NF { print NR; found = 1; exit }
        heading && /^## Exercise / { exit }
        END { if (!found) print (heading ? heading : 1) }' "$1"
}

# Checks one workbook file with the chapters; records its exercises.
check_file() {
    chapter=$1
    shift
    wb=$(workbook_of "$chapter")
    if [ ! -f "$wb" ]; then
        awk -F '\t' -v c="$chapter" '$2 == c { print $1 "\tabsent\t-\t0\t0" }' \
            "$list" >> "$state"
        return
    fi
    rm -rf "$work/check"
    if ! "$TANGLE" --line --skip-not-done -o "$work/check" "$@" "$wb" \
            > "$work/check.log" 2>&1; then
        grep -v ': warning: ' "$work/check.log" >&2
        echo "$wb: left out: the book's code of chapter $(basename "$wb" .md) stands in" >&2
        echo "$wb" >> "$bad_files"
    fi
    awk -F '\t' -v c="$chapter" '$2 == c { print $1 }' "$list" |
    while read -r id; do
        fence=$(find_fence "$wb" "$id")
        if [ -z "$fence" ]; then
            echo "$wb:$(fence_place "$wb" "$id"): error: exercise $id has lost its" \
                 "chunk fence (a line \`\`\`{.c ... .exercise ex=\"$id\"})" >&2
            grep -qx "$wb" "$bad_files" || echo "$wb" >> "$bad_files"
            printf '%s\tbroken\t%s\t0\t0\n' "$id" "$wb" >> "$state"
            continue
        fi
        set -- $fence
        kind=$([ "$3" = 1 ] && echo started || echo "not-started")
        printf '%s\t%s\t%s\t%s\t%s\n' "$id" "$kind" "$wb" "$1" "$2" >> "$state"
    done
}

good_files() {
    for chapter in "$@"; do
        wb=$(workbook_of "$chapter")
        [ -f "$wb" ] && ! grep -qx "$wb" "$bad_files" && echo "$wb"
    done
}

# tangle_to NN CHAPTER.md...: the chapters and their good workbook files,
# tangled into $WB_BUILD/tangle/chNN.
tangle_to() {
    into=$WB_BUILD/tangle/ch$1
    shift
    # shellcheck disable=SC2046  # one workbook path a word
    "$TANGLE" --line --skip-not-done -o "$into" "$@" \
        $(good_files "$@") 2> "$work/tangle.log" || { cat "$work/tangle.log" >&2; return 1; }
    if [ -d "$into/scenes" ]; then
        ln -sfn "$(pwd)/meshes" "$into/scenes/meshes"
    fi
}

# The graded chapter's program, and the chapter before's: some suites
# compare the two programs' pictures.
tangle_all() {
    tangle_to "$target" "$@" || return 1
    [ -n "$previous" ] || return 0
    # shellcheck disable=SC2046  # the chapters but the last, a word each
    tangle_to "$previous" $(echo "$@" | sed 's/ [^ ]*$//')
}

# Two jobs, unless a parent make shares its own (make -j2 grade).
case ${MAKEFLAGS:-} in
    *jobserver*) jobs="" ;;
    *) jobs="-j${GRADE_JOBS:-2}" ;;
esac

# The compiler's warnings about the reader's code, at the workbook's lines
# (each once: the chapter before's program compiles the same lines).
show_warnings() {
    awk -v wb="$WB_DIR/" 'index($0, wb) == 1 && / warning: / && !seen[$0]++' \
        "$work/build.log" >&2
}

# Builds; a workbook file named by a compiler error is left out, once.
# The suites and the programs of the tangle in WB_BUILD, of WB_DIR.
make_programs() {
    $MAKE $jobs --no-print-directory -s WB_DIR="$WB_DIR" WB_BUILD="$WB_BUILD" \
        WB_REUSE="$target" "$WB_BUILD/test/ch$target" "$WB_BUILD/bin/ch$target" \
        ${previous:+"$WB_BUILD/bin/ch$previous"}
}

build() {
    for attempt in 1 2 3; do
        tangle_all "$@" || return 1
        if make_programs > "$work/build.log" 2>&1; then
            show_warnings
            return 0
        fi
        cat "$work/build.log" >&2
        culprits=$(sed -n "s|^\($WB_DIR/[^:]*\.md\):[0-9]*:.*error.*|\1|p" \
                       "$work/build.log" | sort -u)
        [ -n "$culprits" ] || return 1
        for wb in $culprits; do
            echo "$wb: does not compile: the book's code of chapter" \
                 "$(basename "$wb" .md) stands in" >&2
            echo "$wb" >> "$bad_files"
        done
    done
    return 1
}

# The book's own programs, byte for byte (a workbook whose every started
# exercise holds the book's code): the results make test-chNN logged for
# them, when it logged them after they were built, stand for a run.
book_results() {
    [ -n "${BOOK_BUILD:-}" ] && [ -n "${BOOK_BIN:-}" ] || return 1
    log=$BOOK_BUILD/test/ch$target.log
    set -- "$WB_BUILD/test/ch$target" "$BOOK_BUILD/test/ch$target" \
           "$WB_BUILD/bin/ch$target" "$BOOK_BIN/ch$target"
    [ -n "$previous" ] &&
        set -- "$@" "$WB_BUILD/bin/ch$previous" "$BOOK_BIN/ch$previous"
    while [ "$#" -gt 0 ]; do
        [ -f "$log" ] && [ "$log" -nt "$2" ] && cmp -s "$1" "$2" || return 1
        shift 2
    done
    echo "(the programs are the book's own: the results of make" \
         "test-ch$target stand)" >&2
    cp "$log" "$work/tests.log"
}

run_suites() {
    book_results && return
    CK_FORK=yes CK_VERBOSITY=verbose CK_TIMEOUT_MULTIPLIER=0.25 \
    CK_DEFAULT_TIMEOUT=$((GRADE_TIMEOUT * 4)) \
    CHAPTER_BIN=$WB_BUILD/bin/ch$target \
        timeout 900 sh "$tools_dir/../checks/run_shards.sh" "$WB_BUILD/test/ch$target" \
        > "$work/tests.log" 2>&1
}

# A failing test does not say which exercise is wrong: it may run the
# code of several, or of one that does not name it. When a few started
# exercises fail (GRADE_ALONE, default 8, at most), each of them is built
# again alone under WB_BUILD/alone, the book's code standing in for every
# other started exercise, and its failing tests are run again; a test
# that then passes is not the exercise's fault, and it is cleared of it (a
# line "ID<tab>TEST" in $work/cleared.tsv). A test that fails and that no
# exercise keeps is the reader's code elsewhere, or of two together
# (tools/workbook/grade_report.awk).
cleared=$work/cleared.tsv
alone=$WB_BUILD/alone

# "ID<tab>TESTS": each started exercise that names a failing test, and
# those tests.
failing_exercises() {
    awk -F '\t' -v state="$state" -v tests_log="$work/tests.log" '
        BEGIN {
            while ((getline l < state) > 0) {
                split(l, f, "\t")
                if (f[2] == "started") started[f[1]] = 1
            }
            while ((getline l < tests_log) > 0) {
                if (split(l, p, ":") < 6 || p[3] !~ /^[FE]$/) continue
                failed[p[5]] = 1; failed[p[5] ":" p[6]] = 1
            }
        }
        started[$1] {
            k = split($6, named, " "); which = ""
            for (i = 1; i <= k; i++)
                if (named[i] in failed) which = which " " named[i]
            if (which != "") print $1 "\t" substr(which, 2)
        }' "$list"
}

# Exercise ID built alone: the good workbook files copied to
# WB_BUILD/alone/wb, a line "// NOT DONE" put in every other started
# exercise, then tangled and built as build() does. Arguments: ID
# CHAPTER.md...
build_alone() {
    id=$1
    shift
    rm -rf "$alone/wb"
    mkdir -p "$alone/wb"
    for wb in $(good_files "$@"); do
        awk -v id="$id" -v state="$state" -v file="$wb" '
            BEGIN {
                while ((getline l < state) > 0) {
                    split(l, f, "\t")
                    if (f[2] == "started" && f[3] == file && f[1] != id)
                        others["ex=\"" f[1] "\""] = 1
                }
            }
            { print }
            /^```/ { for (o in others) if (index($0, o)) print "// NOT DONE" }
        ' "$wb" > "$alone/wb/$(basename "$wb")" || return 1
    done
    (WB_DIR=$alone/wb WB_BUILD=$alone
     tangle_all "$@" && make_programs) > "$work/alone.log" 2>&1
}

# Does the program built alone pass test NAME (TEST or TEST:ITERATION)?
passes_alone() {
    RUNNER_ONLY=${1%%:*} CK_FORK=yes CK_VERBOSITY=verbose \
        CK_TIMEOUT_MULTIPLIER=0.25 CK_DEFAULT_TIMEOUT=$((GRADE_TIMEOUT * 4)) \
        CHAPTER_BIN=$alone/bin/ch$target \
        timeout 900 "$alone/test/ch$target" > "$work/alone-run.log" 2>&1
    awk -F ':' -v t="$1" '$3 ~ /^[PFE]$/ && ($5 == t || $5 ":" $6 == t) {
            seen = 1; if ($3 != "P") bad = 1 }
        END { exit !(seen && !bad) }' "$work/alone-run.log"
}

isolate_failures() {
    failing_exercises > "$work/failing.tsv"
    count=$(wc -l < "$work/failing.tsv")
    [ "$count" -gt 0 ] && [ "$count" -le "${GRADE_ALONE:-8}" ] || return 0
    while IFS='	' read -r id names; do
        build_alone "$id" "$@" < /dev/null || continue
        for name in $names; do
            passes_alone "$name" < /dev/null &&
                printf '%s\t%s\n' "$id" "$name"
        done
    done < "$work/failing.tsv" >> "$cleared"
}

for chapter in "$@"; do
    check_file "$chapter" "$@"
done

# GRADE_TANGLE_ONLY=1 (make chart-ch02 WORKBOOK=1): the tangle and the state
# of each exercise, in $work/state.tsv, and nothing else.
if [ "${GRADE_TANGLE_ONLY:-}" = 1 ]; then
    tangle_all "$@"
    exit
fi

: > "$work/tests.log"
: > "$cleared"
# The tests of the chapters after NN: an exercise may name one (its code
# is tested again there), and a grade of chapter NN does not run it.
later=$work/later-tests
for f in tests/ch[0-9][0-9]_*.c; do
    [ "$(basename "$f" | cut -c3-4)" -gt "$target" ] &&
        sed -n 's/^START_TEST(\([a-z0-9_]*\)).*/\1/p' "$f"
done > "$later"
started=$(awk -F '\t' '$2 == "started"' "$state" | wc -l)
built=no
if [ "$started" -gt 0 ]; then
    if build "$@"; then
        built=yes
        run_suites
        isolate_failures "$@"
    fi
fi

awk -v built="$built" -v bad_files="$bad_files" -v cleared="$cleared" \
    -v later="$later" \
    -f "$tools_dir/grade_report.awk" "$list" "$state" "$work/tests.log"
