set terminal pngcairo size 1100,620 font 'sans,10'
set output 'table1.png'
set title "Table 1: utilization, round robin vs spatial partition\nAMD EPYC, 2 hardware threads, commit fe327c7"
set style data histograms
set style histogram clustered gap 1
set style fill solid 0.85 border -1
set boxwidth 0.9
set yrange [0:105]
set ylabel 'utilization (%)'
set key outside right top
set grid ytics
plot 'table1.dat' using 2:xtic(1) title 'paper: round robin (P=25, Pixel-Planes 5)' lc rgb '#9ecae1', '' using 3 title 'paper: graph partition (P=25)' lc rgb '#3182bd', '' using 4 title 'SIMULATED: round robin (P=25)' lc rgb '#fdae6b', '' using 5 title 'SIMULATED: spatial (P=25)' lc rgb '#e6550d', '' using 6 title 'MEASURED: round robin (P=2)' lc rgb '#a1d99b', '' using 7 title 'MEASURED: spatial (P=2)' lc rgb '#31a354'
