# ch06_offset.gp: the chart of bench/ch06_offset.c.
#   gnuplot -e "csv='figures/ch06-offset.csv'; stem='figures/ch06-offset'" bench/ch06_offset.gp
# stem-speed-accuracy.svg, three panels: shadow rays that hit their own
# surface, and contact shadows lost, against the scene's scale (solid,
# filled: double; dashed, open: float); and time per shadow ray against
# the worst error over the scales, in double.
load "bench/chart.gp"
set terminal svg size 1150,520 font "Helvetica,12" background "white"
set output stem.'-speed-accuracy.svg'
names = "none epsilon normal skip bound"
labels = "'t > 0 (no offset)' 't > 10^{-4}' 'normal offset 10^{-4}' 'skip the primitive' 'error bound (used)'"
colors = "#999999 #d95f02 #7570b3 #e7298a #1b9e77"
points = "5 9 11 13 7"
# make chart-ch06 WORKBOOK=1 passes yours (exercise 6.1 started): the
# reader's offset, in double, in black.
if (exists("yours")) {
  names = names." yours"
  labels = labels." 'yours (exercise 6.1)'"
  colors = colors." #000000"
  points = points." 3"
}
n = words(names)
lo = -4
hi = 2
pct(f) = at_zero(100 * f)
# the rows of one series: METHOD-PRECISION and one error kind
rows(m, kind) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' %s", m, kind, csv)
eval machine_label
set multiplot layout 1,3 title "Chapter 6: starting a shadow ray on its surface, as the scene grows" margins 0.06,0.98,0.14,0.88 spacing 0.07
set grid
eval zero_axis_y
set logscale x
set xrange [0.3:3e6]
set format x "10^{%L}"
set xlabel "scale and distance from the origin"
set ylabel "% of shadow rays"
set title "hitting their own surface (acne)"
set key off
plot for [k=1:n] rows(word(names,k)."-double", "self_hit_rate") using 2:(pct($4)) \
       with linespoints pt (word(points,k)+0) ps 1.4 lw 2 lc rgb word(colors,k) notitle, \
     for [k=1:4] rows(word(names,k)."-float", "self_hit_rate") using ($2*1.2):(pct($4)) \
       with linespoints pt (word(points,k)-1) ps 1.4 lw 1.5 dt 2 lc rgb word(colors,k) notitle
set title "missing a contact shadow"
plot for [k=1:n] rows(word(names,k)."-double", "lost_contact_rate") using 2:(pct($4)) \
       with linespoints pt (word(points,k)+0) ps 1.4 lw 2 lc rgb word(colors,k) notitle, \
     for [k=1:4] rows(word(names,k)."-float", "lost_contact_rate") using ($2*1.2):(pct($4)) \
       with linespoints pt (word(points,k)-1) ps 1.4 lw 1.5 dt 2 lc rgb word(colors,k) notitle
set title "speed against accuracy (double)"
unset logscale x
set xrange [*:*]
set offsets graph 0.1, graph 0.1, 0, 0
set format x "%g"
set xlabel "time per shadow ray (microseconds)"
set ylabel "worst % of errors of both kinds over the scales"
set key at graph 0.5, graph 0.5 center center box font ",10" title "solid, filled: double; dashed, open: float"
worst(m) = sprintf("< awk -F, '$1 == \"%s\" { e[$2] += $4; t += $3; n++ } END { w = 0; for (s in e) if (e[s] > w) w = e[s]; print t / n \",\" w }' %s", m, csv)
plot for [k=1:n] worst(word(names,k)."-double") using ($1/1000):(pct($2)) \
       with points pt (word(points,k)+0) ps 2 lc rgb word(colors,k) title word(labels,k)
unset multiplot
