#!/bin/sh
# probe_native.sh CC FLAGS...: the flags to add to FLAGS (which hold
# -march=native) so that CC compiles tools/book/probe_avx512.c right. Prints
# nothing for a compiler without the bug; -fno-tree-slp-vectorize for one
# with it (GCC 12.2 with AVX-512); -mno-avx512f if even that fails. The
# probe runs here, so it answers for the machine that builds and runs.
cc=$1
shift
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
here=$(dirname "$0")
for extra in "" "-fno-tree-slp-vectorize" "-mno-avx512f"; do
  # shellcheck disable=SC2086  # the flags are meant to split into words
  if $cc "$@" $extra -o "$dir/probe" "$here/probe_avx512.c" 2>/dev/null &&
     "$dir/probe"; then
    echo "$extra"
    exit 0
  fi
done
echo "-mno-avx512f"
