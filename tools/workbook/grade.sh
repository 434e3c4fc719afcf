#!/bin/sh
# grade.sh -- grade the reader's workbook against the chapters' tests.
#
# Usage (the Makefile's grade and grade-chNN targets run it):
#     tools/workbook/grade.sh NN CHAPTER.md...     (the chapters 01..NN, in order)
# Environment: TANGLE (the tangler), MAKE, WB_DIR (the workbook, default
# workbook), WB_BUILD (where it is built, default build/workbook),
# GRADE_TIMEOUT (seconds a test may take, default 10; a test whose test
# case sets a limit of its own, as the heavy ones do, gets that limit
# times GRADE_TIMEOUT / 10), GRADE_EX (an exercise, 2.1: the exit status
# is its verdict alone), GRADE_TANGLE_ONLY (1: check and tangle the
# workbook, build and run nothing), GRADE_ALONE (the most exercises
# failing their own tests for which failing tests are laid on one
# exercise, default 16; more, as every stub started, and each is failing
# already), GRADE_TSAN (0:
# no run under ThreadSanitizer), BOOK_BUILD and BOOK_BIN (the book's build
# and programs: their logged results stand for a workbook that builds the
# very same programs).
#
# For every chapter its workbook file WB_DIR/NN-name.md (make workbook
# writes them) is checked alone first: one the tangler rejects (a fence
# deleted, a chunk renamed), or in which a started exercise has lost a
# <<chunk>> line of the book's code (later chapters put their code there),
# is reported at its file and line and left out, and its chapter is graded
# with the book's code. The chapters and the good workbook files are then
# tangled together, the reader's started exercises (no "// NOT DONE" line)
# replacing the book's chunks (tangle --skip-not-done), so that #line
# directives send every compiler message to the workbook line the reader
# typed. A workbook file that does not compile is left out the same way; a
# warning at the lines of an exercise fails that exercise. In a handout,
# the book's code of the exercises is not there to tangle: book/forward/
# NN-name.md stands in for every exercise not started, calling the book's
# code compiled (book/chNN.o), and book/export/NN-name.md lets that code
# call the reader's (tools/workbook/book_code.sh).
#
# The program and the suites of chapters 01..NN, and the program of the
# chapter before (some suites compare the two), are built under WB_BUILD
# (make, incrementally) and every suite runs in Check's fork mode with a
# time limit per test. The tests that start threads in their own process
# run again, the reader's files built with ThreadSanitizer, which sees a
# data race whether or not it changed a result. A failing test does not
# say which exercise is wrong: it may run the code of several, or of one
# that does not name it. So the failing tests run again with some of the
# reader's exercises in place and the book's code in the others: first
# each exercise that names one of them alone, then halves of the others,
# and halves of those, until a test is laid on the one exercise that
# alone makes it fail (tools/workbook/grade_report.awk prints the verdicts). One
# line per exercise follows: done, failing (the first of its tests to
# fail, or a test laid on it, or a compiler warning, or a data race),
# timed out (with the limit and the machine's load), crashed (signal N),
# not started; then the failing tests that no one exercise causes, and
# "Progress: D of N exercises". It writes WB_BUILD/junit.xml, a JUnit
# report (a test case an exercise). The exit status is 0 only when every
# started exercise is done, no test fails and every workbook file is good
# (with GRADE_EX: when that exercise is done).
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
# (every process counts: a grade runs hundreds of them, and on some
# machines each costs milliseconds; builtins where they do)
case $0 in */*) tools_dir=${0%/*} ;; *) tools_dir=. ;; esac
work=$WB_BUILD/ch$target
previous=""
[ "$#" -gt 1 ] && previous=$(printf '%02d' "$((${target#0} - 1))")
mkdir -p "$work"
list=$work/exercises.tsv     # ID CHAPTER LINE KIND KEY TESTS
state=$work/state.tsv        # ID STATE WORKBOOK FIRST LAST
bad_files=$work/bad-files    # workbook files left out
lost=$work/lost.tsv          # ID MESSAGE: a <<chunk>> line lost
warned=$work/warned.tsv      # ID MESSAGE: the compiler's warning
races=$work/races.tsv        # ID MESSAGE: ThreadSanitizer's report
laid=$work/laid.tsv          # ID TEST: fails with ID alone started
cleared=$work/cleared.tsv    # ID TEST: passes with ID alone started
stubs_fail=$work/stubs-fail  # TEST: fails with none of the reader's started
for f in "$state" "$bad_files" "$lost" "$warned" "$races" "$laid" \
         "$cleared" "$stubs_fail"; do
    : > "$f"
done

awk -f "$tools_dir/exercises.awk" "$@" > "$list" || exit 1
awk -f "$tools_dir/test_index.awk" tests/ch[0-9][0-9]_*.c > "$work/tests.tsv"

# Whether workbook file $1 is left out (in $bad_files).
is_bad() {
    while IFS= read -r bad; do
        [ "$bad" = "$1" ] && return 0
    done < "$bad_files"
    return 1
}

# The handout's stand-ins for the book's code of chapters "$@", before
# (forward) or after (export) the workbook: nothing outside a handout.
book_code() {
    kind=$1
    shift
    [ -d book/$kind ] && [ "${GRADE_BOOK_CODE:-}" != no ] || return 0
    for chapter in "$@"; do
        [ -f "book/$kind/${chapter##*/}" ] && echo "book/$kind/${chapter##*/}"
    done
}

# Checks one workbook file with the chapters; records its exercises.
check_file() {
    chapter=$1
    shift
    wb=$WB_DIR/${chapter##*/}
    if [ ! -f "$wb" ]; then
        awk -F '\t' -v c="$chapter" '$2 == c { print $1 "\tabsent\t-\t0\t0" }' \
            "$list" >> "$state"
        return
    fi
    rm -rf "$work/check"
    # shellcheck disable=SC2046  # one file a word
    if ! "$TANGLE" --line --skip-not-done -o "$work/check" "$@" \
            $(book_code forward "$@") "$wb" $(book_code export "$@") \
            > "$work/check.log" 2>&1; then
        grep -v ': warning: ' "$work/check.log" >&2
        base=${wb##*/}
        echo "$wb: left out: the book's code of chapter ${base%.md} stands in" >&2
        echo "$wb" >> "$bad_files"
    fi
    awk -v chapter="$chapter" -v wb="$wb" -v state="$state" -v lost="$lost" \
        -v bad_files="$bad_files" -f "$tools_dir/fences.awk" \
        "$list" "$chapter" "$wb"
}

good_files() {
    for chapter in "$@"; do
        wb=$WB_DIR/${chapter##*/}
        [ -f "$wb" ] && ! is_bad "$wb" && echo "$wb"
    done
}

# tangle_to NN CHAPTER.md...: the chapters and their good workbook files
# (with the handout's stand-ins), tangled into $WB_BUILD/tangle/chNN.
tangle_to() {
    into=$WB_BUILD/tangle/ch$1
    shift
    # shellcheck disable=SC2046  # one path a word
    "$TANGLE" --line --skip-not-done -o "$into" "$@" \
        $(book_code forward "$@") $(good_files "$@") $(book_code export "$@") \
        2> "$work/tangle.log" || { cat "$work/tangle.log" >&2; return 1; }
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
# (each once: the chapter before's program compiles the same lines), and
# each laid on the exercise whose lines it names.
show_warnings() {
    # each object's compiler messages are kept beside it (the Makefile):
    # a file compiled in an earlier grade keeps its warnings
    for d in "$WB_BUILD/obj/ch$target" ${previous:+"$WB_BUILD/obj/ch$previous"}; do
        cat "$d"/*.o.warnings 2> /dev/null
    done | awk -v wb="$WB_DIR/" 'index($0, wb) == 1 && / warning: / && !seen[$0]++' \
        > "$work/warnings"
    cat "$work/warnings" >&2
    awk -F '\t' -v warnings="$work/warnings" '
        $2 == "started" { file[$1] = $3; first[$1] = $4; last[$1] = $5; ids[++n] = $1 }
        END {
            while ((getline line < warnings) > 0) {
                split(line, p, ":")
                for (i = 1; i <= n; i++) {
                    id = ids[i]
                    if (p[1] == file[id] && p[2] + 0 > first[id] &&
                        p[2] + 0 < last[id] && !(id in told)) {
                        told[id] = 1
                        print id "\t" line
                    }
                }
            }
        }' "$state" >> "$warned"
}

# Builds; a workbook file named by a compiler error is left out, once.
# The suites and the programs of the tangle in WB_BUILD, of WB_DIR.
make_programs() {
    $MAKE $jobs --no-print-directory -s WB_DIR="$WB_DIR" WB_BUILD="$WB_BUILD" \
        WB_REUSE="$target" "$WB_BUILD/test/ch$target" "$WB_BUILD/bin/ch$target" \
        ${previous:+"$WB_BUILD/bin/ch$previous"}
}

# Whether folder $1 holds an object.
has_objects() {
    for o in "$1"/*.o; do
        [ -e "$o" ] && return 0
    done
    return 1
}

build() {
    # an object compiled before its messages were kept: compiled again
    # (and what it was linked into, which make would not remake)
    for o in "$WB_BUILD"/obj/ch*/*.o; do
        [ -e "$o" ] && [ ! -e "$o.warnings" ] &&
            rm -f "$o" "$WB_BUILD"/bin/ch* "$WB_BUILD"/test/ch*
    done
    for d in "$WB_BUILD"/obj/ch*; do # none left, but the programs stand
        [ -d "$d" ] && ! has_objects "$d" &&
            rm -f "$WB_BUILD"/bin/ch* "$WB_BUILD"/test/ch*
    done
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
            base=${wb##*/}
            echo "$wb: does not compile: the book's code of chapter" \
                 "${base%.md} stands in" >&2
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

# Every test's limit: Check's default (GRADE_TIMEOUT) for most, a test
# case's own times GRADE_TIMEOUT / 10 for the heavy ones; on a machine
# busier than it has cores (the load, as the grade starts, above the
# cores), every limit times load / cores, and one runner a core instead of
# four: a test then gets the share of a core that it would get alone.
cores=$(nproc 2> /dev/null || sysctl -n hw.ncpu 2> /dev/null || echo 1)
load=
{ read -r load _ < /proc/loadavg; } 2> /dev/null ||
    load=$(uptime 2> /dev/null | sed 's/.*: //; s/,.*//')
busy_multiplier=$(awk -v l="${load:-0}" -v c="$cores" -v g="$GRADE_TIMEOUT" '
    BEGIN { b = l > c ? l / c : 1; printf "%s %.3g\n", b, g / 10 * b }')
busy=${busy_multiplier% *}
multiplier=${busy_multiplier#* }
[ "$busy" = 1 ] || export SHARDS="${SHARDS:-$cores}"

# run_tests RUNNER PROGRAM LOG [NAMES]: the runner's tests (only NAMES,
# when given), forked and timed, shard by shard.
run_tests() {
    RUNNER_ONLY=${4:-} CK_FORK=yes CK_VERBOSITY=verbose \
    CK_DEFAULT_TIMEOUT=10 CK_TIMEOUT_MULTIPLIER=$multiplier \
    CHAPTER_BIN=$2 timeout 1800 sh "$tools_dir/../checks/run_shards.sh" "$1" > "$3" 2>&1
}

run_suites() {
    [ -z "${GRADE_TESTS:-}" ] && book_results && book_own=yes && return
    run_tests "$WB_BUILD/test/ch$target" "$WB_BUILD/bin/ch$target" \
        "$work/tests.log" "${GRADE_TESTS:-}"
}

# ---- the tests that start threads, under ThreadSanitizer
# The files of the tangle in DIR whose code (their own, or a header's they
# include) holds the reader's lines: the .c files, no suffix, each
# followed by a blank.
readers_files() {
    set -- "$1" "$1"/*.c "$1"/*.h
    dir=$1
    shift
    for f in "$@"; do # a glob that matched nothing is no file
        shift
        [ -f "$f" ] && set -- "$@" "$f"
    done
    [ "$#" -gt 0 ] || return 0
    awk -v dir="$dir" -v wb="$WB_DIR/" '
        FNR == 1 { file = FILENAME; sub(/.*\//, "", file) }
        /^#line [0-9]* "/ {
            rest = $0
            sub(/^#line [0-9]* /, "", rest)
            if (index(rest, "\"" wb) == 1) mine[file] = 1
        }
        function reads(file,    line, name) {
            if (file in mine) return 1
            if (file in done) return 0
            done[file] = 1
            while ((getline line < (dir "/" file)) > 0)
                if (line ~ /^#include "/) {
                    name = line
                    sub(/^#include "/, "", name); sub(/".*/, "", name)
                    if (reads(name)) { close(dir "/" file); return 1 }
                }
            close(dir "/" file)
            return 0
        }
        END {
            for (i = 1; i < ARGC; i++) {
                f = ARGV[i]
                if (f !~ /\.c$/) continue
                sub(/.*\//, "", f)
                split("", done) # each file followed anew, as alone
                if (reads(f)) { sub(/\.c$/, "", f); printf "%s ", f }
            }
        }' "$@" < /dev/null
}

# The tests of chapters 01..NN that start threads in their own process.
threaded_tests() {
    awk -v upto="$target" '
        FNR == 1 { mine = substr(FILENAME, index(FILENAME, "/ch") + 3, 2) + 0 <= upto + 0 }
        mine { text[FILENAME] = text[FILENAME] $0 " "; if (!(FILENAME in seen)) order[++n] = FILENAME; seen[FILENAME] = 1 }
        END {
            for (i = 1; i <= n; i++) {
                t = text[order[i]]
                while (match(t, /tcase_add_threaded_test\([^,]*,[^)]*\)/)) {
                    name = substr(t, RSTART, RLENGTH)
                    t = substr(t, RSTART + RLENGTH)
                    sub(/.*,[ ]*/, "", name)
                    sub(/[ )]*$/, "", name)
                    print name
                }
            }
        }' tests/ch[0-9][0-9]_*.c
}

# Runs the threaded tests with the reader's files built with
# ThreadSanitizer; each report is laid on the exercise whose line it
# names first.
run_threads_sanitized() {
    [ "${GRADE_TSAN:-1}" = 1 ] && [ -z "${book_own:-}" ] || return 0
    names=$(threaded_tests)
    [ -z "${GRADE_TESTS:-}" ] || names=$(minus "$names" "$(minus "$names" "$GRADE_TESTS")")
    [ -n "$(echo $names)" ] || return 0
    files=$(readers_files "$WB_BUILD/tangle/ch$target")
    [ -n "$files" ] || return 0
    probe=$work/tsan-probe
    printf 'int main(void) { return 0; }\n' > "$probe.c"
    ${CC:-cc} -fsanitize=thread "$probe.c" -o "$probe" 2> /dev/null &&
        "$probe" 2> /dev/null || {
        echo "(no ThreadSanitizer with this compiler: data races are not looked for)" >&2
        return 0
    }
    rm -f "$WB_BUILD/tsan/test/ch$target" # linked again: the files may differ
    $MAKE $jobs --no-print-directory -s WB_DIR="$WB_DIR" WB_BUILD="$WB_BUILD" \
        WB_REUSE="$target" WB_TSAN_FILES="$files" \
        "$WB_BUILD/tsan/test/ch$target" > "$work/tsan-build.log" 2>&1 || {
        cat "$work/tsan-build.log" >&2
        echo "(the build with ThreadSanitizer failed: data races are not looked for)" >&2
        return 0
    }
    rm -rf "$work/tsan"
    mkdir -p "$work/tsan"
    # one test a core at a time (several wait on clocks or on each other's
    # threads); each writes its own files, read in order below. A test
    # stops at its first report (halt_on_error): once a race is seen, every
    # access after it is checked against the reports made, which can take
    # seconds of a core; one report lays the race on its exercise
    TSAN_DIR=$work/tsan TSAN_RUNNER=$WB_BUILD/tsan/test/ch$target \
    TSAN_PROGRAM=$WB_BUILD/bin/ch$target \
    TSAN_MULTIPLIER=$(awk -v m="$multiplier" 'BEGIN { print 4 * m }') \
    xargs -P "$cores" -n 1 sh -c '
        TSAN_OPTIONS="exitcode=66 halt_on_error=1 report_signal_unsafe=0 log_path=$TSAN_DIR/$0" \
        RUNNER_ONLY=$0 CK_FORK=yes CK_VERBOSITY=verbose \
        CK_DEFAULT_TIMEOUT=10 CK_TIMEOUT_MULTIPLIER=$TSAN_MULTIPLIER \
        CHAPTER_BIN=$TSAN_PROGRAM \
            timeout 1800 "$TSAN_RUNNER" > "$TSAN_DIR/$0.out" 2>&1
        exit 0' <<EOF
$names
EOF
    for name in $names; do
        for report in "$work/tsan/$name".*; do
            [ -f "$report" ] || continue
            awk -v wb="$WB_DIR/" -v cwd="$PWD/" -v test="$name" -v state="$state" '
                BEGIN {
                    while ((getline l < state) > 0) {
                        split(l, f, "\t")
                        if (f[2] == "started") { file[f[1]] = f[3]; lo[f[1]] = f[4]; hi[f[1]] = f[5]; ids[++n] = f[1] }
                    }
                }
                # a report a block; each printed at the next one or at the end
                /WARNING: ThreadSanitizer:/ {
                    report()
                    what = $0; sub(/.*ThreadSanitizer: /, "", what); sub(/ \(pid.*/, "", what)
                    where = func = variable = id = ""
                }
                # (Clang names a file by its absolute path: made relative)
                /^ *#[0-9]+ / && where == "" {
                    for (i = 1; i <= NF; i++)
                        if (index($i, cwd wb) == 1) $i = substr($i, length(cwd) + 1)
                    for (i = 1; i <= NF; i++)
                        if (index($i, wb) == 1) {
                            where = $i; func = $2
                            split(where, p, ":")
                            for (k = 1; k <= n; k++)
                                if (p[1] == file[ids[k]] && p[2] + 0 > lo[ids[k]] && p[2] + 0 < hi[ids[k]])
                                    id = ids[k]
                        }
                }
                /Location is global / && variable == "" {
                    variable = $0; sub(/.*Location is global \047/, "", variable)
                    sub(/\047.*/, "", variable); sub(/\.[0-9]+$/, "", variable)
                }
                function report() {
                    if (what == "") return
                    printf "%s\ta %s (ThreadSanitizer) at %s in %s, seen by %s: %s\n",
                        id == "" ? "-" : id, what, where == "" ? "the book'\''s code" : where, func, test,
                        variable == "" ? "state that the threads share" : \
                        "on " variable ", a static variable, which every thread shares: make it a local one"
                }
                END { report() }' "$report" >> "$races"
        done
    done
}

# ---- laying each failing test on the exercise that alone makes it fail
alone=$WB_BUILD/alone

# The tests that failed in LOG: TEST:ITERATION, one a line.
failed_in() {
    awk -F ':' '$3 ~ /^[FE]$/ && NF >= 6 && !seen[$5 ":" $6]++ { print $5 ":" $6 }' "$1"
}

# The started exercises that were built (in good files), one a line.
built_exercises() {
    awk -F '\t' -v bad="$bad_files" '
        BEGIN { while ((getline l < bad) > 0) out[l] = 1 }
        $2 == "started" && !($3 in out) { print $1 }' "$state"
}

# build_only IDS CHAPTER.md...: the program with only the exercises IDS
# (blank-separated) started, the book's code in every other: the good
# workbook files copied to WB_BUILD/alone/wb with a line "// NOT DONE"
# in every other started exercise, then tangled and built as build() does.
build_only() {
    only=" $1 "
    shift
    rm -rf "$alone/wb"
    mkdir -p "$alone/wb"
    for wb in $(good_files "$@"); do
        awk -v only="$only" -v state="$state" -v file="$wb" '
            BEGIN {
                while ((getline l < state) > 0) {
                    split(l, f, "\t")
                    if (f[2] == "started" && f[3] == file && !index(only, " " f[1] " "))
                        others["ex=\"" f[1] "\""] = 1
                }
            }
            { print }
            /^```/ { for (o in others) if (index($0, o)) print "// NOT DONE" }
        ' "$wb" > "$alone/wb/${wb##*/}" || return 1
    done
    (WB_DIR=$alone/wb WB_BUILD=$alone
     tangle_all "$@" && make_programs) > "$work/alone.log" 2>&1
}

# probe IDS TESTS CHAPTER.md...: of TESTS (TEST:ITERATION, blank-
# separated), those that fail with only IDS started, one a line.
probe() {
    ids=$1 tests=$2
    shift 2
    [ -z "${GRADE_DEBUG:-}" ] || echo "probe $ids: $(date +%s.%N | cut -c1-14) ${tests%% *}..." >&2
    build_only "$ids" "$@" < /dev/null || { echo "$tests" | tr ' ' '\n'; return; }
    [ -z "${GRADE_DEBUG:-}" ] || echo "  built $(date +%s.%N | cut -c1-14)" >&2
    names=$(echo "$tests" | tr ' ' '\n' | sed 's/:[0-9]*$//' | sort -u | tr '\n' ' ')
    run_tests "$alone/test/ch$target" "$alone/bin/ch$target" \
        "$work/alone-run.log" "$names" < /dev/null
    failed_in "$work/alone-run.log" > "$work/alone-failed"
    [ -z "${GRADE_DEBUG:-}" ] || echo "  ran $(date +%s.%N | cut -c1-14)" >&2
    for t in $tests; do
        grep -qxF -- "$t" "$work/alone-failed" && echo "$t"
    done
}

# minus A B: the words of A that are not in B.
minus() {
    for w in $1; do
        case " $2 " in *" $w "*) ;; *) printf '%s ' "$w" ;; esac
    done
}

# bisect TESTS IDS CHAPTER.md...: every test of TESTS fails with IDS
# started; lays each on one exercise of IDS that alone makes it fail,
# halving IDS, or leaves it unexplained.
bisect() {
    tests=$1 ids=$2
    shift 2
    set -- $ids "--" "$@"
    count=0
    for w in $ids; do count=$((count + 1)); done
    if [ "$count" = 1 ]; then
        for t in $tests; do printf '%s\t%s\n' $ids "$t"; done >> "$laid"
        return
    fi
    half=$((count / 2))
    low="" high=""
    k=0
    for w in $ids; do
        k=$((k + 1))
        if [ "$k" -le "$half" ]; then low="$low $w"; else high="$high $w"; fi
    done
    shift $((count + 1))
    fail_low=$(probe "$low" "$tests" "$@" | tr '\n' ' ')
    rest=$(minus "$tests" "$fail_low")
    fail_high=""
    [ -n "$rest" ] && fail_high=$(probe "$high" "$rest" "$@" | tr '\n' ' ')
    [ -n "$fail_low" ] && (bisect "$fail_low" "$low" "$@")
    [ -n "$fail_high" ] && (bisect "$fail_high" "$high" "$@")
    return 0
}

# The built exercises that name a test that failed, one a line.
failing_named() {
    failing=$(failed_in "$work/tests.log" | tr '\n' ' ')
    ids=$(built_exercises | tr '\n' ' ')
    awk -F '\t' -v failing=" $failing " -v ids=" $ids " '
        index(ids, " " $1 " ") {
            k = split($6, t, " ")
            for (i = 1; i <= k; i++)
                if (index(failing, " " t[i] " ") || index(failing, " " t[i] ":")) { print $1; break }
        }' "$list"
}

# More than GRADE_ALONE exercises failing their own tests (every stub
# started): each is failing already; nothing is run again.
too_many_failing() {
    [ "$(failing_named | wc -l)" -gt "${GRADE_ALONE:-16}" ]
}

lay_failures() {
    failing=$(failed_in "$work/tests.log" | tr '\n' ' ')
    [ -n "$failing" ] || return 0
    # what fails with none of the reader's exercises, the stubs of the
    # parts of functions not started standing in, is theirs: laid on no
    # one, it waits for them
    if [ -n "$(echo $fragments_waiting)" ]; then
        probe "-" "$failing" "$@" > "$stubs_fail"
        failing=$(minus "$failing" "$(tr '\n' ' ' < "$stubs_fail")")
        [ -n "$(echo $failing)" ] || return 0
    fi
    ids=$(built_exercises | tr '\n' ' ')
    [ -n "$ids" ] || return 0
    set -- $ids "--" "$@"
    if [ "$1" != "--" ] && [ "$2" = "--" ]; then # one exercise: its own
        for t in $failing; do printf '%s\t%s\n' "$1" "$t"; done >> "$laid"
        return 0
    fi
    while [ "$1" != "--" ]; do shift; done
    shift
    # first the exercises that name a failing test, each alone (but one
    # whose failing tests are all laid on another already)
    named=$(failing_named | tr '\n' ' ')
    rest=$failing
    for id in $named; do
        # its own failing tests, and those still unexplained
        own=$(awk -F '\t' -v id="$id" -v failing="$failing" '
            $1 == id {
                k = split($6, t, " "); n = split(failing, all, " ")
                for (j = 1; j <= n; j++)
                    for (i = 1; i <= k; i++)
                        if (all[j] == t[i] || index(all[j], t[i] ":") == 1) {
                            print all[j]; break
                        }
            }' "$list" | tr '\n' ' ')
        [ -n "$(minus "$own" "$(cut -f 2 "$laid" | tr '\n' ' ')")" ] || continue
        tests=$(echo "$rest $own" | tr ' ' '\n' | sed '/^$/d' | sort -u | tr '\n' ' ')
        [ -n "$tests" ] || continue
        fails=$(probe "$id" "$tests" "$@" | tr '\n' ' ')
        for t in $fails; do printf '%s\t%s\n' "$id" "$t"; done >> "$laid"
        for t in $(minus "$own" "$fails"); do printf '%s\t%s\n' "$id" "$t"; done >> "$cleared"
        rest=$(minus "$rest" "$fails")
    done
    [ -n "$(echo $rest)" ] || return 0
    others=$(minus "$ids" "$named")
    [ -n "$(echo $others)" ] || return 0
    # then the others together (all of them: as graded), and by halves
    if [ -z "$(echo $named)" ]; then
        fails=$rest
    else
        fails=$(probe "$others" "$rest" "$@" | tr '\n' ' ')
    fi
    [ -n "$(echo $fails)" ] && bisect "$fails" "$others" "$@"
    return 0
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
# The tests of the chapters after NN: an exercise may name one (its code
# is tested again there), and a grade of chapter NN does not run it.
# With GRADE_TESTS, the tests left out are held against no one either.
later=$work/later-tests
awk -v upto="$target" -v only="${GRADE_TESTS:-}" '
    BEGIN { n = split(only, w, " "); for (i = 1; i <= n; i++) kept[w[i]] = 1 }
    match($0, /^START_TEST\([a-z0-9_]*\)/) {
        name = substr($0, 12, RLENGTH - 12)
        if (substr(FILENAME, index(FILENAME, "/ch") + 3, 2) + 0 > upto + 0)
            print name
        if (only != "" && !(name in kept))
            left_out[++k] = name
    }
    END { for (i = 1; i <= k; i++) print left_out[i] }' tests/ch[0-9][0-9]_*.c > "$later"
# In a handout, an exercise that is a part of a function's body has no
# function to call the book's code through: its stub stands in until it is
# started, and the tests that name it wait for it.
stubbed=$(book_code forward "$@" | xargs -r awk '
    /^```\{\.c chunk="/ { name = $0; sub(/^```\{\.c chunk="/, "", name)
                         sub(/".*/, "", name); body = ""; next }
    /^```[ \t]*$/ { if (name != "" && body == "return 0; /* your code here */\n")
                      print name
                  name = ""; next }
    name != "" { body = body $0 "\n" }' |
    awk -F '\t' 'NR == FNR { fragment[$0] = 1; next }
                 $4 == "chunk" && ($5 in fragment) { printf "%s ", $1 }' - "$list")
# Of them, those not started: their stubs stand in in every build.
fragments_waiting=$(awk -F '\t' -v ids=" $stubbed" '
    $2 != "started" && index(ids, " " $1 " ") { printf "%s ", $1 }' "$state")
started=$(awk -F '\t' '$2 == "started"' "$state" | wc -l)
built=no
if [ "$started" -gt 0 ]; then
    if build "$@"; then
        built=yes
        run_suites
        # without the book's code (a handout on another machine) the
        # stubs of the exercises not started fail tests of their own
        if [ "${GRADE_BOOK_CODE:-}" != no ] && ! too_many_failing; then
            run_threads_sanitized
            lay_failures "$@"
        fi
    fi
fi
awk -v built="$built" -v bad_files="$bad_files" -v later="$later" \
    -v laid="$laid" -v cleared="$cleared" -v lost="$lost" \
    -v warned="$warned" -v races="$races" -v index_file="$work/tests.tsv" \
    -v multiplier="$multiplier" -v load="${load:-?}" -v cores="$cores" \
    -v only="${GRADE_EX:-}" -v junit="$WB_BUILD/junit.xml" \
    -v chapter="$target" -v stubs="$([ "${GRADE_BOOK_CODE:-}" = no ] && echo yes)" \
    -v stubbed="$stubbed" -v stubs_fail="$stubs_fail" \
    -v fragments_waiting="$fragments_waiting" \
    -f "$tools_dir/grade_report.awk" "$list" "$state" "$work/tests.log"
