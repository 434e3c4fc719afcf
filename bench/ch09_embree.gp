# ch09_embree.gp: the chart of bench/ch09_embree.c's CSV.
#   gnuplot -e "csv='figures/ch09-embree.csv'; stem='figures/ch09-embree'" bench/ch09_embree.gp
# stem.svg: left, rays per second of this program's kd-tree and of Embree
#   on the same rays (bars: the median of interleaved rounds; error bars:
#   the rates of the time's interquartile range, 1e3/q3 to 1e3/q1), with
#   our rate as a fraction of Embree's above each pair; right, the build
#   times (median, interquartile range). Where Embree was absent (the CSV
#   has the row embree,absent: make chart-embree-absent), only this
#   program's bars are drawn, and the chart says so.
load "bench/chart.gp"
set grid noxtics ytics
set terminal svg size 1000,480 font "Helvetica,12" background "white"
set bmargin 4.5
set output stem.'.svg'
absent = int(system("grep -c '^embree,absent' ".csv))
is(m, k) = strcol(1) eq m && strcol(5) eq k
case(s) = s eq "bunny-1.0" ? 0 : s eq "bunny-2.5" ? 1 : s eq "teapot-1.0" ? 2 : s eq "teapot-2.5" ? 3 : NaN
mesh(s) = s eq "bunny" ? 0 : s eq "teapot" ? 1 : NaN
# x of a program's bar: ours left of the pair's middle, Embree's right
rate_x(m) = is(m, "mrays_per_s") ? case(strcol(2)) + (m eq "kdtree" ? -0.19 : 0.19) : NaN
build_x(m) = is(m, "build_ms") ? mesh(strcol(2)) + (m eq "kdtree-build" ? -0.19 : 0.19) : NaN
# Embree's key entries and the subtitles' ratios only where Embree was there
theirs_title(t) = absent ? "" : t
ratios(t) = absent ? "" : t
ours = "#1b9e77"
theirs = "#7570b3"
set style fill solid 0.85 noborder
set boxwidth 0.36

eval machine_label
set multiplot layout 1,2 title (absent ? "Chapter 9: chapter 8's kd-tree (Embree was absent when this chart was made)" : "Chapter 9: chapter 8's kd-tree against Embree 3, the same rays, one thread each") font ",14"
set xrange [-0.6:3.6]
set yrange [0:*]
set offsets 0, 0, graph 0.25, 0
set xtics ("bunny\nK = 1" 0, "bunny\nK = 2.5" 1, "teapot\nK = 1" 2, "teapot\nK = 2.5" 3)
set ylabel "million closest-hit rays per second (bars: interquartile range)"
set key top left box opaque font ",10"
set title "1024 x 1024 rays".ratios("; numbers: our rate / Embree's (medians)") font ",10"
plot csv using (rate_x("kdtree")):4 with boxes lc rgb ours title "kd-tree, double, watertight (chapter 8)", \
     csv using (rate_x("embree")):4 with boxes lc rgb theirs title theirs_title("Embree 3, rtcIntersect1, high-quality BVH"), \
     for [m in "kdtree embree"] csv using (rate_x(m)):(1e3 / $7):(0):(1e3 / $6 - 1e3 / $7) @quartile_bars, \
     csv using (is("ratio","kdtree_over_embree") ? case(strcol(2)) - 0.19 : NaN):(2):(sprintf("%.2f", $4)) with labels font ",11" tc rgb "white" notitle

set xrange [-0.6:1.6]
set xtics ("bunny\n69,451 triangles" 0, "teapot\n4,032 triangles" 1)
set logscale y
set format y "10^{%L}"
set yrange [1:*]
set offsets 0, 0, 0, 0
set ylabel "build time (ms, log scale; bars: interquartile range)"
set title (absent ? "build time" : "numbers: our build time / Embree's (medians)") font ",10"
plot csv using (build_x("kdtree-build")):4 with boxes lc rgb ours title "kd-tree, SAH, events sorted once", \
     csv using (build_x("embree-build")):4 with boxes lc rgb theirs title theirs_title("Embree 3, RTC\\_BUILD\\_QUALITY\\_HIGH"), \
     for [m in "kdtree-build embree-build"] csv using (build_x(m)):($6 / 1e6):(0):(($7 - $6) / 1e6) @quartile_bars, \
     csv using (is("build","build_kdtree_over_embree") ? mesh(strcol(2)) : NaN):(1.5):(sprintf("%.2f", $4)) with labels font ",11" tc rgb "white" notitle
unset multiplot
