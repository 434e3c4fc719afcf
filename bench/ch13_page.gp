# ch13_page.gp: the chart of the programs in the book's page (make
# chart-ch13_page, tools/checks/page_check.sh --speed).
#   gnuplot -e "csv='figures/ch13-page.csv'; stem='figures/ch13-page'" bench/ch13_page.gp
# stem.svg: for each chapter, the render of its own scene in the page
# (WebAssembly, one thread) over the same render by bin/chNN on one
# thread: the ratio of the medians (bars) and the interval from the
# quartiles (page q1 / native q3 to page q3 / native q1); points: the
# page over the same program built by clang, the page's compiler; a line
# at 1.
load "bench/chart.gp"
set terminal svg size 900,460 font "Helvetica,12" background "white"
set output stem.'.svg'
set grid noxtics ytics
set bmargin 5
clang = sprintf("< awk -F, '$5 == \"page_over_clang\" {print substr($2, 3) + 0 \",\" $4}' %s", csv)
rows = sprintf("< awk -F, '$5 == \"render_ms\" {q1[$1 $2] = $6; q3[$1 $2] = $7} $1 == \"ratio\" {n = substr($2, 3) + 0; print n \",\" $4 \",\" q1[\"page\" $2] / q3[\"native\" $2] \",\" q3[\"page\" $2] / q1[\"native\" $2]}' %s", csv)
set xrange [0.4:12.6]
set yrange [0:*]
set xtics 1
set xlabel "chapter (its own scene, at the size in the title)"
set ylabel "render time in the page / bin/chNN's (one thread)"
set style fill solid 0.85 noborder
set boxwidth 0.6
set key top left box opaque font ",10"
size = system("sed -n 's/^# size: //p' '".csv."' | head -n 1")
set title "Chapter 13: each chapter's program in the page against bin/chNN, ".size." pixels" font ",13"
set arrow 1 from graph 0, first 1 to graph 1, first 1 nohead dashtype 2 lc rgb "#555555"
eval machine_label
plot rows using 1:2 with boxes lc rgb "#1b9e77" title "median render time, page over native", \
     rows using 1:3:(0):($4 - $3) @quartile_bars, \
     clang using 1:2 with points pt 7 ps 0.8 lc rgb "#d95f02" title "median, page over the same program built by clang"
