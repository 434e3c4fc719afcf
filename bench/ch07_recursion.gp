# ch07_recursion.gp: the chart of bench/ch07_recursion.c.
#   gnuplot -e "csv='figures/ch07-recursion.csv'; stem='figures/ch07-recursion'" bench/ch07_recursion.gp
# stem.svg: rays per pixel against the rms error, for depth limits (no
# cutoff) and for contribution cutoffs (depth limit 100), in a scene of
# glass balls between two mirrors.
load "bench/chart.gp"
set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'.svg'
set title "Chapter 7: ending the tree of rays that glass makes"
set grid
set logscale xy
set format x "%g"
set format y "10^{%L}"
set xrange [1.5:150]
set yrange [1e-7:3]
set bmargin 5
set xlabel "rays per pixel (primary, shadow, reflection and refraction; log scale)"
set ylabel "rms error against the reference (linear light)"
rows(m) = sprintf("< awk -F, '$1 == \"%s\" && $4 > 0'  %s", m, csv)
set key top right box opaque
eval machine_label
plot rows("depth") using 9:4 with linespoints pt 5 ps 1.2 lw 2 lc rgb "#d95f02" title "depth limit D, no cutoff", \
     rows("depth") using 9:4:(sprintf("%d", $2)) with labels offset 0.2,1 font ",9" tc rgb "#d95f02" notitle, \
     rows("cutoff") using 9:4 with linespoints pt 7 ps 1.2 lw 2 lc rgb "#1b9e77" title "cutoff W, depth limit 100", \
     rows("cutoff") using 9:4:(sprintf("%g", $2)) with labels offset -2.2,-0.6 font ",9" tc rgb "#1b9e77" notitle
