set terminal pngcairo size 1100,560 font 'sans,10'
set output 'table2.png'
set multiplot layout 1,2 title "Table 2: greedy rendering, paper (SGI Onyx RE2) vs MEASURED here\nAMD EPYC, 2 hardware threads, commit fe327c7"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set grid ytics
set key top left font ',8'
set xtics rotate by -20 font ',8'
set title 'rates'
set ylabel 'per second'
plot 'table2.dat' using 2:xtic(1) title 'paper tessellations/s' lc rgb '#9ecae1', '' using 3 title 'paper updates/s' lc rgb '#3182bd', '' using 4 title 'MEASURED tessellations/s' lc rgb '#a1d99b', '' using 5 title 'MEASURED updates/s' lc rgb '#31a354'
set title 'average lag (frames)'
set ylabel 'frames'
plot 'table2.dat' using 6:xtic(1) title 'paper' lc rgb '#3182bd', '' using 7 title 'MEASURED' lc rgb '#31a354'
unset multiplot
