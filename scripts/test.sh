#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the test suite. Extra arguments go to ctest
# (e.g. scripts/test.sh -R Hbao -j4). Tests run on Mesa's software renderer (llvmpipe) unless
# OBSCURA_GPU=1 is set, in which case the machine's GPU driver is used.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
OBSCURA_BUILD_TESTS=ON "$root/scripts/build.sh"

if [[ "${OBSCURA_GPU:-0}" != 1 ]]; then
  export EGL_PLATFORM=surfaceless LIBGL_ALWAYS_SOFTWARE=1
fi
cd "${OBSCURA_BUILD_DIR:-$root/build}"
ctest --output-on-failure "$@"
