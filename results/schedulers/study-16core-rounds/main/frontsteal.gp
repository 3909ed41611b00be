# gnuplot script written by frontsteal; run from main: gnuplot frontsteal.gp
set terminal pngcairo size 1200,760 font 'sans,10'
set key outside right top
set grid
set output 'frontsteal-speedup.png'
set title "Paired speed-up over the serial loop (measured; per-round T1 / T(P), 95 % interval; open marks: not decided): plant:15906, 15906 surfaces\nIntel(R) Xeon(R) Processor, 16 hardware threads; 48 rounds per comparison"
set xlabel 'workers P'
set ylabel 'speed-up (T1 / T_P)'
set xrange [0.5:16.5]
set yrange [0:*]
plot for [i=0:13] 'frontsteal-speedup.dat' index i using 1:2 with lines lt 1+i%8 dt 1+i/8 title columnheader(1), \
  for [i=0:13] 'frontsteal-speedup.dat' index i using 1:2:3:4 with yerrorbars lt 1+i%8 pt 0 notitle, \
  for [i=0:13] 'frontsteal-speedup.dat' index i using 1:5 with points lt 1+i%8 pt 7 notitle, \
  for [i=0:13] 'frontsteal-speedup.dat' index i using 1:6 with points lt 1+i%8 pt 6 ps 1.5 notitle, \
  (x <= 16 ? x : 16) with lines dashtype 2 lc 'black' title 'ideal'
set output 'frontsteal-verdicts.png'
set title "Every scheduler against queue-mutex at the same P (measured): per-round time ratio to queue-mutex, 95 % interval; shaded: the +-2.0 % margin\nIntel(R) Xeon(R) Processor, 16 hardware threads; 48 rounds per comparison"
set xlabel 'time relative to queue-mutex (< 1: faster)'
unset ylabel
set ytics ("P=1 round-robin" -1, "P=1 spatial-annealing" -2, "P=1 spatial-morton" -3, "P=1 moodycamel-queue" -4, "P=1 counter-atomic" -5, "P=1 stealing/SeqCst" -6, "P=1 stealing/Fenced" -7, "P=1 stealing/Minimal" -8, "P=1 stealing/Asymmetric" -9, "P=1 chase-lev" -10, "P=1 tbb-affinity" -11, "P=1 openmp-dynamic" -12, "P=1 openmp-static-steal" -13, "P=2 round-robin" -14, "P=2 spatial-annealing" -15, "P=2 spatial-morton" -16, "P=2 moodycamel-queue" -17, "P=2 counter-atomic" -18, "P=2 stealing/SeqCst" -19, "P=2 stealing/Fenced" -20, "P=2 stealing/Minimal" -21, "P=2 stealing/Asymmetric" -22, "P=2 chase-lev" -23, "P=2 tbb-affinity" -24, "P=2 openmp-dynamic" -25, "P=2 openmp-static-steal" -26, "P=4 round-robin" -27, "P=4 spatial-annealing" -28, "P=4 spatial-morton" -29, "P=4 moodycamel-queue" -30, "P=4 counter-atomic" -31, "P=4 stealing/SeqCst" -32, "P=4 stealing/Fenced" -33, "P=4 stealing/Minimal" -34, "P=4 stealing/Asymmetric" -35, "P=4 chase-lev" -36, "P=4 tbb-affinity" -37, "P=4 openmp-dynamic" -38, "P=4 openmp-static-steal" -39, "P=8 round-robin" -40, "P=8 spatial-annealing" -41, "P=8 spatial-morton" -42, "P=8 moodycamel-queue" -43, "P=8 counter-atomic" -44, "P=8 stealing/SeqCst" -45, "P=8 stealing/Fenced" -46, "P=8 stealing/Minimal" -47, "P=8 stealing/Asymmetric" -48, "P=8 chase-lev" -49, "P=8 tbb-affinity" -50, "P=8 openmp-dynamic" -51, "P=8 openmp-static-steal" -52, "P=16 round-robin" -53, "P=16 spatial-annealing" -54, "P=16 spatial-morton" -55, "P=16 moodycamel-queue" -56, "P=16 counter-atomic" -57, "P=16 stealing/SeqCst" -58, "P=16 stealing/Fenced" -59, "P=16 stealing/Minimal" -60, "P=16 stealing/Asymmetric" -61, "P=16 chase-lev" -62, "P=16 tbb-affinity" -63, "P=16 openmp-dynamic" -64, "P=16 openmp-static-steal" -65) font 'sans,8'
set autoscale x
set yrange [-66:0]
set key outside right top
set object 1 rectangle from 0.980392, graph 0 to 1.02, graph 1 fillcolor rgb '#dddddd' fillstyle solid 0.5 noborder behind
plot for [i=0:3] 'frontsteal-verdicts.dat' index i using 1:2:3:4 with xerrorbars pt 7 lc i+1 title columnheader(1), 1/0 notitle
unset object 1
set ytics autofreq font 'sans,10'
set key outside right top
set output 'frontsteal-frames.png'
set title 'Frame time along the camera path (measured), P = 16 (frames 0-11 orbit, then zoom)'
set xlabel 'frame'
set ylabel 'ms'
set autoscale x
set yrange [0:*]
plot for [i=0:14] 'frontsteal-frames.dat' index i using 1:2 with linespoints lt 1+i%8 dt 1+i/8 pt 1+i title columnheader(1)
