#!/usr/bin/env bash
# Installs the Debian 12 packages the build, the renderer and the tests need, only when one is
# missing (so a warm machine skips apt entirely). Runs apt-get as root, or through sudo.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config        # build
  libvulkan-dev mesa-vulkan-drivers       # Vulkan loader + lavapipe (software device)
  vulkan-validationlayers                 # Khronos validation layer (tests)
  glslang-tools spirv-tools               # GLSL -> SPIR-V, spirv-val
  libglm-dev                              # math
  libtinygltf-dev nlohmann-json3-dev      # glTF scenes
  libdraco-dev libmeshoptimizer-dev       # glTF KHR_draco_mesh_compression, EXT_meshopt_compression
  libopenimageio-dev                      # EXR / PNG / texture I/O
  libembree-dev                           # ray tracing for the CPU ground truth (gi/truth)
  libglfw3-dev libimgui-dev libstb-dev    # the interactive viewer: window, input, panel
  xvfb xauth                              # a display for the viewer's tests (xvfb-run)
  openimageio-tools                       # idiff: the viewer's tests compare images
  gnuplot-nox                             # the benchmark's charts (scripts/bench_charts.sh)
  time                                    # peak memory in scripts/load_bench.sh
  libgtest-dev                            # tests
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "installing: ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "error: need root or sudo to install ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
