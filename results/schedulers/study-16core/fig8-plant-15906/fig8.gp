set terminal pngcairo size 1500,900 font 'sans,10'
set output 'fig8.png'
set multiplot layout 2,1 title "Tessellation rate against processors: lines SIMULATED (trace-driven), points MEASURED\nIntel(R) Xeon(R) Processor, 16 hardware threads, commit 66cb7b0"
set grid
set key left top font ',8'
set xlabel 'processors P'
set title 'plant:15906 (15906 surfaces)'
set ylabel 'frames per second'
plot 'fig8-0.dat' using 1:(24.1086*$1) with lines dt 2 lc 'gray40' title 'ideal (serial x P)', '' using 1:2 with lines lw 2 lc rgb '#d62728' title 'static (spatial partition) (simulated)', '' using 1:3 with lines lw 2 lc rgb '#ff7f0e' title 'global queue (mutex) (simulated)', '' using 1:4 with lines lw 2 lc rgb '#1f77b4' title 'load stealing (Fenced) (simulated)', '' using 1:5 with lines lw 2 lc rgb '#2ca02c' title 'Chase-Lev (simulated)', '' using 1:6 with points pt 5 ps 1.4 lc rgb '#d62728' title 'static (spatial partition) (measured)', '' using 1:7 with points pt 7 ps 1.4 lc rgb '#ff7f0e' title 'global queue (mutex) (measured)', '' using 1:8 with points pt 9 ps 1.4 lc rgb '#1f77b4' title 'load stealing (Fenced) (measured)', '' using 1:9 with points pt 11 ps 1.4 lc rgb '#2ca02c' title 'Chase-Lev (measured)'
set ylabel '% of ideal (serial trace x P)'
set yrange [0:110]
set key left bottom font ',8'
set title 'plant:15906: efficiency'
plot 'fig8-0.dat' using 1:(100) with lines dt 2 lc 'gray40' title 'ideal', '' using 1:(100*$2/(24.1086*$1)) with lines lw 2 lc rgb '#d62728' title 'static (spatial partition) (simulated)', '' using 1:(100*$3/(24.1086*$1)) with lines lw 2 lc rgb '#ff7f0e' title 'global queue (mutex) (simulated)', '' using 1:(100*$4/(24.1086*$1)) with lines lw 2 lc rgb '#1f77b4' title 'load stealing (Fenced) (simulated)', '' using 1:(100*$5/(24.1086*$1)) with lines lw 2 lc rgb '#2ca02c' title 'Chase-Lev (simulated)', '' using 1:(100*$6/(24.1086*$1)) with points pt 5 ps 1.4 lc rgb '#d62728' title 'static (spatial partition) (measured)', '' using 1:(100*$7/(24.1086*$1)) with points pt 7 ps 1.4 lc rgb '#ff7f0e' title 'global queue (mutex) (measured)', '' using 1:(100*$8/(24.1086*$1)) with points pt 9 ps 1.4 lc rgb '#1f77b4' title 'load stealing (Fenced) (measured)', '' using 1:(100*$9/(24.1086*$1)) with points pt 11 ps 1.4 lc rgb '#2ca02c' title 'Chase-Lev (measured)'
unset multiplot
