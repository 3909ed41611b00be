# gnuplot script written by frontsteal-mpi-simulate; run from results/distributed/plots_simulated: gnuplot simulated-efficiency.gp
set terminal pngcairo size 1100,640 font 'sans,10' noenhanced
set output 'simulated-efficiency.png'
set title "SIMULATED efficiency = work / (ranks x threads x time), not a measurement\n200000 items/frame, light 2000 ns, heavy fifth x20; shm = shared memory, tcp = over TCP (owner calls into MPI every 50 us)"
set logscale x 2
set xlabel 'ranks'
set ylabel 'efficiency'
set yrange [0:1.05]
set grid
set key outside right top
plot for [i=0:13] 'simulated-efficiency.dat' index i using 1:2 with linespoints lt 1+i%4 dt 1+i/4 pt 1+i title columnheader(1)
