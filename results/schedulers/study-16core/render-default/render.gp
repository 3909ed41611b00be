# gnuplot script written by frontsteal-render; run from results/schedulers/study-16core/render-default: gnuplot render.gp
set terminal pngcairo size 900,420
set output 'render-lag.png'
set datafile separator ','
set title 'Greedy rendering: lag of the drawn triangles behind the view (measured)'
set xlabel 'pusher update'
set ylabel 'lag (frames)'
set key top left
plot 'render.csv' every ::1 using 1:4 with lines lw 2 title 'mean over components', '' every ::1 using 1:5 with lines title 'max'
