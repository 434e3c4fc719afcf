#!/bin/sh
# chart_yours.sh -- a chapter's chart with the reader's methods as "yours".
#
# Usage (make chart-chNN WORKBOOK=1 runs it, after tools/workbook/grade.sh has
# tangled the workbook and make has compiled the workbook's objects):
#   tools/workbook/chart_yours.sh BENCH STATE.tsv OUTDIR "ID=MACRO..." "OBJECT..."
#                        "SYMBOL..." CC "CFLAGS" LINK_OBJECT...
# For each exercise ID the reader has started (in the grader's STATE.tsv)
# the benchmark bench/BENCH.c is compiled with -DMACRO. Every SYMBOL is
# renamed yours_SYMBOL in copies of the workbook's OBJECTs, and made their
# only global names (so that they link beside the book's own objects,
# LINK_OBJECTs). The benchmark times the reader's functions in the same
# interleaved rounds as the book's methods; its CSV and charts go to
# OUTDIR/chNN-x.csv and .svg (gnuplot gets yours="ID ..."), never to
# figures/. Exits 3, drawing nothing, when none of the IDs is started.
set -eu
bench=$1 state=$2 out=$3 specs=$4 objects=$5 symbols=$6 cc=$7 cflags=$8
shift 8
mkdir -p "$out"
stem=$out/$(echo "$bench" | tr _ -)

defines="" ids=""
for spec in $specs; do
    id=${spec%%=*}
    awk -F '\t' -v id="$id" '$1 == id && $2 == "started" { found = 1 } END { exit !found }' \
        "$state" || continue
    defines="$defines -D${spec#*=}"
    ids="$ids $id"
done
if [ -z "$ids" ]; then # exit 3: this chart left out, the chapter's others drawn
    echo "chart: $bench left out: none of the exercises" \
         "$(echo "$specs" | sed 's/=[^ ]*//g') is started" >&2
    exit 3
fi

renames=""
for symbol in $symbols; do
    renames="$renames --redefine-sym $symbol=yours_$symbol -G yours_$symbol"
done
copies=""
for object in $objects; do
    copy=$out/yours_$(basename "$object")
    # shellcheck disable=SC2086  # the options are words
    objcopy $renames "$object" "$copy"
    copies="$copies $copy"
done
# shellcheck disable=SC2086  # CFLAGS, the defines and the copies are lists
$cc $cflags $defines -o "$out/$bench" "bench/$bench.c" $copies "$@" -lm
"$out/$bench" > "$stem.csv"
gnuplot -e "csv='$stem.csv'; stem='$stem'; yours='${ids# }'" "bench/$bench.gp"
echo "wrote $stem*.svg: yours is exercise${ids}"
