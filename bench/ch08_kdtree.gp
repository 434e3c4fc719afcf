# ch08_kdtree.gp: charts from the CSV of bench/ch08_kdtree.c.
#   gnuplot -e "csv='figures/ch08-kdtree.csv'; stem='figures/ch08-kdtree'" bench/ch08_kdtree.gp
# stem-speed-accuracy.svg: top left, time per ray against the number of
#   triangles (brute force, median-split tree, SAH tree) and of spheres (a
#   list, a tree); the other three panels, build time against time per ray
#   for each of the SAH's parameters, moved one at a time from the defaults.
# figures/ch08-build-scaling.svg: build time per triangle against the
#   number of triangles for the three builds, and the same divided by
#   log2 N.
# Every time is a median over interleaved rounds, drawn with its quartiles
# (bench/chart.gp's quartile bars); both charts carry the machine line.
load "bench/chart.gp"
set terminal svg size 1000,820 font "Helvetica,12" background "white"
set output stem.'-speed-accuracy.svg'
is(m, k) = strcol(1) eq m && strcol(5) eq k
# The rows of one method and kind, in the order of the file (of N, or of
# the parameter's value): a series' line, which other rows cannot break.
rows(m, k) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' '%s'", m, k, csv)

eval machine_label
set multiplot layout 2,2 title "Chapter 8: kd-trees, time per ray against N, and what the SAH's parameters cost" font ",14" margins 0.08,0.97,0.1,0.92 spacing 0.09,0.12
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [0.7:2e5]
set xlabel "triangles (or spheres) searched (log scale)"
set ylabel "time per ray (ns, log scale)"
set key top left box opaque font ",10"
set title "64 x 64 rays at K = 1; every tree agrees with brute force on every ray" font ",11"
plot rows("brute-force","triangle_tests_per_ray") using 2:3 with linespoints pt 7 ps 0.8 lc rgb "#d95f02" title "brute force (every triangle)", \
     rows("median","triangle_tests_per_ray") using 2:3 with linespoints pt 5 ps 0.8 lc rgb "#7570b3" title "median-split tree", \
     rows("sah","triangle_tests_per_ray") using 2:3 with linespoints pt 9 ps 0.9 lc rgb "#1b9e77" title "SAH tree (used)", \
     rows("objects-list","sphere_tests_per_ray") using 2:3 with linespoints pt 6 ps 0.8 dt 2 lc rgb "#e7298a" title "spheres: a list", \
     rows("objects-tree","sphere_tests_per_ray") using 2:3 with linespoints pt 8 ps 0.8 dt 2 lc rgb "#66a61e" title "spheres: a tree", \
     csv using (strcol(5) eq "triangle_tests_per_ray" || strcol(5) eq "sphere_tests_per_ray" ? $2 : NaN):6:(0):($7 - $6) @quartile_bars

# The SAH's panels: a point is (build time, time per ray); the rows
# sah-FAMILY carry the time per ray and its quartiles, sah-build-FAMILY the
# build time (ns) and its quartiles.
trace(f) = is("sah-".f, "build_ms")
built(f) = is("sah-build-".f, "ns_per_ray")
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
f = "traversal-cost"
plot rows("sah-".f, "build_ms") using 4:3 with linespoints pt 7 ps 0.9 lc rgb "#1b9e77", \
     csv using (trace(f) ? $4 : NaN):3:2 with labels offset 0.6,0.8 font ",10" tc rgb "#1b9e77", \
     csv using (trace(f) ? $4 : NaN):6:(0):($7 - $6) @quartile_bars, \
     csv using (built(f) ? $6 / 1e6 : NaN):4:(($7 - $6) / 1e6):(0) @quartile_bars
set title "empty bonus; default 0.2" font ",11"
f = "empty-bonus"
plot csv using (trace(f) ? $4 : NaN):3 with points pt 5 ps 0.9 lc rgb "#7570b3", \
     csv using (trace(f) ? $4 : NaN):3:2 with labels offset 0.6,0.8 font ",10" tc rgb "#7570b3", \
     csv using (trace(f) ? $4 : NaN):6:(0):($7 - $6) @quartile_bars, \
     csv using (built(f) ? $6 / 1e6 : NaN):4:(($7 - $6) / 1e6):(0) @quartile_bars
set title "maximum depth; default 8 + 1.3 log_2 N = 28" font ",11"
set logscale y
set format y "10^{%L}"
f = "max-depth"
plot rows("sah-".f, "build_ms") using 4:3 with linespoints pt 9 ps 1 lc rgb "#d95f02", \
     csv using (trace(f) ? $4 : NaN):3:2 with labels offset 0.6,0.8 font ",10" tc rgb "#d95f02", \
     csv using (trace(f) ? $4 : NaN):6:(0):($7 - $6) @quartile_bars, \
     csv using (built(f) ? $6 / 1e6 : NaN):4:(($7 - $6) / 1e6):(0) @quartile_bars
unset multiplot

set terminal svg size 1000,460 font "Helvetica,12" background "white"
# in stem's folder, as every chart (check-charts draws into build/chartcheck)
set output stem[1:strlen(stem) - strlen('ch08-kdtree')].'ch08-build-scaling.svg'
unset logscale
set logscale x
set format x "10^{%L}"
set format y "%g"
set xrange [800:2e6]
set yrange [0:*]
set xlabel "triangles (log scale)"
set key top left box opaque font ",10"
any_build = 'strcol(5) eq "build_ms" && strcol(1)[1:6] eq "build-"'
eval machine_label
set multiplot layout 1,2 title "Chapter 8: build time against N (bumpy spheres, made by the benchmark)" font ",14" margins 0.08,0.97,0.2,0.86 spacing 0.09
set title "per triangle" font ",11"
set ylabel "build time per triangle (microseconds)"
plot rows("build-sah", "build_ms") using 2:($3/1000) with linespoints pt 9 ps 1 lc rgb "#1b9e77" title "SAH, events sorted once", \
     rows("build-sorting", "build_ms") using 2:($3/1000) with linespoints pt 7 ps 1 lc rgb "#d95f02" title "SAH, events sorted at every node", \
     rows("build-median", "build_ms") using 2:($3/1000) with linespoints pt 5 ps 1 lc rgb "#7570b3" title "median split", \
     csv using (@any_build ? $2 : NaN):($6/1000):(0):(($7 - $6)/1000) @quartile_bars
set title "per triangle and per level, log_2 N: flat for an O(N log N) build" font ",11"
set ylabel "build time / (N log_2 N) (ns)"
per_level(v) = v / log($2) * log(2)
plot rows("build-sah", "build_ms") using 2:(per_level($3)) with linespoints pt 9 ps 1 lc rgb "#1b9e77" title "SAH, events sorted once", \
     rows("build-sorting", "build_ms") using 2:(per_level($3)) with linespoints pt 7 ps 1 lc rgb "#d95f02" title "SAH, events sorted at every node", \
     rows("build-median", "build_ms") using 2:(per_level($3)) with linespoints pt 5 ps 1 lc rgb "#7570b3" title "median split", \
     csv using (@any_build ? $2 : NaN):(per_level($6)):(0):(per_level($7) - per_level($6)) @quartile_bars
unset multiplot
