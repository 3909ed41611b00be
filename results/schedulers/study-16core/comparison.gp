set terminal pngcairo size 1600,900 font 'sans,10'
set output 'comparison.png'
set multiplot layout 1,4 title "Simulator prediction (lines, SIMULATED before the run) against the 16-core measurement (points with 95 % intervals, MEASURED)"
set key top left
set grid
set xlabel 'P (workers)'
set xrange [0:17]
set title 'main job: plant:15906'
set ylabel 'speed-up over the serial loop'
plot x with lines lc rgb '#bbbbbb' title 'ideal', 'comparison.dat' index 0 using 1:2:3:4 with yerrorbars lc 1 pt 7 title 'spatial-annealing measured', '' index 0 using 1:5 with lines lc 1 dt 2 title 'spatial-annealing predicted', 'comparison.dat' index 1 using 1:2:3:4 with yerrorbars lc 2 pt 7 title 'queue-mutex measured', '' index 1 using 1:5 with lines lc 2 dt 2 title 'queue-mutex predicted', 'comparison.dat' index 2 using 1:2:3:4 with yerrorbars lc 3 pt 7 title 'stealing/Fenced measured', '' index 2 using 1:5 with lines lc 3 dt 2 title 'stealing/Fenced predicted', 'comparison.dat' index 3 using 1:2:3:4 with yerrorbars lc 4 pt 7 title 'chase-lev measured', '' index 3 using 1:5 with lines lc 4 dt 2 title 'chase-lev predicted'
set title 'fig8: plant:10604'
set ylabel 'frames/s over the same scheduler at P = 1'
plot x with lines lc rgb '#bbbbbb' title 'ideal', 'comparison.dat' index 4 using 1:2:3:4 with yerrorbars lc 1 pt 7 title 'spatial-annealing measured', '' index 4 using 1:5 with lines lc 1 dt 2 title 'spatial-annealing predicted', 'comparison.dat' index 5 using 1:2:3:4 with yerrorbars lc 2 pt 7 title 'queue-mutex measured', '' index 5 using 1:5 with lines lc 2 dt 2 title 'queue-mutex predicted', 'comparison.dat' index 6 using 1:2:3:4 with yerrorbars lc 3 pt 7 title 'stealing/Fenced measured', '' index 6 using 1:5 with lines lc 3 dt 2 title 'stealing/Fenced predicted', 'comparison.dat' index 7 using 1:2:3:4 with yerrorbars lc 4 pt 7 title 'chase-lev measured', '' index 7 using 1:5 with lines lc 4 dt 2 title 'chase-lev predicted'
set title 'fig8: plant:15906'
set ylabel 'frames/s over the same scheduler at P = 1'
plot x with lines lc rgb '#bbbbbb' title 'ideal', 'comparison.dat' index 8 using 1:2:3:4 with yerrorbars lc 1 pt 7 title 'spatial-annealing measured', '' index 8 using 1:5 with lines lc 1 dt 2 title 'spatial-annealing predicted', 'comparison.dat' index 9 using 1:2:3:4 with yerrorbars lc 2 pt 7 title 'queue-mutex measured', '' index 9 using 1:5 with lines lc 2 dt 2 title 'queue-mutex predicted', 'comparison.dat' index 10 using 1:2:3:4 with yerrorbars lc 3 pt 7 title 'stealing/Fenced measured', '' index 10 using 1:5 with lines lc 3 dt 2 title 'stealing/Fenced predicted', 'comparison.dat' index 11 using 1:2:3:4 with yerrorbars lc 4 pt 7 title 'chase-lev measured', '' index 11 using 1:5 with lines lc 4 dt 2 title 'chase-lev predicted'
set title 'fig8: plant:5302'
set ylabel 'frames/s over the same scheduler at P = 1'
plot x with lines lc rgb '#bbbbbb' title 'ideal', 'comparison.dat' index 12 using 1:2:3:4 with yerrorbars lc 1 pt 7 title 'spatial-annealing measured', '' index 12 using 1:5 with lines lc 1 dt 2 title 'spatial-annealing predicted', 'comparison.dat' index 13 using 1:2:3:4 with yerrorbars lc 2 pt 7 title 'queue-mutex measured', '' index 13 using 1:5 with lines lc 2 dt 2 title 'queue-mutex predicted', 'comparison.dat' index 14 using 1:2:3:4 with yerrorbars lc 3 pt 7 title 'stealing/Fenced measured', '' index 14 using 1:5 with lines lc 3 dt 2 title 'stealing/Fenced predicted', 'comparison.dat' index 15 using 1:2:3:4 with yerrorbars lc 4 pt 7 title 'chase-lev measured', '' index 15 using 1:5 with lines lc 4 dt 2 title 'chase-lev predicted'
unset multiplot
