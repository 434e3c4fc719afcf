# ch02_sphere.gp: two charts from the CSV of bench/ch02_sphere.c.
#   gnuplot -e "csv='figures/ch02-sphere.csv'; stem='figures/ch02-sphere'" bench/ch02_sphere.gp
# stem-speed-accuracy.svg: time per intersection (median, interquartile
#   range) against the median relative error of t for a unit sphere 10^4
#   radii away, one point per form.
# stem-distance.svg: median relative error of t and share of misclassified
#   rays against the distance, one line per form and precision.
# A relative error of exactly 0 has no place on a log axis and never occurs
# here: it would be dropped (positive). Misclassified shares are often 0:
# they get a row labelled 0 of their own (bench/chart.gp).
load "bench/chart.gp"
names = "geometric-double quadratic-double robust-double geometric-float quadratic-float robust-float"
labels = "'geometric (sheet), double' 'textbook quadratic, double' 'robust (used), double' 'geometric (sheet), float' 'textbook quadratic, float' 'robust, float'"
colors = "#d95f02 #7570b3 #1b9e77 #d95f02 #7570b3 #1b9e77"
points = "7 5 9 6 4 8"
# make chart-ch02 WORKBOOK=1 passes yours (the started exercises, "2.1 2.3"):
# the reader's forms, in black.
form_of(id) = id eq "2.1" ? "geometric" : id eq "2.2" ? "quadratic" : "robust"
if (exists("yours")) {
  do for [k=1:words(yours)] {
    f = form_of(word(yours, k))
    names = names." yours-".f."-double yours-".f."-float"
    labels = labels." 'yours (".f.", exercise ".word(yours, k)."), double' 'yours (".f."), float'"
    colors = colors." #000000 #000000"
    points = points." ".word("1 2 3", k)." ".word("12 13 14", k)
  }
}
n = words(names)
is(m, kind) = strcol(1) eq m && strcol(5) eq kind

set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'-speed-accuracy.svg'
set bmargin 5
set title "Chapter 2: ray-sphere forms, unit sphere at distance 10^{4}: speed against accuracy"
set logscale y
set format y "10^{%L}"
set xrange [0:*]
set offsets graph 0, graph 0.12, 0, 0
set yrange [1e-17:1e-2]
set xlabel "time per intersection (ns; bars: interquartile range)"
set ylabel "median relative error of t"
set key bottom left box opaque font ",11"
eval machine_label
plot for [k=1:n] csv using (is(word(names,k),"t_rel_median") && $2 == 10000 ? $3 : NaN):(positive($4)) \
       with points pt (word(points,k)+0) ps 1.6 lc rgb word(colors,k) title word(labels,k), \
     csv using (strcol(5) eq "t_rel_median" && $2 == 10000 ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars

set output stem.'-distance.svg'
set terminal svg size 760,800 font "Helvetica,13" background "white"
unset label 100 # the machine line goes under the bottom panel only
set multiplot layout 2,1 title "Chapter 2: where each ray-sphere form fails"
unset title
set bmargin
set logscale xy
set format x "10^{%L}"
set xrange [1:1.5e7]
set xlabel "distance of a unit sphere (radii, log scale)"
set offsets 0, 0, 0, 0
set ylabel "median relative error of t"
set yrange [1e-22:1e-2]
set key bottom right box opaque font ",10"
plot for [k=1:n] csv using (is(word(names,k),"t_rel_median") ? $2 : NaN):(positive($4)) \
     with linespoints pt (word(points,k)+0) ps 0.8 lc rgb word(colors,k) title word(labels,k)
set bmargin 5
eval machine_label
set ylabel "misclassified rays (%, log scale)"
lo = -2
hi = 2
eval zero_axis_y
set key top left box opaque font ",10"
plot for [k=1:n] csv using (is(word(names,k),"misclassified") ? $2 : NaN):(at_zero(100 * $4)) \
     with linespoints pt (word(points,k)+0) ps 0.8 lc rgb word(colors,k) title word(labels,k)
unset multiplot
