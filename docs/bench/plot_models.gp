# Plot of docs/bench/models_poses.csv (written by bench_models): time per
# pose along the approach, one panel per pair. Regenerate with
#   gnuplot docs/bench/plot_models.gp
# (paths are relative to this file). Output: models_approach.png.
# Columns: pair index, pose, s - s_contact (distance travelled relative to
# first contact; negative: before it), FCL distance, then the per-pose median
# ns of proxima triangles distance / collide, proxima part hulls distance /
# collide, FCL distance / collide. Blocks (pairs) are separated by two blank
# lines; block k's title is in models.csv's pair column, order of the run.

dir = system("dirname '" . ARG0 . "'")
dat = dir . "/models_poses.csv"
csv = dir . "/models.csv"
npairs = int(system(sprintf("awk -F, 'NR>1 && $4==\"distance\" && $1==\"fcl-obbrss\" {n++} END {print n+0}' '%s'", csv)))
pairname(k) = system(sprintf("awk -F, 'NR>1 && $4==\"distance\" && $1==\"fcl-obbrss\" {n++; if (n==%d) print $2}' '%s'", k + 1, csv))

set terminal pngcairo size 1200,380*npairs font "DejaVu Sans,10"
set output dir . "/models_approach.png"
set multiplot layout npairs,1
set logscale y
set grid xtics ytics mytics lc rgb "#dddddd"
set xlabel "travel relative to first contact (scaled units; bounding-box diagonal 1)"
set ylabel "time per query (µs)"
set format y "10^{%T}"
set key outside right top spacing 1.1
c_px = "#d62728"; c_pp = "#ff7f0e"; c_f = "#1f77b4"
do for [k=0:npairs-1] {
  set title pairname(k) . ": B approaching A (200 poses, warm proxima caches)"
  plot dat index k u 3:($5/1000) w l lc rgb c_px lw 2 dt 1 t "proxima triangles distance", \
       dat index k u 3:($6/1000) w l lc rgb c_px lw 1 dt 2 t "proxima triangles collide", \
       dat index k u 3:($7/1000) w l lc rgb c_pp lw 2 dt 1 t "proxima part hulls distance", \
       dat index k u 3:($8/1000) w l lc rgb c_pp lw 1 dt 2 t "proxima part hulls collide", \
       dat index k u 3:($9/1000) w l lc rgb c_f lw 2 dt 1 t "FCL OBBRSS distance", \
       dat index k u 3:($10/1000) w l lc rgb c_f lw 1 dt 2 t "FCL OBBRSS collide"
}
unset multiplot
