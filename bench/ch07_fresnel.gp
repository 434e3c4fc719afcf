# ch07_fresnel.gp: figures/ch07-fresnel-speed-accuracy.svg from the CSV of
# bench/ch07_fresnel.c.
#   gnuplot -e "csv='figures/ch07-fresnel.csv'; stem='figures/ch07-fresnel'" bench/ch07_fresnel.gp
# Top: time per evaluation against the largest error over all angles, for
#   water, glass and diamond (marks), light from outside (filled) and from
#   inside (open). Middle: the same against the rms error over all angles.
# Bottom: the reflectance of glass against the angle of incidence, from
#   outside and from inside, by each method.
load "bench/chart.gp"
set terminal svg size 760,1240 font "Helvetica,13" background "white"
set output stem.'-speed-accuracy.svg'
set multiplot layout 3,1 title "Chapter 7: Fresnel reflectance, speed against accuracy"
names = "exact schlick schlick-tir"
labels = "'exact (used)' 'Schlick' 'Schlick with TIR'"
colors = "#1b9e77 #d95f02 #7570b3"
media = "1.33 1.5 2.42"
mnames = "'water 1.33' 'glass 1.5' 'diamond 2.42'"
points = "5 7 9"  # square, circle, triangle: filled; the open one is one less
# make chart-ch07 WORKBOOK=1 passes yours (exercise 7.3 started): the
# reader's three, in darker shades of the book's colours.
if (exists("yours")) {
  names = names." yours-exact yours-schlick yours-schlick-tir"
  labels = labels." 'yours: exact (exercise 7.3)' 'yours: Schlick' 'yours: Schlick with TIR'"
  colors = colors." #0b4f3b #6c2f01 #3a3859"
}
n = words(names)
is(m, p) = strcol(1) eq m && strcol(2) eq p && strcol(5) eq kind
kind = "max_abs"

set logscale y
set format y "10^{%L}"
set yrange [1e-17:10]
set xrange [0:*]
set offsets graph 0.05, graph 0.1, 0, 0
set xlabel "time per evaluation (ns; bars: interquartile range)"
set ylabel "largest error over all angles"
set key at graph 0.02, graph 0.8 left top box opaque font ",10" \
    title "filled: light from outside, open: from inside"
plot for [m=1:n] csv using (is(word(names,m), word(media,2).":outside") ? $3 : NaN):(positive($4)) \
       with points pt 7 ps 1.6 lc rgb word(colors,m) title word(labels,m), \
     for [k=1:3] csv using (NaN):(NaN) with points pt (word(points,k)+0) ps 1.4 lc rgb "#555555" \
       title word(mnames,k), \
     for [m=1:n] for [k=1:3] csv using (is(word(names,m), word(media,k).":outside") ? $3 : NaN):(positive($4)) \
       with points pt (word(points,k)+0) ps 1.6 lc rgb word(colors,m) notitle, \
     for [m=1:n] for [k=1:3] csv using (is(word(names,m), word(media,k).":inside") ? $3 : NaN):(positive($4)) \
       with points pt (word(points,k)-1) ps 1.8 lc rgb word(colors,m) notitle, \
     csv using (strcol(5) eq kind ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars


kind = "rms"
set ylabel "rms error over all angles"
set key off
plot for [m=1:n] csv using (is(word(names,m), word(media,2).":outside") ? $3 : NaN):(positive($4)) \
       with points pt 7 ps 1.6 lc rgb word(colors,m) title word(labels,m), \
     for [k=1:3] csv using (NaN):(NaN) with points pt (word(points,k)+0) ps 1.4 lc rgb "#555555" \
       title word(mnames,k), \
     for [m=1:n] for [k=1:3] csv using (is(word(names,m), word(media,k).":outside") ? $3 : NaN):(positive($4)) \
       with points pt (word(points,k)+0) ps 1.6 lc rgb word(colors,m) notitle, \
     for [m=1:n] for [k=1:3] csv using (is(word(names,m), word(media,k).":inside") ? $3 : NaN):(positive($4)) \
       with points pt (word(points,k)-1) ps 1.8 lc rgb word(colors,m) notitle, \
     csv using (strcol(5) eq kind ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars

unset logscale y
set format y "%g"
set offsets 0, 0, 0, 0
set bmargin 5
eval machine_label
set xrange [0:90]
set yrange [0:1.02]
set xtics 10
set xlabel "angle of incidence (degrees)"
set ylabel "reflectance F_R of glass, n = 1.5"
set key default
set key at graph 0.5, graph 0.9 left top box opaque font ",10" title ""
curve(m, side) = strcol(1) eq m && strcol(5) eq "reflectance" && strcol(2)[1:strlen(side)+5] eq "1.5:".side.":"
angle(s) = real(s[strstrt(s[5:], ":")+5:])
plot csv using (curve("exact","outside") ? angle(strcol(2)) : NaN):4 with lines lw 2.5 lc rgb "#1b9e77" title "exact, light from outside", \
     csv using (curve("schlick","outside") ? angle(strcol(2)) : NaN):4 with lines lw 2 dashtype 2 lc rgb "#d95f02" title "Schlick, both forms, from outside", \
     csv using (curve("exact","inside") ? angle(strcol(2)) : NaN):4 with lines lw 2.5 lc rgb "#1b9e77" dashtype 1 title "exact, from inside", \
     csv using (curve("schlick","inside") ? angle(strcol(2)) : NaN):4 with lines lw 2 dashtype 3 lc rgb "#d95f02" title "Schlick, from inside (as outside)", \
     csv using (curve("schlick-tir","inside") ? angle(strcol(2)) : NaN):4 with lines lw 2 dashtype 2 lc rgb "#7570b3" title "Schlick with TIR, from inside"
unset multiplot
