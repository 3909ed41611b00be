# gnuplot script written by frontsteal-mpi-simulate; run from results/distributed/plots_simulated: gnuplot hier-loss-account.gp
set terminal pngcairo size 1100,640 font 'sans,10' noenhanced
set output 'hier-loss-account.png'
set title "SIMULATED: where the workers' time went (share of ranks x threads x time), not a measurement\n200000 items/frame, light 2000 ns, heavy fifth x20"
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set yrange [0:1.05]
set ylabel 'share of the workers time'
set grid y
set xtics rotate by -30
set key outside right top
plot for [i=2:8] 'hier-loss-account.dat' using i:xtic(1) title columnheader(i)
