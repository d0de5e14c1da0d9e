# Stress history of the crane's detail D from examples/crane's CSV.
#   gnuplot -e "dir='crane_output'" docs/plot_crane.gp   -> docs/crane_history.png
if (!exists("dir")) dir = 'crane_output'
if (!exists("out")) out = 'docs/crane_history.png'
set terminal pngcairo size 1000,700 font ",10"
set output out
set datafile separator ","
set multiplot layout 3,1 title "Crane work cycle: stroke, boom angle and the stress at detail D"
set grid
set ylabel "stroke (m)"
set y2label "boom angle (deg)"
set y2tics
set ytics nomirror
plot dir."/crane_history.csv" using 1:2 with lines lw 2 title "cylinder stroke", \
     "" using 1:3 axes x1y2 with lines lw 2 title "boom angle"
unset y2tics
unset y2label
set ylabel "stress (MPa)"
plot dir."/crane_history.csv" using 1:4 with lines lw 2 title "hot spot (IIW type a, toe centre)", \
     "" using 1:8 with lines lw 1 title "hot spot, max along the toe line", \
     "" using 1:(-$7) with lines lw 1 title "nominal (minus bottom flange)"
set ylabel "strain (microstrain)"
set xlabel "time (s)"
plot dir."/crane_history.csv" using 1:5 with lines lw 2 title "gauge at 0.4t", \
     "" using 1:6 with lines lw 2 title "gauge at 1.0t"
unset multiplot
