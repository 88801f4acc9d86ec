#!/usr/bin/env bash
# Configures (Release, warnings as errors, samples on) and builds Obscura in $OBSCURA_BUILD_DIR
# (default <repo>/build). The test suite is configured unless OBSCURA_BUILD_TESTS=OFF is set in the
# environment. Arguments are build targets (default: all).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build_dir="${OBSCURA_BUILD_DIR:-$root/build}"

cmake -S "$root" -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DOBSCURA_WARNINGS_AS_ERRORS=ON \
  -DOBSCURA_BUILD_SAMPLES=ON -DOBSCURA_BUILD_TESTS="${OBSCURA_BUILD_TESTS:-ON}"
targets=()
for target in "$@"; do
  targets+=(--target "$target")
done
cmake --build "$build_dir" --parallel "$(nproc)" "${targets[@]}"
