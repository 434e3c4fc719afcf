#!/bin/sh
# watch.sh -- grade again whenever a workbook file changes.
#
# Usage: WB_DIR=workbook WB_BUILD=build/workbook tools/workbook/watch.sh MAKE...
# (make watch runs it; MAKE... is the make command, to which it adds
# grade or grade-chNN). First it grades every chapter. Then it waits for a
# file of WB_DIR to change (inotifywait where it is installed, else a look
# at the files' sizes and times every second) and grades the chapter that
# changed first (make grade-chNN); then, where a later chapter's code or
# tests use a function of the exercises that changed, the last such
# chapter (whose grade runs every suite up to it). The screen then shows
# the later chapters' exercises that are not done, and last, so that it
# stays in view, the changed chapter's verdict: its started exercises,
# the tests laid on no exercise, and the progress. What the files were is
# noted before each grade, not after: a file saved while a grade runs is
# graded as soon as that grade ends. Stop it with Ctrl-C.
set -u
WB_DIR=${WB_DIR:-workbook}
WB_BUILD=${WB_BUILD:-build/workbook}
state=$WB_BUILD/watch
mkdir -p "$state/graded"

snapshot() {
    for f in "$WB_DIR"/*.md; do
        [ -f "$f" ] && cksum "$f"
    done 2> /dev/null
}

# Waits until the workbook differs from the snapshot in file $1.
wait_for_change() {
    while [ "$(snapshot)" = "$(cat "$1")" ]; do
        if command -v inotifywait > /dev/null; then
            inotifywait -qq -t 2 -e close_write,moved_to,create,delete "$WB_DIR"
        else
            sleep 1
        fi
    done
}

# The code of exercise ID in workbook file FILE.
exercise_code() {
    awk -v id="ex=\"$2\"" 'index($0, id) && /^```/ { code = 1; next }
        code && /^```/ { exit } code' "$1" 2> /dev/null
}

# The exercises of FILE whose code differs from the copy graded last.
changed_exercises() {
    sed -n 's/^```.*ex="\([0-9.]*\)".*/\1/p' "$1" | while read -r id; do
        [ "$(exercise_code "$1" "$id")" = "$(exercise_code "$2" "$id")" ] ||
            echo "$id"
    done
}

# The names of the functions the code on standard input defines (of
# MACRO(NAME), NAME).
defined_functions() {
    awk '/^[A-Za-z_].*\(/ && !/;[ \t]*$/ {
            line = $0; sub(/\(.*/, "", line); sub(/.*[^A-Za-z_0-9]/, "", line)
            if (line ~ /^[A-Z_0-9]+$/) { # a macro: its argument
                line = $0; sub(/^[^(]*\(/, "", line); sub(/\).*/, "", line)
            }
            if (line != "") print line
        }'
}

# The last chapter after NN whose code chunks or tests name one of the
# functions (on standard input, a name a line), or nothing.
last_user() {
    names=$(sort -u | tr '\n' ' ')
    [ -n "$names" ] || return 0
    last=""
    for c in chapters/[0-9][0-9]-*.md; do
        n=$(basename "$c" | cut -c1-2)
        [ "$n" -gt "$1" ] || continue
        for name in $names; do # its code, not its prose, and its tests
            if awk '/^(```|~~~)/ { code = !code; next } code' "$c" |
                    cat - tests/ch"$n"_*.c 2> /dev/null | grep -qw -- "$name"; then
                last=$n
                break
            fi
        done
    done
    echo "$last"
}

# A grade's lines for the screen: started exercises, what follows them.
started_lines() {
    grep -v ' not started' "$1"
}

clear_screen() { printf '\033[H\033[2J'; }  # as rustlings watch does

clear_screen
snapshot > "$state/before"
cp "$WB_DIR"/*.md "$state/graded/" 2> /dev/null
"$@" grade
while :; do
    echo "watching $WB_DIR/ (Ctrl-C to stop)"
    wait_for_change "$state/before"
    snapshot > "$state/before"  # noted now: a save from here on counts
    changed=""
    for f in "$WB_DIR"/[0-9][0-9]-*.md; do
        cmp -s "$f" "$state/graded/$(basename "$f")" ||
            changed="$changed $(basename "$f" | cut -c1-2)"
    done
    functions=""
    for n in $changed; do
        f=$(ls "$WB_DIR/$n"-*.md)
        for id in $(changed_exercises "$f" "$state/graded/$(basename "$f")"); do
            functions="$functions $(exercise_code "$f" "$id" | defined_functions)"
        done
    done
    first=$(echo $changed | cut -d ' ' -f 1)
    rm -f "$state/graded"/*.md
    cp "$WB_DIR"/*.md "$state/graded/" 2> /dev/null
    [ -n "$first" ] || { clear_screen; "$@" grade; continue; }
    "$@" "grade-ch$first" > "$state/first.out" 2>&1
    later=$(echo $functions | tr ' ' '\n' | last_user "$first")
    if [ -n "$later" ]; then
        "$@" "grade-ch$later" > "$state/later.out" 2>&1
    fi
    clear_screen
    if [ -n "$later" ]; then
        echo "== chapter $later, which uses what you changed: its exercises not done"
        awk -v n="$first" '/^  [0-9]+\.[0-9]+ / && int($1) > n + 0 &&
            !/ done$/ && !/ not started/' "$state/later.out"
        grep -A 1000 '^Failing, and laid' "$state/later.out" | grep -v '^Progress'
        grep '^Progress' "$state/later.out" | sed 's/^/chapter '"$later"': /'
    fi
    echo "== chapter $first changed: graded first"
    started_lines "$state/first.out"
done
