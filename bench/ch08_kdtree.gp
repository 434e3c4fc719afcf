# ch08_kdtree.gp: charts from the CSV of bench/ch08_kdtree.c.
#   gnuplot -e "csv='figures/ch08-kdtree.csv'; stem='figures/ch08-kdtree'" bench/ch08_kdtree.gp
# stem-speed-accuracy.svg: top left, time per ray against the number of
#   triangles (brute force, median-split tree, SAH tree) and of spheres (a
#   list, a tree); the other three panels, build time against time per ray
#   for each of the SAH's parameters, moved one at a time from the defaults.
# figures/ch08-build-scaling.svg: build time per triangle against the
#   number of triangles for the three builds, and the same divided by
#   log2 N.
# Both carry the CSV's machine line (bench/chart.gp). Their series are not
# timed by the harness yet (bench/ch08_kdtree.c, sections 3-5), so they have
# no quartile bars.
load "bench/chart.gp"
set terminal svg size 1000,820 font "Helvetica,12" background "white"
set output stem.'-speed-accuracy.svg'
is(m, k) = strcol(1) eq m && strcol(5) eq k
# (smooth unique joins each series' points, which other rows interleave)

eval machine_label
set multiplot layout 2,2 title "Chapter 08: kd-trees, time per ray against N, and what the SAH's parameters cost" font ",14" margins 0.08,0.97,0.1,0.92 spacing 0.09,0.12
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [0.7:2e5]
set xlabel "triangles (or spheres) searched (log scale)"
set ylabel "time per ray (ns, log scale)"
set key top left box opaque font ",10"
set title "64 x 64 rays at K = 1; every tree agrees with brute force on every ray" font ",11"
plot csv using (is("brute-force","triangle_tests_per_ray") ? $2 : NaN):3 smooth unique with linespoints pt 7 ps 0.8 lc rgb "#d95f02" title "brute force (every triangle)", \
     csv using (is("median","triangle_tests_per_ray") ? $2 : NaN):3 smooth unique with linespoints pt 5 ps 0.8 lc rgb "#7570b3" title "median-split tree", \
     csv using (is("sah","triangle_tests_per_ray") ? $2 : NaN):3 smooth unique with linespoints pt 9 ps 0.9 lc rgb "#1b9e77" title "SAH tree (used)", \
     csv using (is("objects-list","sphere_tests_per_ray") ? $2 : NaN):3 smooth unique with linespoints pt 6 ps 0.8 dt 2 lc rgb "#e7298a" title "spheres: a list", \
     csv using (is("objects-tree","sphere_tests_per_ray") ? $2 : NaN):3 smooth unique with linespoints pt 8 ps 0.8 dt 2 lc rgb "#66a61e" title "spheres: a tree"

unset logscale
set logscale x
set format x "%g"
set format y "%g"
set xrange [*:*]
set yrange [*:*]
set xlabel "build time of the bunny's tree (ms, log scale)"
set ylabel "time per ray, bunny, K = 1, 256 x 256 rays (ns)"
unset key
set title "traversal cost K_T (intersection cost K_I = 20); default 80" font ",11"
plot csv using (is("sah-traversal-cost","build_ms") ? $4 : NaN):3 smooth unique with linespoints pt 7 ps 0.9 lc rgb "#1b9e77", \
     csv using (is("sah-traversal-cost","build_ms") ? $4 : NaN):3:2 with labels offset 0.6,0.8 font ",10" tc rgb "#1b9e77"
set title "empty bonus; default 0.2" font ",11"
plot csv using (is("sah-empty-bonus","build_ms") ? $4 : NaN):3 with points pt 5 ps 0.9 lc rgb "#7570b3", \
     csv using (is("sah-empty-bonus","build_ms") ? $4 : NaN):3:2 with labels offset 0.6,0.8 font ",10" tc rgb "#7570b3"
set title "maximum depth; default 8 + 1.3 log_2 N = 28" font ",11"
set logscale y
plot csv using (is("sah-max-depth","build_ms") ? $4 : NaN):3 smooth unique with linespoints pt 9 ps 1 lc rgb "#d95f02", \
     csv using (is("sah-max-depth","build_ms") ? $4 : NaN):3:2 with labels offset 0.6,0.8 font ",10" tc rgb "#d95f02"
unset multiplot

set terminal svg size 1000,460 font "Helvetica,12" background "white"
set output 'figures/ch08-build-scaling.svg'
unset logscale
set logscale x
set format x "10^{%L}"
set format y "%g"
set xrange [800:2e6]
set yrange [0:*]
set xlabel "triangles (log scale)"
set key top left box opaque font ",10"
eval machine_label
set multiplot layout 1,2 title "Chapter 08: build time against N (bumpy spheres, made by the benchmark)" font ",14" margins 0.08,0.97,0.2,0.86 spacing 0.09
set title "per triangle" font ",11"
set ylabel "build time per triangle (microseconds)"
plot csv using (is("build-sah","build_ms") ? $2 : NaN):($3/1000) smooth unique with linespoints pt 9 ps 1 lc rgb "#1b9e77" title "SAH, events sorted once", \
     csv using (is("build-sorting","build_ms") ? $2 : NaN):($3/1000) smooth unique with linespoints pt 7 ps 1 lc rgb "#d95f02" title "SAH, events sorted at every node", \
     csv using (is("build-median","build_ms") ? $2 : NaN):($3/1000) smooth unique with linespoints pt 5 ps 1 lc rgb "#7570b3" title "median split"
set title "per triangle and per level, log_2 N: flat for an O(N log N) build" font ",11"
set ylabel "build time / (N log_2 N) (ns)"
plot csv using (is("build-sah","build_ms") ? $2 : NaN):($3/log($2)*log(2)) smooth unique with linespoints pt 9 ps 1 lc rgb "#1b9e77" title "SAH, events sorted once", \
     csv using (is("build-sorting","build_ms") ? $2 : NaN):($3/log($2)*log(2)) smooth unique with linespoints pt 7 ps 1 lc rgb "#d95f02" title "SAH, events sorted at every node", \
     csv using (is("build-median","build_ms") ? $2 : NaN):($3/log($2)*log(2)) smooth unique with linespoints pt 5 ps 1 lc rgb "#7570b3" title "median split"
unset multiplot
