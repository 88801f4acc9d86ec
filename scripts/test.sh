#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the test suite twice: a Release build, then a
# Debug build with AddressSanitizer + UndefinedBehaviorSanitizer (OBSCURA_SANITIZE=ON; set
# OBSCURA_SKIP_SANITIZE=1 to skip it). Extra arguments go to both ctest runs (e.g. -R Hbao).
# Tests run on Mesa's software renderer (llvmpipe) unless OBSCURA_GPU=1 is set, in which case the
# machine's GPU driver is used.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"

if [[ "${OBSCURA_GPU:-0}" != 1 ]]; then
  export EGL_PLATFORM=surfaceless LIBGL_ALWAYS_SOFTWARE=1
fi
jobs="$(nproc)"

echo "== Release build and tests"
OBSCURA_BUILD_TESTS=ON "$root/scripts/build.sh"
(cd "${OBSCURA_BUILD_DIR:-$root/build}" && ctest --output-on-failure -j "$jobs" "$@")

if [[ "${OBSCURA_SKIP_SANITIZE:-0}" != 1 ]]; then
  echo "== Debug build with AddressSanitizer + UBSan, and tests"
  asan_dir="${OBSCURA_ASAN_BUILD_DIR:-$root/build-asan}"
  cmake -S "$root" -B "$asan_dir" -DCMAKE_BUILD_TYPE=Debug -DOBSCURA_WARNINGS_AS_ERRORS=ON \
    -DOBSCURA_SANITIZE=ON -DOBSCURA_BUILD_SAMPLES=OFF -DOBSCURA_BUILD_TESTS=ON
  cmake --build "$asan_dir" --parallel "$jobs"
  (cd "$asan_dir" && ctest --output-on-failure -j "$jobs" "$@")
fi
