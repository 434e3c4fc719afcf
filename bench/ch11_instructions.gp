# ch11_instructions.gp: the chart of bench/ch11_instructions.c's CSV.
#   gnuplot -e "csv='figures/ch11-instructions.csv'; stem='figures/ch11-instructions'" bench/ch11_instructions.gp
# stem.svg: the instructions a closest-hit ray costs (callgrind's count,
#   the loop's own taken off), for the bunny's rays at K = 1, by kind of
#   ray (all, those that miss the mesh's box, those that enter it and hit
#   nothing, those that hit), in the BVH exact (bvh), decided in float
#   (fast), and in Embree; each bar labelled with its count. Where
#   Valgrind was absent (the row instructions,absent), the chart says so.
load "bench/chart.gp"
set terminal svg size 900,480 font "Helvetica,12" background "white"
set output stem.'.svg'
absent = int(system("grep -c '^instructions,absent' ".csv))
kinds = "all miss-box enter-miss hit"
methods = "bvh fast embree"
title(m) = m eq "bvh" ? "the BVH, exact" : m eq "fast" ? "the BVH in float (fast)" : "Embree 3"
colour(k) = word("#1b9e77 #7570b3 #d95f02", k)
# the count of method m on kind k (0 when absent)
count(m, k) = real(system(sprintf("awk -F, '$1 == \"instructions\" && $2 == \"%s@%s\" {print $4} END {print \"\"}' %s | head -n 1", m, k, csv)) + 0)
# the x of method j's bar in kind i's group
bar_x(i, j) = i - 1 + (j - 2) * 0.27

vector = system("awk -F, '$1 == \"vector\" {print $2}' ".csv)
eval machine_label
set label 101 "the walk's node test: ".vector at screen 0.01, screen 0.06 left noenhanced font ',9' textcolor rgb '#555555' front
set title (absent ? "Chapter 11: instructions a ray (Valgrind was absent when this chart was made)" : \
           "Chapter 11: instructions a ray by kind of ray, the bunny at K = 1 (callgrind)") font ",13"
set xrange [-0.6:3.6]
set yrange [0:*]
set ylabel "instructions a ray"
set xtics ("all rays" 0, "miss the box" 1, "enter, hit nothing" 2, "hit" 3)
set key top left
set bmargin 5
set boxwidth 0.25
set style fill solid 0.9 noborder
if (absent) { plot 1/0 notitle } else {
plot for [j=1:3] '+' using (bar_x(int($0) + 1, j)):(count(word(methods, j), word(kinds, int($0) + 1))) \
       every ::0::3 with boxes lc rgb colour(j) title title(word(methods, j)), \
     for [j=1:3] '+' using (bar_x(int($0) + 1, j)):(count(word(methods, j), word(kinds, int($0) + 1))): \
       (sprintf("%.0f", count(word(methods, j), word(kinds, int($0) + 1)))) \
       every ::0::3 with labels offset 0,0.7 font ",9" notitle
}
