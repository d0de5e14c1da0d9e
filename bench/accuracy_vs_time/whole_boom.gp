# Renders the whole-boom reference (whole_boom_reference's CSV output):
#   gnuplot -e "dir='whole-boom-out'" bench/accuracy_vs_time/whole_boom.gp
# whole_boom.png: the sub-model's hot-spot history over the cycle (line) and, at the chosen
# instants, the hot spot of the brick model of the whole boom loaded with the same forces
# (circles), the sub-model's without and with its own inertia (crosses, pluses), and the
# force-driven sub-model's (triangles).
if (!exists("dir")) dir = 'whole-boom-out'
set datafile separator ','
set terminal pngcairo size 1100,650 font ',10'
set output dir.'/whole_boom.png'
set title "Hot spot at detail D: beam + sub-model against a brick model of the whole boom"
set grid lc rgb '#dddddd'
set xlabel 'time (s)'
set ylabel 'hot-spot stress (MPa)'
set key inside bottom center
plot dir.'/whole_boom_history.csv' skip 1 u 1:2 w l lw 1.5 lc rgb '#888888' \
       t 'sub-model with inertia, whole cycle', \
     dir.'/whole_boom.csv' skip 1 u 1:4 w p pt 6 ps 2 lw 2 lc rgb '#e51e10' t 'whole boom, bricks', \
     '' skip 1 u 1:2 w p pt 2 ps 1.2 lw 2 lc rgb '#0072b2' t 'sub-model (paper: no sub-model inertia)', \
     '' skip 1 u 1:3 w p pt 1 ps 1.2 lw 2 lc rgb '#009e73' t 'sub-model with inertia', \
     '' skip 1 u 1:9 w p pt 8 ps 1.5 lw 2 lc rgb '#9400d3' t 'force-driven sub-model (crane --force-driven)'
