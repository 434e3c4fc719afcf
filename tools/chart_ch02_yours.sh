#!/bin/sh
# chart_ch02_yours.sh -- chapter 2's sphere chart with the reader's forms.
#
# Usage (make chart-ch02 WORKBOOK=1 runs it, after tools/grade.sh has
# tangled the workbook and make has compiled its sphere_roots*.o):
#     tools/chart_ch02_yours.sh STATE.tsv OUTDIR CC CFLAGS LINK_OBJECTS...
# The started ones of exercises 2.1 (geometric), 2.2 (quadratic) and 2.3
# (robust), read from the grader's STATE.tsv, are renamed yours_... in
# copies of the workbook's objects (WB_OBJ, the folder of sphere_roots.o),
# compiled into bench/ch02_sphere.c with -DYOURS_FORMS and timed in the
# same interleaved rounds as the book's six; the CSV and both charts go to
# OUTDIR (ch02-sphere.csv, ch02-sphere-*.svg), never to figures/.
set -eu
state=$1 out=$2 cc=$3 cflags=$4 wb_obj=$5
shift 5
mkdir -p "$out"

forms=""
names=""
labels=""
renames=""
for entry in 2.1:geometric 2.2:quadratic 2.3:robust; do
    id=${entry%%:*} form=${entry#*:}
    renames="$renames --redefine-sym sphere_roots_$form=yours_sphere_roots_$form"
    renames="$renames --redefine-sym sphere_roots_${form}_float=yours_sphere_roots_${form}_float"
    awk -F '\t' -v id="$id" '$1 == id && $2 == "started" { found = 1 } END { exit !found }' \
        "$state" || continue
    forms="$forms Y(\"$form\", \"double\", yours_sphere_roots_$form)"
    forms="$forms Y(\"$form\", \"float\", yours_sphere_roots_${form}_float)"
    names="$names yours-$form-double yours-$form-float"
    labels="$labels 'yours ($form, exercise $id), double' 'yours ($form), float'"
done
if [ -z "$forms" ]; then
    echo "chart-ch02: start exercise 2.1, 2.2 or 2.3 in the workbook first" >&2
    exit 1
fi

# shellcheck disable=SC2086  # the options are words
objcopy $renames "$wb_obj/sphere_roots.o" "$out/yours_sphere_roots.o"
# shellcheck disable=SC2086
objcopy $renames "$wb_obj/sphere_roots_float.o" "$out/yours_sphere_roots_float.o"
# shellcheck disable=SC2086  # CFLAGS is a list of options
$cc $cflags "-DYOURS_FORMS=$forms" -o "$out/ch02_sphere" bench/ch02_sphere.c \
    "$out/yours_sphere_roots.o" "$out/yours_sphere_roots_float.o" "$@" -lm
"$out/ch02_sphere" > "$out/ch02-sphere.csv"
gnuplot -e "csv='$out/ch02-sphere.csv'; stem='$out/ch02-sphere'" \
        -e "yours_names='${names# }'; yours_labels=\"${labels# }\"" bench/ch02_sphere.gp
echo "wrote $out/ch02-sphere-speed-accuracy.svg and $out/ch02-sphere-distance.svg"
