#!/usr/bin/env bash
# What each way of making VSGLs costs in code, like [S3]'s Table 3: compute shaders, dispatches
# per frame, and lines of GLSL and C++. Usage: scripts/code_size.sh [BUILD_DIR] (default build).
#
# What is counted (docs/techniques/kmeans.md "Code size"):
# - A method's own stage only, from the attribute pyramids' level 0 to the VSGL records; the
#   passes every method shares (RSM, attributes, BRSM, ISM, shading) are left out.
# - Shaders: the compute shaders that stage dispatches. GLSL lines: those shaders and every file
#   they include (once per method), non-blank lines that are not only a comment. Tok15 and
#   modified FIS share vsgl_generate.comp; each is charged the other rule's functions less.
# - C++ lines: the host files of those passes, same rule.
# - Dispatches: counted while vsgl_render records one frame after a warm-up frame (k-means
#   starts from the previous frame's centres, so its seeding pass is not in it) at the default
#   RSM of 256^2 (the mip passes dispatch once per level and pyramid: 6 x 8) and the default
#   4 k-means iterations; the image size does not change them.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
render="$build/samples/vsgl_render"
[ -x "$render" ] || { echo "code_size.sh: $render not found (build first)" >&2; exit 1; }

# Non-blank lines of the given files that hold code, not only a comment.
code_lines() {
  awk '
    {
      line = $0
      if (inblock) { if (sub(/.*\*\//, "", line)) inblock = 0; else next }
      while (match(line, /\/\*/)) {
        rest = substr(line, RSTART + 2)
        if (match(rest, /\*\//)) line = substr(line, 1, RSTART - 1) substr(rest, RSTART + 2)
        else { line = substr(line, 1, RSTART - 1); inblock = 1 }
      }
      sub(/\/\/.*/, "", line)
      if (line ~ /[^ \t]/) n++
    }
    END { print n + 0 }' "$@"
}

# Code lines of the definition of function $2 in file $1 (from its signature to its closing
# brace).
function_lines() {
  awk -v name="$2" '
    !inside && $0 ~ "^[A-Za-z].*[ \t]" name "\\(" { inside = 1 }
    inside {
      print
      opened += gsub(/\{/, "{"); closed += gsub(/\}/, "}")
      if (opened > 0 && opened == closed) exit
    }' "$1" | code_lines
}

# The shaders and every file they include, transitively (paths under shaders/).
with_includes() {
  local pending=("$@") seen=() f inc
  while [ ${#pending[@]} -gt 0 ]; do
    f=${pending[0]}
    pending=("${pending[@]:1}")
    [[ " ${seen[*]} " == *" $f "* ]] && continue
    seen+=("$f")
    for inc in $(sed -n 's/^#include "\(.*\)"/\1/p' "shaders/$f"); do
      # Relative to shaders/, or to the including file's folder (shared/ headers).
      [ -f "shaders/$inc" ] || inc="$(dirname "$f")/$inc"
      pending+=("$inc")
    done
  done
  printf '%s\n' "${seen[@]}"
}

# Dispatches of the VSGL stage in one frame of `vsgl_render --method $1`.
dispatches() {
  local out
  out=$(mktemp -d)
  "$render" --scene cornell --width 32 --height 18 --rsm 256 --count 64 --frames 1 --warmup 1 \
    --method "$1" --reuse off --out "$out" |
    awk '$1 == "gi" && ($2 == "filtered" || $2 == "attribute" || $2 == "k-means") { n += $NF }
         END { print n + 0 }'
  rm -rf "$out"
}

fis_shaders=(gi/mip_reduce.comp gi/vsgl_generate.comp)
fis_cpp=(gi/src/passes/mip_pyramid.h gi/src/passes/mip_pyramid.cpp gi/src/passes/vsgl_generate.h
         gi/src/passes/vsgl_generate.cpp)
kmeans_shaders=(gi/mip_reduce.comp gi/kmeans_seed.comp gi/kmeans_assign.comp gi/kmeans_fill.comp
                sort/radix_histogram.comp sort/radix_scan.comp sort/radix_scatter.comp
                gi/kmeans_bounds.comp gi/kmeans_sum.comp)
kmeans_cpp=(gi/src/passes/mip_pyramid.h gi/src/passes/mip_pyramid.cpp gi/src/passes/kmeans.h
            gi/src/passes/kmeans.cpp engine/include/engine/radix_sort.h engine/src/radix_sort.cpp)

glsl_lines() {
  local files=()
  mapfile -t files < <(with_includes "$@")
  code_lines "${files[@]/#/shaders/}"
}

fis_glsl=$(glsl_lines "${fis_shaders[@]}")
generate=shaders/gi/vsgl_generate.comp
tok15_only=$(function_lines "$generate" tok15Level)
modified_only=$(( $(function_lines "$generate" kernelMass) + $(function_lines "$generate" modifiedFisLevel) ))
kmeans_glsl=$(glsl_lines "${kmeans_shaders[@]}")

echo "| method | compute shaders | dispatches per frame | GLSL lines | C++ lines |"
echo "|---|---|---|---|---|"
echo "| Tok15 FIS | ${#fis_shaders[@]} | $(dispatches tok15) | $((fis_glsl - modified_only)) | $(code_lines "${fis_cpp[@]}") |"
echo "| modified FIS | ${#fis_shaders[@]} | $(dispatches modified) | $((fis_glsl - tok15_only)) | $(code_lines "${fis_cpp[@]}") |"
for m in kmeans-2d kmeans-3d; do
  echo "| $m | ${#kmeans_shaders[@]} | $(dispatches $m) | $kmeans_glsl | $(code_lines "${kmeans_cpp[@]}") |"
done
