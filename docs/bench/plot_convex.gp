# Plots of docs/bench/convex.csv (written by bench_convex). Regenerate with
#   gnuplot docs/bench/plot_convex.gp
# from the repository root (or from anywhere: paths are relative to this file).
# Output: convex_time_vs_n.png (distance: median time per query against n,
# log-log: one line per method x mode x shape; incremental at delta = 1 %),
# convex_incremental_delta.png (lin-canny incremental medians for every delta),
# convex_methods_vs_n.png (distance: lin-canny, gjk, hybrid, FCL, scratch and
# incremental at delta = 1 %), convex_penetration_vs_n.png and
# convex_translation_vs_n.png (the other two query kinds against their peers).
# CSV columns: query,method,shape,n,mode,delta,median_ns,... (bench_convex).

dir = system("dirname '" . ARG0 . "'")
csv = dir . "/convex.csv"

# Rows of one series: query, method, shape, mode, delta ("" for scratch) -> "n median_us".
qseries(q, m, s, mode, delta) = sprintf("< awk -F, '$1==\"%s\" && $2==\"%s\" && $3==\"%s\" && $5==\"%s\" && $6==\"%s\" {print $4, $7/1000}' '%s' | sort -n", q, m, s, mode, delta, csv)
series(m, s, mode, delta) = qseries("distance", m, s, mode, delta)

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
  series("fcl-gjk-libccd", "balanced", "scratch", "")     w lp lc rgb c_t dt 1 pt 7 t "FCL tol 1e-9  scratch  balanced", \
  series("fcl-gjk-libccd", "thin", "scratch", "")         w lp lc rgb c_t dt 1 pt 5 t "FCL tol 1e-9  scratch  thin", \
  series("fcl-gjk-libccd", "balanced", "incremental", "0.01") w lp lc rgb c_t dt 2 pt 6 t "FCL tol 1e-9  incr. 1%  balanced", \
  series("fcl-gjk-libccd", "thin", "incremental", "0.01")     w lp lc rgb c_t dt 2 pt 4 t "FCL tol 1e-9  incr. 1%  thin", \
  series("fcl-gjk-libccd-tol1e-6", "balanced", "scratch", "")     w lp lc rgb c_d dt 1 pt 7 t "FCL default  scratch  balanced", \
  series("fcl-gjk-libccd-tol1e-6", "thin", "scratch", "")         w lp lc rgb c_d dt 1 pt 5 t "FCL default  scratch  thin", \
  series("fcl-gjk-libccd-tol1e-6", "balanced", "incremental", "0.01") w lp lc rgb c_d dt 2 pt 6 t "FCL default  incr. 1%  balanced", \
  series("fcl-gjk-libccd-tol1e-6", "thin", "incremental", "0.01")     w lp lc rgb c_d dt 2 pt 4 t "FCL default  incr. 1%  thin", \
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

# Distance: the three proxima methods against FCL (tolerance 1e-9).
set output dir . "/convex_methods_vs_n.png"
set title "Distance: proxima lin-canny / gjk / hybrid vs FCL 0.7 GJK (libccd, tol 1e-9); scratch (solid), incremental δ = 1% (dashed)"
set autoscale y
set format y "10^{%T}"
c_g = "#9467bd"; c_h = "#ff7f0e"
plot \
  series("lin-canny", "balanced", "scratch", "")         w lp lc rgb c_px dt 1 pt 7 lw 2 t "lin-canny  scratch  balanced", \
  series("lin-canny", "thin", "scratch", "")             w lp lc rgb c_px dt 1 pt 5 lw 2 t "lin-canny  scratch  thin", \
  series("lin-canny", "balanced", "incremental", "0.01") w lp lc rgb c_px dt 2 pt 6 lw 2 t "lin-canny  incr. 1%  balanced", \
  series("lin-canny", "thin", "incremental", "0.01")     w lp lc rgb c_px dt 2 pt 4 lw 2 t "lin-canny  incr. 1%  thin", \
  series("gjk", "balanced", "scratch", "")               w lp lc rgb c_g dt 1 pt 7 lw 2 t "gjk  scratch  balanced", \
  series("gjk", "thin", "scratch", "")                   w lp lc rgb c_g dt 1 pt 5 lw 2 t "gjk  scratch  thin", \
  series("gjk", "balanced", "incremental", "0.01")       w lp lc rgb c_g dt 2 pt 6 lw 2 t "gjk  incr. 1%  balanced", \
  series("gjk", "thin", "incremental", "0.01")           w lp lc rgb c_g dt 2 pt 4 lw 2 t "gjk  incr. 1%  thin", \
  series("hybrid", "balanced", "scratch", "")            w lp lc rgb c_h dt 1 pt 7 lw 2 t "hybrid  scratch  balanced", \
  series("hybrid", "thin", "scratch", "")                w lp lc rgb c_h dt 1 pt 5 lw 2 t "hybrid  scratch  thin", \
  series("hybrid", "balanced", "incremental", "0.01")    w lp lc rgb c_h dt 2 pt 6 lw 2 t "hybrid  incr. 1%  balanced", \
  series("hybrid", "thin", "incremental", "0.01")        w lp lc rgb c_h dt 2 pt 4 lw 2 t "hybrid  incr. 1%  thin", \
  series("fcl-gjk-libccd", "balanced", "scratch", "")    w lp lc rgb c_t dt 1 pt 7 t "FCL tol 1e-9  scratch  balanced", \
  series("fcl-gjk-libccd", "thin", "scratch", "")        w lp lc rgb c_t dt 1 pt 5 t "FCL tol 1e-9  scratch  thin"

# Penetration depth: proxima (signed query) vs FCL signed distance and libccd.
set output dir . "/convex_penetration_vs_n.png"
set title "Penetration depth from scratch: proxima (signed query) vs FCL signed distance and libccd MPR / EPA (brute-force support)"
pseries(m, s) = qseries("penetration", m, s, "scratch", "")
plot \
  pseries("lin-canny", "balanced")  w lp lc rgb c_px dt 1 pt 7 lw 2 t "lin-canny  balanced", \
  pseries("lin-canny", "thin")      w lp lc rgb c_px dt 2 pt 5 lw 2 t "lin-canny  thin", \
  pseries("gjk", "balanced")        w lp lc rgb c_g dt 1 pt 7 lw 2 t "gjk  balanced", \
  pseries("gjk", "thin")            w lp lc rgb c_g dt 2 pt 5 lw 2 t "gjk  thin", \
  pseries("hybrid", "balanced")     w lp lc rgb c_h dt 1 pt 7 lw 2 t "hybrid  balanced", \
  pseries("hybrid", "thin")         w lp lc rgb c_h dt 2 pt 5 lw 2 t "hybrid  thin", \
  pseries("fcl-signed", "balanced") w lp lc rgb c_t dt 1 pt 7 t "FCL signed  balanced", \
  pseries("fcl-signed", "thin")     w lp lc rgb c_t dt 2 pt 5 t "FCL signed  thin", \
  pseries("libccd-mpr", "balanced") w lp lc rgb c_d dt 1 pt 7 t "libccd MPR  balanced", \
  pseries("libccd-mpr", "thin")     w lp lc rgb c_d dt 2 pt 5 t "libccd MPR  thin", \
  pseries("libccd-epa", "balanced") w lp lc rgb "#8c564b" dt 1 pt 7 t "libccd EPA  balanced", \
  pseries("libccd-epa", "thin")     w lp lc rgb "#8c564b" dt 2 pt 5 t "libccd EPA  thin"

# Collision translation: px_translation vs FCL conservative advancement.
set output dir . "/convex_translation_vs_n.png"
set title "Collision translation: proxima px_translation (scratch, incremental δ = 1%) vs FCL continuousCollide (conservative advancement)"
tseries(m, s, mode, delta) = qseries("translation", m, s, mode, delta)
plot \
  tseries("raycast-advance", "balanced", "scratch", "")           w lp lc rgb c_g dt 1 pt 7 lw 2 t "px_translation  scratch  balanced", \
  tseries("raycast-advance", "thin", "scratch", "")               w lp lc rgb c_g dt 1 pt 5 lw 2 t "px_translation  scratch  thin", \
  tseries("raycast-advance", "balanced", "incremental", "0.01")   w lp lc rgb c_g dt 2 pt 6 lw 2 t "px_translation  incr. 1%  balanced", \
  tseries("raycast-advance", "thin", "incremental", "0.01")       w lp lc rgb c_g dt 2 pt 4 lw 2 t "px_translation  incr. 1%  thin", \
  tseries("fcl-ccd", "balanced", "scratch", "")       w lp lc rgb c_t dt 1 pt 7 t "FCL CA  scratch  balanced", \
  tseries("fcl-ccd", "thin", "scratch", "")           w lp lc rgb c_t dt 1 pt 5 t "FCL CA  scratch  thin", \
  tseries("fcl-ccd", "balanced", "incremental", "0.01") w lp lc rgb c_t dt 2 pt 6 t "FCL CA  incr. 1%  balanced", \
  tseries("fcl-ccd", "thin", "incremental", "0.01")   w lp lc rgb c_t dt 2 pt 4 t "FCL CA  incr. 1%  thin", \
  5 w l lc rgb "#000000" dt 3 t "target: scratch 5 µs at 200k", \
  0.5 w l lc rgb "#888888" dt 3 t "target: incremental 0.5 µs at 200k"
