#!/usr/bin/env bash
# Per-pass GPU times (median of N measured frames after a warm-up frame) of the foundation
# passes for every built-in scene at 640x360 and 1920x1088, as a Markdown table. Run after
# scripts/build.sh, on an otherwise idle machine (lavapipe shares the CPU with everything else).
set -euo pipefail
cd "$(dirname "$0")/.."
frames="${1:-5}"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
out="$(mktemp -d)"
echo "| scene | size | raster setup | raster coverage | gbuffer resolve | shadow maps | direct light | frame |"
echo "|---|---|---|---|---|---|---|---|"
for scene in cornell atrium checker; do
  for size in 640x360 1920x1088; do
    w="${size%x*}" h="${size#*x}"
    log="$(./build/samples/vsgl_render --scene "$scene" --width "$w" --height "$h" --frames "$frames" --out "$out")"
    ms() { echo "$log" | awk -v pass="$1" '$0 ~ "^  "pass" " {print $(NF - 1)}'; }
    echo "| $scene | $size | $(ms 'raster setup') | $(ms 'raster coverage') | $(ms 'gbuffer resolve') | $(ms 'shadow maps') | $(ms 'direct light') | $(ms 'host frame') |"
  done
done
rm -rf "$out"
