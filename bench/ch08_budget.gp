# ch08_budget.gp: the chart of bench/ch08_budget.c's CSV.
#   gnuplot -e "csv='figures/ch08-budget.csv'; stem='figures/ch08-budget'" bench/ch08_budget.gp
# figures/ch08-model-budget.svg: left, render time per pixel (median; bars:
#   interquartile range) against the share of the shape's pixels more than
#   one code off, one point per level (labelled), for the icosphere (flat,
#   smooth) and the teapot, with the tree and by brute force; right, that
#   share against the level of a smooth icosphere, one line per size on
#   screen. A share of 0 is drawn on the row "0" below the log axis.
load "bench/chart.gp"
set terminal svg size 1000,480 font "Helvetica,12" background "white"
# in stem's folder, as every chart (check-charts draws into build/chartcheck)
set output stem[1:strlen(stem) - strlen('ch08-budget')].'ch08-model-budget.svg'
# the rows of one method and kind, in the order of the file (of the levels)
rows(m, k) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' %s", m, k, csv)
# the smallest non-zero share is one pixel of some 30,000: above 10^-5
lo = -5
hi = 0

eval machine_label
set multiplot layout 1,2 title "Chapter 8: how much model a picture needs" font ",14" margins 0.08,0.98,0.17,0.86 spacing 0.08
eval zero_axis_y
set logscale x
set format x "10^{%L}"
set xlabel "render time per pixel, 320 x 240 (ns, log scale; bars: interquartile range)"
set ylabel "share of the shape's pixels off by more than one code"
set key bottom right box opaque font ",9"
set title "one point per level; labels: icosphere level, teapot quads a side" font ",10"
plot rows("sphere-flat-tree","over_one_code") using 3:(at_zero($4)) with linespoints pt 6 ps 0.8 lc rgb "#d95f02" title "sphere, flat, tree", \
     rows("sphere-flat-brute","over_one_code") using 3:(at_zero($4)) with linespoints pt 6 ps 0.8 dt 2 lc rgb "#d95f02" title "sphere, flat, brute force", \
     rows("sphere-smooth-tree","over_one_code") using 3:(at_zero($4)) with linespoints pt 7 ps 0.8 lc rgb "#1b9e77" title "sphere, smooth, tree", \
     rows("sphere-smooth-brute","over_one_code") using 3:(at_zero($4)) with linespoints pt 7 ps 0.8 dt 2 lc rgb "#1b9e77" title "sphere, smooth, brute force", \
     rows("sphere-smooth-tree","over_one_code") using 3:(at_zero($4)):2 with labels offset 0.8,0.6 font ",8" tc rgb "#1b9e77" notitle, \
     rows("teapot-tree","over_one_code") using 3:(at_zero($4)) with linespoints pt 5 ps 0.8 lc rgb "#7570b3" title "teapot, tree", \
     rows("teapot-brute","over_one_code") using 3:(at_zero($4)) with linespoints pt 5 ps 0.8 dt 2 lc rgb "#7570b3" title "teapot, brute force", \
     rows("teapot-tree","over_one_code") using 3:(at_zero($4)):2 with labels offset -0.9,-0.6 font ",8" tc rgb "#7570b3" notitle, \
     for [m in "sphere-flat-tree sphere-flat-brute sphere-smooth-tree sphere-smooth-brute teapot-tree teapot-brute"] \
       rows(m, "over_one_code") using ($6):(at_zero($4)):($7 - $6):(0) @quartile_bars, \
     1e-3 with lines dt 3 lc rgb "#555555" title "one pixel in a thousand"

unset logscale x
set format x "%g"
set xrange [-0.3:8.3]
set xlabel "icosphere level L (20 4^L triangles), smooth"
set title "the same share against the level, for spheres D pixels across" font ",10"
set key top right box opaque font ",9"
lv(s) = int(substr(s, strstrt(s, ":") + 1, strlen(s)))
sz(s) = int(substr(s, 1, strstrt(s, ":") - 1))
plot for [d in "25 50 100 200 400"] csv using (strcol(1) eq "needed-curve" && sz(strcol(2)) == int(d) ? lv(strcol(2)) : NaN):(at_zero($4)) with linespoints pt 7 ps 0.7 title "D = ".d, \
     1e-3 with lines dt 3 lc rgb "#555555" title "one pixel in a thousand"
unset multiplot
