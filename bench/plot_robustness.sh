#!/usr/bin/env bash
# Robustness of single-shape detection (paper Fig. 4): runs bench_symmetry on three shared models with
# vertex noise and triangle deletion, prints the table and draws bench/robustness.png with gnuplot.
#   bench/plot_robustness.sh [BUILD_DIR]     (installs gnuplot-nox when it is missing)
set -euo pipefail
if ! command -v gnuplot >/dev/null; then
  sudo=""; [[ $(id -u) -eq 0 ]] || sudo="sudo"
  $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq gnuplot-nox >/dev/null
fi
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
data="$(mktemp)"
trap 'rm -f "$data"' EXIT
"$build/bench_symmetry" robustness "$here/../shared/models" "$data"
gnuplot <<PLOT
set terminal png size 1100,450
set output "$here/bench/robustness.png"
set multiplot layout 1,2 title "Angular error of the detected axis (degrees), tolerance 3% of the diagonal"
set logscale y
set format y "%.0e"
set key top left
set xlabel "vertex noise, rms, % of the bounding-box diagonal"
set ylabel "axis error (degrees)"
plot "$data" index 0 using 1:(\$2 > 0 ? \$2 : 1e-9) with linespoints title "coffee cup (mirror)", \
     "$data" index 2 using 1:(\$2 > 0 ? \$2 : 1e-9) with linespoints title "torus knot (3-fold)", \
     "$data" index 4 using 1:(\$2 > 0 ? \$2 : 1e-9) with linespoints title "menger sponge (4-fold)"
set xlabel "triangles deleted, %"
plot "$data" index 1 using 1:(\$2 > 0 ? \$2 : 1e-9) with linespoints title "coffee cup (mirror)", \
     "$data" index 3 using 1:(\$2 > 0 ? \$2 : 1e-9) with linespoints title "torus knot (3-fold)", \
     "$data" index 5 using 1:(\$2 > 0 ? \$2 : 1e-9) with linespoints title "menger sponge (4-fold)"
unset multiplot
PLOT
echo "wrote $here/bench/robustness.png"
