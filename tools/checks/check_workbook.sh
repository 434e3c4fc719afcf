#!/bin/sh
# check_workbook.sh -- the workbook's own tests (make check-workbook, in make test).
#
# Usage: MAKE=make [WB_CHECK_DIR=DIR] tools/checks/check_workbook.sh
# Works in DIR (default build/wbcheck/): each check below has a folder of its own there
# (NAME/wb, the workbook; NAME/build, where make grade builds it,
# incrementally from one run to the next), and checks 2, 3 and 5 run side
# by side, check 4 after 3 in its folder (the wrong answers recompile only
# the files they are in). Checks that
#   1. an untouched workbook grades "Progress: 0 of N", N >= 36, at least 4
#      exercises a chapter, exit 0; make workbook overwrites no file; no
#      task holds TeX ($...$);
#   2. with every stub started, no exercise passes (each stub fails one of
#      its tests), and the exit status is not 0;
#   3. a SOLVED=1 workbook grades "Progress: N of N", exit 0, and builds
#      the book's programs byte for byte (their logged results stand);
#   4. the course sheet's forms typed in as answers fail with a message
#      naming the correction (sphere, half vector, tone map, Snell),
#      a loop is "timed out" and a null pointer "crashed (signal 11)"; in
#      the same grade, a syntax error is reported at its workbook line, a
#      lost fence where it was, and the other chapters'
#      exercises pass their tests but are not done, the program failing
#      elsewhere; the exit status is 1;
#   5. a 1.1 that passes its own tests but breaks chapter 5's camera is not
#      done, chapter 5's failing tests are listed as failing elsewhere, and
#      the exit status is 1; in the same grade, 2.4 taking the far root,
#      6.3's points not stratified and the sheet's normal in 5.2 fail with
#      messages naming the mistake (5.2 is in vec.h, which every file
#      includes: here, in a build of chapters 1 to 6, and not in check 4,
#      whose answers then recompile only the files they are in).
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

# The book's code of exercise ID, from the (solved) workbook file FILE.
solution() {
    awk -v id="ex=\"$1\"" 'index($0, id) { code = 1; next } code && /^```/ { exit } code' \
        "$wb/$2"
}

# Replaces the code of exercise ID in workbook file FILE by the file ANSWER.
answer() {
    awk -v id="$2" -v answer="$3" '
        !open && /^```/ && index($0, "ex=\"" id "\"") {
            print; open = 1
            while ((getline line < answer) > 0) print line
            next
        }
        open && /^```[ \t]*$/ { open = 0 }
        !open { print }' "$1" > "$1.new" && mv "$1.new" "$1"
}

list=$top/list
awk -f tools/workbook/exercises.awk chapters/[0-9][0-9]-*.md > "$list" || exit 1
n=$(wc -l < "$list")
[ "$n" -ge 36 ] || { echo "check-workbook: only $n exercises, fewer than 36"; exit 1; }
for c in chapters/[0-9][0-9]-*.md; do
    k=$(awk -F '\t' -v c="$c" '$2 == c' "$list" | wc -l)
    [ "$k" -ge 4 ] || { echo "check-workbook: $c has $k exercises, fewer than 4"; exit 1; }
done

# ---- 1. untouched
use untouched
fresh
echo "my own line" >> "$wb/01-camera.md"
$MAKE -s --no-print-directory workbook WB_DIR="$wb" > "$t/out" 2>&1
grep -qx "my own line" "$wb/01-camera.md" || fail "make workbook overwrote a file"
# the tasks are read as plain text: no TeX left in them
tex=$(awk '/^```/ { code = !code; next } !code && /\$[^$ ][^$]*\$/' "$wb"/*.md | head -3)
[ -z "$tex" ] || fail "a task holds TeX: $tex"
grade ""
[ "$status" = 0 ] || fail "an untouched workbook should grade with status 0"
grep -qx "Progress: 0 of $n exercises" "$t/out" || fail "expected Progress: 0 of $n"

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

# ---- 4. the sheet's forms, a loop and a crash; in the same grade, a syntax
# error in chapter 4 and a lost fence in chapter 6 (chapters the wrong
# answers are not in, so that each is seen)
check_wrong() {
    use solved # after check 3, in its folder: only what changes is compiled
    fresh SOLVED=1
    answer "$wb/02-spheres.md" 2.3 "$data/sheet-sphere.c"
    answer "$wb/03-phong.md" 3.1 "$data/sheet-half-vector.c"
    answer "$wb/03-phong.md" 3.3 "$data/sheet-tone-map.c"
    answer "$wb/07-refraction.md" 7.1 "$data/sheet-snell.c"
    answer "$wb/01-camera.md" 1.2 "$data/loops.c"
    answer "$wb/07-refraction.md" 7.3 "$data/crashes.c"
    fence=$(grep -n 'ex="4.1"' "$wb/04-triangles.md" | cut -d: -f1)
    sed -i "$((fence + 1))i this is not C" "$wb/04-triangles.md"
    lost=$(grep -n 'ex="6.1"' "$wb/06-shadows.md" | cut -d: -f1)
    sed -i '/ex="6.1"/d' "$wb/06-shadows.md"
    GRADE_TIMEOUT=4 grade ""
    [ "$status" != 0 ] || fail "wrong answers should not grade with status 0"
    expect_verdict 2.3 "measure from the ray's origin, c - o"
    expect_verdict 3.1 "h is the unit vector (l + v) / |l + v|"
    expect_verdict 3.3 "the tone map is min(alpha I^beta, 1), not the sheet's max"
    expect_verdict 7.1 "sin1 / sin2 = eta2 / eta1, not the sheet's eta1 / eta2"
    expect_verdict 1.2 "timed out: test_gamma_22"
    expect_verdict 7.3 "crashed (signal 11): test_brewster_angle_of_glass_is_56_31_degrees"
    grep -q "^$wb/04-triangles.md:$((fence + 1)):[0-9]*: error" "$t/out" ||
        fail "the syntax error should be reported at $wb/04-triangles.md:$((fence + 1))"
    grep -q "^$wb/06-shadows.md:$lost: error: exercise 6.1" "$t/out" ||
        fail "the lost fence should be reported where it was, $wb/06-shadows.md:$lost"
    ! grep -q '__builtin_' "$t/out" ||
        fail "a message shows what a macro expanded to, not the macro"
    expect_verdict 4.1 "not graded"
    expect_verdict 6.1 "not graded"
    # the chapters that hold no wrong answer are graded all the same: their
    # tests pass, and they are not done while the program fails elsewhere
    for id in $(awk -F '\t' '$2 ~ /\/(0[89]|[1-9][0-9])-/ { print $1 }' "$list"); do
        verdict "$id" | grep -q ' its tests pass, but [0-9]* other test(s) fail' ||
            fail "exercise $id, untouched, should pass its tests, not be done"
    done
}

# ---- 5. only three exercises started: 1.1, the book's code without the
# line that lets chapter 5 place the camera: 1.1's tests pass, chapter 5's
# look-at tests fail, no started exercise names them, and the grade says
# so; 2.4 taking the far root, 6.3 with points that are not stratified and
# 5.2 moving normals as the sheet does, each caught by a message that
# names the mistake; and 4.3 wrong with 4.4 right, which share tests: only
# 4.3 is failing
check_elsewhere() {
    use elsewhere
    fresh SOLVED=1
    solution 1.1 01-camera.md | grep -vx '    <<place the primary ray>>' \
        > "$t/camera.c"
    # the far root: the larger root whenever it lies past t_min
    near='roots\[0\] > t_min ? roots\[0\] : roots\[1\]'
    far='roots[1] > t_min ? roots[1] : roots[0]'
    solution 2.4 02-spheres.md | sed "s/$near/$far/" > "$t/far-root.c"
    grep -q 'roots\[1\] > t_min' "$t/far-root.c" ||
        fail "2.4's code no longer picks its root as the far-root plant expects"
    # 4.3 keeping only the hits whose edge functions are all positive, and
    # 4.4 right: the tests they share fail, and 4.3 alone is blamed
    both='(u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0)'
    solution 4.3 04-triangles.md | sed "s/$both/u < 0 || v < 0 || w < 0/" \
        > "$t/one-winding.c"
    grep -q 'if (u < 0 || v < 0 || w < 0)$' "$t/one-winding.c" ||
        fail "4.3's code no longer tests its signs as the one-winding plant expects"
    solution 4.4 04-triangles.md > "$t/shear.c"
    fresh
    answer "$wb/01-camera.md" 1.1 "$t/camera.c"
    answer "$wb/02-spheres.md" 2.4 "$t/far-root.c"
    answer "$wb/06-shadows.md" 6.3 "$data/unstratified.c"
    answer "$wb/05-transforms.md" 5.2 "$data/sheet-normal.c"
    answer "$wb/04-triangles.md" 4.3 "$t/one-winding.c"
    answer "$wb/04-triangles.md" 4.4 "$t/shear.c"
    grade -ch06
    [ "$status" != 0 ] || fail "a program that breaks chapter 5 should not grade with status 0"
    expect_verdict 1.1 "its tests pass, but"
    expect_verdict 2.4 "test_the_nearer_root_is_the_hit: t = 6: the nearer root is 4"
    expect_verdict 6.3 "is outside its cell"
    expect_verdict 5.2 "a normal moves by (M^-1)^T n, not by M n"
    expect_verdict 4.3 "failing: test_"
    expect_verdict 4.4 "its tests pass, but"
    grep -A 1000 '^Failing, and the fault of no exercise you started' "$t/out" |
        grep -q '^  test_look_at_keeps_up_up (tests/ch05_transforms.c:' ||
        fail "chapter 5's look-at test should be listed as failing elsewhere"
}

# 2, 3 then 4, and 5 side by side; each prints only when it fails.
check_stubs > "$top/stubs.verdict" 2>&1 & stubs=$!
{ check_solved && check_wrong; } > "$top/solved.verdict" 2>&1 & solved=$!
check_elsewhere > "$top/elsewhere.verdict" 2>&1 & elsewhere=$!
failed=0
for check in stubs solved elsewhere; do
    eval "pid=\$$check"
    wait "$pid" || { failed=1; cat "$top/$check.verdict"; }
done
[ "$failed" = 0 ] || exit 1

echo "check-workbook: $n exercises; stubs fail, the book's code passes, the sheet's" \
     "forms are named, errors are located"
