set terminal pngcairo size 960,620 font ',10'
set output 'docs/bench/csg-plot.png'
set title "csg: error against time, each knob swept alone (320x180, llvmpipe (LLVM 15.0.6, 256 bits))" noenhanced
set logscale xy
set xlabel 'ms per image (median)'
set ylabel 'colour RMSE against the reference'
set key outside right top noenhanced
set grid
plot 'docs/bench/csg-plot.dat' index 0 using 1:2 with linespoints pt 7 ps 0.8 title 'max_steps', 'docs/bench/csg-plot.dat' index 1 using 1:2 with linespoints pt 7 ps 0.8 title 'hit_k', 'docs/bench/csg-plot.dat' index 2 using 1:2 with linespoints pt 7 ps 0.8 title 'step_factor', 'docs/bench/csg-plot.dat' index 3 using 1:2 with linespoints pt 7 ps 0.8 title 'over_relax', 'docs/bench/csg-plot.dat' index 4 using 1:2 with linespoints pt 7 ps 0.8 title 'linear_step', 'docs/bench/csg-plot.dat' index 5 using 1:2 with linespoints pt 7 ps 0.8 title 'step_growth', 'docs/bench/csg-plot.dat' index 6 using 1:2 with linespoints pt 7 ps 0.8 title 'binary_steps', 'docs/bench/csg-plot.dat' index 7 using 1:2 with linespoints pt 7 ps 0.8 title 'shadow_steps', 'docs/bench/csg-plot.dat' index 8 using 1:2 with linespoints pt 7 ps 0.8 title 'ao_samples', 'docs/bench/csg-plot.dat' index 9 using 1:2 with linespoints pt 7 ps 0.8 title 'bounces', 'docs/bench/csg-plot.dat' index 10 using 1:2 with linespoints pt 7 ps 0.8 title 'aniso_taps', 'docs/bench/csg-plot.dat' index 11 using 1:2 with linespoints pt 7 ps 0.8 title 'spp', 'docs/bench/csg-plot.dat' index 12 using 1:2 with linespoints pt 7 ps 0.8 title 'resolution_scale', 'docs/bench/csg-plot.dat' index 13 using 1:2 with linespoints pt 7 ps 0.8 title 'preset', 'docs/bench/csg-plot.dat' index 14 using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front'
