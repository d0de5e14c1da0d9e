# Midpoint deflection of the slider crank's rod, from the programs' CSV files:
#   mkdir -p sc-out
#   ./slider_crank --start smooth --output sc-out/defaults
#   ./slider_crank --start smooth --step 1e-4 --output sc-out/fine
#   ./simeon_reference --ini 1 --every 100 > sc-out/simeon.csv
#   gnuplot -e "dir='sc-out'" examples/slider_crank/plot.gp   (writes docs/slider_crank.png)
if (!exists("dir")) dir = 'sc-out'
set datafile separator ','
set terminal pngcairo size 1000,520 font ',11'
set output 'docs/slider_crank.png'
set lmargin 12
set xlabel 'time (s)'
set ylabel 'midpoint deflection (mm)'
set grid
set key below
set title "Flexible slider crank (Simeon 1996, IVP Test Set 'crank'): the rod's midpoint relative to its pins"
plot dir.'/simeon.csv' using 1:($2*1e3) with lines lw 4 lc rgb '#bbbbbb' title 'Test Set equations (RK4, 1e-6 s)', \
     dir.'/fine/slider_crank.csv' using 1:($2*1e3) with lines lw 2 lc rgb '#2471a3' title 'flexstress, defaults, 0.1 ms steps', \
     dir.'/defaults/slider_crank.csv' using 1:($2*1e3) with lines lw 1 lc rgb '#c0392b' title 'flexstress, defaults (1 ms steps)'
