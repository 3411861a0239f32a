# Plot of docs/bench/scene.csv (written by bench_scene): median time per step
# against the number of bodies, per method, convex bodies (solid) and Puma
# link models (dashed). Regenerate with
#   gnuplot docs/bench/plot_scene.gp
# (paths are relative to this file). Output: scene.png.
# Columns: method, kind, bodies, steps_timed, median_step_ns, p90_step_ns, ...

dir = system("dirname '" . ARG0 . "'")
csv = dir . "/scene.csv"
sel(m, k) = sprintf("< awk -F, 'NR>1 && $1==\"%s\" && $2==\"%s\" && $5!=\"\" {print $3, $5, $6}' '%s'", m, k, csv)

set terminal pngcairo size 900,680 font "DejaVu Sans,10"
set output dir . "/scene.png"
set logscale xy
set grid xtics ytics mytics lc rgb "#dddddd"
set xlabel "bodies"
set ylabel "median time per step (µs)"
set format y "10^{%T}"
set offsets graph 0.05, graph 0.05, 0, 0
set key outside below maxrows 4 spacing 1.1
set title "Moving bodies, margin 0.1: every pair within the margin with its exact distance"
c_px = "#d62728"; c_f = "#1f77b4"; c_b = "#7f7f7f"
plot sel("proxima-scene", "convex") u 1:($2/1000) w lp lc rgb c_px lw 2 pt 7 dt 1 t "proxima px\\_scene, convex", \
     sel("proxima-scene-2t", "convex") u 1:($2/1000) w lp lc rgb "#ff7f0e" lw 2 pt 7 dt 1 t "proxima px\\_scene, 2 threads, convex", \
     sel("fcl-dynamic-aabb", "convex") u 1:($2/1000) w lp lc rgb c_f lw 2 pt 5 dt 1 t "FCL DynamicAABBTree + distance, convex", \
     sel("bruteforce", "convex") u 1:($2/1000) w lp lc rgb c_b lw 2 pt 9 dt 1 t "brute force all pairs, convex", \
     sel("proxima-scene", "model") u 1:($2/1000) w lp lc rgb c_px lw 2 pt 6 dt 2 t "proxima px\\_scene, Puma link models", \
     sel("proxima-scene-2t", "model") u 1:($2/1000) w lp lc rgb "#ff7f0e" lw 2 pt 6 dt 2 t "proxima, 2 threads, Puma link models", \
     sel("fcl-dynamic-aabb", "model") u 1:($2/1000) w lp lc rgb c_f lw 2 pt 4 dt 2 t "FCL, Puma link models", \
     sel("bruteforce", "model") u 1:($2/1000) w lp lc rgb c_b lw 2 pt 8 dt 2 t "brute force, Puma link models", \
     1000 w l lc rgb "#2ca02c" dt 3 t "target, 10,000 convex: 1 ms", 100 w l lc rgb "#2ca02c" dt 4 t "target, 1,000 convex: 0.1 ms"
