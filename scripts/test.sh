#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the test suite twice: a Release build, then a
# Debug build with AddressSanitizer + UndefinedBehaviorSanitizer (OBSCURA_SANITIZE=ON; set
# OBSCURA_SKIP_SANITIZE=1 to skip it). Extra arguments go to both ctest runs (e.g. -R Hbao).
# Then the libFuzzer targets (tests/fuzz, Clang, OBSCURA_FUZZ=ON) fuzz the settings and the render API for
# OBSCURA_FUZZ_SECONDS each (default 60, both at once): set OBSCURA_SKIP_FUZZ=1 to skip them.
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
build_dir="${OBSCURA_BUILD_DIR:-$root/build}"
# The viewer and its tests are built only where ImGui's backends (/usr/share/doc/libimgui-dev/examples, absent from
# images that drop /usr/share/doc) and xvfb-run exist: CMake then warns and leaves them out. Here that is a failure,
# not a suite that passes without them.
# (The configure's own verdict, not the binary: a stale one from an earlier configure may lie in a reused build dir.)
if ! grep -q '^OBSCURA_HAVE_VIEWER:INTERNAL=ON' "$build_dir/CMakeCache.txt" || ! command -v xvfb-run > /dev/null; then
  echo "test.sh: obscura-viewer was not built or xvfb-run is missing, so the viewer tests would not run" >&2
  exit 1
fi
(cd "$build_dir" && ctest --output-on-failure -j "$jobs" "$@")

if [[ "${OBSCURA_SKIP_SANITIZE:-0}" != 1 ]]; then
  echo "== Debug build with AddressSanitizer + UBSan, and tests"
  asan_dir="${OBSCURA_ASAN_BUILD_DIR:-$root/build-asan}"
  cmake -S "$root" -B "$asan_dir" -DCMAKE_BUILD_TYPE=Debug -DOBSCURA_WARNINGS_AS_ERRORS=ON \
    -DOBSCURA_SANITIZE=ON -DOBSCURA_BUILD_SAMPLES=OFF -DOBSCURA_BUILD_TESTS=ON
  cmake --build "$asan_dir" --parallel "$jobs"
  (cd "$asan_dir" && ctest --output-on-failure -j "$jobs" "$@")
fi

if [[ "${OBSCURA_SKIP_FUZZ:-0}" != 1 ]]; then
  # Only the fuzz targets and their ctest entries (no GoogleTest suite in this tree); a crash input lands in
  # tests/fuzz/artifacts/<target>/ of the build tree (docs/testing.md, "Fuzzing").
  echo "== libFuzzer targets (Clang, ASan + UBSan): ${OBSCURA_FUZZ_SECONDS:-60} s each"
  fuzz_dir="${OBSCURA_FUZZ_BUILD_DIR:-$root/build-fuzz}"
  CC=clang CXX=clang++ cmake -S "$root" -B "$fuzz_dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DOBSCURA_WARNINGS_AS_ERRORS=ON -DOBSCURA_FUZZ=ON -DOBSCURA_BUILD_SAMPLES=OFF -DOBSCURA_BUILD_TESTS=OFF \
    -DOBSCURA_FUZZ_SECONDS="${OBSCURA_FUZZ_SECONDS:-60}"
  cmake --build "$fuzz_dir" --parallel "$jobs"
  (cd "$fuzz_dir" && ctest --output-on-failure -L fuzz -j 2)
fi
