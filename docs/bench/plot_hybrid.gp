# Plots of docs/bench/hybrid.csv (written by bench_hybrid: seed 001 §6 timing
# experiments). Regenerate with
#   gnuplot docs/bench/plot_hybrid.gp
# from anywhere (paths are relative to this file). Output:
#   hybrid_translation.png: total time of 10^4 small translations against the
#     vertex count, with (warm) and without (cold) tracking, per method
#     (seed 001 Figures 1-2);
#   hybrid_rotation.png: mean time per query of a 50-point polyhedron under
#     continuous rotation against the rotational speed, tracking on (Figure 3).
# CSV columns: experiment,method,tracking,n,speed_deg,queries,total_ms,mean_us,max_rel_err

dir = system("dirname '" . ARG0 . "'")
csv = dir . "/hybrid.csv"

tr(m, t) = sprintf("< awk -F, '$1==\"translation\" && $2==\"%s\" && $3==\"%s\" {print $4, $7}' '%s' | sort -n", m, t, csv)
rot(m) = sprintf("< awk -F, '$1==\"rotation\" && $2==\"%s\" {print $5, $8}' '%s' | sort -g", m, csv)

set terminal pngcairo size 1100,720 font "DejaVu Sans,10"
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key outside right top spacing 1.1
c_lc = "#d62728"; c_g = "#9467bd"; c_h = "#ff7f0e"; c_f = "#1f77b4"

set output dir . "/hybrid_translation.png"
set title "Seed 001 §6 (a): 10^4 small translations of a random polyhedron past another, total time"
set logscale xy
set xlabel "vertices per polyhedron (n)"
set ylabel "total time of 10^4 queries (ms)"
plot \
  tr("lin-canny", "warm")      w lp lc rgb c_lc dt 2 pt 6 lw 2 t "lin-canny  tracking", \
  tr("lin-canny", "cold")      w lp lc rgb c_lc dt 1 pt 7 lw 2 t "lin-canny  no tracking", \
  tr("gjk", "warm")            w lp lc rgb c_g dt 2 pt 6 lw 2 t "gjk  tracking", \
  tr("gjk", "cold")            w lp lc rgb c_g dt 1 pt 7 lw 2 t "gjk  no tracking", \
  tr("hybrid", "warm")         w lp lc rgb c_h dt 2 pt 6 lw 2 t "hybrid  tracking", \
  tr("hybrid", "cold")         w lp lc rgb c_h dt 1 pt 7 lw 2 t "hybrid  no tracking", \
  tr("fcl-gjk-libccd", "cold") w lp lc rgb c_f dt 1 pt 5 t "FCL GJK (libccd)  no state"

set output dir . "/hybrid_rotation.png"
set title "Seed 001 §6 (b): 50-point polyhedron under continuous rotation, 10^4 steps, tracking on"
unset logscale y
set logscale x
set xlabel "rotational speed (degrees per step)"
set ylabel "mean time per query (µs)"
set yrange [0:*]
plot \
  rot("lin-canny")      w lp lc rgb c_lc pt 7 lw 2 t "lin-canny", \
  rot("gjk")            w lp lc rgb c_g pt 7 lw 2 t "gjk", \
  rot("hybrid")         w lp lc rgb c_h pt 7 lw 2 t "hybrid", \
  rot("fcl-gjk-libccd") w lp lc rgb c_f pt 5 t "FCL GJK (libccd, no state)"
