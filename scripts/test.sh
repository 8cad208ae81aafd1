#!/usr/bin/env bash
# The whole test suite: install what is missing, build, run every test with CTest. GPU tests
# run on lavapipe under the Khronos validation layer (any validation message fails a test) and
# are skipped, with the reason, when no Vulkan device exists.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install_deps.sh
scripts/build.sh -DVSGL_BUILD_TESTS=ON
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout 600
