# ch01_srgb.gp: figures/ch01-srgb.svg from the CSV of bench/ch01_srgb.c.
#   gnuplot -e "csv='figures/ch01-srgb.csv'; stem='figures/ch01-srgb'" bench/ch01_srgb.gp
# x: time per encoded channel, the median with its interquartile range;
# y: share of inputs that get a wrong 8-bit code, zero on its own row.
load "bench/chart.gp"
set terminal svg size 760,520 font "Helvetica,13" background "white"
set output stem.'.svg'
set bmargin 5
set logscale x
set xrange [0.8:30]
set format x "%g"
lo = -4
hi = 2
eval zero_axis_y
set key bottom left box opaque font ",11"
set xlabel "time per channel (ns, log scale; bars: interquartile range)"
set ylabel "inputs with a wrong 8-bit code (%, log scale)"
set title "Chapter 1: encoding sRGB, speed against accuracy"
eval machine_label
pct(f) = at_zero(100 * f)
is(m) = strcol(1) eq m && strcol(5) eq "wrong_code_fraction"
# make chart-ch01 WORKBOOK=1 passes yours (the started exercises): the
# reader's encoder, in black.
yours_points = exists("yours") ? \
  ', csv using (is("yours") ? $3 : NaN):(pct($4)) with points pt 3 ps 2 lw 2 lc rgb "#000000" title "yours (exercise 1.2)"' : ""
plot csv using (is("pow") ? $3 : NaN):(pct($4)) with points pt 7 ps 1.6 lc rgb "#1b9e77" title "exact sRGB, double pow (used)", \
     csv using (is("powf") ? $3 : NaN):(pct($4)) with points pt 5 ps 1.4 lc rgb "#66a61e" title "exact sRGB, float powf", \
     csv using (is("gamma") ? $3 : NaN):(pct($4)) with points pt 9 ps 1.6 lc rgb "#d95f02" title "pure gamma 2.2 (the sheet)", \
     csv using (is("sqrt") ? $3 : NaN):(pct($4)) with points pt 11 ps 1.6 lc rgb "#e7298a" title "gamma 2.0 (one sqrt)", \
     csv using (is("root-fit") ? $3 : NaN):(pct($4)) with points pt 13 ps 1.6 lc rgb "#7570b3" title "fit in roots (three sqrt)", \
     csv using (is("lut") ? $3 : NaN):(pct($4)) with points pt 6 ps 1.4 lc rgb "#444444" title "lookup table", \
     csv using (is("lut") ? $3 : NaN):(pct($4)):(sprintf(" %s entries", strcol(2))) with labels left offset 0.6,0 font ",10" notitle, \
     csv using (strcol(5) eq "wrong_code_fraction" ? $6 : NaN):(pct($4)):($7 - $6):(0) @quartile_bars @yours_points
