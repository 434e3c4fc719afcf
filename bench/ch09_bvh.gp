# ch09_bvh.gp: two charts from the CSV of bench/ch09_bvh.c.
#   gnuplot -e "csv='figures/ch09-bvh.csv'; stem='figures/ch09-bvh'" bench/ch09_bvh.gp
# stem.svg: time per ray (median, interquartile range) against the rays
#   answered unlike brute force, per million, zero on a row of its own;
#   colour: the method; mark: the mesh; filled: ordinary rays, open:
#   rays aimed at vertices and edges and along axes through vertices.
# stem-build.svg: build time per triangle against time per ray (median,
#   interquartile range), the kd-tree and the BVH of 4 to 64 bins, for
#   the bunny and the teapot.
load "bench/chart.gp"
set terminal svg size 760,540 font "Helvetica,13" background "white"
set output stem.'.svg'
set bmargin 5
set title "Chapter 9: the kd-tree and the BVH, time per ray against wrong answers"
kd = "#1b9e77"
bvh = "#7570b3"
naive = "#d95f02"
color_of(m) = m eq "kdtree" ? kd : m eq "naive" ? naive : bvh
meshes = "bunny teapot bunny-far"
mesh_labels = "'bunny' 'teapot' 'bunny moved by 10^6'"
mesh_points = "7 5 9"   # filled; the open version is one less
methods = "kdtree bvh-4 bvh-8 bvh-16 bvh-32 bvh-64 naive"
is(m, where, kind) = strcol(1) eq m && strcol(2) eq where && strcol(5) eq kind
lo = 2
hi = 6
eval zero_axis_y
set logscale x
set format x "10^{%L}"
set xrange [30:3e6]
set xlabel "time per ray, closest hit (ns, log scale; bars: interquartile range)"
set ylabel "rays answered unlike brute force (per million)"
set key at graph 0.98, graph 0.62 right top box opaque font ",10" spacing 1.1
eval machine_label
plot for [j=1:3] for [k=1:words(methods)] \
       csv using (is(word(methods,k), word(meshes,j), "ordinary_wrong_per_million") ? $3 : NaN):(at_zero($4)) \
       with points pt (word(mesh_points,j)+0) ps 1.4 lc rgb color_of(word(methods,k)) notitle, \
     for [j=1:3] for [k=1:words(methods)] \
       csv using (is(word(methods,k), word(meshes,j), "adversarial_wrong_per_million") ? $3 : NaN):(at_zero($4)) \
       with points pt (word(mesh_points,j)-1) ps 2.2 lc rgb color_of(word(methods,k)) notitle, \
     csv using (strcol(5) eq "ordinary_wrong_per_million" ? $6 : NaN):(at_zero($4)):($7 - $6):(0) @quartile_bars, \
     NaN with points pt 7 ps 1.4 lc rgb kd title "kd-tree (chapter 8; the default)", \
     NaN with points pt 7 ps 1.4 lc rgb bvh title "BVH, 4 to 64 bins", \
     NaN with points pt 7 ps 1.4 lc rgb naive title "naive BVH: rounded to nearest", \
     for [j=1:3] NaN with points pt (word(mesh_points,j)+0) ps 1.4 lc rgb "#555555" title word(mesh_labels,j), \
     NaN with points pt 6 ps 2.2 lc rgb "#555555" title "open marks: adversarial rays"

set output stem.'-build.svg'
unset label 100
unset arrow 90
set title "Chapter 9: what a faster build costs the rays (bunny and teapot)"
set logscale x
set format x "10^{%L}"
set xrange [100:1e4]
unset logscale y
set yrange [0:*]
set ytics auto
set format y "%g"
set offsets 0, 0, graph 0.1, 0
set xlabel "build time per triangle (ns, log scale)"
set ylabel "time per ray, closest hit (ns; bars: interquartile range)"
set key top right box opaque font ",10"
trade(m, where) = strcol(1) eq "tradeoff" && strcol(2) eq m."@".where
is_bvh(where) = strcol(1) eq "tradeoff" && strcol(2)[1:4] eq "bvh-" && \
                strcol(2)[strlen(strcol(2)) - strlen(where):] eq "@".where
bins(s) = s[5:strstrt(s, "@") - 1]
# the labels of 8 and 32 bins below their marks, the others above: 4 and
# 8 bins lie close together
below(s) = bins(s) eq "8" || bins(s) eq "32"
eval machine_label
plot for [j=1:2] csv using (is_bvh(word(meshes,j)) ? $4 : NaN):3 \
       with linespoints pt (word(mesh_points,j)+0) ps 1.2 lc rgb bvh \
       title "BVH, ".word(meshes,j).": M = 4 to 64 bins", \
     for [j=1:2] csv using (is_bvh(word(meshes,j)) && !below(strcol(2)) ? $4 : NaN):3:(bins(strcol(2))) \
       with labels offset 0,1.1 font ",9" notitle, \
     for [j=1:2] csv using (is_bvh(word(meshes,j)) && below(strcol(2)) ? $4 : NaN):3:(bins(strcol(2))) \
       with labels offset 0,-1.1 font ",9" notitle, \
     for [j=1:2] csv using (trade("kdtree", word(meshes,j)) ? $4 : NaN):3 \
       with points pt (word(mesh_points,j)+0) ps 1.6 lc rgb kd \
       title "kd-tree, ".word(meshes,j), \
     csv using (strcol(1) eq "tradeoff" ? $4 : NaN):6:(0):($7 - $6) @quartile_bars
