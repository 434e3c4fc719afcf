# ch08_embree.gp: the chart of bench/ch08_embree.c's CSV.
#   gnuplot -e "csv='figures/ch08-embree.csv'; stem='figures/ch08-embree'" bench/ch08_embree.gp
# stem.svg: left, rays per second of this program's kd-tree and of Embree
#   on the same rays (bars: the median round; ticks: the slowest and the
#   fastest), with our rate as a fraction of Embree's above each pair;
#   right, the build times. Where Embree was absent (the CSV has the row
#   embree,absent), only this program's bars are drawn, and the chart says
#   so.
set datafile separator ","
set grid ytics
set terminal svg size 1000,480 font "Helvetica,12" background "white"
set bmargin 4.5
set output stem.'.svg'
absent = int(system("grep -c '^embree,absent' ".csv))
is(m, k) = strcol(1) eq m && strcol(5) eq k
case(s) = s eq "bunny-1.0" ? 0 : s eq "bunny-2.5" ? 1 : s eq "teapot-1.0" ? 2 : s eq "teapot-2.5" ? 3 : NaN
mesh(s) = s eq "bunny" ? 0 : s eq "teapot" ? 1 : NaN
ours = "#1b9e77"
theirs = "#7570b3"
set style fill solid 0.85 noborder
set boxwidth 0.36

set multiplot layout 1,2 title (absent ? "Chapter 08: this program's kd-tree (Embree was absent when this chart was made)" : "Chapter 08: this program's kd-tree against Embree 3, the same rays, one thread each") font ",14"
set xrange [-0.6:3.6]
set yrange [0:*]
set offsets 0, 0, graph 0.12, 0
set xtics ("bunny\nK = 1" 0, "bunny\nK = 2.5" 1, "teapot\nK = 1" 2, "teapot\nK = 2.5" 3)
set ylabel "million closest-hit rays per second"
set key top left box opaque font ",10"
set title "1024 x 1024 rays; numbers: our rate / Embree's (median of the rounds)" font ",10"
plot csv using (is("kdtree","mrays_per_s") ? case(strcol(2)) - 0.19 : NaN):4 with boxes lc rgb ours title "kd-tree, double, watertight (this chapter)", \
     csv using (is("embree","mrays_per_s") ? case(strcol(2)) + 0.19 : NaN):4 with boxes lc rgb theirs title "Embree 3, rtcIntersect1, high-quality BVH", \
     csv using (is("kdtree","mrays_per_s_min") || is("kdtree","mrays_per_s_max") ? case(strcol(2)) - 0.19 : NaN):4 with points pt 1 ps 1.2 lc rgb "#333333" notitle, \
     csv using (is("embree","mrays_per_s_min") || is("embree","mrays_per_s_max") ? case(strcol(2)) + 0.19 : NaN):4 with points pt 1 ps 1.2 lc rgb "#333333" notitle, \
     csv using (is("ratio","kdtree_over_embree") ? case(strcol(2)) - 0.19 : NaN):(2):(sprintf("%.2f", $4)) with labels font ",11" tc rgb "white" notitle

set xrange [-0.6:1.6]
set xtics ("bunny\n69,451 triangles" 0, "teapot\n4,032 triangles" 1)
set logscale y
set yrange [1:*]
set offsets 0, 0, 0, 0
set ylabel "build time (ms, log scale)"
set title "numbers: our build time / Embree's" font ",10"
plot csv using (is("build","kdtree_build_ms") ? mesh(strcol(2)) - 0.19 : NaN):4 with boxes lc rgb ours title "kd-tree, SAH, events sorted once", \
     csv using (is("build","embree_build_ms") ? mesh(strcol(2)) + 0.19 : NaN):4 with boxes lc rgb theirs title "Embree 3, RTC\\_BUILD\\_QUALITY\\_HIGH", \
     csv using (is("build","build_kdtree_over_embree") ? mesh(strcol(2)) : NaN):(1.5):(sprintf("%.2f", $4)) with labels font ",11" tc rgb "white" notitle
unset multiplot
