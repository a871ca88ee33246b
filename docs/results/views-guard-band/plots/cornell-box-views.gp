set terminal png size 900,520
set grid
set key outside right
set output 'plots/cornell-box-views-distribution.png'
set title 'cornell-box: HDR-FLIP over 100 views'
set xlabel 'fraction of views'
set ylabel 'HDR-FLIP (full image)'
plot 'plots/cornell-box-views-sorted.dat' index 0 using 1:2 with linespoints title 'direct', \
    'plots/cornell-box-views-sorted.dat' index 1 using 1:2 with linespoints title 'isr-medium'
set output 'plots/cornell-box-views-error-vs-time.png'
set logscale x
set title 'cornell-box: mean HDR-FLIP over views against frame time'
set xlabel 'frame time (ms, median over views)'
set ylabel 'HDR-FLIP (full), mean +- sd'
plot 'plots/cornell-box-views-summary.dat' using 2:3:4 with yerrorbars pt 7 title 'method/preset', \
     '' using 2:3:1 with labels offset 0,1 font ',8' notitle
