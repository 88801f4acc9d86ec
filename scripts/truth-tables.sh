#!/usr/bin/env bash
# Measures what docs/quality.md and docs/choosing-a-method.md report against the geometry truth: every method
# at its defaults on every built-in scene at 640x360 against the geometry truth (1024 rays) and the
# screen-space reference (64 rays); REFERENCE itself at thickness 0 / 0.1 / 0.3 / 1 m against the geometry
# truth on every scene; the atrium at 320x180, 1280x720 and 1920x1080; HBAO K=16 N=48 and FFAO SAAO on the
# atrium, clutter and terrain. One `obscura compare` JSON report per run in OUT_DIR (default truth-tables/),
# with its images beside it. Needs a built CLI (scripts/build.sh). On the 2-core llvmpipe machine it took
# 59 minutes on 2026-12-01, sharing the cores with scripts/parameter-guide.sh for the first 26; most of it is
# the screen-space references whose falloff never reaches zero (their rays run to the buffer's edge).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bin="${OBSCURA_BUILD_DIR:-$root/build}/bin/obscura"
out="${1:-truth-tables}"
if [[ "${OBSCURA_GPU:-0}" != 1 ]]; then
  export EGL_PLATFORM=surfaceless LIBGL_ALWAYS_SOFTWARE=1
fi
mkdir -p "$out"

run() {  # NAME ARGS...: one compare, its log and report under $out/NAME
  local name="$1"
  shift
  echo "== $name: obscura compare $*" >&2
  local start=$SECONDS
  "$bin" compare "$@" --out-dir "$out/$name" --json "$out/$name.json" >"$out/$name.log" 2>"$out/$name.err"
  echo "   $((SECONDS - start)) s" >&2
}

thickness="reference:rays=128:thickness=0,reference:rays=128:thickness=0.1,reference:rays=128:thickness=0.3,reference:rays=128:thickness=1"
for scene in atrium terrain objects clutter analytic room bunny; do
  run "${scene}_640x360" --scene "$scene" --size 640x360 --truth both --truth-rays 1024 --reference-rays 64
  run "${scene}_thickness" --scene "$scene" --size 640x360 --truth geometry --truth-rays 1024 --methods "$thickness"
done
run atrium_320x180 --scene atrium --size 320x180 --truth both --truth-rays 1024 --reference-rays 64
run atrium_1280x720 --scene atrium --size 1280x720 --truth both --truth-rays 512 --reference-rays 64
run atrium_1920x1080 --scene atrium --size 1920x1080 --truth geometry --truth-rays 256
# The summary's other rows: HBAO at the papers' quality setting and FFAO with SAAO, on the three scenes it shows.
for scene in atrium clutter terrain; do
  run "${scene}_640x360_more" --scene "$scene" --size 640x360 --truth geometry --truth-rays 1024 \
    --methods hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16,ffao:saao=on
done
