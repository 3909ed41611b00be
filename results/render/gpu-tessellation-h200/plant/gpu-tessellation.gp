# gnuplot script written by frontsteal-gpu-tessellate; gnuplot gpu-tessellation.gp
set terminal pngcairo size 900,480
set output 'gpu-tessellation.png'
set datafile separator ','
set title 'Untrimmed patch tessellation rate (measured; ETER: published, other GPU)'
set xlabel 'grid n (n x n steps per patch)'
set ylabel 'triangles / s'
set logscale xy
set key bottom right
set grid
plot 'gpu-tessellation.csv' every ::1 using 1:3 with linespoints lw 2 title 'GPU (compute shader)', '' every ::1 using 1:5 with linespoints title 'CPU, all cores', '' every ::1 using 1:4 with linespoints title 'CPU, one core', '' every ::1 using 1:6 with lines dt 2 title 'ETER, published'
