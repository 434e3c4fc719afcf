#!/bin/sh
# run_shards.sh RUNNER: runs a test binary made by tests/runner.c as N
# processes at once, each with RUNNER_SHARD=K/N (its share of the tests),
# then prints their output in order, shard by shard; exits 0 only when
# every shard passed. N is $SHARDS, or the number of cores.
set -u
runner=$1
n=${SHARDS:-$(nproc 2>/dev/null || sysctl -n hw.ncpu 2>/dev/null || echo 2)}
dir=$(mktemp -d) || exit 1
trap 'rm -rf "$dir"' EXIT
k=0
while [ "$k" -lt "$n" ]; do
  RUNNER_SHARD="$k/$n" "$runner" > "$dir/$k.out" 2>&1 &
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
exit $status
