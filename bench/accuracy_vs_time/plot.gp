# Renders the accuracy-versus-time study from its CSV output:
#   gnuplot -e "dir='accuracy-out'" bench/accuracy_vs_time/plot.gp
# accuracy_vs_time.png: max hot-spot error against CPU time per simulated second (log-log; a
# larger step is dearer per step but needs fewer), Pareto front joined;
# histories.png: the reference hot-spot history against the paper's configuration and two fast
# ones.
if (!exists("dir")) dir = 'accuracy-out'
set datafile separator ','
f = dir.'/accuracy_vs_time.csv'

set terminal pngcairo size 1100,750 font ',10'
set output dir.'/accuracy_vs_time.png'
set title "Crane work cycle: hot-spot error against CPU time per simulated second"
set logscale xy
set grid xtics ytics mxtics mytics lc rgb '#dddddd'
set xlabel 'CPU time per simulated second, integration + stress recovery (ms/s, medians)'
set ylabel 'max |error| of the hot-spot history (% of the reference stress range)'
set key outside right top
set format y '%g'
set format x '%g'
# Column 2: knob group, 22: max error %, 30: Pareto flag, 31: CPU ms per simulated s.
grp(g) = (strcol(2) eq g && $22 > 0) ? $22 : NaN
set arrow from 5, graph 0 to 5, graph 1 nohead dt 3 lc rgb 'blue'
set label '5 us/step at h = 1 ms' at 5, graph 0.97 right offset -0.5,0 tc rgb 'blue' font ',8'
groups = "modes step integrator reduction formulation density attachment paper base scalar effects recovery newton fast"
colors = "#9400d3 #009e73 #56b4e9 #4b0082 #e69f00 #c8b400 #0072b2 #e51e10 #000000 #ff69b4 #8b4513 #00a0a0 #808000 #ff4500"
# Labels on the Pareto front and the paper's configuration only (the table has every run).
lab(x) = ($30 == 1 || strcol(2) eq 'paper') && $22 > 0 ? x : NaN
plot for [i=1:words(groups)] f skip 1 u 31:(grp(word(groups, i))) w p pt (4 + 2 * ((i - 1) % 4)) \
       lc rgb word(colors, i) ps 1.5 lw 2 t word(groups, i), \
     '< sort -t, -k31 -g '.f." | awk -F, '$30==1'" u 31:22 w l lw 2 lc rgb 'black' t 'Pareto front', \
     f skip 1 u 31:(lab($22)):1 w labels font ',8' offset 0.8,0.5 left notitle, \
     1 w l dt 2 lc rgb 'red' t '1 % of the range'

set output dir.'/histories.png'
set title "Hot-spot stress at detail D over the work cycle"
unset logscale
unset arrow
unset label
set xlabel 'time (s)'
set ylabel 'hot-spot stress (MPa)'
set key inside top right
h = dir.'/histories.csv'
plot for [c=2:5] h u 1:c w l lw (c == 2 ? 3 : 1.5) t columnheader(c)
