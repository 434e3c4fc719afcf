# chart.gp: what every chart of bench/ shares. Each bench/chNN_x.gp loads it
# first, after gnuplot has been given csv= (make runs gnuplot from the
# repository's root, so the path is "bench/chart.gp"):
#
#   load "bench/chart.gp"
#
# It sets up reading the CSV (commas; lines starting with '#' are comments;
# the header line has no numbers and draws nothing) and defines:
#
#   machine        the CSV's "# machine: ..." line (CPU, compiler and flags,
#                  date), printed at the bottom left of the canvas by
#   eval machine_label      (and removed again by: unset label 100)
#
#   Times. Every time is the median over interleaved rounds; draw its
#   interquartile range (columns 6 and 7 of the CSV) as a bar in dark grey
#   ON TOP of the method's mark, so that a spread narrower than the mark
#   still shows as the bar's end ticks:
#     plot ... with points ..., \
#          csv using ($6):(y):($7 - $6):(0) @quartile_bars     time along x
#          csv using (x):($6):(0):($7 - $6) @quartile_bars     time along y
#
#   Log axes on which an error can be exactly zero. A log axis has no 0, so
#   zero is drawn on a row of its own one decade below the axis, labelled
#   "0" and set off by a dotted line; no decade tick is ever a stand-in for
#   zero. Set lo and hi, the decades shown (10^lo .. 10^hi), then
#     eval zero_axis_y             y tics, range and the dotted line
#     ... using ...:(at_zero(value)) ...
#   Non-zero values below 10^lo would be clipped: choose lo below the
#   smallest possible non-zero value.
#   Log axes without a zero: format "10^{%L}" (never "%g", which writes
#   0.0001), and values of 0 dropped by positive(value).
set datafile separator ","
set datafile commentschars "#"
set grid

machine = system("sed -n 's/^# machine: //p' '".csv."' | head -n 1")
machine_label = "set label 100 'machine: '.machine at screen 0.01, screen 0.02 left noenhanced font ',9' textcolor rgb '#555555' front"

quartile_bars = 'with vectors heads size screen 0.006,90 fixed lw 1.5 lc rgb "#222222" notitle'

lo = -4
hi = 2
at_zero(v) = v == 0 ? 10.0**(lo - 1) : v
positive(v) = v > 0 ? v : NaN
zero_axis_y = "set logscale y; set yrange [10.0**(lo - 1.4):10.0**(hi + 0.35)]; " . \
  "set ytics ('0' 10.0**(lo - 1)); do for [e=lo:hi] { set ytics add (sprintf('10^{%d}', e) 10.0**e) }; " . \
  "set arrow 90 from graph 0, first 10.0**(lo - 0.5) to graph 1, first 10.0**(lo - 0.5) nohead dashtype 3 linecolor rgb '#555555' front"
