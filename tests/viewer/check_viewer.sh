#!/usr/bin/env bash
# vsgl_viewer against vsgl_render (docs/viewer.md, "Tests"). Runs the viewer under Xvfb with
# the given arguments (a --script or --frames N --screenshot BASE) and the validation layer, in
# OUT; then renders every screenshot again with the batch command the viewer printed for it and
# requires the files the viewer named ("batch compare:") to be equal to the bit (idiff -fail 0):
# the viewer is a host of the same library, and its screenshot's .gltf and .settings carry the
# camera, lights and settings exactly. --differ A B requires screenshots A and B (bases, as the
# script names them) to differ (the step between them changed the picture); --same A B requires
# them to be equal (a step whose change was refused). --direct BASE STEM "ARGS" renders
# vsgl_render ARGS itself (a built-in scene, not the viewer's .gltf) and requires its STEM.exr
# and STEM.png to equal screenshot BASE. --stderr REGEX requires the viewer to have said it (repeatable).
#   check_viewer.sh BIN_DIR OUT [--differ A B]... [--same A B]... [--direct BASE STEM ARGS]...
#                   [--stderr REGEX]... -- VIEWER_ARGS...
set -euo pipefail
bin=$1 out=$2
shift 2
differ=()
same=()
direct=()
stderr=()
while [ "$1" != "--" ]; do
  case $1 in
    --direct) direct+=("$2|$3|$4"); shift 4 ;;
    --stderr) stderr+=("$2"); shift 2 ;;
    --differ) differ+=("$2 $3"); shift 3 ;;
    --same) same+=("$2 $3"); shift 3 ;;
    *) echo "check_viewer.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
shift
rm -rf "$out" && mkdir -p "$out" && cd "$out"
# Each test starts its own X server (-a picks a free display number).
if ! xvfb-run -a -s "-screen 0 1024x768x24" "$bin/vsgl_viewer" "$@" --validation \
     >viewer.log 2>viewer.err; then
  cat viewer.log viewer.err
  exit 1
fi
cat viewer.log viewer.err

bases=()
command=""
while IFS= read -r line; do
  case $line in
    "wrote "*) base=${line#wrote }; base=${base%%.\{exr*}; bases+=("$base") ;;
    "  batch: vsgl_render "*) command=${line#  batch: vsgl_render } ;;
    "  batch compare:"*)
      compare=${line#  batch compare:}
      [ -n "$compare" ] || continue
      # shellcheck disable=SC2086  # the command line is the viewer's words
      "$bin/vsgl_render" $command --frames 1 --validation --out render >render.log 2>&1 ||
        { cat render.log; exit 1; }
      stem=$(basename "$base")
      for suffix in $compare; do
        case $suffix in _*) mine=$base.png ;; *) mine=$base$suffix ;; esac
        idiff -fail 0 -warn 0 "$mine" "render/$stem$suffix" >idiff.log ||
          { echo "$mine differs from vsgl_render's render/$stem$suffix:"; cat idiff.log; exit 1; }
        echo "equal: $mine and vsgl_render's $stem$suffix"
      done ;;
  esac
done <viewer.log
[ ${#bases[@]} -gt 0 ] || { echo "the viewer wrote no screenshot"; exit 1; }

for pair in "${differ[@]}"; do
  set -- $pair
  if idiff -fail 0 -warn 0 "$1.exr" "$2.exr" >/dev/null; then
    echo "$2.exr equals $1.exr: the step between them changed nothing"
    exit 1
  fi
  echo "different: $1.exr and $2.exr"
done
for pair in "${same[@]}"; do
  set -- $pair
  idiff -fail 0 -warn 0 "$1.exr" "$2.exr" >idiff.log || { echo "$1 and $2 differ"; cat idiff.log; exit 1; }
  echo "equal: $1.exr and $2.exr"
done
for entry in "${direct[@]}"; do
  IFS='|' read -r base stem args <<<"$entry"
  # shellcheck disable=SC2086  # the test's words
  "$bin/vsgl_render" $args --frames 1 --validation --out direct >render.log 2>&1 ||
    { cat render.log; exit 1; }
  for suffix in .exr .png; do
    idiff -fail 0 -warn 0 "$base$suffix" "direct/$stem$suffix" >idiff.log ||
      { echo "$base$suffix differs from vsgl_render $args:"; cat idiff.log; exit 1; }
    echo "equal: $base$suffix and vsgl_render $args"
  done
done
for said in "${stderr[@]}"; do
  grep -Eq "$said" viewer.err || { echo "the viewer did not say: $said"; exit 1; }
done
