set terminal pngcairo size 960,620 font ',10'
set output 'docs/bench/mandelbulb-plot.png'
set title "mandelbulb: error against time, each knob swept alone (320x180, llvmpipe (LLVM 15.0.6, 256 bits))" noenhanced
set logscale xy
set xlabel 'ms per image (median)'
set ylabel 'colour RMSE against the reference'
set key outside right top noenhanced
set grid
plot 'docs/bench/mandelbulb-plot.dat' index 0 using 1:2 with linespoints pt 7 ps 0.8 title 'max_steps', 'docs/bench/mandelbulb-plot.dat' index 1 using 1:2 with linespoints pt 7 ps 0.8 title 'hit_k', 'docs/bench/mandelbulb-plot.dat' index 2 using 1:2 with linespoints pt 7 ps 0.8 title 'step_factor', 'docs/bench/mandelbulb-plot.dat' index 3 using 1:2 with linespoints pt 7 ps 0.8 title 'over_relax', 'docs/bench/mandelbulb-plot.dat' index 4 using 1:2 with linespoints pt 7 ps 0.8 title 'iterations', 'docs/bench/mandelbulb-plot.dat' index 5 using 1:2 with linespoints pt 7 ps 0.8 title 'shadow_steps', 'docs/bench/mandelbulb-plot.dat' index 6 using 1:2 with linespoints pt 7 ps 0.8 title 'ao_samples', 'docs/bench/mandelbulb-plot.dat' index 7 using 1:2 with linespoints pt 7 ps 0.8 title 'spp', 'docs/bench/mandelbulb-plot.dat' index 8 using 1:2 with linespoints pt 7 ps 0.8 title 'resolution_scale', 'docs/bench/mandelbulb-plot.dat' index 9 using 1:2 with linespoints pt 7 ps 0.8 title 'preset', 'docs/bench/mandelbulb-plot.dat' index 10 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'
