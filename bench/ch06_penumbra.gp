# ch06_penumbra.gp: the chart of bench/ch06_penumbra.c.
#   gnuplot -e "csv='figures/ch06-penumbra.csv'; stem='figures/ch06-penumbra'" bench/ch06_penumbra.gp
# stem-speed-accuracy.svg: time per pixel against the rms error of a soft
# shadow, for N = 1 ... 256 shadow rays per point, one series per pattern.
load "bench/chart.gp"
set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'-speed-accuracy.svg'
set title "Chapter 6: a soft shadow, N = 1 ... 256 shadow rays per point"
set grid
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "time per pixel (ns, log scale; bars: interquartile range)"
set ylabel "rms error against 16,384 samples (linear light)"
rows(m) = sprintf("< awk -F, '$1 == \"%s\"' %s", m, csv)
set key top right box opaque
eval machine_label
plot rows("uniform") using 3:4 with linespoints pt 5 ps 1.2 lw 2 lc rgb "#d95f02" title "uniform random", \
     rows("grid") using 3:4 with linespoints pt 9 ps 1.2 lw 2 lc rgb "#7570b3" title "grid (cell centres)", \
     rows("stratified") using 3:4 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1b9e77" title "stratified (used)", \
     rows("stratified") using 3:4:(sprintf("%d", $2)) with labels offset 0,-1 font ",9" notitle, \
     for [m in "uniform grid stratified"] rows(m) using ($6):($4):($7 - $6):(0) @quartile_bars
