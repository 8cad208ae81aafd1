#!/usr/bin/env bash
# Charts of a vsgl_benchmark run (docs/benchmarks.md), as PNG and SVG beside its CSVs:
#   <scene>_accuracy.{png,svg}  relMSE against the module's frame time, one curve per method
#                               (and K), each point labelled with its VSGL count
#   <scene>_generation.{png,svg} the same against the VSGL stage's time (no VPL gather)
#   <scene>_passes.{png,svg}    the frame split into passes (medians), one stacked bar per row
# Usage: scripts/bench_charts.sh DIR (the benchmark's --out). Needs gnuplot (gnuplot-nox).
set -euo pipefail
dir=${1:?usage: scripts/bench_charts.sh DIR}
csv="$dir/benchmark.csv"
passes="$dir/benchmark_passes.csv"
for f in "$csv" "$passes"; do
  [ -f "$f" ] || { echo "bench_charts.sh: $f not found (run vsgl_benchmark --out $dir)" >&2; exit 1; }
done
command -v gnuplot >/dev/null || { echo "bench_charts.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# A curve's name: the method and K, or the method alone where K does not apply.
series_key='function series() { return ($2 ~ /^kmeans|^vpl/) ? $2 : $2 " K=" ($4 + 0) }'

# The gnuplot plot clause of relMSE (column 11) against time column $2 of scene $1: one curve per
# method and K, "time relMSE count" per point, each point labelled with its VSGL count. $3 = 1
# leaves out the VPL gather (it has no VSGL stage).
accuracy_plot() {
  local scene=$1 column=$2 skip_vpl=$3 series=() key file
  while IFS= read -r key; do
    file="$work/${scene}_${column}_${key// /_}.dat"
    awk -F, -v s="$scene" -v key="$key" -v c="$column" "$series_key"'
      NR > 1 && $1 == s && series() == key { print $c, $11, $3 }' "$csv" | sort -n -k3 > "$file"
    series+=("'$file' using 1:2 with linespoints title '$key', '$file' using 1:2:3 with labels offset 0.8,0.6 font ',8' notitle")
  done < <(awk -F, -v s="$scene" -v skip="$skip_vpl" "$series_key"'
             NR > 1 && $1 == s && !(skip && $2 == "vpl-gather") { print series() }' "$csv" | sort -u)
  (IFS=,; echo "${series[*]}")
}

for scene in $(tail -n +2 "$csv" | cut -d, -f1 | sort -u); do
  frame_plot=$(accuracy_plot "$scene" 5 0)
  generation_plot=$(accuracy_plot "$scene" 8 1)

  # Passes: a table with one line per row (label, then one column per pass). Adaptive shading
  # times its levels inside the "vsgl shading" scope: such rows stack the levels, not the total.
  table="$work/${scene}_passes.dat"
  awk -F, -v s="$scene" '
    NR > 1 && $1 == s {
      row = $2 " N=" $3 " K=" $4
      if (!(row in seen)) { seen[row] = 1; rows[++n] = row }
      if (!($5 in known)) { known[$5] = 1; names[++m] = $5 }
      ms[row, $5] = $6
      if ($5 ~ /^vsgl shading L/) levels[row] = 1
    }
    END {
      printf "row"; for (j = 1; j <= m; ++j) printf "\t\"%s\"", names[j]; printf "\n"
      for (i = 1; i <= n; ++i) {
        printf "\"%s\"", rows[i]
        for (j = 1; j <= m; ++j) {
          total = names[j] == "vsgl shading" && (rows[i] in levels)
          printf "\t%s", (!total && (rows[i], names[j]) in ms) ? ms[rows[i], names[j]] : 0
        }
        printf "\n"
      }
    }' "$passes" > "$table"
  columns=$(head -1 "$table" | awk -F'\t' '{ print NF }')

  for format in png svg; do
    if [ "$format" = png ]; then term="pngcairo size 1000,700"; else term="svg size 1000,700"; fi
    gnuplot <<EOF
set terminal $term
set output '$dir/${scene}_accuracy.$format'
set title "$scene: accuracy against time (labels: VSGL count; VPL gather: RSM side)"
set xlabel 'module frame time (ms, median)'
set ylabel 'relMSE against the path tracer'
set logscale xy
set grid
set key outside right
plot $frame_plot
EOF
    gnuplot <<EOF
set terminal $term
set output '$dir/${scene}_generation.$format'
set title "$scene: accuracy against the VSGL stage's time (labels: VSGL count)"
set xlabel 'VSGL stage time (ms, median): filtered sampling, or every k-means pass'
set ylabel 'relMSE against the path tracer'
set logscale xy
set grid
set key outside right
plot $generation_plot
EOF
    gnuplot <<EOF
set terminal $term
set output '$dir/${scene}_passes.$format'
set title "$scene: GPU time per pass (median)"
set ylabel 'ms'
set style data histograms
set style histogram rowstacked
set style fill solid 0.8 border -1
set boxwidth 0.7
set xtics rotate by -45 font ',8'
set key outside right font ',8'
set datafile separator '\t'
plot for [c=2:$columns] '$table' using c:xtic(1) title columnheader(c)
EOF
  done
  echo "wrote $dir/${scene}_accuracy.{png,svg}, $dir/${scene}_generation.{png,svg} and $dir/${scene}_passes.{png,svg}"
done
