# Speed against error (issue 10 section 3): plot of
# docs/bench/decomposition_curves.dat, written by bench_decomp with
# decomposition.csv. Regenerate with
#   gnuplot docs/bench/plot_decomposition.gp
# (paths are relative to this file). Output: decomposition.png.
# One panel per mesh (bunny00 elephant armadillo puma-link2 puma-link4
# teapot, always in that order); per panel 5 blocks: proxima-approx,
# bullet-cd, bullet-hacd, proxima-parts, proxima-triangles (the exact
# reference: error 0, drawn as a horizontal line). Columns: probe error
# (the largest |d_model - d_exact| over 2000 fixed probe points around and
# near the mesh; bounding-box diagonal 1; errors below 1e-5 drawn at 1e-5),
# median distance time per pose on the approach (µs), pieces, and the
# approach line's own error (not drawn). A method or mesh missing from the
# run is a block of one NaN line.

dir = system("dirname '" . ARG0 . "'")
dat = dir . "/decomposition_curves.dat"
meshes = "bunny00 elephant armadillo puma-link2 puma-link4 teapot"
nmesh = words(meshes)
nblk = 5

set terminal pngcairo size 1500,900 font "DejaVu Sans,10"
set output dir . "/decomposition.png"
set multiplot layout 2,3 title "Model distance on the coherent approach (each mesh against a copy of itself): time per pose against probe error"
set logscale xy
set xrange [1e-5:1]
# Fixed, so that the panels compare and a mesh missing from the run leaves
# an empty panel rather than an error.
set yrange [0.1:300]
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set xlabel "probe error: max |d_{model}(p) - d_{exact}(p)| over 2000 points p (diagonal 1)"
set ylabel "distance time per pose, median (µs)"
set format x "10^{%T}"
set key top right font ",8" spacing 0.9
c_ap = "#d62728"; c_cd = "#1f77b4"; c_hacd = "#2ca02c"; c_pp = "#ff7f0e"; c_tri = "#7f7f7f"
do for [m=0:nmesh-1] {
  set title word(meshes, m + 1)
  b = m * nblk
  plot dat index b u 1:2 w lp lc rgb c_ap pt 7 ps 0.8 lw 2 t "proxima approximate (tolerance 0.2 .. 0.01)", \
       dat index b u 1:2:3 w labels offset 0.9,0.6 font ",7" tc rgb c_ap notitle, \
       dat index b+1 u 1:2 w lp lc rgb c_cd pt 5 ps 0.8 lw 1 t "Bullet ConvexDecomposition", \
       dat index b+1 u 1:2:3 w labels offset 0.9,-0.6 font ",7" tc rgb c_cd notitle, \
       dat index b+2 u 1:2 w lp lc rgb c_hacd pt 9 ps 0.9 lw 1 t "Bullet HACD", \
       dat index b+3 u 1:2 w p lc rgb c_pp pt 13 ps 1.2 t "one hull per part", \
       dat index b+4 u 1:2 w l lc rgb c_tri dt 2 lw 1 t "exact triangle leaves (error 0)"
}
unset multiplot
