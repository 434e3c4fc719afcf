# ch10_packets.gp: the chart of bench/ch10_packets.c's CSV.
#   gnuplot -e "csv='figures/ch10-packets.csv'; stem='figures/ch10-packets'" bench/ch10_packets.gp
# stem.svg: each form of the BVH's leaves, for every mesh and distance,
#   its time a ray as a fraction of the packets' (x, the medians) against
#   its answers: left, the rays whose answer is not the exact one, per
#   million; right, the largest relative difference of t from the exact t
#   where both hit the same triangle. Exact forms sit on the zero rows.
load "bench/chart.gp"
set terminal svg size 1100,480 font "Helvetica,12" background "white"
set output stem.'.svg'
# one row per method and case: method,case,time ratio,other answers per
# million,largest t error
join = "< awk -F, '$1 == \"hits\" && $5 == \"rays\" {n[$2] = $4} " . \
       "$1 == \"ratio\" && $5 == \"over_packets\" {split($2, a, \"@\"); r[a[1], a[2]] = $4} " . \
       "$1 == \"hits\" && $5 ~ /_other_answers$/ {m = $5; sub(/_other_answers$/, \"\", m); o[m, $2] = $4; cs[$2] = 1} " . \
       "$1 == \"hits\" && $5 ~ /_largest_t_error$/ {m = $5; sub(/_largest_t_error$/, \"\", m); e[m, $2] = $4} " . \
       "END {split(\"ch09 tightened packets float\", ms, \" \"); for (c in cs) for (k = 1; k <= 4; k++) " . \
       "printf \"%s,%s,%s,%.6g,%s\\n\", ms[k], c, r[ms[k], c], 1e6 * o[ms[k], c] / n[c], e[ms[k], c]}' ".csv." | sort"
colour(k) = word("#666666 #d95f02 #1b9e77 #7570b3", k)
point(k) = word("6 4 7 9", k) + 0
names = "ch09 tightened packets float"
title(k) = k == 1 ? "chapter 9's leaves" : k == 2 ? "tightened leaves" : \
           k == 3 ? "packets, exact" : "packets, in float (bvh-float)"
of(m) = strcol(1) eq m ? $3 : NaN
eval machine_label
set multiplot layout 1,2 title "Chapter 10: the BVH's leaves, their time against their answers (the bunny and the teapot, K = 1 and 2.5)" font ",13" margins 0.08,0.98,0.2,0.84 spacing 0.1
set xlabel "time a ray / the exact packets' time (medians)"
set xrange [0.8:1.1]
set key top right box opaque font ",9"
lo = -1
hi = 2
eval zero_axis_y
set ylabel "rays with another answer than the exact one, per million"
set title "other answers: another triangle, or a hit for a miss" font ",10"
plot for [k=1:4] join using (of(word(names, k))):(at_zero($4)) with points pt point(k) ps 1.2 \
       lc rgb colour(k) title title(k)
lo = -8
hi = -4
eval zero_axis_y
set ylabel "largest relative difference of t from the exact t"
set title "the largest error of t, where both hit the same triangle" font ",10"
unset key
plot for [k=1:4] join using (of(word(names, k))):(at_zero($5)) with points pt point(k) ps 1.2 \
       lc rgb colour(k) notitle
unset multiplot
