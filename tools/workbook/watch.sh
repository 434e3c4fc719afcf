#!/bin/sh
# watch.sh -- run a command again whenever a workbook file changes.
#
# Usage: WB_DIR=workbook tools/workbook/watch.sh COMMAND...   (make watch runs it)
# Clears the screen and runs COMMAND, then waits for a file of WB_DIR to
# change: with inotifywait where it is installed, else by looking at the
# files' times and sizes once a second. When a chapter's file changed, that
# chapter is graded first, by COMMAND with "-chNN" after its last word
# (make grade-chNN), and says so; then COMMAND. Stop it with Ctrl-C.
set -u
WB_DIR=${WB_DIR:-workbook}

snapshot() { ls -l --time-style=+%s.%N "$WB_DIR" 2>/dev/null | md5sum; }

wait_for_change() {
    if command -v inotifywait > /dev/null; then
        inotifywait -qq -e close_write,moved_to,create,delete "$WB_DIR"
        return
    fi
    before=$(snapshot)
    while [ "$(snapshot)" = "$before" ]; do
        sleep 1
    done
}

# The chapter number of the workbook file changed last, or nothing.
last_changed() {
    newest=$(ls -t "$WB_DIR"/[0-9][0-9]-*.md 2>/dev/null | head -n 1)
    [ -n "$newest" ] && basename "$newest" | cut -c1-2
}

changed=""
while :; do
    printf '\033[H\033[2J'  # clear the screen, as rustlings watch does
    if [ -n "$changed" ]; then
        echo "== chapter $changed changed: graded first"
        "$@"-ch"$changed"
        echo "== every chapter"
    fi
    "$@"
    echo "watching $WB_DIR/ (Ctrl-C to stop)"
    wait_for_change
    changed=$(last_changed)
done
