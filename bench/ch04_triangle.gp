# ch04_triangle.gp: two charts from the CSV of bench/ch04_triangle.c.
#   gnuplot -e "csv='figures/ch04-triangle.csv'; stem='figures/ch04-triangle'" bench/ch04_triangle.gp
# stem-speed-accuracy.svg: time per ray-triangle test (median,
#   interquartile range) against the share of rays aimed at shared edges and
#   vertices that miss every triangle there, zero on a row of its own;
#   filled marks: mesh at the origin, open marks: translated by 1e4.
# stem-brute-force.svg: time per ray (median, interquartile range) against
#   the number of triangles tested.
load "bench/chart.gp"
set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'-speed-accuracy.svg'
set bmargin 5
set title "Chapter 4: ray-triangle tests, speed against leaks through shared edges"
names = "sheet-double moller-trumbore-double watertight-double sheet-float moller-trumbore-float watertight-float"
labels = "'sheet (areas), double' 'Moller-Trumbore, double' 'watertight (used), double' 'sheet (areas), float' 'Moller-Trumbore, float' 'watertight, float'"
colors = "#d95f02 #7570b3 #1b9e77 #d95f02 #7570b3 #1b9e77"
points = "5 9 7 13 11 15"  # filled; the open version is one less
# make chart-ch04 WORKBOOK=1 passes yours (the started exercises, "4.1 4.3"):
# the reader's methods, in black, with the marks of the book's.
form_of(id) = id eq "4.1" ? "sheet" : id eq "4.2" ? "moller-trumbore" : "watertight"
mark_of(f) = f eq "sheet" ? "5 13" : f eq "moller-trumbore" ? "9 11" : "7 15"
if (exists("yours")) {
  do for [k=1:words(yours)] {
    f = form_of(word(yours, k))
    if (strstrt(names, "yours-".f."-double") == 0) {  # 4.3 and 4.4: one method
      names = names." yours-".f."-double yours-".f."-float"
      labels = labels." 'yours (".f.", exercise ".word(yours, k)."), double' 'yours (".f."), float'"
      colors = colors." #000000 #000000"
      points = points." ".mark_of(f)
    }
  }
}
n = words(names)
is(m, where) = strcol(1) eq m && strcol(2) eq where && strcol(5) eq "leak_rate"
lo = -3
hi = 2
eval zero_axis_y
pct(f) = at_zero(100 * f)
set xrange [0:*]
set offsets graph 0.02, graph 0.15, 0, 0
set xlabel "time per ray-triangle test (ns; bars: interquartile range)"
set ylabel "rays through edges and vertices that leak (%)"
set key at graph 0.98, graph 0.52 right top box opaque font ",10" title "filled: mesh at the origin, open: moved by 10^4"
eval machine_label
plot for [k=1:n] csv using (is(word(names,k),"origin") ? $3 : NaN):(pct($4)) \
       with points pt (word(points,k)+0) ps 1.8 lc rgb word(colors,k) title word(labels,k), \
     for [k=1:n] csv using (is(word(names,k),"1e4") ? $3 : NaN):(pct($4)) \
       with points pt (word(points,k)-1) ps 2.2 lc rgb word(colors,k) notitle, \
     csv using (strcol(5) eq "leak_rate" ? $6 : NaN):(pct($4)):($7 - $6):(0) @quartile_bars

set output stem.'-brute-force.svg'
set title "Chapter 4: brute force, the Stanford bunny's first N triangles"
unset arrow 90
set logscale xy
set offsets 0, 0, 0, 0
set xrange [50:2e5]
set yrange [*:*]
set ytics auto
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "triangles in the mesh (log scale)"
set ylabel "time per ray (ns, log scale; bars: interquartile range)"
set key default
set key inside top left box opaque font ",11"
plot csv using (strcol(1) eq "brute-force" ? $2 : NaN):3 with linespoints pt 7 ps 1.2 lc rgb "#d95f02" title "every triangle tested (bounding box hit)", \
     csv using (strcol(1) eq "brute-force" ? $2 : NaN):6:(0):($7 - $6) @quartile_bars
