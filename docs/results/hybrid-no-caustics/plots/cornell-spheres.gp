set terminal png size 900,520
set logscale x
set grid
set key outside right
set xlabel 'frame time (ms, median)'
set output 'plots/cornell-spheres-error-vs-time.png'
set title 'cornell-spheres: error against frame time'
set ylabel 'HDR-FLIP (full image)'
set y2label 'RMSE (indirect layer)'
set ytics nomirror
set y2tics
plot 'plots/cornell-spheres.dat' using 2:3 with points pt 7 ps 1.5 title 'HDR-FLIP (full)', \
     '' using 2:4 axes x1y2 with points pt 5 ps 1.5 title 'RMSE (indirect)', \
     '' using 2:3:1 with labels offset 0,1 font ',8' notitle
unset y2tics
unset y2label
set ytics mirror
set output 'plots/cornell-spheres-pareto.png'
set title 'cornell-spheres: Pareto front, methods x presets'
set ylabel 'HDR-FLIP (full)'
plot 'plots/cornell-spheres.dat' using 2:3 with points pt 7 ps 1.5 title 'method/preset', \
     '' using 2:3:1 with labels offset 0,1 font ',8' notitle, \
     'plots/cornell-spheres-pareto.dat' using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', \
     'plots/cornell-spheres-pareto.dat' using 1:2 with points pt 6 ps 2.5 lc rgb 'black' notitle
