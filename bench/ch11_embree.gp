# ch11_embree.gp: the chart of bench/ch11_embree.c's CSV.
#   gnuplot -e "csv='figures/ch11-embree.csv'; stem='figures/ch11-embree'" bench/ch11_embree.gp
# stem.svg: left, what each step of chapters 10 and 11 is worth on the bunny at
#   K = 1: the rays per second of every method, in the order the chapter
#   takes them, Embree's last (bars: the median of interleaved rounds;
#   error bars: the rates of the time's interquartile range, 1e3/q3 to
#   1e3/q1; numbers: the rate as a fraction of Embree's at HIGH, its
#   spatial-split build; MEDIUM is Embree's default build); middle, the
#   program's BVH (of the default width) and kd-tree as fractions of
#   Embree's rate, closest hit, for every mesh and distance (points:
#   Embree's own MEDIUM build, the same way); right, the
#   same for shadow rays (any hit, against rtcOccluded1). Where Embree was
#   absent (the CSV has the row embree,absent: make chart-embree-absent),
#   only chapter 8's rates are drawn, and the chart says so.
load "bench/chart.gp"
set grid noxtics ytics
set terminal svg size 1250,520 font "Helvetica,12" background "white"
set bmargin 6.5
set output stem.'.svg'
absent = int(system("grep -c '^embree,absent' ".csv))
# the program's default width's BVH (bvh4 in CSVs older than the row)
default = system("awk -F, '$5 == \"default_method\" {print $2}' ".csv)
default = default eq "" ? "bvh4" : default
# the bunny's closest-hit methods at K = 1, in the file's order: "name rate"
steps = system("awk -F, '$2 == \"bunny-1.0\" && $5 == \"mrays_per_s\" && $1 !~ /-any$/ {printf \"%s \", $1}' ".csv)
step(k) = word(steps, k)
label(m) = m eq "kdtree-ch08" ? "kd-tree\nch. 8" : m eq "kdtree" ? "kd-tree\ntight" : \
           m eq "bvh4-double" ? "BVH4\ncopies" : m eq "bvh4-double-mesh" ? "BVH4\nof mesh" : \
           m eq "bvh2" ? "BVH2" : m eq "bvh4" ? "BVH4" : m eq "bvh8" ? "BVH8" : \
           m eq "fast" ? "BVH".default[4:]."\nin float" : \
           m eq "embree" ? "Embree\nHIGH" : m eq "embree-medium" ? "Embree\nMED." : m
in_steps(m) = strstrt(" ".steps, " ".m." ") > 0
step_x(m) = in_steps(m) ? sum [k=1:words(steps)] (step(k) eq m ? k - 1 : 0) : NaN
is(m, k) = strcol(1) eq m && strcol(5) eq k
cases = "bunny-1.0 bunny-2.5 teapot-1.0 teapot-2.5 scanned-1.0 scanned-2.5 needles-1.0 slivers-1.0"
case_x(s) = strstrt(" ".cases." ", " ".s." ") > 0 ? sum [k=1:words(cases)] (word(cases, k) eq s ? k - 1 : 0) : NaN
ratio_of(m, s) = strcol(1) eq "ratio" && strcol(5) eq "over_embree" && strcol(2) eq m."@".s
# the ratio rows of method m: x of its case, shifted
ratio_x(m, shift) = strcol(1) eq "ratio" && strcol(5) eq "over_embree" && \
                    strcol(2)[1:strlen(m) + 1] eq m."@" ? case_x(strcol(2)[strlen(m) + 2:]) + shift : NaN
ours = "#1b9e77"
kd = "#d95f02"
theirs = "#7570b3"
set style fill solid 0.85 noborder

eval machine_label
set multiplot layout 1,3 title (absent ? "Chapter 11: chapter 8's kd-tree (Embree was absent when this chart was made)" : "Chapter 11: each step against Embree 3 (HIGH builds; MEDIUM, its default, beside), the same rays, one thread each") font ",14" margins 0.06,0.99,0.22,0.82 spacing 0.06
set boxwidth 0.7
set xrange [-0.6:words(steps) - 0.4]
set yrange [0:*]
set offsets 0, 0, graph 0.15, 0
set xtics () font ",8"
do for [k=1:words(steps)] { set xtics add (label(step(k)) k - 1) }
set ylabel "million closest-hit rays per second (bars: interquartile range)"
vector = system("awk -F, '$1 == \"vector\" {print $2}' ".csv)
set title "the bunny at K = 1, step by step".(absent ? "" : "; numbers: the rate / Embree's")."\nnode tests in ".(vector eq "" ? "double" : vector) font ",10"
plot csv using (is(strcol(1), "mrays_per_s") && strcol(2) eq "bunny-1.0" && strcol(1)[1:6] ne "embree" ? step_x(strcol(1)) : NaN):4 with boxes lc rgb ours notitle, \
     csv using (is(strcol(1), "mrays_per_s") && strcol(2) eq "bunny-1.0" && strcol(1)[1:6] eq "embree" ? step_x(strcol(1)) : NaN):4 with boxes lc rgb theirs notitle, \
     csv using (is(strcol(1), "mrays_per_s") && strcol(2) eq "bunny-1.0" ? step_x(strcol(1)) : NaN):(1e3 / $7):(0):(1e3 / $6 - 1e3 / $7) @quartile_bars, \
     csv using (strcol(1) eq "ratio" && strcol(5) eq "over_embree" && strcol(2)[strlen(strcol(2)) - 9:] eq "@bunny-1.0" ? step_x(strcol(2)[1:strlen(strcol(2)) - 10]) : NaN):(0.5):(sprintf("%.2f", $4)) with labels font ",9" tc rgb "white" notitle

set boxwidth 0.36
set xrange [-0.6:words(cases) - 0.4]
set yrange [0:*]
# room above the bars for the key
set offsets 0, 0, graph 0.4, 0
set xtics ("bunny\n1" 0, "bunny\n2.5" 1, "teapot\n1" 2, "teapot\n2.5" 3, "scan\n1" 4, "scan\n2.5" 5, "needle\n1" 6, "sliver\n1" 7) font ",8"
set xlabel "mesh, and K" font ",9"
set ylabel "rate / Embree's rate (medians)"
set key top right box opaque font ",9"
set title "closest hit, every mesh" font ",10"
plot csv using (ratio_x(default, -0.19)):4 with boxes lc rgb ours title "BVH, ".default[4:]." wide", \
     csv using (ratio_x("kdtree", 0.19)):4 with boxes lc rgb kd title "kd-tree, tight leaves", \
     csv using (ratio_x("embree-medium", 0)):4 with points pt 7 ps 0.9 lc rgb theirs title "Embree, MEDIUM", \
     1 with lines dt 2 lc rgb theirs title "Embree, HIGH"

set title "shadow rays (any hit), against rtcOccluded1" font ",10"
set xrange [-0.6:5.6]
plot csv using (ratio_x("bvh-any", -0.19)):4 with boxes lc rgb ours title "BVH, any hit", \
     csv using (ratio_x("kdtree-any", 0.19)):4 with boxes lc rgb kd title "kd-tree, any hit", \
     1 with lines dt 2 lc rgb theirs title "Embree"
unset multiplot

# stem-exactness.svg: what exactness costs. For every mesh and K, each
# method's rate as a fraction of Embree's (HIGH) along x, and along y, on
# log axes with a row for zero: left, the rays whose answer is not the
# exact one (another triangle, or a hit for a miss), per million rays;
# right, the largest relative difference of t from the exact t, over the
# rays that hit the exact answer's triangle (another triangle is counted
# on the left, as another answer).
# The program's default BVH is exact by construction (its rows say it
# agrees with the kd-tree on every ray): it sits on the zero rows.
if (!absent) {
reset
load "bench/chart.gp"
set terminal svg size 1000,460 font "Helvetica,12" background "white"
set output stem.'-exactness.svg'
set bmargin 5
# method,case,rate/Embree,other answers per million rays,largest t error
join = "< awk -F, '$1 == \"hits\" && $5 == \"rays\" {n[$2] = $4} " . \
       "$1 == \"ratio\" && $5 == \"over_embree\" {split($2, a, \"@\"); r[a[1], a[2]] = $4} " . \
       "$1 == \"hits\" && $5 ~ /_other_answers$/ {m = $5; sub(/_other_answers$/, \"\", m); o[m, $2] = $4; cs[$2] = 1} " . \
       "$1 == \"hits\" && $5 ~ /_largest_t_error$/ {m = $5; sub(/_largest_t_error$/, \"\", m); e[m, $2] = $4} " . \
       "END {for (c in cs) {printf \"default,%s,%s,0,0\\n\", c, r[\"default\", c]; " . \
       "printf \"embree,%s,1,%.6g,%s\\n\", c, 1e6 * o[\"embree\", c] / n[c], e[\"embree\", c]; " . \
       "split(\"fast embree-medium\", ms, \" \"); for (k = 1; k <= 2; k++) " . \
       "printf \"%s,%s,%s,%.6g,%s\\n\", ms[k], c, r[ms[k], c], 1e6 * o[ms[k], c] / n[c], e[ms[k], c]}}' ".csv." | sort"
ours = "#1b9e77"
theirs = "#7570b3"
eval machine_label
set multiplot layout 1,2 title "Chapter 11: what exactness costs, every mesh and distance, the same rays" font ",14" margins 0.08,0.98,0.2,0.84 spacing 0.1
set xlabel "rate / Embree's rate, HIGH (medians)"
set xrange [0:*]
set key top left box opaque font ",9"
of(m) = strcol(1) eq m ? $3 : NaN
lo = -1
hi = 3
eval zero_axis_y
set ylabel "rays with another answer than the exact one, per million"
set title "other answers: another triangle, or a hit for a miss" font ",10"
plot join using (of("default")):(at_zero($4)) with points pt 7 ps 1.1 lc rgb ours title "BVH, exact (the default)", \
     join using (of("fast")):(at_zero($4)) with points pt 9 ps 1.3 lc rgb ours title "BVH, in float (bvh-float)", \
     join using (of("embree")):(at_zero($4)) with points pt 5 ps 1.0 lc rgb theirs title "Embree, HIGH", \
     join using (of("embree-medium")):(at_zero($4)) with points pt 4 ps 1.0 lc rgb theirs title "Embree, MEDIUM"
lo = -8
hi = -2
eval zero_axis_y
set ylabel "largest relative difference of t from the exact t"
set title "the largest error of t, where both hit the same triangle" font ",10"
unset key
plot join using (of("default")):(at_zero($5)) with points pt 7 ps 1.1 lc rgb ours notitle, \
     join using (of("fast")):(at_zero($5)) with points pt 9 ps 1.3 lc rgb ours notitle, \
     join using (of("embree")):(at_zero($5)) with points pt 5 ps 1.0 lc rgb theirs notitle, \
     join using (of("embree-medium")):(at_zero($5)) with points pt 4 ps 1.0 lc rgb theirs notitle
unset multiplot
}
