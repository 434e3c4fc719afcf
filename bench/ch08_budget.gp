# ch08_budget.gp: the chart of bench/ch08_budget.c's CSV.
#   gnuplot -e "csv='figures/ch08-budget.csv'; stem='figures/ch08-budget'" bench/ch08_budget.gp
# figures/ch08-model-budget.svg: left, render time per pixel against the
#   share of the shape's pixels more than one code off, one point per level
#   (labelled), for the icosphere (flat, smooth) and the teapot, with the
#   tree and by brute force; right, that share against the level of a smooth
#   icosphere, one line per size on screen. The share is drawn at 10^-5 when
#   it is 0.
set datafile separator ","
set grid
set terminal svg size 1000,480 font "Helvetica,12" background "white"
set output 'figures/ch08-model-budget.svg'
is(m, k) = strcol(1) eq m && strcol(5) eq k
# the rows of one method and kind, in the order of the file (of the levels)
rows(m, k) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' %s", m, k, csv)
floor = 1e-5
share(x) = x < floor ? floor : x

set multiplot layout 1,2 title "Chapter 08: how much model a picture needs" font ",14"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set yrange [5e-6:2]
set xlabel "render time per pixel, 320 x 240 (ns, log scale)"
set ylabel "share of the shape's pixels off by more than one code"
set key bottom right box opaque font ",9"
set title "one point per level; labels: icosphere level, teapot quads a side" font ",10"
plot rows("sphere-flat-tree","over_one_code") using 3:(share($4)) with linespoints pt 6 ps 0.8 lc rgb "#d95f02" title "sphere, flat, tree", \
     rows("sphere-flat-brute","over_one_code") using 3:(share($4)) with linespoints pt 6 ps 0.8 dt 2 lc rgb "#d95f02" title "sphere, flat, brute force", \
     rows("sphere-smooth-tree","over_one_code") using 3:(share($4)) with linespoints pt 7 ps 0.8 lc rgb "#1b9e77" title "sphere, smooth, tree", \
     rows("sphere-smooth-brute","over_one_code") using 3:(share($4)) with linespoints pt 7 ps 0.8 dt 2 lc rgb "#1b9e77" title "sphere, smooth, brute force", \
     rows("sphere-smooth-tree","over_one_code") using 3:(share($4)):2 with labels offset 0.8,0.6 font ",8" tc rgb "#1b9e77" notitle, \
     rows("teapot-tree","over_one_code") using 3:(share($4)) with linespoints pt 5 ps 0.8 lc rgb "#7570b3" title "teapot, tree", \
     rows("teapot-brute","over_one_code") using 3:(share($4)) with linespoints pt 5 ps 0.8 dt 2 lc rgb "#7570b3" title "teapot, brute force", \
     rows("teapot-tree","over_one_code") using 3:(share($4)):2 with labels offset -0.9,-0.6 font ",8" tc rgb "#7570b3" notitle, \
     1e-3 with lines dt 3 lc rgb "#555555" title "one pixel in a thousand"

unset logscale x
set format x "%g"
set xrange [-0.3:8.3]
set xlabel "icosphere level L (20 4^L triangles), smooth"
set title "the same share against the level, for spheres D pixels across" font ",10"
set key top right box opaque font ",9"
lv(s) = int(substr(s, strstrt(s, ":") + 1, strlen(s)))
sz(s) = int(substr(s, 1, strstrt(s, ":") - 1))
plot for [d in "25 50 100 200 400"] csv using (strcol(1) eq "needed-curve" && sz(strcol(2)) == int(d) ? lv(strcol(2)) : NaN):(share($4)) with linespoints pt 7 ps 0.7 title "D = ".d, \
     1e-3 with lines dt 3 lc rgb "#555555" title "one pixel in a thousand"
unset multiplot
