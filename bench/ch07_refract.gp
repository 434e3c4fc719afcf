# ch07_refract.gp: two charts from the CSV of bench/ch07_refract.c.
#   gnuplot -e "csv='figures/ch07-refract.csv'; stem='figures/ch07-refract'" bench/ch07_refract.gp
# stem-speed-accuracy.svg: time per refraction against the largest error
#   over all angles into and out of glass.
# stem-accuracy.svg: top, into glass as the ray nears grazing: the largest
#   errors in Snell's law and in |t|; middle, the share of NaN directions,
#   down to exactly grazing; bottom, out of glass as the ray nears the
#   critical angle: the errors in Snell's law, in |t| and in the direction.
load "bench/chart.gp"
set terminal svg size 760,480 font "Helvetica,13" background "white"
set output stem.'-speed-accuracy.svg'
set title "Chapter 7: the refracted direction, speed against accuracy"
is(m, p, kind) = strcol(1) eq m && strcol(2) eq p && strcol(5) eq kind
set logscale y
set format y "10^{%L}"
set yrange [1e-17:1e-12]
set xrange [0:*]
set offsets graph 0.05, graph 0.25, 0, 0
set xlabel "time per refraction (ns; bars: interquartile range)"
set bmargin 5
eval machine_label
set ylabel "largest error over all angles"
set key top left box opaque font ",10"
# make chart-ch07 WORKBOOK=1 passes yours (the started exercises, "7.1 7.2"):
# the reader's forms, in black, with the marks of the book's.
yours_of(id) = id eq "7.1" ? "standard" : id eq "7.2" ? "sheet" : ""
yours_points = ""
if (exists("yours")) {
  do for [k=1:words(yours)] {
    f = yours_of(word(yours, k))
    if (f ne "") {
      m = "yours-".f
      p = f eq "standard" ? "7 5 9" : "6 4 8"
      yours_points = yours_points.sprintf(', csv using (is("%s","all","snell") ? $3 : NaN):(positive($4)) with points pt %s ps 1.8 lc rgb "#000000" title "yours (%s, exercise %s): Snell''s law"', m, word(p,1), f, word(yours, k)) \
        .sprintf(', csv using (is("%s","all","unit") ? $3 : NaN):(positive($4)) with points pt %s ps 1.6 lc rgb "#000000" title "yours: |t| - 1"', m, word(p,2)) \
        .sprintf(', csv using (is("%s","all","angle") ? $3 : NaN):(positive($4)) with points pt %s ps 1.8 lc rgb "#000000" title "yours: direction (rad)"', m, word(p,3))
    }
  }
}
plot csv using (is("standard","all","snell") ? $3 : NaN):(positive($4)) with points pt 7 ps 1.8 lc rgb "#1b9e77" title "standard (used): Snell's law", \
     csv using (is("standard","all","unit") ? $3 : NaN):(positive($4)) with points pt 5 ps 1.6 lc rgb "#1b9e77" title "standard: |t| - 1", \
     csv using (is("standard","all","angle") ? $3 : NaN):(positive($4)) with points pt 9 ps 1.8 lc rgb "#1b9e77" title "standard: direction (rad)", \
     csv using (is("sheet","all","snell") ? $3 : NaN):(positive($4)) with points pt 6 ps 1.8 lc rgb "#d95f02" title "sheet: Snell's law", \
     csv using (is("sheet","all","unit") ? $3 : NaN):(positive($4)) with points pt 4 ps 1.6 lc rgb "#d95f02" title "sheet: |t| - 1", \
     csv using (is("sheet","all","angle") ? $3 : NaN):(positive($4)) with points pt 8 ps 1.8 lc rgb "#d95f02" title "sheet: direction (rad)", \
     csv using (strcol(2) eq "all" && strcol(5) ne "nan" && strcol(5) ne "wrong" ? $6 : NaN):(positive($4)):($7 - $6):(0) @quartile_bars @yours_points

set output stem.'-accuracy.svg'
set terminal svg size 760,1180 font "Helvetica,13" background "white"
unset title
unset label 100
set bmargin
set multiplot layout 3,1 title "Chapter 7: the refracted direction near grazing and near the critical angle"
sweep(m, prefix, kind) = strcol(1) eq m && strcol(2)[1:strlen(prefix)] eq prefix && strcol(5) eq kind
# param "prefix:L" holds log10 of the x value; "axis:zero" is drawn at 1e-308
x(prefix) = 10**real(strcol(2)[strlen(prefix)+1:])
xg(prefix) = strcol(2) eq "axis:zero" ? 1e-308 : x(prefix)

# 1: errors as the ray into glass nears grazing, in turned frames
set logscale x
set xrange [1:1e-16]
set format x "10^{%L}"
set xtics auto
set offsets 0, 0, 0, 0
set yrange [1e-17:1e-14]
set xlabel "cos θ_{1} into glass (log scale)"
set ylabel "largest error"
set key at graph 0.02, graph 0.97 left top box opaque font ",10"
plot csv using (sweep("standard","grazing:","snell") ? x("grazing:") : NaN):(positive($4)) with linespoints pt 7 ps 0.6 lc rgb "#1b9e77" title "standard: Snell's law", \
     csv using (sweep("sheet","grazing:","snell") ? x("grazing:") : NaN):(positive($4)) with linespoints pt 6 ps 0.6 lc rgb "#d95f02" title "sheet: Snell's law", \
     csv using (sweep("standard","grazing:","unit") ? x("grazing:") : NaN):(positive($4)) with linespoints pt 5 ps 0.5 lc rgb "#66a61e" title "standard: |t| - 1", \
     csv using (sweep("sheet","grazing:","unit") ? x("grazing:") : NaN):(positive($4)) with linespoints pt 4 ps 0.5 lc rgb "#e7298a" title "sheet: |t| - 1"

# 2: the share of NaN directions, down to exactly grazing
unset logscale y
set format y "%g"
set xrange [1:1e-308]
set xtics ("1" 1, "10^{-50}" 1e-50, "10^{-100}" 1e-100, "10^{-150}" 1e-150, "10^{-200}" 1e-200, "10^{-250}" 1e-250, "10^{-300}" 1e-300, "0" 1e-308)
set yrange [-5:105]
set ytics 0, 25, 100
set xlabel "cos θ_{1} into glass (log scale; exactly 0 at the right edge)"
set ylabel "NaN directions (%)"
set key at graph 0.02, graph 0.8 left top box opaque font ",10"
plot csv using (sweep("sheet","grazing:","nan") ? x("grazing:") : NaN):(100 * $4) with linespoints pt 6 ps 0.6 lc rgb "#d95f02" title "sheet, turned frames", \
     csv using (sweep("sheet","axis:","nan") ? xg("axis:") : NaN):(100 * $4) with linespoints pt 4 ps 0.6 lc rgb "#e7298a" title "sheet, normal along an axis", \
     csv using (sweep("standard","grazing:","nan") ? x("grazing:") : NaN):(100 * $4) with linespoints pt 7 ps 0.6 lc rgb "#1b9e77" title "standard, turned frames", \
     csv using (sweep("standard","axis:","nan") ? xg("axis:") : NaN):(100 * $4) with linespoints pt 5 ps 0.6 lc rgb "#66a61e" title "standard, normal along an axis"

# 3: errors as the ray out of glass nears the critical angle
set logscale y
set format y "10^{%L}"
set ytics auto
set xrange [0.1:1e-16]
set xtics auto
set format x "10^{%L}"
set yrange [1e-17:1e-6]
set xlabel "θ_{c} − θ_{1} out of glass (radians, log scale)"
set bmargin 5
eval machine_label
set ylabel "largest error"
set key at graph 0.02, graph 0.97 left top box opaque font ",10"
plot csv using (sweep("standard","critical:","angle") ? x("critical:") : NaN):(positive($4)) with linespoints pt 9 ps 0.8 lc rgb "#1b9e77" title "standard: direction (rad)", \
     csv using (sweep("sheet","critical:","angle") ? x("critical:") : NaN):(positive($4)) with linespoints pt 8 ps 0.8 lc rgb "#d95f02" title "sheet: direction (rad)", \
     csv using (sweep("standard","critical:","snell") ? x("critical:") : NaN):(positive($4)) with linespoints pt 7 ps 0.6 lc rgb "#1b9e77" title "standard: Snell's law", \
     csv using (sweep("sheet","critical:","snell") ? x("critical:") : NaN):(positive($4)) with linespoints pt 6 ps 0.6 lc rgb "#d95f02" title "sheet: Snell's law", \
     csv using (sweep("standard","critical:","unit") ? x("critical:") : NaN):(positive($4)) with linespoints pt 5 ps 0.5 lc rgb "#66a61e" title "standard: |t| - 1", \
     csv using (sweep("sheet","critical:","unit") ? x("critical:") : NaN):(positive($4)) with linespoints pt 4 ps 0.5 lc rgb "#e7298a" title "sheet: |t| - 1"
unset multiplot
