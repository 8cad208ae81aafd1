#!/usr/bin/env bash
# Charts of a vsgl_environment run (docs/techniques/environment.md, "Measured"), as PNG and SVG
# beside its CSV, in the manner of Krivanek and Colbert 2008 Fig. 3:
#   error_vs_samples.{png,svg}  left: relative RMS of diffuse + glossy against samples per pixel
#                               N, one curve per method, with an N^-1/2 guide; right: the FIS
#                               pass's GPU time against N
# Usage: scripts/env_charts.sh DIR (vsgl_environment's --out). Needs gnuplot (gnuplot-nox).
set -euo pipefail
dir=${1:?usage: scripts/env_charts.sh DIR}
csv="$dir/environment.csv"
[ -f "$csv" ] || { echo "env_charts.sh: $csv not found (run vsgl_environment --out $dir)" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "env_charts.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One data file per method: "N relative_rms ms" (CSV columns 2, 7, 3), by N.
error_plot=() time_plot=()
while IFS= read -r method; do
  file="$work/$method.dat"
  awk -F, -v m="$method" 'NR > 1 && $1 == m { print $2, $7, $3 }' "$csv" | sort -n > "$file"
  error_plot+=("'$file' using 1:2 with linespoints title '$method'")
  time_plot+=("'$file' using 1:3 with linespoints title '$method'")
done < <(awk -F, 'NR > 1 && !seen[$1]++ { print $1 }' "$csv")
# The guide: c N^-1/2 through the first row's point (the first method at its smallest N).
read -r n0 e0 < <(awk -F, 'NR == 2 { print $2, $7 }' "$csv")
guide="$e0 * sqrt($n0) / sqrt(x) with lines dashtype 2 lc rgb 'grey50' title 'N^{-1/2}'"

for format in png svg; do
  if [ "$format" = png ]; then term="pngcairo size 1200,500"; else term="svg size 1200,500"; fi
  gnuplot <<EOF
set terminal $term
set output '$dir/error_vs_samples.$format'
set multiplot layout 1,2
set title 'relative RMS error of diffuse + glossy against the reference'
set xlabel 'samples per pixel N'
set ylabel 'relative RMS (RMS / mean reference)'
set logscale xy
set grid
set key top right
plot $(IFS=,; echo "${error_plot[*]}"), $guide
set title 'GPU time of the FIS pass (median)'
set ylabel 'ms'
plot $(IFS=,; echo "${time_plot[*]}")
unset multiplot
EOF
done
echo "wrote $dir/error_vs_samples.{png,svg}"
