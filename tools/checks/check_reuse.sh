#!/bin/sh
# check_reuse.sh REUSE_OBJECT CC -- tools/book/reuse_object's own test (make
# check-reuse, in make test). In a scratch folder, two "chapters" p/ and n/
# of a file a.c that includes a.h, compiled with -MMD -MP as the Makefile
# does. Checks that the object of p/ is copied when n/ holds the same text
# (a marker in the compiler's place proves that it did not run); that it
# is compiled when a header differs; that --code takes a #line directive
# that differs as the same code, and any other line as different.
set -u
reuse=$1
cc=$2
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
fail() { echo "check-reuse: $*"; exit 1; }
mkdir -p "$dir/p" "$dir/n" "$dir/obj"
printf '#include "a.h"\nint f(void) { return A; }\n' > "$dir/p/a.c"
printf '#line 1 "one.md"\n#define A 1\n' > "$dir/p/a.h"
$cc -MMD -MP -I"$dir/p" -c -o "$dir/obj/p.o" "$dir/p/a.c" || fail "cannot compile"

# try [--code]: 0 when reuse_object copied p.o to n.o, 1 when it ran the
# "compiler" (a script that only leaves a marker).
try() {
    rm -f "$dir/obj/n.o" "$dir/ran"
    "$reuse" "$@" "$dir/obj/p.o" "$dir/p" "$dir/n" -- \
        sh -c ': > "$1"' sh "$dir/ran" -o "$dir/obj/n.o" || fail "exit status $?"
    if [ -f "$dir/ran" ]; then return 1; fi
    cmp -s "$dir/obj/p.o" "$dir/obj/n.o" || fail "a copy that is not the object"
    grep -q "$dir/n/a.h" "$dir/obj/n.d" || fail "the copied .d names p/, not n/"
}

cp "$dir/p/a.c" "$dir/p/a.h" "$dir/n/"
try || fail "the same text was compiled again"
printf '#line 1 "one.md"\n#define A 2\n' > "$dir/n/a.h"
! try || fail "a header that differs was not compiled"
! try --code || fail "--code: a line that differs was taken as the same"
printf '#line 7 "two.md"\n#define A 1\n' > "$dir/n/a.h"
! try || fail "without --code, a #line that differs is a difference"
try --code || fail "--code: a #line that differs should not count"
echo "check-reuse: objects are copied for the same code and compiled otherwise"
