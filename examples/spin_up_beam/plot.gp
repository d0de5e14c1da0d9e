# Tip deflection of the spin-up beam, from the example's CSV:
#   gnuplot -e "dir='spin-up-out'" examples/spin_up_beam/plot.gp   (writes docs/spin_up_beam.png)
if (!exists("dir")) dir = 'spin-up-out'
set datafile separator ','
set terminal pngcairo size 1000,560 font ',11'
set output 'docs/spin_up_beam.png'
set multiplot layout 2,1
set lmargin 12
set ylabel 'tip deflection (m)'
set yrange [-1:1]
set grid
set key top right
set title 'Spin-up beam (Kane et al. 1987): in-plane tip deflection relative to the hub'
plot dir.'/spin_up.csv' using 1:3 with lines lw 2 lc rgb '#c0392b' title 'linear, hub frame (diverges)', \
     '' using 1:5 with lines lw 2 lc rgb '#e67e22' title 'linear, floating frame', \
     '' using 1:4 with lines lw 3 lc rgb '#2471a3' title 'geometric stiffening, hub frame', \
     '' using 1:6 with lines lw 1 dt 2 lc rgb '#111111' title 'geometric stiffening, floating frame'
unset title
set yrange [*:*]
set xlabel 'time (s)'
set ylabel 'hub rate (rad/s)'
plot dir.'/spin_up.csv' using 1:2 with lines lw 2 lc rgb '#555555' notitle
unset multiplot
