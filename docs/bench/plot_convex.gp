# Plots of docs/bench/convex.csv (written by bench_convex). Regenerate with
#   gnuplot docs/bench/plot_convex.gp
# from the repository root (or from anywhere: paths are relative to this file).
# Output: convex_time_vs_n.png (median time per query against n, log-log: one
# line per method x mode x shape; incremental at delta = 1 %) and
# convex_incremental_delta.png (lin-canny incremental medians for every delta).

dir = system("dirname '" . ARG0 . "'")
csv = dir . "/convex.csv"

# Rows of one series: method, shape, mode, delta ("" for scratch) -> "n median_us".
series(m, s, mode, delta) = sprintf("< awk -F, '$1==\"%s\" && $2==\"%s\" && $4==\"%s\" && $5==\"%s\" {print $3, $6/1000}' '%s' | sort -n", m, s, mode, delta, csv)

set terminal pngcairo size 1100,720 font "DejaVu Sans,10"
set logscale xy
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set xlabel "vertices per polytope (n)"
set ylabel "median time per query (µs)"
set key outside right top spacing 1.1
set format y "10^{%T}"
set xrange [150:260000]

# line colour per method, dash per mode, point type per shape
c_px = "#d62728"; c_t = "#1f77b4"; c_d = "#2ca02c"

set output dir . "/convex_time_vs_n.png"
set title "Distance between two convex polytopes (ellipsoid hulls): proxima Lin-Canny vs FCL 0.7 GJK (libccd)"
plot \
  series("lin-canny", "balanced", "scratch", "")           w lp lc rgb c_px dt 1 pt 7 lw 2 t "lin-canny  scratch  balanced", \
  series("lin-canny", "thin", "scratch", "")               w lp lc rgb c_px dt 1 pt 5 lw 2 t "lin-canny  scratch  thin", \
  series("lin-canny", "balanced", "incremental", "0.01")   w lp lc rgb c_px dt 2 pt 6 lw 2 t "lin-canny  incr. 1%  balanced", \
  series("lin-canny", "thin", "incremental", "0.01")       w lp lc rgb c_px dt 2 pt 4 lw 2 t "lin-canny  incr. 1%  thin", \
  series("fcl-gjk-tol1e-9", "balanced", "scratch", "")     w lp lc rgb c_t dt 1 pt 7 t "FCL tol 1e-9  scratch  balanced", \
  series("fcl-gjk-tol1e-9", "thin", "scratch", "")         w lp lc rgb c_t dt 1 pt 5 t "FCL tol 1e-9  scratch  thin", \
  series("fcl-gjk-tol1e-9", "balanced", "incremental", "0.01") w lp lc rgb c_t dt 2 pt 6 t "FCL tol 1e-9  incr. 1%  balanced", \
  series("fcl-gjk-tol1e-9", "thin", "incremental", "0.01")     w lp lc rgb c_t dt 2 pt 4 t "FCL tol 1e-9  incr. 1%  thin", \
  series("fcl-gjk-default", "balanced", "scratch", "")     w lp lc rgb c_d dt 1 pt 7 t "FCL default  scratch  balanced", \
  series("fcl-gjk-default", "thin", "scratch", "")         w lp lc rgb c_d dt 1 pt 5 t "FCL default  scratch  thin", \
  series("fcl-gjk-default", "balanced", "incremental", "0.01") w lp lc rgb c_d dt 2 pt 6 t "FCL default  incr. 1%  balanced", \
  series("fcl-gjk-default", "thin", "incremental", "0.01")     w lp lc rgb c_d dt 2 pt 4 t "FCL default  incr. 1%  thin", \
  0.15 w l lc rgb "#888888" dt 3 t "target: incremental 0.15 µs", \
  (log(x) / log(200))**2 w l lc rgb "#000000" dt 3 t "target: scratch 1 µs · (log n / log 200)^2"

set output dir . "/convex_incremental_delta.png"
set title "proxima Lin-Canny, incremental (warm cache): median time per query by step size δ"
set yrange [0.05:10]
set format y "%g"
plot \
  series("lin-canny", "balanced", "incremental", "0.01")    w lp lc rgb "#d62728" pt 7 t "δ = 1%  balanced", \
  series("lin-canny", "balanced", "incremental", "0.005")   w lp lc rgb "#ff7f0e" pt 7 t "δ = 0.5%  balanced", \
  series("lin-canny", "balanced", "incremental", "0.0025")  w lp lc rgb "#9467bd" pt 7 t "δ = 0.25%  balanced", \
  series("lin-canny", "balanced", "incremental", "0.00125") w lp lc rgb "#17becf" pt 7 t "δ = 0.125%  balanced", \
  series("lin-canny", "thin", "incremental", "0.01")        w lp lc rgb "#d62728" dt 2 pt 5 t "δ = 1%  thin", \
  series("lin-canny", "thin", "incremental", "0.005")       w lp lc rgb "#ff7f0e" dt 2 pt 5 t "δ = 0.5%  thin", \
  series("lin-canny", "thin", "incremental", "0.0025")      w lp lc rgb "#9467bd" dt 2 pt 5 t "δ = 0.25%  thin", \
  series("lin-canny", "thin", "incremental", "0.00125")     w lp lc rgb "#17becf" dt 2 pt 5 t "δ = 0.125%  thin", \
  0.15 w l lc rgb "#888888" dt 3 t "target 0.15 µs"
