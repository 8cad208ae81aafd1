#!/usr/bin/env bash
# Checks a vsgl_flicker capture's flicker_summary.csv (docs/flicker.md).
#   check_flicker.sh DIR static   every figure of every method is exactly 0: nothing moved and the
#                                 pipeline is deterministic. k-means must have reached its fixed
#                                 point in the warm-up: Lloyd's cost never rises and assignments
#                                 take finitely many values, so it gets there; the test's capture
#                                 needs 38 to 40 warm-up frames (measured: 37 leave k-means 2-D and
#                                 3-D moving, 40 do not) and is given 80, twice that.
#   check_flicker.sh DIR order    modified FIS flickers less than Tok15, K = 4 less than K = 1, and
#                                 adaptive shading no more than full shading (methods tok15,
#                                 modified, modified-k4, modified-full), with margins:
#     - image flicker, modified <= 0.8 x Tok15. The capture is deterministic, so the figures repeat
#       exactly run to run; the margin is there so that a small change of scene or settings
#       cannot flip the ordering unnoticed. Measured on the test's orbit: 0.58.
#     - VSGL power change, modified <= 0.5 x Tok15 (measured 0.08: Tok15's kernels at PDF minima
#       take huge, changing power, [S3] Fig. 5).
#     - VSGL power change, K = 4 <= 0.9 x K = 1 (measured 0.59). On the image figure the two are
#       within 2 % of each other in this capture (K = 4 is steadier but blurrier, and its error
#       changes as much); docs/flicker.md has the figures.
#     - image flicker, adaptive shading (modified) <= 1.05 x every pixel shaded (modified-full):
#       its decisions must not add visible flicker. Measured 1.00 on 160 x 90 orbits and sweeps of
#       the three built-in scenes (docs/techniques/adaptive-shading.md).
set -euo pipefail
csv="${1:?usage: check_flicker.sh DIR static|order}/flicker_summary.csv"
[ -f "$csv" ] || { echo "check_flicker.sh: $csv not found" >&2; exit 1; }
cat "$csv"
case "${2:?}" in
  static)
    awk -F, 'NR > 1 { rows++; if ($2 != 0 || $3 != 0) { print "not static: " $0; bad = 1 } }
             END { if (rows == 0) { print "no methods"; exit 1 } exit bad }' "$csv" ;;
  order)
    awk -F, 'NR > 1 { image[$1] = $2; power[$1] = $3 }
      END {
        if (!("tok15" in image) || !("modified" in image) || !("modified-k4" in image) ||
            !("modified-full" in image)) {
          print "need tok15, modified, modified-k4 and modified-full"; exit 1 }
        printf "image flicker: modified / Tok15 = %.3f (<= 0.8)\n", image["modified"] / image["tok15"]
        printf "VSGL power change: modified / Tok15 = %.3f (<= 0.5)\n", power["modified"] / power["tok15"]
        printf "VSGL power change: K = 4 / K = 1 = %.3f (<= 0.9)\n", power["modified-k4"] / power["modified"]
        printf "image flicker: adaptive / full shading = %.3f (<= 1.05)\n", image["modified"] / image["modified-full"]
        exit !(image["tok15"] > 0 && image["modified"] <= 0.8 * image["tok15"] &&
               power["modified"] <= 0.5 * power["tok15"] &&
               power["modified-k4"] <= 0.9 * power["modified"] &&
               image["modified"] <= 1.05 * image["modified-full"])
      }' "$csv" ;;
  *) echo "check_flicker.sh: mode must be static or order" >&2; exit 1 ;;
esac
