#!/bin/sh
# check_workbook.sh -- the workbook's own tests (make check-workbook, in make test).
#
# Usage: MAKE=make [WB_CHECK_DIR=DIR] tools/checks/check_workbook.sh
# Works in DIR (default build/wbcheck/): each check below has a folder of its own there
# (NAME/wb, the workbook; NAME/build, where make grade builds it,
# incrementally from one run to the next), and they run side by side, in
# three lines (1, 8; 3 then 4 in its folder; 5, 2, 7), each grading no
# more chapters than its mistakes need, which it finds by the exercises'
# chunk names (a chapter put before another renumbers them). Checks that
#   1. an untouched workbook grades "Progress: 0 of N", N >= 36, at least 4
#      exercises a chapter, exit 0; make workbook overwrites no file; no
#      task holds TeX ($...$); and make grade EX=N.k exits 0 for a right
#      1.1, and not 0 for 1.2, not started;
#   2. with every stub started, no exercise passes (each stub fails one of
#      its tests), and the exit status is not 0;
#   3. a SOLVED=1 workbook grades "Progress: N of N", exit 0, and builds
#      the book's programs byte for byte (their logged results stand);
#   4. the course sheet's forms typed in as answers fail with a message
#      naming the correction (sphere, half vector, tone map, Snell),
#      a loop is "timed out" with its limit and the load, a null pointer
#      "crashed (signal 11)"; 1.3 taking +12x34 for a size and 3.2 with a
#      directional light at distance 0 are each caught by a test of its
#      own chapter; in
#      the same grade, a syntax error is reported at its workbook line, a
#      lost fence where it was, and the other chapters' exercises are
#      done (every failure is laid on an exercise); the exit status is 1,
#      and the JUnit report has a failure for each exercise not done;
#   5. (chapters 1 to 6) a 1.1 that passes its own tests but breaks
#      chapter 5's camera (it sets the ray's direction again after the
#      chunk that places it) is failing, chapter 5's test laid on it, found
#      by halves of the exercises that name no failing test; in the same
#      grade, 2.4 taking the far root, 6.3's points not stratified, the
#      sheet's normal in 5.2, 3.2's cone that leaves out its edge and 6.2
#      seeded by three of the six coordinates fail with messages naming
#      the mistake, and 4.3 wrong with 4.4 right, which share tests: only
#      4.3 is failing, 4.4 and the right answers 2.1 and 3.3 are done;
#      and 1.3 without its last return fails on the compiler's warning;
#   6. (chapters 1 to 10) 9.1 with static first and last, and 10.1 with a
#      static hash state: data races, both caught by ThreadSanitizer (where
#      the compiler has it) and laid on their exercises; 10.1's hash also
#      leaves out the axis, which its own test sees; and 8.3 with an
#      uninitialised variable and a write past an array, failing on the
#      compiler's warnings at its lines; and 2.4 that forgets inside,
#      caught by a test of its own chapter;
#   7. (chapters 1 to 8) 8.3 that clips one edge short: every failing test,
#      its own and the others, laid on it; and 2.4 without its line <<the
#      sphere's hit-point bound>> (kept for chapter 6) fails, saying so,
#      its file left out (the book's code stands in).
# Prints what went wrong in each failed check and exits 1.
set -u
MAKE=${MAKE:-make}
export SHARDS=1  # the checks run side by side already: one runner each
top=${WB_CHECK_DIR:-build/wbcheck}
data=tests/data/workbook
mkdir -p "$top"

# use NAME: the check's folder t, its workbook wb.
use() {
    t=$top/$1
    wb=$t/wb
    mkdir -p "$t"
    : > "$t/out"
}

# Ends the check (a subshell when run side by side) with what went wrong.
fail() {
    echo "check-workbook: $*"
    sed 's/^/  | /' "$t/out" | head -60
    exit 1
}

fresh() {
    rm -rf "$wb"
    $MAKE -s --no-print-directory workbook WB_DIR="$wb" "$@" > "$t/out" 2>&1 ||
        fail "make workbook failed"
}

grade() {
    $MAKE -s --no-print-directory "grade$1" WB_DIR="$wb" WB_BUILD="$t/build" \
        > "$t/out" 2>&1
    status=$?
}

# The grader's line for exercise ID.
verdict() { grep -E "^  $1 " "$t/out"; }

expect_verdict() {
    verdict "$1" | grep -qF -- "$2" ||
        fail "exercise $1 should say '$2'"
}

# The exercises are named by their chunk or file (KEY), not by number:
# a chapter put before another renumbers them. id_of KEY: "2.1";
# file_of KEY: its workbook file's name; chapter_of KEY: "02".
id_of() { awk -F '\t' -v k="$1" '$5 == k { print $1; exit }' "$list"; }
file_of() { awk -F '\t' -v k="$1" '$5 == k { sub(/.*\//, "", $2); print $2; exit }' "$list"; }
chapter_of() { file_of "$1" | cut -c1-2; }

# expect KEY TEXT: exercise KEY's verdict holds TEXT.
expect() { expect_verdict "$(id_of "$1")" "$2"; }

# The last chapter of the exercises KEY...: what a grade of them needs.
last_chapter() {
    for key in "$@"; do chapter_of "$key"; done | sort | tail -n 1
}

# The book's code of exercise KEY, from the solved workbook.
solution() {
    awk -v id="ex=\"$(id_of "$1")\"" 'index($0, id) { code = 1; next } code && /^```/ { exit } code' \
        "$top/book/$(file_of "$1")"
}

# answer KEY FILE: exercise KEY started with the code in FILE.
answer() {
    awk -v id="$(id_of "$1")" -v answer="$2" '
        !open && /^```/ && index($0, "ex=\"" id "\"") {
            print; open = 1
            while ((getline line < answer) > 0) print line
            next
        }
        open && /^```[ \t]*$/ { open = 0 }
        !open { print }' "$wb/$(file_of "$1")" > "$t/answer.md" &&
        mv "$t/answer.md" "$wb/$(file_of "$1")"
}

# plant KEY SED_SCRIPT: exercise KEY started with the book's code edited
# by SED_SCRIPT; fails the check when the edit changes nothing (the
# book's code moved on: the plant must follow it).
plant() {
    solution "$1" > "$t/plant.orig"
    sed "$2" "$t/plant.orig" > "$t/plant.c"
    ! cmp -s "$t/plant.orig" "$t/plant.c" ||
        fail "exercise $1's code no longer holds what the plant '$2' edits"
    answer "$1" "$t/plant.c"
}

# right KEY...: each started with the book's code.
right() {
    for key in "$@"; do
        solution "$key" > "$t/right.c"
        answer "$key" "$t/right.c"
    done
}

list=$top/list
awk -f tools/workbook/exercises.awk chapters/[0-9][0-9]-*.md > "$list" || exit 1
n=$(wc -l < "$list")
[ "$n" -ge 36 ] || { echo "check-workbook: only $n exercises, fewer than 36"; exit 1; }
for c in chapters/[0-9][0-9]-*.md; do
    k=$(awk -F '\t' -v c="$c" '$2 == c' "$list" | wc -l)
    [ "$k" -ge 4 ] || { echo "check-workbook: $c has $k exercises, fewer than 4"; exit 1; }
done

rm -rf "$top/book"
$MAKE -s --no-print-directory workbook WB_DIR="$top/book" SOLVED=1 > /dev/null 2>&1 ||
    { echo "check-workbook: make workbook SOLVED=1 failed"; exit 1; }

# ---- 1. untouched; then one exercise's verdict as the exit status
check_untouched() {
    use untouched
    fresh
    mine=$(ls "$wb" | head -n 1)
    echo "my own line" >> "$wb/$mine"
    $MAKE -s --no-print-directory workbook WB_DIR="$wb" > "$t/out" 2>&1
    grep -qx "my own line" "$wb/$mine" || fail "make workbook overwrote a file"
    # the tasks are read as plain text: no TeX left in them
    # (a formula may span lines: a line with a dollar or a command is TeX)
    tex=$(awk '/^```/ { code = !code; next } !code && /\$[^ ]|\\[a-zA-Z]+/' "$wb"/*.md | head -3)
    [ -z "$tex" ] || fail "a task holds TeX: $tex"
    grade ""
    [ "$status" = 0 ] || fail "an untouched workbook should grade with status 0"
    grep -qx "Progress: 0 of $n exercises" "$t/out" || fail "expected Progress: 0 of $n"
    # one exercise's verdict as the exit status (the grade of its chapter)
    right camera.c
    $MAKE -s --no-print-directory grade EX="$(id_of camera.c)" WB_DIR="$wb" \
        WB_BUILD="$t/build" > "$t/out" 2>&1 ||
        fail "make grade EX=$(id_of camera.c) should exit 0: it is right"
    $MAKE -s --no-print-directory grade EX="$(id_of "colour encoding")" WB_DIR="$wb" \
        WB_BUILD="$t/build" > "$t/out" 2>&1 &&
        fail "make grade EX=$(id_of "colour encoding") should not exit 0: it is not started"
    return 0
}

# ---- 2. every stub started: each one fails
check_stubs() {
    use stubs
    fresh
    sed -i '/^\/\/ NOT DONE/d' "$wb"/*.md
    grade ""
    [ "$status" != 0 ] || fail "the stubs should not grade with status 0"
    passed=$(grep -cE '^  [0-9]+\.[0-9]+ .* done$' "$t/out")
    [ "$passed" = 0 ] || fail "$passed stubs pass their tests: those exercises cannot be graded"
    graded=$(grep -cE '^  [0-9]+\.[0-9]+ .* (failing|timed out|crashed)' "$t/out")
    [ "$graded" = "$n" ] || fail "only $graded of $n stubs were graded as failing"
}

# ---- 3. the book's code passes
check_solved() {
    use solved
    fresh SOLVED=1
    grade ""
    [ "$status" = 0 ] || fail "a SOLVED=1 workbook should grade with status 0"
    grep -qx "Progress: $n of $n exercises" "$t/out" || fail "expected Progress: $n of $n"
    # typed in, the book's code builds the book's programs, byte for byte
    grep -q "^(the programs are the book's own" "$t/out" ||
        fail "the book's code, typed in, should build the book's programs"
}

# ---- 4. the sheet's forms, a loop, a crash and a hash without the axis;
# in the same grade, a syntax error and a lost fence in two chapters that
# hold no wrong answer, so that each is seen
check_wrong() {
    use solved # after check 3, in its folder: only what changes is compiled
    fresh SOLVED=1
    answer "robust form" "$data/sheet-sphere.c"
    answer highlights "$data/sheet-half-vector.c"
    answer "tone mapping" "$data/sheet-tone-map.c"
    answer optics.c "$data/sheet-snell.c"
    answer "colour encoding" "$data/loops.c"
    answer "Fresnel reflectance" "$data/crashes.c"
    # mistakes that passed before, each caught at its own chapter
    plant "parse a size" "/if (text\[0\] < '0' || text\[0\] > '9')/,/return false;/d"
    plant lights 's/vec3_scale(L->direction, -1), INFINITY,/vec3_scale(L->direction, -1), 0,/'
    syntax=$wb/$(file_of "the sheet's method")
    fence=$(grep -n "ex=\"$(id_of "the sheet's method")\"" "$syntax" | cut -d: -f1)
    sed -i "$((fence + 1))i this is not C" "$syntax"
    fenced=$wb/$(file_of offset.c)
    lost=$(grep -n "ex=\"$(id_of offset.c)\"" "$fenced" | cut -d: -f1)
    sed -i "/ex=\"$(id_of offset.c)\"/d" "$fenced"
    upto=$(last_chapter "robust form" highlights "tone mapping" optics.c \
        "colour encoding" "Fresnel reflectance" "the sheet's method" offset.c)
    GRADE_TIMEOUT=4 grade "-ch$upto"
    [ "$status" != 0 ] || fail "wrong answers should not grade with status 0"
    expect "robust form" "measure from the ray's origin, c - o"
    expect highlights "h is the unit vector (l + v) / |l + v|"
    expect "tone mapping" "the tone map is min(alpha I^beta, 1), not the sheet's max"
    expect optics.c "sin1 / sin2 = eta2 / eta1, not the sheet's eta1 / eta2"
    expect "colour encoding" "s (its limit; the machine's load was"
    expect "colour encoding" "timed out after "
    expect "colour encoding" "test_gamma_22"
    expect "Fresnel reflectance" "crashed (signal 11): test_brewster_angle_of_glass_is_56_31_degrees"
    expect "parse a size" "failing: test_command_line_numbers_are_digits_only"
    expect lights "a directional light at distance 0, not infinity"
    grep -q "^$syntax:$((fence + 1)):[0-9]*: error" "$t/out" ||
        fail "the syntax error should be reported at $syntax:$((fence + 1))"
    grep -q "^$fenced:$lost: error: exercise $(id_of offset.c)" "$t/out" ||
        fail "the lost fence should be reported where it was, $fenced:$lost"
    ! grep -q '__builtin_' "$t/out" ||
        fail "a message shows what a macro expanded to, not the macro"
    expect "the sheet's method" "not graded"
    expect offset.c "not graded"
    # the exercises of the chapters that hold no wrong answer and no error
    # are done: every failure is laid on the wrong answer that causes it
    touched=$(for key in "robust form" highlights optics.c "colour encoding" \
                  "the sheet's method" offset.c; do
                  chapter_of "$key"; done | sort -u | tr '\n' ' ')
    for id in $(awk -F '\t' -v touched=" $touched" -v upto="$upto" '{
            c = $2; sub(/.*\//, "", c); c = substr(c, 1, 2)
            if (!index(touched, " " c " ") && c <= upto) print $1 }' "$list"); do
        expect_verdict "$id" " done"
    done
    ! grep -q '^Failing, and laid on no one' "$t/out" ||
        fail "every failure should be laid on an exercise"
    not_done=$(grep -E '^  [0-9]+\.[0-9]+ ' "$t/out" | grep -vc ' done$\| not started')
    [ "$(grep -c '<failure message=' "$t/build/junit.xml")" = "$not_done" ] ||
        fail "the JUnit report should hold a failure for each of the $not_done exercises not done"
    return 0
}

# ---- 5. mistakes that another chapter's test catches, that share tests,
# that the compiler sees, and that a message names
check_elsewhere() {
    use elsewhere
    fresh
    # 1.1 sets the ray's direction again after <<place the primary ray>>:
    # its own tests pass, the look-at camera's fail
    plant camera.c '/^    <<place the primary ray>>$/a\
    r.dir = vec3_normalize(on_plane); /* the direction, to be sure */'
    # the far root: the larger root whenever it lies past t_min
    plant sphere.c \
        's/roots\[0\] > t_min ? roots\[0\] : roots\[1\]/roots[1] > t_min ? roots[1] : roots[0]/'
    # 4.3 keeping only the hits whose edge functions are all positive, and
    # 4.4 right: the tests they share fail, and 4.3 alone is blamed
    plant watertight \
        's/(u < 0 || v < 0 || w < 0) \&\& (u > 0 || v > 0 || w > 0)/u < 0 || v < 0 || w < 0/'
    right "shear the ray onto the z axis" "geometric form" "tone mapping"
    answer "points in the unit square" "$data/unstratified.c"
    answer "4x4 matrices" "$data/sheet-normal.c"
    plant lights 's/if (cos_theta < L->cos_cutoff)/if (cos_theta <= L->cos_cutoff)/'
    plant "the random stream" 's/for (int k = 0; k < 6; k++) {/for (int k = 0; k < 3; k++) {/'
    plant "parse a size" '/^    return true;$/d'
    grade "-ch$(last_chapter camera.c sphere.c watertight "points in the unit square" \
        "4x4 matrices" lights "the random stream")"
    [ "$status" != 0 ] || fail "a program that breaks the look-at camera should not grade with status 0"
    expect camera.c "test_look_at_"
    expect camera.c "_transforms.c:"
    expect camera.c "it fails with your $(id_of camera.c) alone"
    expect sphere.c "test_the_nearer_root_is_the_hit: t = 6: the nearer root is 4"
    expect "points in the unit square" "is outside its cell"
    expect "4x4 matrices" "a normal moves by (M^-1)^T n, not by M n"
    expect watertight "failing: test_"
    expect lights "the edge is inside the cone"
    expect "the random stream" "every coordinate's bits must seed it"
    expect "parse a size" "the compiler warns at your line: $wb/$(file_of "parse a size"):"
    expect "parse a size" "[-Wreturn-type]"
    for key in "shear the ray onto the z axis" "geometric form" "tone mapping"; do
        expect "$key" " done"
    done
}

# ---- 6. state the threads share; the compiler's warnings in 8.3
check_races() {
    use races
    fresh
    plant "a thread's bands" 's/^    int first, last;$/    static int first, last;/'
    plant sphere.c '/h->inside = /d'
    # 10.1 keeps its hash in a static variable, and leaves out the axis
    plant "the sample hash" 's/^    uint64_t h = mix64(/    static uint64_t h;\
    h = mix64(/; s/h = mix64(h ^ ((uint64_t)(uint32_t)k << 1 | (uint64_t)(axis \& 1)));/h = mix64(h ^ (uint64_t)(uint32_t)k);/'
    plant "clipping a polygon" 's/^    int m = 0;$/    int m;/; /^    for (int i = 0; i < n; i++) {$/i\
    vec3 first[1];\
    first[1] = poly[0]; /* the first corner, kept */\
    if (n < 1)\
        out[0] = first[1];'
    grade "-ch$(last_chapter "a thread's bands" "the sample hash" "clipping a polygon" sphere.c)"
    [ "$status" != 0 ] || fail "data races should not grade with status 0"
    expect sphere.c "the hit must say so (inside)"
    clip=$wb/$(file_of "clipping a polygon")
    expect "clipping a polygon" "the compiler warns at your line: $clip:"
    grep -q "^$clip:[0-9]*:[0-9]*: warning: .*m.* uninitialized" "$t/out" ||
        fail "the compiler should warn of 8.3's m, used uninitialized"
    grep -Eq "^$clip:[0-9]*:[0-9]*: warning: array (subscript|index) 1 is (above|past)" "$t/out" ||
        fail "the compiler should warn of 8.3's write past its array"
    expect "the sample hash" "the axis must change the number"
    if grep -q "^(no ThreadSanitizer" "$t/out"; then
        return 0
    fi
    expect "a thread's bands" "data race (ThreadSanitizer) at $wb/$(file_of "a thread's bands"):"
    expect "a thread's bands" "a static variable, which every thread shares"
    # the race, which the verdict does not show behind the failing test
    grep -q "^$(id_of "the sample hash")	a data race (ThreadSanitizer) at $wb/$(file_of "the sample hash"):.* on h, a static variable" \
        "$t/build/ch$(chapter_of "the sample hash")/races.tsv" ||
        fail "ThreadSanitizer should see 10.1's static h"
}

# ---- 7. 8.3's loop one edge short
check_kd() {
    use kd
    fresh
    plant "clipping a polygon" 's/^    for (int i = 0; i < n; i++) {$/    for (int i = 0; i < n - 1; i++) {/'
    plant sphere.c "/^<<the sphere's hit-point bound>>\$/d"
    grade "-ch$(last_chapter "clipping a polygon" sphere.c)"
    [ "$status" != 0 ] || fail "8.3 one edge short should not grade with status 0"
    expect "clipping a polygon" "failing: test_tree_agrees_with_brute_force"
    expect sphere.c "failing: lost its line <<the sphere's hit-point bound>>"
    grep -q "^$wb/$(file_of sphere.c):[0-9]*: error: exercise $(id_of sphere.c) lost its line" "$t/out" ||
        fail "the lost chunk line should be reported at its exercise in $wb/$(file_of sphere.c)"
    ! grep -q '^Failing, and laid on no one' "$t/out" ||
        fail "every failure should be laid on 8.3"
}

# timed NAME: check_NAME, its seconds noted in $top/seconds.
timed() {
    start=$(date +%s)
    "check_$1" || return 1
    echo "$1 $(($(date +%s) - start))" >> "$top/seconds"
}

# Three lines of checks side by side; each prints only when it fails.
: > "$top/seconds"
{ timed untouched && timed kd; } > "$top/first.verdict" 2>&1 & first=$!
{ timed solved && timed wrong; } > "$top/solved.verdict" 2>&1 & solved=$!
{ timed elsewhere && timed stubs && timed races; } > "$top/elsewhere.verdict" 2>&1 & elsewhere=$!
failed=0
for check in first solved elsewhere; do
    eval "pid=\$$check"
    wait "$pid" || { failed=1; cat "$top/$check.verdict"; }
done
[ "$failed" = 0 ] || exit 1

echo "check-workbook: $n exercises; stubs fail, the book's code passes, the sheet's" \
     "forms are named, errors are located, every mistake is laid on its exercise"
