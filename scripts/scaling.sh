#!/usr/bin/env bash
# The scaling report (docs/performance.md, "Scaling"): every pass's GPU time from vsgl_render's
# pass table (median of FRAMES measured frames) against
#   triangles   sphere-room:N, N from 10 k to 1 M sphere triangles in the Cornell box
#   outside     sphere-room-outside:N, the same with 90 % of them outside the spot's cone
#   pixels      the Cornell box from 160x90 to 1280x720
#   rsm         the Cornell box's RSM from 64^2 to 1024^2 texels
#   vsgls       the Cornell box with 32 to 1024 VSGLs
# (320x180, 128 VSGLs, RSM 256^2, reuse off unless varied), each with the fitted growth exponent
# k of time ~ size^k per pass (least squares in log-log); and every motion of vsgl_flicker with
# reuse on and off on the Cornell box and on sphere-room:1000000.
# Writes OUT/scaling.csv (sweep,size,pass,ms), OUT/motions.csv (scene,motion,reuse,pass,ms),
# OUT/scaling.md (the tables) and, with gnuplot, OUT/scaling_<sweep>.{png,svg}.
# Usage: scripts/scaling.sh [OUT [FRAMES]] (default out/scaling, 3). About 10 minutes on two
# cores; run it on an otherwise idle machine, after scripts/build.sh. With FRAMES = report, it
# only writes the tables and charts again from OUT's CSVs.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/scaling}
frames=${2:-3}
render=./build/samples/vsgl_render
measure=true
if [ "$frames" = report ]; then
  measure=false
  frames=$(sed -nE '1s/.*, ([0-9]+) measured frames.*/\1/p' "$out/scaling.md" 2>/dev/null || true)
fi
$measure || [ -f "$out/scaling.csv" ] || { echo "scaling.sh: $out/scaling.csv not found" >&2; exit 1; }
$measure && { [ -x "$render" ] || { echo "scaling.sh: $render not found (run scripts/build.sh)" >&2; exit 1; }; }
mkdir -p "$out"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
images=$(mktemp -d)
trap 'rm -rf "$images"' EXIT

# The pass table of one run as "pass,ms" lines.
passes() {
  "$render" --out "$images" --frames "$frames" "$@" |
    sed -nE 's/^  ([a-z].*[^ ]) +([0-9]+\.[0-9]+) +[0-9]+.*$/\1,\2/p'
}

csv="$out/scaling.csv"
motions="$out/motions.csv"
# Every run: the sweeps into $csv, the motions into $motions.
measure_all() {
  echo "sweep,size,pass,ms" > "$csv"
  sweep() {  # sweep size vsgl_render-arguments...
    local name=$1 size=$2
    shift 2
    echo "scaling.sh: $name $size" >&2
    passes --reuse off "$@" | sed "s/^/$name,$size,/" >> "$csv"
  }
  for n in 10000 30000 100000 300000 1000000; do
    sweep triangles "$n" --scene "sphere-room:$n" --width 320 --height 180
    sweep outside "$n" --scene "sphere-room-outside:$n" --width 320 --height 180
  done
  for size in 160x90 320x180 640x360 1280x720; do
    sweep pixels $((${size%x*} * ${size#*x})) --scene cornell --width "${size%x*}" --height "${size#*x}"
  done
  for rsm in 64 128 256 512 1024; do
    sweep rsm $((rsm * rsm)) --scene cornell --width 320 --height 180 --rsm "$rsm"
  done
  for count in 32 64 128 256 512 1024; do
    sweep vsgls "$count" --scene cornell --width 320 --height 180 --count "$count"
  done

  echo "scene,motion,reuse,pass,ms" > "$motions"
  for scene in cornell sphere-room:1000000; do
    for motion in static orbit sweep move; do
      for reuse in on off; do
        echo "scaling.sh: $scene $motion reuse $reuse" >&2
        passes --scene "$scene" --width 320 --height 180 --motion "$motion" --reuse "$reuse" |
          sed "s/^/$scene,$motion,$reuse,/" >> "$motions"
      done
    done
  done
}
$measure && measure_all

# Tables: per sweep, one row per pass (those above 0.5 ms somewhere), one column per size, and
# the fitted exponent over all sizes and between the largest two (where fixed costs matter
# least); then the motions' frame totals and their ratio with reuse on to off.
report="$out/scaling.md"
{
  echo "# Scaling report ($(date -u +%Y-%m-%d), $frames measured frames per run, times in ms)"
  for name in triangles outside pixels rsm vsgls; do
    echo
    echo "## $name"
    echo
    awk -F, -v s="$name" '
      NR > 1 && $1 == s {
        if (!($2 in seenSize)) { seenSize[$2] = 1; sizes[++n] = $2 }
        if (!($3 in seenPass)) { seenPass[$3] = 1; names[++m] = $3 }
        ms[$2, $3] = $4
        if ($4 > peak[$3]) peak[$3] = $4
      }
      END {
        printf "| pass |"; for (i = 1; i <= n; ++i) printf " %s |", sizes[i]
        print " k, all sizes | k, largest two |"
        printf "|---|"; for (i = 1; i <= n; ++i) printf "---|"; print "---|---|"
        for (j = 1; j <= m; ++j) {
          p = names[j]
          if (peak[p] < 0.5) continue
          printf "| %s |", p
          sx = sy = sxx = sxy = count = 0
          for (i = 1; i <= n; ++i) {
            v = ((sizes[i], p) in ms) ? ms[sizes[i], p] : 0
            printf " %.3g |", v
            if (v > 0) {
              x = log(sizes[i]); y = log(v)
              sx += x; sy += y; sxx += x * x; sxy += x * y; ++count
            }
          }
          d = count * sxx - sx * sx
          if (count >= 2 && d > 0) printf " %.2f |", (count * sxy - sx * sy) / d
          else printf " — |"
          a = ((sizes[n - 1], p) in ms) ? ms[sizes[n - 1], p] : 0
          b = ((sizes[n], p) in ms) ? ms[sizes[n], p] : 0
          if (a > 0 && b > 0) printf " %.2f |\n", log(b / a) / log(sizes[n] / sizes[n - 1])
          else print " — |"
        }
      }' "$csv"
  done
  echo
  echo "## motions (module frame: gi frame; host frame: the whole frame)"
  echo
  echo "| scene | motion | gi frame, reuse on | reuse off | on / off | host frame, reuse on | reuse off |"
  echo "|---|---|---|---|---|---|---|"
  awk -F, '
    NR > 1 && ($4 == "gi frame" || $4 == "host frame") {
      key = $1 "|" $2
      if (!(key in seen)) { seen[key] = 1; keys[++n] = key }
      ms[key, $3, $4] = $5
    }
    END {
      for (i = 1; i <= n; ++i) {
        k = keys[i]; split(k, part, "|")
        on = ms[k, "on", "gi frame"]; off = ms[k, "off", "gi frame"]
        ratio = off > 0 ? on / off : 0
        printf "| %s | %s | %.3g | %.3g | %.2g | %.3g | %.3g |\n", part[1], part[2], on, off,
               ratio, ms[k, "on", "host frame"], ms[k, "off", "host frame"]
      }
    }' "$motions"
} > "$report"
echo "wrote $report, $csv and $motions" >&2

command -v gnuplot > /dev/null || {
  echo "scaling.sh: gnuplot not found (apt-get install gnuplot-nox): no charts" >&2
  exit 0
}
# Charts: log-log time against size, one line per pass above 2 ms somewhere (adaptive shading's
# levels left out: `gi vsgl shading` is their sum).
label() {
  case $1 in
    triangles) echo 'sphere triangles (all in the light and the view)' ;;
    outside) echo 'sphere triangles (90 % outside the light and the view)' ;;
    pixels) echo 'image pixels' ;;
    rsm) echo 'RSM texels' ;;
    vsgls) echo 'VSGLs' ;;
  esac
}
for name in triangles outside pixels rsm vsgls; do
  series=()
  while IFS= read -r pass; do
    file="$images/${name}_${pass// /_}.dat"
    awk -F, -v s="$name" -v p="$pass" 'NR > 1 && $1 == s && $3 == p && $4 > 0 { print $2, $4 }' \
      "$csv" > "$file"
    series+=("'$file' using 1:2 with linespoints title '$pass'")
  done < <(awk -F, -v s="$name" 'NR > 1 && $1 == s && $4 > 2 && $3 !~ / L[0-9]$/ { print $3 }' \
             "$csv" | sort -u)
  plot=$(IFS=,; echo "${series[*]}")
  for format in png svg; do
    if [ "$format" = png ]; then term="pngcairo size 1000,700"; else term="svg size 1000,700"; fi
    gnuplot <<EOF
set terminal $term
set output '$out/scaling_$name.$format'
set title "GPU time per pass against $(label "$name") (median of $frames frames, log-log)"
set xlabel '$(label $name)'
set ylabel 'ms'
set logscale xy
set grid
set key outside right font ',8'
plot $plot
EOF
  done
done
echo "wrote $out/scaling_{triangles,outside,pixels,rsm,vsgls}.{png,svg}" >&2
