# ch08_kdtree.gp: charts from the CSV of bench/ch08_kdtree.c.
#   gnuplot -e "csv='figures/ch08-kdtree.csv'; stem='figures/ch08-kdtree'" bench/ch08_kdtree.gp
# stem-speed-accuracy.svg: left, time per ray against the number of
#   triangles (brute force, median-split tree, SAH tree) and of objects (a
#   list, a tree); right, build time against time per ray for the SAH's
#   parameters, one at a time from the defaults.
# figures/ch08-build-scaling.svg: build time per triangle against the
#   number of triangles, for the three builds.
set datafile separator ","
set grid
set terminal svg size 1000,470 font "Helvetica,12" background "white"
set output stem.'-speed-accuracy.svg'
is(m, k) = strcol(1) eq m && strcol(5) eq k

set multiplot layout 1,2 title "Chapter 08: kd-trees, time per ray against N, and what the SAH's parameters cost" font ",14"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [0.7:2e5]
set xlabel "triangles (or objects) searched (log scale)"
set ylabel "time per ray (ns, log scale)"
set key top left box opaque font ",10"
set title "every tree agrees with brute force on every ray" font ",11"
plot csv using (is("brute-force","triangle_tests_per_ray") ? $2 : NaN):3 with linespoints pt 7 ps 0.8 lc rgb "#d95f02" title "brute force (every triangle)", \
     csv using (is("median","triangle_tests_per_ray") ? $2 : NaN):3 with linespoints pt 5 ps 0.8 lc rgb "#7570b3" title "median-split tree", \
     csv using (is("sah","triangle_tests_per_ray") ? $2 : NaN):3 with linespoints pt 9 ps 0.9 lc rgb "#1b9e77" title "SAH tree (used)", \
     csv using (is("objects-list","sphere_tests_per_ray") ? $2 : NaN):3 with linespoints pt 6 ps 0.8 dt 2 lc rgb "#e7298a" title "spheres: a list", \
     csv using (is("objects-tree","sphere_tests_per_ray") ? $2 : NaN):3 with linespoints pt 8 ps 0.8 dt 2 lc rgb "#66a61e" title "spheres: a tree"

unset logscale
set logscale x
set format x "%g"
set format y "%g"
set xrange [*:*]
set yrange [*:*]
set xlabel "build time of the bunny's tree (ms, log scale)"
set ylabel "time per ray, bunny, K = 1 (ns)"
set title "labels: the parameter's value (defaults K_T = 15, K_I = 20, bonus 0.2, depth 8 + 1.3 log_2 N)" font ",10"
set key top right box opaque font ",10"
plot csv using (is("sah-traversal-cost","build_ms") ? $4 : NaN):3 with linespoints pt 7 ps 0.8 lc rgb "#1b9e77" title "traversal cost K_T (K_I = 20)", \
     csv using (is("sah-traversal-cost","build_ms") ? $4 : NaN):3:2 with labels offset 0.9,0.6 font ",9" tc rgb "#1b9e77" notitle, \
     csv using (is("sah-empty-bonus","build_ms") ? $4 : NaN):3 with linespoints pt 5 ps 0.8 lc rgb "#7570b3" title "empty bonus", \
     csv using (is("sah-empty-bonus","build_ms") ? $4 : NaN):3:2 with labels offset -0.9,-0.6 font ",9" tc rgb "#7570b3" notitle, \
     csv using (is("sah-max-depth","build_ms") ? $4 : NaN):3 with linespoints pt 9 ps 0.9 lc rgb "#d95f02" title "maximum depth", \
     csv using (is("sah-max-depth","build_ms") ? $4 : NaN):3:2 with labels offset 0,-0.9 font ",9" tc rgb "#d95f02" notitle
unset multiplot

set terminal svg size 760,480 font "Helvetica,13" background "white"
set output 'figures/ch08-build-scaling.svg'
set title "Chapter 08: build time per triangle against N (bumpy spheres)" font ",14"
unset logscale
set logscale x
set format x "10^{%L}"
set xrange [800:2e6]
set yrange [0:*]
set xlabel "triangles (log scale)"
set ylabel "build time per triangle (microseconds)"
set key top left box opaque font ",11"
plot csv using (is("build-sah","build_ms") ? $2 : NaN):($3/1000) with linespoints pt 9 ps 1 lc rgb "#1b9e77" title "SAH, events sorted once: O(N log N)", \
     csv using (is("build-sorting","build_ms") ? $2 : NaN):($3/1000) with linespoints pt 7 ps 1 lc rgb "#d95f02" title "SAH, events sorted at every node: O(N log^2 N)", \
     csv using (is("build-median","build_ms") ? $2 : NaN):($3/1000) with linespoints pt 5 ps 1 lc rgb "#7570b3" title "median split"
