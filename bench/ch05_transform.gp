# ch05_transform.gp: three charts from the CSV of bench/ch05_transform.c.
#   gnuplot -e "csv='figures/ch05-transform.csv'; stem='figures/ch05-transform'" bench/ch05_transform.gp
# stem-speed-accuracy.svg: left, time per normal (median, interquartile
#   range) against the largest angle error, one point per method and
#   transform; right, time per inverse (median, interquartile range) against
#   its error from the exact inverse, one point per condition number.
# stem-condition.svg: the inverses' errors against the condition number.
# stem-drift.svg: a rotation composed with itself N times, error against N;
#   an error of exactly 0 (double's axes after one frame) on a row of its own.
# The errors of the first two charts are never exactly 0 here: a 0 would be
# dropped (positive), not drawn at a made-up decade.
load "bench/chart.gp"
set terminal svg size 900,580 font "Helvetica,12" background "white"
set output stem.'-speed-accuracy.svg'
set multiplot layout 1,2 title "Chapter 5: transforms, speed against accuracy"
set bmargin 10

nm = "sheet-Mn inverse-transpose cofactor inverse-each-time"
nl = "'sheet M n' 'inverse transpose, kept (used)' 'cofactor matrix, kept' 'inverse transpose, inverted per normal'"
nc = "#d95f02 #1b9e77 #7570b3 #e7298a"
np = "7 5 9 13"
set logscale xy
set xrange [3:300]
set yrange [1e-16:1000]
set format y "10^{%L}"
set xtics ("5" 5, "10" 10, "20" 20, "50" 50, "100" 100, "200" 200) # ns: no decade to speak of
set xlabel "time per normal (ns, log scale; bars: interquartile range)"
set ylabel "largest angle to the true normal (degrees, log scale)"
set key at screen 0.25, screen 0.06 center bottom box font ",9"
set title "normals: rotation, uniform and non-uniform scales, shears" font ",11"
eval machine_label # under the left panel only: once on the canvas
plot for [k=1:4] csv using (strcol(1) eq word(nm,k) && strcol(5) eq "max_angle_deg" ? $3 : NaN):(positive($4)) \
       with points pt (word(np,k)+0) ps 1.5 lc rgb word(nc,k) title word(nl,k), \
     csv using (strcol(5) eq "max_angle_deg" ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars
unset label 100

im = "gauss-jordan affine-cofactor closed-form"
il = "'Gauss-Jordan, partial pivoting' 'affine: cofactors / det' 'closed form, step by step (used)'"
ic = "#7570b3 #d95f02 #1b9e77"
ip = "9 5 7"
# make chart-ch05 WORKBOOK=1 passes yours (exercise 5.3 started): the closed
# form composed by the reader's products, in black.
if (exists("yours")) {
  im = im." yours-closed-form"
  il = il." 'yours: closed form, your products (exercise 5.3)'"
  ic = ic." #000000"
  ip = ip." 3"
}
set xrange [30:200]
set xtics ("30" 30, "40" 40, "50" 50, "70" 70, "100" 100, "150" 150, "200" 200)
set yrange [1e-16:100]
set xlabel "time per inverse (ns, log scale; bars: interquartile range)"
set ylabel "error of M^{-1}: ||X - X*|| / ||X*|| (log scale)"
set title "inverses of T R S R at condition numbers 1 to 10^{12}" font ",11"
set key at screen 0.75, screen 0.06 center bottom box font ",9"
plot for [k=1:words(im)] csv using (strcol(1) eq word(im,k) && strcol(5) eq "forward" ? $3 : NaN):(positive($4)) \
       with points pt (word(ip,k)+0) ps 1.4 lc rgb word(ic,k) title word(il,k), \
     csv using (strcol(1) eq "affine-cofactor" && strcol(5) eq "forward" ? $3 : NaN):(positive($4)):(strcol(2)) \
       with labels left offset 1,0 font ",8" notitle, \
     csv using (strcol(5) eq "forward" ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars
unset multiplot

set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'-condition.svg'
set title "Chapter 5: inverses against the condition number of M = T R S R" font ",13"
set bmargin 5
set xtics auto
set xrange [0.5:2e12]
set yrange [1e-17:1e4]
set format x "10^{%L}"
set xlabel "condition number of the 3x3 part (log scale)"
set ylabel "error (log scale)"
set key default
set key top left box opaque font ",10"
kappa(s) = real(substr(s, 3, strlen(s)))
# one method's rows of one kind, without the rows between that would break its line
rows(m, kind) = sprintf("< awk -F, '$1 == \"%s\" && $5 == \"%s\"' '%s'", m, kind, csv)
eval machine_label
plot for [k=1:3] rows(word(im,k), "forward") using (10**kappa(strcol(2))):(positive($4)) \
       with linespoints pt (word(ip,k)+0) ps 1.3 lw 2 lc rgb word(ic,k) title word(il,k).": ||X - X*|| / ||X*||", \
     for [k=1:3] rows(word(im,k), "residual") using (10**kappa(strcol(2))):(positive($4)) \
       with linespoints pt (word(ip,k)-1) ps 1.1 lw 1 dt 2 lc rgb word(ic,k) title word(il,k).": ||M X - I||"

set terminal svg size 820,680 font "Helvetica,13" background "white"
set output stem.'-drift.svg'
set title "Chapter 5: a 0.7-degree rotation composed with itself N times"
set xrange [0.8:2e7]
set format x "10^{%L}"
set xlabel "compositions N (frames, log scale)"
set ylabel "error (degrees, log scale)"
lo = -16   # the smallest non-zero error drawn is 4e-16
hi = 2
eval zero_axis_y
set key default
set key at screen 0.5, screen 0.05 center bottom box font ",10"  # above the machine line
set bmargin 12
is(m, k) = strcol(1) eq m && strcol(5) eq k
set arrow from 0.8,0.01 to 2e7,0.01 nohead dt 3 lc rgb "#888888"
set label "0.01 degree" at 1.2,0.025 font ",10" tc rgb "#666666"
eval machine_label
plot csv using (is("drift-float-composed", "orthogonality_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 7 ps 1.3 lc rgb "#d95f02" title "float, composed: axes off 90 degrees", \
     csv using (is("drift-float-composed", "angle_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 6 ps 1.6 lc rgb "#d95f02" title "float, composed: turned too far or short", \
     csv using (is("drift-double-composed", "orthogonality_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 5 ps 1.3 lc rgb "#7570b3" title "double, composed: axes off 90 degrees", \
     csv using (is("drift-double-composed", "angle_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 4 ps 1.6 lc rgb "#7570b3" title "double, composed: turned too far or short", \
     csv using (is("drift-float-reorthonormalized", "orthogonality_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 9 ps 1.3 lc rgb "#e7298a" title "float, re-orthonormalised: axes off 90 degrees", \
     csv using (is("drift-float-reorthonormalized", "angle_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 8 ps 1.6 lc rgb "#e7298a" title "float, re-orthonormalised: turned too far or short", \
     csv using (is("drift-float-from-angle", "angle_deg") ? $2 : NaN):(at_zero($4)) \
       with points pt 13 ps 1.4 lc rgb "#1b9e77" title "float, from the frame number: turned too far or short"
