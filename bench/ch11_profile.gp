# ch11_profile.gp: the chart of bench/ch11_profile.c's CSV.
#   gnuplot -e "csv='figures/ch11-profile.csv'; stem='figures/ch11-profile'" bench/ch11_profile.gp
# stem.svg: for the kd-tree, the BVH and the BVH in float (bvh-float),
#   the bunny at K = 1 and K = 2.5,
#   the share of the instructions in each group of functions (the ray's
#   setup, the interior nodes, the leaves, the triangle tests in double,
#   the rest), as a bar of 100%. Where Valgrind was absent (the CSV has the
#   row profile,absent), the chart says so.
load "bench/chart.gp"
set terminal svg size 1000,520 font "Helvetica,12" background "white"
set output stem.'.svg'
absent = int(system("grep -c '^profile,absent' ".csv))
runs = "kdtree@1.0 kdtree@2.5 bvh@1.0 bvh@2.5 bvh-float@1.0 bvh-float@2.5"
groups = "setup interior leaves double other"
label(r) = r eq "kdtree@1.0" ? "kd-tree, K = 1" : r eq "kdtree@2.5" ? "kd-tree, K = 2.5" : \
           r eq "bvh@1.0" ? "BVH, K = 1" : r eq "bvh@2.5" ? "BVH, K = 2.5" : \
           r eq "bvh-float@1.0" ? "BVH in float, K = 1" : "BVH in float, K = 2.5"
title(g) = g eq "setup" ? "the ray's setup (constants, root box)" : \
           g eq "interior" ? "interior nodes" : \
           g eq "leaves" ? "leaves (kd-tree: the loop; BVH: the float filter, or test)" : \
           g eq "double" ? "triangle tests in double" : "the rest (the loop over the rays)"
colour(k) = word("#7570b3 #1b9e77 #e6ab02 #d95f02 #999999", k)
# the share of group g in run r, in per cent
share(r, g) = real(system(sprintf("awk -F, '$1 == \"profile\" && $2 == \"%s\" && $5 == \"share_%s\" {print 100 * $4}' %s", r, g, csv)))
# the left end of group k's bar in run r: the shares of the groups before
before(r, k) = k <= 1 ? 0 : sum [j=1:k-1] share(r, word(groups, j))

eval machine_label
set title (absent ? "Chapter 11: where a ray's instructions go (Valgrind was absent when this chart was made)" : \
           "Chapter 11: where a ray's instructions go, closest hits through the bunny (callgrind)") font ",13"
set xrange [0:100]
set yrange [-0.7:5.7]
set xlabel "share of the instructions (%)"
set ytics () 
do for [k=1:words(runs)] { set ytics add (label(word(runs, k)) words(runs) - k) }
set key at screen 0.5, screen 0.13 center horizontal maxrows 2 font ",10" width 2
set bmargin 9
set style fill solid 0.9 noborder
if (absent) { plot 1/0 notitle } else {
plot for [g=1:words(groups)] '+' using (before(word(runs, int($0) + 1), g)):(5 - $0): \
       (before(word(runs, int($0) + 1), g)):(before(word(runs, int($0) + 1), g) + share(word(runs, int($0) + 1), word(groups, g))): \
       (5 - $0 - 0.35):(5 - $0 + 0.35) every ::0::5 with boxxyerror lc rgb colour(g) title title(word(groups, g))
}
