# ch12_build.gp: the chart of bench/ch12_build.c's CSV.
#   gnuplot -e "csv='figures/ch12-build.csv'; stem='figures/ch12-build'" bench/ch12_build.gp
# stem.svg: left, the build time per triangle (median; bars: interquartile
#   range) against the number of triangles of a terrain, log scale, one
#   line per structure: a build in O(N log N) is a straight line rising
#   to the right, one in O(N) is flat; right, the bytes per triangle that
#   each structure holds, against the same numbers of triangles.
load "bench/chart.gp"
set terminal svg size 1000,480 font "Helvetica,12" background "white"
set output stem.'.svg'
# the terrains' rows of one structure (their param is a number)
rows(m) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"ns_per_triangle\" && $2 + 0 > 0' %s", m, csv)
bytes(m) = sprintf("< awk -F, '$1 == \"bytes\" && $5 == \"bytes_per_triangle\" {split($2, p, \"@\"); if (p[1] == \"%s\" && p[2] + 0 > 0) print p[2] \",\" $4}' %s", m, csv)
names = system("awk -F, '$5 == \"ns_per_triangle\" && !seen[$1]++ {printf \"%s \", $1}' ".csv)
colour(k) = word("#d95f02 #1b9e77 #7570b3 #e7298a #66a61e #a6761d", k)

eval machine_label
set multiplot layout 1,2 title "Chapter 12: building the trees, from a thousand triangles to two million" font ",14" margins 0.08,0.98,0.17,0.86 spacing 0.08
set logscale x
set xrange [600:4e6]
set format x "10^{%L}"
set xlabel "triangles (a terrain; log scale)"
set ylabel "build time per triangle (ns; bars: interquartile range)"
set yrange [0:*]
set key top left box opaque font ",9"
set title "O(N log N): a straight line rising to the right" font ",10"
plot for [k=1:words(names)] rows(word(names, k)) using 2:4 with linespoints pt 7 ps 0.7 lc rgb colour(k) title word(names, k), \
     for [k=1:words(names)] rows(word(names, k)) using 2:($6 / $2):(0):(($7 - $6) / $2) @quartile_bars

set ylabel "bytes per triangle (the structure alone)"
set title "memory" font ",10"
plot for [k=1:words(names)] bytes(word(names, k)) using 1:2 with linespoints pt 7 ps 0.7 lc rgb colour(k) title word(names, k)
unset multiplot
