# pacifica-bench-soak's curves: cd into this folder, then gnuplot soak.gp
set terminal pngcairo size 1400,1000 font 'DejaVu Sans,11' noenhanced
set output 'soak.png'
set datafile separator ','
set key autotitle columnhead
set multiplot layout 2,2 title "pacifica-bench-soak, 100000 frames at 64x36, NVIDIA H200/PCIe/SSE2"
set grid
set xlabel 'frame'
set title 'resident memory since the first sample (MiB; dashed: the bound)'
set yrange [-1:17]
first = system("sed -n 2p soak.csv | cut -d, -f3") + 0
plot 'soak.csv' using 1:($3 - first) with lines lw 2 title 'rss_mib', 16 with lines dt 2 title 'bound'
set autoscale y
set title 'GL objects alive'
plot for [c=6:13] 'soak.csv' using 1:c with steps, 'soak.csv' using 1:14 with steps lw 2
set title 'frame time, median of each sample window (ms, steady_clock around render + glFinish)'
plot 'soak.csv' using 1:5 with lines
set title 'effects and views'
plot for [c=15:18] 'soak.csv' using 1:c with steps
unset multiplot
