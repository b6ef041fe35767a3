# accuracy.gp, written by pacifica-accuracy: draws accuracy.png from accuracy.dat
# (cd into this directory, then: gnuplot accuracy.gp)
set terminal pngcairo size 1400,900 font 'DejaVu Sans,11' noenhanced
set output 'accuracy.png'
set title "Pacifica accuracy sweep: image error vs cost - NVIDIA H200/PCIe/SSE2 (GL_TIME_ELAPSED timer query)\nfilled and joined: each model's Pareto front; references (RMSE 0) are off the log axis"
set logscale xy
set xlabel "median ms per frame (GL_TIME_ELAPSED timer query)"
set ylabel "image RMSE vs the model's reference (scene-linear RGB)"
set grid xtics ytics mxtics mytics
set key outside right top
plot 'accuracy.dat' index 0 using 1:2 with points pt 6 ps 1.3 lc rgb "#1f77b4" title "octaves", \
     '' index 1 using 1:2 with linespoints pt 7 ps 1.8 lw 1.5 lc rgb "#1f77b4" title "octaves Pareto front", \
     '' index 1 using 1:($2*1.15**($4-1)):3 with labels left offset 0.8,0 font ',9' textcolor rgb "#1f77b4" notitle, \
     'accuracy.dat' index 2 using 1:2 with points pt 6 ps 1.3 lc rgb "#2ca02c" title "gerstner", \
     '' index 3 using 1:2 with linespoints pt 7 ps 1.8 lw 1.5 lc rgb "#2ca02c" title "gerstner Pareto front", \
     '' index 3 using 1:($2*1.15**($4-1)):3 with labels left offset 0.8,0 font ',9' textcolor rgb "#2ca02c" notitle, \
     'accuracy.dat' index 4 using 1:2 with points pt 6 ps 1.3 lc rgb "#d62728" title "fft", \
     '' index 5 using 1:2 with linespoints pt 7 ps 1.8 lw 1.5 lc rgb "#d62728" title "fft Pareto front", \
     '' index 5 using 1:($2*1.15**($4-1)):3 with labels left offset 0.8,0 font ',9' textcolor rgb "#d62728" notitle
