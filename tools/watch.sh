#!/bin/sh
# watch.sh -- run a command again whenever a workbook file changes.
#
# Usage: WB_DIR=workbook tools/watch.sh COMMAND...   (make watch runs it)
# Clears the screen and runs COMMAND, then waits for a file of WB_DIR to
# change: with inotifywait where it is installed, else by looking at the
# files' times and sizes once a second. Stop it with Ctrl-C.
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

while :; do
    printf '\033[H\033[2J'  # clear the screen, as rustlings watch does
    "$@"
    echo "watching $WB_DIR/ (Ctrl-C to stop)"
    wait_for_change
done
