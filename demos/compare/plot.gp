# SPDX-License-Identifier: MIT
# Accuracy against cost from rope_compare's PREFIX.dat (see rope_compare.cpp writePlotData).
# gnuplot -e "data='results.dat'; out='accuracy_vs_cost.png'" demos/compare/plot.gp
if (!exists("data")) data = 'demos/compare/results.dat'
if (!exists("out")) out = 'demos/compare/accuracy_vs_cost.png'
set terminal pngcairo size 1400,560 font ",11"
set output out
set multiplot layout 1,2 title "Accuracy against cost (each point: one resolution / solver setting; lower left is better)"
set logscale xy
set grid
set xlabel "wall time per simulated second, s (median)"
set ylabel "|error|, % (floored at 0.001 %)"
set key top right
set arrow 1 from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc rgb "#888888"
set title "(1) catenary, slack 1.25: sag vs analytic catenary"
plot data index 0 using 1:2 with points pt 7 ps 1.6 lc rgb "#d62728" title "SplineRope", \
     data index 1 using 1:2 with points pt 5 ps 1.2 lc rgb "#1f77b4" title "Bullet soft body", \
     data index 2 using 1:2 with points pt 9 ps 1.4 lc rgb "#2ca02c" title "MuJoCo chain"
set title "(2) heavy load, 10 kg on 1 m / 10 g: strain vs W/(EA) (soft body ~24000 %: load on the ground)"
plot data index 3 using 1:2 with points pt 7 ps 1.6 lc rgb "#d62728" title "SplineRope", \
     data index 4 using 1:2 with points pt 5 ps 1.2 lc rgb "#1f77b4" title "Bullet soft body", \
     data index 5 using 1:2 with points pt 9 ps 1.4 lc rgb "#2ca02c" title "MuJoCo chain (100 %: rigid links)"
unset multiplot
