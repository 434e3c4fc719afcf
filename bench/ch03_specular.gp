# ch03_specular.gp: figures/ch03-specular-speed-accuracy.svg from the CSV of
# bench/ch03_specular.c.
#   gnuplot -e "csv='figures/ch03-specular.csv'; stem='figures/ch03-specular'" bench/ch03_specular.gp
# Top: time per highlight evaluation (median, interquartile range) against
#   the rms error over the hemisphere (against Phong in long double), for
#   k = 10 (filled) and 100 (open). An rms error of exactly 0 never occurs
#   here; it would be dropped (positive), not drawn at a stand-in tick.
# Bottom: the largest error of Blinn-Phong against Phong over all viewer
#   directions, as the light moves from the normal (0 degrees) to grazing.
load "bench/chart.gp"
set terminal svg size 760,840 font "Helvetica,13" background "white"
set output stem.'-speed-accuracy.svg'
set multiplot layout 2,1 title "Chapter 3: highlights, speed against accuracy"
names = "phong-pow phong-squaring phong-schlick blinn-4k blinn-fitted"
labels = "'Phong, pow (used)' 'Phong, repeated squaring' 'Phong, Schlick rational' 'Blinn-Phong, exponent 4k' 'Blinn-Phong, fitted exponent'"
colors = "#1b9e77 #66a61e #e7298a #d95f02 #7570b3"
points = "7 5 9 11 13"
# make chart-ch03 WORKBOOK=1 passes yours (exercise 3.1 started): the
# reader's Phong and Blinn-Phong, in black.
if (exists("yours")) {
  names = names." yours-phong yours-blinn"
  labels = labels." 'yours, Phong (exercise 3.1)' 'yours, Blinn-Phong'"
  colors = colors." #000000 #000000"
  points = points." 3 1"
}
n = words(names)
is(m, k, kind) = strcol(1) eq m && strcol(2) eq k && strcol(5) eq kind

set logscale y
set format y "10^{%L}"
set yrange [1e-17:1]
set xrange [0:*]
set offsets graph 0, graph 0.1, 0, 0
set xlabel "time per evaluation (ns; bars: interquartile range)"
set ylabel "rms error over the hemisphere"
set key bottom left box opaque font ",10" title "filled: k = 10, open: k = 100"
plot for [m=1:n] csv using (is(word(names,m),"10","rms") ? $3 : NaN):(positive($4)) \
       with points pt (word(points,m)+0) ps 1.6 lc rgb word(colors,m) title word(labels,m), \
     for [m=1:n] csv using (is(word(names,m),"100","rms") ? $3 : NaN):(positive($4)) \
       with points pt (word(points,m)-1) ps 1.6 lc rgb word(colors,m) notitle, \
     csv using (strcol(5) eq "rms" ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars

set offsets 0, 0, 0, 0
set bmargin 5
eval machine_label
set xrange [0:90]
set yrange [1e-3:2]
set xtics 10
set xlabel "angle between the light and the normal (degrees)"
set ylabel "largest error over all viewers"
set format y "10^{%L}"
set key top left box opaque font ",10" title ""
incidence(m, k) = strcol(1) eq m && strcol(5) eq "max_abs_at_incidence" && strcol(2)[1:strlen(k)+1] eq k.":"
angle(s) = real(s[strstrt(s, ":")+1:])
plot csv using (incidence("blinn-4k","10") ? angle(strcol(2)) : NaN):(positive($4)) with linespoints pt 11 ps 0.8 lc rgb "#d95f02" title "Blinn-Phong 4k, k = 10", \
     csv using (incidence("blinn-4k","100") ? angle(strcol(2)) : NaN):(positive($4)) with linespoints pt 10 ps 0.8 lc rgb "#d95f02" dashtype 2 title "Blinn-Phong 4k, k = 100", \
     csv using (incidence("blinn-fitted","10") ? angle(strcol(2)) : NaN):(positive($4)) with linespoints pt 13 ps 0.8 lc rgb "#7570b3" title "Blinn-Phong fitted, k = 10", \
     csv using (incidence("blinn-fitted","100") ? angle(strcol(2)) : NaN):(positive($4)) with linespoints pt 12 ps 0.8 lc rgb "#7570b3" dashtype 2 title "Blinn-Phong fitted, k = 100"
unset multiplot
