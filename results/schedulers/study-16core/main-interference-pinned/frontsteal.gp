# gnuplot script written by frontsteal; run from results/schedulers/study-16core/main-interference-pinned: gnuplot frontsteal.gp
set terminal pngcairo size 1200,760 font 'sans,10'
set key outside right top
set grid
set output 'frontsteal-speedup.png'
set title "Tessellation speed-up over the serial loop (measured): plant:15906, 15906 surfaces\nIntel(R) Xeon(R) Processor, 16 hardware threads"
set xlabel 'workers P'
set ylabel 'speed-up (T1 / T_P)'
set xrange [0.5:16.5]
set yrange [0:*]
plot for [i=0:13] 'frontsteal-speedup.dat' index i using 1:2 with linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1), (x <= 16 ? x : 16) with lines dashtype 2 lc 'black' title 'ideal'
set output 'frontsteal-frames.png'
set title 'Frame time along the camera path (measured), P = 16 (frames 0-11 orbit, then zoom), interference on'
set xlabel 'frame'
set ylabel 'ms'
set autoscale x
set yrange [0:*]
plot for [i=0:14] 'frontsteal-frames.dat' index i using 1:2 with linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1)
