#!/usr/bin/env bash
# The main job: install what is missing, build, render the default built-in scene to out/
# (linear EXR + tone-mapped PNG) and print per-pass GPU times. Arguments go to vsgl_render.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh
# The Vulkan loader and Mesa warn when XDG_RUNTIME_DIR is unset (containers, CI); we render
# offscreen, so any private directory will do.
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
./build/samples/vsgl_render "$@"
