#!/bin/sh
# run_shards.sh RUNNER: runs a test binary made by tests/runner.c as N
# processes at once, each with RUNNER_SHARD=K/N (its share of the tests),
# then prints their output in order, shard by shard; exits 0 only when
# every shard passed. N is $SHARDS, or four times the number of cores:
# the tests are dealt out by their number, not by their time, and one
# shard with a test that waits (a render held still to see its progress
# line) or a slow one would leave the other cores idle at its end; with
# four shards a core, the rest share those cores meanwhile (chapter 10's
# runner on two cores: 9.1 s with two shards, 6.6 s with eight).
# With RUN_LOG=FILE, every test's result line (Check's log, one line a
# test, passes too) is kept in FILE when all passed, and FILE is removed
# when one did not (make grade reads it: tools/workbook/grade.sh).
set -u
runner=$1
cores=$(nproc 2>/dev/null || sysctl -n hw.ncpu 2>/dev/null || echo 2)
n=${SHARDS:-$((4 * cores))}
log=${RUN_LOG:-}
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
[ -z "$log" ] || rm -f "$log"
k=0
while [ "$k" -lt "$n" ]; do
  if [ -n "$log" ]; then
    RUNNER_SHARD="$k/$n" CK_LOG_FILE_NAME="$dir/$k.log" "$runner" \
      > "$dir/$k.out" 2>&1 &
  else
    RUNNER_SHARD="$k/$n" "$runner" > "$dir/$k.out" 2>&1 &
  fi
  echo $! > "$dir/$k.pid"
  k=$((k + 1))
done
status=0
k=0
while [ "$k" -lt "$n" ]; do
  wait "$(cat "$dir/$k.pid")" || status=1
  cat "$dir/$k.out"
  k=$((k + 1))
done
if [ -n "$log" ] && [ "$status" = 0 ]; then
  cat "$dir"/*.log > "$log.tmp" && mv "$log.tmp" "$log"
fi
exit $status
