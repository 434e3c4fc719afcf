# ch06_recursion.gp: the chart of bench/ch06_recursion.c.
#   gnuplot -e "csv='figures/ch06-recursion.csv'; stem='figures/ch06-recursion'" bench/ch06_recursion.gp
# stem.svg: rays per pixel against the rms error, for depth limits (no
# cutoff) and for contribution cutoffs (depth limit 100).
load "bench/chart.gp"
set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'.svg'
set title "Chapter 6: ending the recursion between facing mirrors"
set grid
set logscale y
set format y "10^{%L}"
set yrange [1e-6:0.3]
set xlabel "rays per pixel (primary, shadow and reflection)"
set ylabel "rms error against depth 100 (linear light)"
rows(m) = sprintf("< awk -F, '$1 == \"%s\" && $4 > 0'  %s", m, csv)
set key bottom left box opaque
eval machine_label
plot rows("depth") using 9:4 with linespoints pt 5 ps 1.2 lw 2 lc rgb "#d95f02" title "depth limit D, no cutoff", \
     rows("depth") using 9:4:(sprintf("%d", $2)) with labels offset -0.4,0.9 font ",9" tc rgb "#d95f02" notitle, \
     rows("cutoff") using 9:4 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1b9e77" title "cutoff W, depth limit 100", \
     rows("cutoff") using 9:4:(sprintf("%g", $2)) with labels offset 1.8,-0.6 font ",9" tc rgb "#1b9e77" notitle
