#!/usr/bin/env bash
# Checks that the effect library alone configures, builds and installs with only the Vulkan
# loader, glslang and GLM (issue 23), and that a host builds and runs against the install: the
# lean option set in a mount namespace where every other dependency of the project (OpenImageIO,
# tinygltf, Draco, meshoptimizer, Embree, GoogleTest) is hidden behind empty directories and
# files, as on a machine without them. Needs root (unshare, bind mounts); run after
# scripts/install_deps.sh. Prints what it hid and the consumer's line; exits non-zero on failure.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" != "--inside" ]; then
  exec unshare --mount "$0" --inside
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/empty-dir"
: > "$work/empty-file"
lib=/usr/lib/x86_64-linux-gnu
for p in /usr/include/OpenImageIO "$lib"/cmake/OpenImageIO* "$lib"/cmake/TinyGLTF /usr/include/embree3 \
         "$lib"/cmake/embree* /usr/include/draco "$lib"/cmake/draco "$lib"/cmake/meshoptimizer \
         /usr/include/gtest "$lib"/cmake/GTest; do
  if [ -d "$p" ]; then mount --bind "$work/empty-dir" "$p"; echo "hidden: $p"; fi
done
for f in "$lib"/pkgconfig/OpenImageIO.pc /usr/include/tiny_gltf.h "$lib"/pkgconfig/tinygltf.pc \
         "$lib"/pkgconfig/draco.pc /usr/include/meshoptimizer.h; do
  if [ -f "$f" ]; then mount --bind "$work/empty-file" "$f"; echo "hidden: $f"; fi
done
cmake -S . -B "$work/build" -G Ninja -DVSGL_BUILD_SAMPLES=OFF -DVSGL_BUILD_TRUTH=OFF \
      -DVSGL_BUILD_TESTS=OFF -DCMAKE_INSTALL_PREFIX="$work/prefix" >/dev/null
cmake --build "$work/build" >/dev/null
cmake --install "$work/build" >/dev/null
echo "installed: $(cd "$work/prefix" && find . -type f | wc -l) files, $(cd "$work/prefix/lib" && ls *.a | tr '\n' ' ')"
cmake -S tests/consumer -B "$work/consumer" -G Ninja -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$work}"
"$work/consumer/vsgl_consumer"
