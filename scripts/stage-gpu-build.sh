#!/usr/bin/env bash
# Builds Obscura for a GPU machine without Mesa (no OSMesa backend) in build-gpu/ and stages what
# scripts/bench-gpu.sh needs into .device-build/ (git-ignored; the device tool carries it).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cmake -S "$root" -B "$root/build-gpu" -DCMAKE_BUILD_TYPE=Release -DOBSCURA_SAMPLES_WITH_OSMESA=OFF \
  -DOBSCURA_BUILD_TESTS=ON > /dev/null
cmake --build "$root/build-gpu" --parallel "$(nproc)"
stage="$root/.device-build"
rm -rf "$stage"
mkdir -p "$stage/bin" "$stage/tests" "$stage/lib"
cp "$root/build-gpu/bin/obscura" "$stage/bin/"
cp "$root"/build-gpu/tests/obscura_{gl,pass,unit}_tests "$stage/tests/"
# The shared libraries Debian's packages give this machine and a driver-only GPU machine lacks: tinyobjloader, and
# Embree with its TBB (the geometry truth, linked into the CLI since 2026-12-01).
ldd "$root/build-gpu/bin/obscura" "$root/build-gpu/tests/obscura_gl_tests" |
  awk '/tinyobjloader|embree|libtbb/ {print $3}' | sort -u | xargs -r cp -L -t "$stage/lib/"
# The GL tests find the goldens through OBSCURA_GOLDEN_DIR, which bench-gpu.sh sets to the checkout's.
du -sh "$stage"
