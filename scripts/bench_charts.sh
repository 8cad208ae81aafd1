#!/usr/bin/env bash
# Charts of a vsgl_benchmark run (docs/benchmarks.md), as PNG and SVG beside its CSVs:
#   <scene>_accuracy.{png,svg}  relMSE against the module's frame time, one curve per method
#                               (and K), each point labelled with its VSGL count
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

for scene in $(tail -n +2 "$csv" | cut -d, -f1 | sort -u); do
  # Accuracy: one data block per method and K, "frame_ms relMSE count" per point.
  series=()
  while IFS= read -r key; do
    file="$work/${scene}_${key}.dat"
    awk -F, -v s="$scene" -v key="$key" 'NR > 1 && $1 == s && ($2 " K=" $4) == key {
      print $5, $11, $3 }' "$csv" | sort -n -k3 > "$file"
    series+=("'$file' using 1:2 with linespoints title '$key', '$file' using 1:2:3 with labels offset 0.8,0.6 font ',8' notitle")
  done < <(awk -F, -v s="$scene" 'NR > 1 && $1 == s { print $2 " K=" $4 }' "$csv" | sort -u)
  plot=$(IFS=,; echo "${series[*]}")

  # Passes: a table with one line per row (label, then one column per pass).
  table="$work/${scene}_passes.dat"
  awk -F, -v s="$scene" '
    NR > 1 && $1 == s {
      row = $2 " N=" $3 " K=" $4
      if (!(row in seen)) { seen[row] = 1; rows[++n] = row }
      if (!($5 in known)) { known[$5] = 1; names[++m] = $5 }
      ms[row, $5] = $6
    }
    END {
      printf "row"; for (j = 1; j <= m; ++j) printf "\t\"%s\"", names[j]; printf "\n"
      for (i = 1; i <= n; ++i) {
        printf "\"%s\"", rows[i]
        for (j = 1; j <= m; ++j) printf "\t%s", ((rows[i], names[j]) in ms) ? ms[rows[i], names[j]] : 0
        printf "\n"
      }
    }' "$passes" > "$table"
  columns=$(head -1 "$table" | awk -F'\t' '{ print NF }')

  for format in png svg; do
    if [ "$format" = png ]; then term="pngcairo size 1000,700"; else term="svg size 1000,700"; fi
    gnuplot <<EOF
set terminal $term
set output '$dir/${scene}_accuracy.$format'
set title "$scene: accuracy against time (labels: VSGL count)"
set xlabel 'module frame time (ms, median)'
set ylabel 'relMSE against the path tracer'
set logscale xy
set grid
set key outside right
plot $plot
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
  echo "wrote $dir/${scene}_accuracy.{png,svg} and $dir/${scene}_passes.{png,svg}"
done
