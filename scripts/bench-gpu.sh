#!/usr/bin/env bash
# Runs the GPU benchmark table of docs/performance.md on a machine with an NVIDIA GPU and EGL.
# Usage: scripts/bench-gpu.sh BUILD_DIR OUT_DIR
#   BUILD_DIR holds bin/obscura built here with -DOBSCURA_SAMPLES_WITH_OSMESA=OFF (no Mesa needed there).
#   If .gl/ holds Debian's GLVND .debs (libegl1, libglvnd0, libopengl0 ...), they are unpacked first, for
#   driver-only machines without the GLVND dispatch libraries.
set -euo pipefail
build="${1:?build dir}"
out="${2:?output dir}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if compgen -G "$root/.gl/*.deb" > /dev/null; then
  for f in "$root"/.gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/gpu.txt" || true
bench() { "$build/bin/obscura" bench --frames 200 --warmup 20 "$@"; }
{
  bench --method hbao --method "hbao:blur=off" --method "hbao:directions=16,steps=48" \
        --size 640x360 --size 1280x720 --size 1920x1080 --size 3840x2160 --csv "$out/hbao_gb10.csv"
  bench --guard-band 0.2 --method hbao --method "hbao:directions=16,steps=48" --size 1920x1080 \
        --csv "$out/hbao_gb20.csv"
  bench --method hbao:radius=0.25 --method hbao:radius=1 --method hbao:radius=4 --size 1920x1080 \
        --csv "$out/hbao_radius.csv"
} 2>&1 | tee "$out/bench.txt"
