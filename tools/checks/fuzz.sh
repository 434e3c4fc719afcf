#!/bin/sh
# fuzz.sh SECONDS TARGET...: runs the libFuzzer programs build/fuzz/TARGET_fuzz
# all at once (make fuzz), each for SECONDS on the clock from an empty
# scratch folder of its own, so that a scene's mesh paths find nothing.
# New inputs go to build/fuzz/corpus/TARGET (the committed seeds in
# fuzz/corpus/TARGET are read only); a finding leaves its input in
# build/fuzz/TARGET-crash-* (or leak-, timeout-) and the log in
# build/fuzz/TARGET.log. Prints each one's summary; exits 1 if one found
# a problem.
set -u
seconds=$1
shift
# run TARGET: one libFuzzer run, its output to build/fuzz/TARGET.log
run() {
    mkdir -p "build/fuzz/corpus/$1" "build/fuzz/scratch-$1"
    (cd "build/fuzz/scratch-$1" &&
        "../$1_fuzz" "../corpus/$1" "../../../fuzz/corpus/$1" \
            -dict="../../../fuzz/$1.dict" -max_total_time="$seconds" \
            -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
            -close_fd_mask=3 -artifact_prefix="../$1-" \
            > "../$1.log" 2>&1)
}
for t in "$@"; do
    echo "== fuzzing $t for $seconds s"
    (run "$t"; echo $? > "build/fuzz/$t.status") &
done
wait
status=0
for t in "$@"; do
    grep -E '^(#[0-9]+.*DONE|stat::|==[0-9]+==ERROR|SUMMARY)' \
        "build/fuzz/$t.log" | sed "s/^/$t: /"
    if [ "$(cat "build/fuzz/$t.status")" != 0 ]; then
        echo "fuzz: $t found a problem: see build/fuzz/$t.log"
        status=1
    fi
done
exit $status
