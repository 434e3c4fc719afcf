# ch09_threads.gp: the chart of bench/ch09_threads.c.
#   gnuplot -e "csv='figures/ch09-threads.csv'; stem='figures/ch09-threads'" bench/ch09_threads.gp
# stem.svg: the wall-clock time of chapter 8's bunny scene on one thread and
# on two, stacked: the scene's loading and its trees' build (one core in
# both) under the render (bars: the median over the rounds; error bars:
# the interquartile range of the render's time, and of the loading's).
load "bench/chart.gp"
set terminal svg size 640,480 font "Helvetica,13" background "white"
set output stem.'.svg'
set grid noxtics ytics
set bmargin 5
set xrange [-0.6:1.6]
set yrange [0:*]
set offsets 0, 0, graph 0.3, 0
set xtics ("--threads 1" 0, "--threads 2" 1)
set ylabel "wall-clock time (ms)"
set key top right box opaque
set style fill solid 0.85 noborder
set boxwidth 0.5
load_ms = real(system("awk -F, '$1 == \"scene\" && $5 == \"load_ms\" {print $4}' ".csv))
load_q1 = real(system("awk -F, '$1 == \"scene\" && $5 == \"load_ms\" {print $6 / 1e6}' ".csv))
load_q3 = real(system("awk -F, '$1 == \"scene\" && $5 == \"load_ms\" {print $7 / 1e6}' ".csv))
renders = sprintf("< awk -F, '$1 == \"threads\" && $5 == \"render_ms\"' %s", csv)
speedup = real(system("awk -F, '$1 == \"threads\" && $5 == \"speedup\" {print $4}' ".csv))
set title sprintf("Chapter 9: chapter 8's bunny scene on one core and on two\nthe render %.2f times as fast on two (medians)", speedup)
eval machine_label
plot renders using ($2 - 1):(load_ms + $4) with boxes lc rgb "#1b9e77" title "render", \
     renders using ($2 - 1):(load_ms) with boxes lc rgb "#7570b3" title "reading the scene, building its trees", \
     renders using ($2 - 1):(load_ms + $6 / 1e6):(0):(($7 - $6) / 1e6) @quartile_bars, \
     renders using ($2 - 1 + 0.1):(load_q1):(0):(load_q3 - load_q1) @quartile_bars
