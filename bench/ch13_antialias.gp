# ch13_antialias.gp: the chart of bench/ch13_antialias.c.
#   gnuplot -e "csv='figures/ch13-antialias.csv'; stem='figures/ch13-antialias'" bench/ch13_antialias.gp
# stem.svg: for each way of sampling a pixel, its rays per pixel (left) and
# its time per pixel (right) against the rms error of its 8-bit codes from
# 256 jittered rays a pixel; the twenty spheres above, the checkered floor
# below. One series per pattern; the adaptive points labelled by threshold,
# its remedies for aliasing corners (a minimum depth, jittered corners)
# at threshold 0.05;
# a dashed line at the reference's own error.
load "bench/chart.gp"
set terminal svg size 980,820 font "Helvetica,12" background "white"
set output stem.'.svg'
# rays, rms, ns, q1, q3, param: one line per param of SCENE-METHOD
rows(sc, m) = sprintf("< awk -F, '$1 == \"%s-%s\" && $5 == \"rays_per_pixel\" {r[$2] = $4} $1 == \"%s-%s\" && $5 == \"rms_codes\" {print r[$2] \",\" $4 \",\" $3 \",\" $6 \",\" $7 \",\" $2}' %s", sc, m, sc, m, csv)
set logscale xy
set format x "10^{%L}"
set format y "%g"
set key top right box opaque font ",10"
set multiplot layout 2,2 title "Chapter 13: a pixel's rays against the error of its picture (128 x 96 pixels)" margins 0.08,0.98,0.09,0.93 spacing 0.1,0.15
do for [sc in "spheres checker"] {
  what = sc eq "spheres" ? "twenty spheres (chapter 8)" : "checkered floor to the horizon"
  do for [panel in "rays time"] {
    set title what
    # the key over the spheres only, above their points; the floor's
    # panels share its series
    if (sc eq "spheres") { set key top right box opaque font ",9"; set yrange [0.1:300] } \
    else { unset key; set yrange [0.5:100] }
    set ylabel "rms error (8-bit codes) against 256 jittered rays"
    if (panel eq "rays") {
      set xlabel "rays per pixel (log scale)"
      set xrange [0.8:100]
      set format x "%g"
      x = 1
    } else {
      set xlabel "time per pixel (ns, log scale; bars: interquartile range)"
      set xrange [*:*]
      set format x "10^{%L}"
      x = 3
    }
    if (sc eq "spheres" && panel eq "rays") { eval machine_label } else { unset label 100 }
    # the own error of the reference (its distance from 1,024 rays): a floor
    floor = real(system(sprintf("awk -F, '$1 == \"%s-reference\" && $5 == \"rms_codes\" {print $4}' %s", sc, csv)))
    set arrow 1 from graph 0, first floor to graph 1, first floor nohead dt 2 lc rgb "#666666"
    set label 1 "own error of the reference" at graph 0.02, first floor offset 0,0.6 font ",9" tc rgb "#666666"
    plot rows(sc, "center") using x:2 with points pt 13 ps 1.6 lc rgb "#000000" title "centre (one ray)", \
         rows(sc, "grid") using x:2 with linespoints pt 9 ps 1.2 lw 2 lc rgb "#7570b3" title "grid", \
         rows(sc, "jittered") using x:2 with linespoints pt 7 ps 1.0 lw 2 lc rgb "#1b9e77" title "jittered", \
         rows(sc, "tent") using x:2 with points pt 11 ps 1.4 lc rgb "#e6ab02" title "jittered 4x4, tent", \
         rows(sc, "adaptive") using x:2 with linespoints pt 5 ps 1.0 lw 2 lc rgb "#d95f02" title "adaptive, depth 3 (used)", \
         rows(sc, "adaptive") using x:2:6 with labels offset 0,-0.9 font ",8" notitle, \
         rows(sc, "adaptive-d4") using x:2 with points pt 4 ps 1.4 lw 2 lc rgb "#d95f02" title "adaptive, depth 4", \
         rows(sc, "adaptive-min") using x:2 with linespoints pt 8 ps 1.2 lw 1 dt 3 lc rgb "#d95f02" title "adaptive, min depth 1, 2", \
         rows(sc, "adaptive-jittered") using x:2 with linespoints pt 12 ps 1.3 lw 1 dt 3 lc rgb "#e7298a" title "adaptive, jittered corners, min depth 0, 1", \
         for [m in "center grid jittered tent adaptive adaptive-d4 adaptive-min adaptive-jittered"] rows(sc, m) using (panel eq "time" ? $4 : NaN):2:($5 - $4):(0) @quartile_bars
  }
}
unset multiplot
