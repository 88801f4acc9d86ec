#!/usr/bin/env bash
# Runs the GPU benchmark table of docs/performance.md on a machine with an NVIDIA GPU and EGL.
# Usage: scripts/bench-gpu.sh BUILD_DIR OUT_DIR
#   BUILD_DIR holds bin/obscura built here with -DOBSCURA_SAMPLES_WITH_OSMESA=OFF (no Mesa needed there).
#   If .gl/ holds Debian's GLVND .debs (libegl1, libglvnd0, libopengl0 ...), they are unpacked first, for
#   driver-only machines without the GLVND dispatch libraries.
# The scene is the demo room (--scene room), the one docs/performance.md was measured on; the clock is
# the SDK's GL timer queries (bench reports "clock": "gpu-timer" in its JSON).
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
bench() { "$build/bin/obscura" bench --scene room --frames 200 --warmup 20 "$@"; }
{
  bench --methods hbao,hbao:blur=off,hbao:directions=16:steps=48 \
        --sizes 640x360,1280x720,1920x1080,3840x2160 --csv "$out/hbao_gb10.csv" --json "$out/hbao_gb10.json"
  bench --guard-band 0.2 --methods hbao,hbao:directions=16:steps=48 --sizes 1920x1080 \
        --csv "$out/hbao_gb20.csv" --json "$out/hbao_gb20.json"
  bench --methods hbao:radius=0.25,hbao:radius=1,hbao:radius=4 --sizes 1920x1080 \
        --csv "$out/hbao_radius.csv" --json "$out/hbao_radius.json"
} 2>&1 | tee "$out/bench.txt"
