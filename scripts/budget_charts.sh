#!/usr/bin/env bash
# Charts of a vsgl_budget run (docs/accuracy.md), as PNG and SVG beside its CSV:
#   <scene>_budget.{png,svg}  relMSE against the path tracer of every stage of the error budget
#                             against the VSGL count (left), and the stage's image mean over the
#                             path tracer's (right): the gap between two stages is one source
# Usage: scripts/budget_charts.sh DIR (vsgl_budget's --out). Needs gnuplot (gnuplot-nox).
set -euo pipefail
dir=${1:?usage: scripts/budget_charts.sh DIR}
csv="$dir/budget.csv"
[ -f "$csv" ] || { echo "budget_charts.sh: $csv not found (run vsgl_budget --out $dir)" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "budget_charts.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

for scene in $(tail -n +2 "$csv" | cut -d, -f1 | sort -u); do
  relmse=() mean=()
  # Stages in the order the budget lists them (first appearance in the CSV).
  for stage in $(awk -F, -v s="$scene" 'NR > 1 && $1 == s && !seen[$3]++ { print $3 }' "$csv"); do
    file="$work/${scene}_${stage}.dat"
    awk -F, -v s="$scene" -v st="$stage" 'NR > 1 && $1 == s && $3 == st { print $2, $4, $5 }' \
      "$csv" | sort -n > "$file"
    relmse+=("'$file' using 1:2 with linespoints title '$stage'")
    mean+=("'$file' using 1:3 with linespoints title '$stage'")
  done
  for term in "pngcairo noenhanced size 1200,480" "svg noenhanced size 1200,480"; do
    ext=${term%% *}; ext=${ext%cairo}
    gnuplot <<PLOT
set terminal $term
set output "$dir/${scene}_budget.$ext"
set multiplot layout 1,2 title "$scene: error budget against the path tracer"
set logscale x 2
set xlabel "VSGLs N"
set grid
unset key
set logscale y
set ylabel "relMSE"
plot $(IFS=,; echo "${relmse[*]}")
set key outside right
unset logscale y
set ylabel "image mean / path tracer's"
plot $(IFS=,; echo "${mean[*]}"), 1 with lines dashtype 2 lc rgb "black" notitle
unset multiplot
PLOT
  done
done
echo "wrote $dir/<scene>_budget.{png,svg}"
