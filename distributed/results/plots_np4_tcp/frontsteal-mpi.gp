# gnuplot script written by frontsteal-mpi; run from distributed/results/plots_np4_tcp: gnuplot frontsteal-mpi.gp
set terminal pngcairo size 1100,640 font 'sans,10' noenhanced
set grid
set key outside bottom center horizontal
set output 'frontsteal-mpi-frames.png'
set title "Frame time per scheduler (measured)\n4 ranks, synthetic:20000, 10 frames, commit 7b2e0e7;\nowner progress calls: MPI_Iprobe at most every 50 us (ranks span several nodes;\nosc requested: pt2pt)"
set xlabel 'frame'
set ylabel 'ms'
set yrange [0:*]
plot for [i=0:3] 'frontsteal-mpi-frames.dat' index i using 1:2 with linespoints lt 1+i pt 1+i title columnheader(1)
set output 'frontsteal-mpi-ranks.png'
set title "Busy and idle time per rank, all frames (measured)\n4 ranks, synthetic:20000, 10 frames, commit 7b2e0e7;\nowner progress calls: MPI_Iprobe at most every 50 us (ranks span several nodes;\nosc requested: pt2pt)"
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.75
set xtics rotate by -45
set ylabel 's'
set xlabel ''
unset xrange
plot 'frontsteal-mpi-ranks.dat' using 2:xtic(1) title 'busy (items)' lc rgb '#3b75af', '' using 3 title 'idle (stealing, waiting)' lc rgb '#f0a030', '' using 4 title 'rest of the frame (protocol, progress calls, preemption, barrier)' lc rgb '#c8c8c8'
