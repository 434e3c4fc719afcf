# ch12_threads.gp: the chart of bench/ch12_threads.c.
#   gnuplot -e "csv='figures/ch12-threads.csv'; stem='figures/ch12-threads'" bench/ch12_threads.gp
# stem.svg: left, the wall-clock time of chapter 8's bunny scene on one
# thread and on two, stacked: the scene's loading and its trees' build
# under the render (bars: the median over the rounds; error bars: the
# interquartile range of the render's time, and of the loading's); right,
# the whole run of a terrain of two million triangles drawn at 512 x 512,
# from the process's start to its end, on one thread and on two, with the
# part that reading the scene and building its trees took, and (a narrower
# bar) the parts that stay on one thread: the file's reading into memory,
# the arrays, the walk that closes the gaps, the collapse, the PNG, and the
# process's start and end.
load "bench/chart.gp"
set terminal svg size 1000,480 font "Helvetica,12" background "white"
set output stem.'.svg'
set grid noxtics ytics
set bmargin 5
set xrange [-0.6:1.6]
set yrange [0:*]
set offsets 0, 0, graph 0.3, 0
set xtics ("--threads 1" 0, "--threads 2" 1)
set ylabel "wall-clock time (ms)"
set key top right box opaque font ",10"
set style fill solid 0.85 noborder
set boxwidth 0.5
csv_value(m, p, k, col) = real(system(sprintf("awk -F, '$1 == \"%s\" && $2 == \"%s\" && $5 == \"%s\" {print $%d}' %s", m, p, k, col, csv)))
load_ms = csv_value("scene", "bunny", "load_ms", 4)
load_q1 = csv_value("scene", "bunny", "load_ms", 6) / 1e6
load_q3 = csv_value("scene", "bunny", "load_ms", 7) / 1e6
renders = sprintf("< awk -F, '$1 == \"threads\" && $5 == \"render_ms\"' %s", csv)
speedup = csv_value("threads", "2", "speedup", 4)
whole = int(system("grep -c '^whole,' ".csv))

eval machine_label
set multiplot layout 1,2 title "Chapter 12: on one core and on two" font ",14" margins 0.09,0.98,0.17,0.84 spacing 0.1
set title sprintf("chapter 8's bunny scene: the render %.2f times as fast on two (medians)", speedup) font ",10"
plot renders using ($2 - 1):(load_ms + $4) with boxes lc rgb "#1b9e77" title "render", \
     renders using ($2 - 1):(load_ms) with boxes lc rgb "#7570b3" title "reading the scene, building its trees", \
     renders using ($2 - 1):(load_ms + $6 / 1e6):(0):(($7 - $6) / 1e6) @quartile_bars, \
     renders using ($2 - 1 + 0.1):(load_q1):(0):(load_q3 - load_q1) @quartile_bars

runs = sprintf("< awk -F, '$1 == \"whole\" && $5 == \"run_ms\"' %s", csv)
loads = sprintf("< awk -F, '$1 == \"terrain\" && $5 == \"load_ms\"' %s", csv)
serials = sprintf("< awk -F, '$1 == \"terrain-serial\" && $5 == \"ms\"' %s", csv)
whole_speedup = whole ? csv_value("whole", "2", "speedup", 4) : 0
set title (whole ? sprintf("a terrain of 2,000,000 triangles, 512 x 512: the whole run\n%.2f times as fast on two (medians)", whole_speedup) : "the terrain's whole run was not measured") font ",10"
if (whole) {
plot runs using ($2 - 1):4 with boxes lc rgb "#1b9e77" title "the whole run", \
     loads using ($2 - 1):4 with boxes lc rgb "#7570b3" title "of which reading the scene, building its trees", \
     serials using ($2 - 1):4:(0.2) with boxes lc rgb "#d95f02" title "of which on one thread (all phases)", \
     runs using ($2 - 1):($6 / 1e6):(0):(($7 - $6) / 1e6) @quartile_bars, \
     loads using ($2 - 1 + 0.1):($6 / 1e6):(0):(($7 - $6) / 1e6) @quartile_bars
} else {
    set yrange [0:1]
    unset key
    plot NaN notitle
}
unset multiplot
