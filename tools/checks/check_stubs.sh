#!/bin/sh
# check_stubs.sh -- each exercise's stub, alone, fails one of its tests.
#
# Usage: MAKE=make tools/checks/check_stubs.sh   (make check-stubs; not in make test:
# it grades once per exercise, several minutes)
# make check-workbook starts every stub at once, so a stub that passes its
# own tests could hide behind another's failure. Here a SOLVED=1 workbook
# in build/wbstubs gets one stub at a time (the rest is the book's code),
# and the grader must call that exercise failing, timed out or crashed.
set -u
MAKE=${MAKE:-make}
t=build/wbstubs
mkdir -p "$t"
rm -rf "$t/solved" "$t/stubs" "$t/wb"
$MAKE -s --no-print-directory workbook WB_DIR="$t/solved" SOLVED=1 > /dev/null || exit 1
$MAKE -s --no-print-directory workbook WB_DIR="$t/stubs" > /dev/null || exit 1
bad=0
awk -f tools/workbook/exercises.awk chapters/[0-9][0-9]-*.md | cut -f1,2 |
while read -r id chapter; do
    name=$(basename "$chapter")
    rm -rf "$t/wb" && cp -R "$t/solved" "$t/wb"
    # the stub of this exercise, started, in place of its solution
    awk -v id="$id" -v stubs="$t/stubs/$name" '
        BEGIN {
            while ((getline line < stubs) > 0) {
                if (!inside && line ~ /^```/ && index(line, "ex=\"" id "\"")) { inside = 1; continue }
                if (inside && line ~ /^```[ \t]*$/) inside = 0
                if (inside && line !~ /^\/\/ NOT DONE/) stub = stub line "\n"
            }
        }
        !open && /^```/ && index($0, "ex=\"" id "\"") { print; printf "%s", stub; open = 1; next }
        open && /^```[ \t]*$/ { open = 0 }
        !open { print }' "$t/solved/$name" > "$t/wb/$name"
    $MAKE -s --no-print-directory grade WB_DIR="$t/wb" WB_BUILD="$t/build" > "$t/out" 2>&1
    line=$(grep -E "^  $id " "$t/out")
    case $line in
        *failing*|*"timed out"*|*crashed*) echo "check-stubs: $line" ;;
        *) echo "check-stubs: exercise $id's stub is not caught: $line"; echo bad >> "$t/bad" ;;
    esac
done
if [ -f "$t/bad" ]; then rm -f "$t/bad"; exit 1; fi
echo "check-stubs: every stub, alone, fails its tests"
