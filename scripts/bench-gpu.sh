#!/usr/bin/env bash
# Runs the GPU checks of docs/performance.md on a machine with an NVIDIA GPU and EGL (the lent H100).
# Usage: scripts/bench-gpu.sh BUILD_DIR OUT_DIR [tests] [bench] [lsao] [lsao-error] [ffao]
#   BUILD_DIR holds bin/obscura (and tests/obscura_*_tests for "tests") built on an x86-64 Debian machine
#   with -DOBSCURA_SAMPLES_WITH_OSMESA=OFF (no Mesa needed there), and lib/ with the shared libraries the
#   GPU machine lacks (tinyobjloader, Embree, TBB). scripts/stage-gpu-build.sh prepares it.
#   If .gl/ holds Debian's GLVND .debs (libegl1, libglvnd0, libopengl0 ...), they are unpacked first, for
#   driver-only machines without the GLVND dispatch libraries.
#   tests: the GL, pass and unit test executables on the GPU (goldens are read from the path they were built
#          with, which is linked to this checkout when it does not exist).
#   bench: every method at 1920x1080 + 10 % guard band per side (2304x1296 texels), and the LSAO scaling runs.
#   lsao:  the LSAO sweep variants (segments, warm-up strides and tolerances, hull sizes) at 1920x1080.
#   lsao-error: the AO error each sweep variant costs against whole lines and the exact sweep, per scene.
#   table: every method and preset at 720p / 1080p / 4K, each at half and quarter resolution, the temporal
#          pass still and moving; table_summary.txt has one line per configuration.
#   ffao:  FFAO at 1920x1080: the default 16x2, SAAO 18x2 (the issue's H100 target, <= 0.6 ms), the mipmap
#          baseline, B0 = 5 / 10 / 20 (Table 3), the radius, the sizes of Table 1, per kernel (Tables 2, 4).
# The clock is the SDK's GL timer queries (bench reports "clock": "gpu-timer" in its JSON).
# Every step runs to its end (one failing command does not hide the others' results); the exit status is non-zero
# when any command of any step failed.
set -uo pipefail
build="$(cd "${1:?build dir}" && pwd)" || { echo "bench-gpu.sh: no build directory '$1'" >&2; exit 2; }
out="${2:?output dir}"
shift 2
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if compgen -G "$root/.gl/*.deb" > /dev/null; then
  for f in "$root"/.gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
export LD_LIBRARY_PATH="$build/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export OBSCURA_GL_BACKEND=egl-device
mkdir -p "$out"
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv | tee "$out/gpu.txt" || true
# BENCH_FRAMES, BENCH_WARMUP, TABLE_SIZES and TABLE_SIZE shrink the runs for a dry run on llvmpipe (defaults: the GPU's).
bench() { "$build/bin/obscura" bench --frames "${BENCH_FRAMES:-200}" --warmup "${BENCH_WARMUP:-20}" "$@"; }
status=0
# Runs a command and records a failure in `status`, in this shell: the steps write their output to files and show
# them afterwards, since a group piped into tee runs in a subshell, which would lose the assignment.
run() { "$@" || { echo "FAILED ($?): $*" >&2; status=1; }; }
table_sizes="${TABLE_SIZES:-1280x720,1920x1080,3840x2160}"
table_size="${TABLE_SIZE:-1920x1080}"
for what in "$@"; do
  case "$what" in
    tests)
      # The goldens of this checkout (the tests' compiled-in path is the staging machine's).
      export OBSCURA_GOLDEN_DIR="$root/tests/golden"
      for t in obscura_unit_tests obscura_pass_tests obscura_gl_tests; do
        # A test binary missing from the staged build is a failure, not a pass.
        [[ -x "$build/tests/$t" ]] || { echo "== $t: missing from $build/tests" >&2; status=1; continue; }
        echo "== $t"
        "$build/tests/$t" --gtest_brief=1 > "$out/$t.txt" 2>&1 || status=1
        grep -E '^\[  (PASSED|FAILED) |^\[  FAILED  \]|tests ran' "$out/$t.txt" | head -40
      done
      if [[ -d /tmp/obscura-golden-failures ]]; then
        tar czf "$out/golden_failures.tgz" -C /tmp obscura-golden-failures
      fi
      ;;
    bench)
      {
        run bench --scene atrium --sizes 1920x1080 \
              --methods hbao,hbao:steps=12:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16,hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16,sao,lsao,lsao:preset=k16:tangent_strategy=fixed,lsao:preset=3,lsao:preset=4,lsao:exact=on,gtao,gtao:thickness_mode=bitmask,gtao:preset=low,gtao:preset=medium,gtao:preset=ultra \
              --json "$out/methods_1080.json"
        run bench --scene atrium --sizes 1280x720,2560x1600,3840x2160 --methods hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16,sao,lsao \
              --json "$out/methods_sizes.json"
        run bench --scene atrium --sizes 1920x1080 --methods lsao:radius=0.1,lsao:radius=1,lsao:radius=10 \
              --json "$out/lsao_radius.json"
      } > "$out/bench.txt" 2>&1
      cat "$out/bench.txt"
      ;;
    ffao)
      {
        run bench --scene atrium --sizes 1920x1080 \
              --methods ffao,ffao:saao=on,ffao:saao=on:saao_blur=off,ffao:sectors=18,ffao:segments=1,ffao:geometry=2,ffao:base_interval=5,ffao:base_interval=20,ffao:radius=0.1,ffao:radius=10,ffao:thickness=0.3,hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16,lsao \
              --json "$out/ffao_1080.json"
        run bench --scene atrium --sizes 1280x720,2560x1600,3840x2160 --methods ffao,ffao:saao=on \
              --json "$out/ffao_sizes.json"
      } > "$out/ffao_full.txt" 2>&1
      grep -E '^[a-z].* @ |total|ffao_|z_pyramid|blur|GPU memory|FAILED' "$out/ffao_full.txt" | tee "$out/ffao.txt"
      ;;
    lsao)
      # Sweep parallelism: whole lines vs segments of several lengths and warm-up tolerances.
      run bench --scene atrium --sizes 1920x1080 \
            --methods lsao:segment_steps=-1,lsao,lsao:segment_steps=64,lsao:segment_steps=256,lsao:warmup_stride=1,lsao:warmup_stride=2,lsao:warmup_stride=8,lsao:warmup_stride=16,lsao:warmup_tolerance=0.01,lsao:warmup_tolerance=0.2,lsao:hull_capacity=16,lsao:hull_capacity=64,lsao:hull_capacity=16:segment_steps=-1,lsao:hull_capacity=64:segment_steps=-1,lsao:hull_capacity=16:warmup_stride=8,lsao:hull_capacity=32,lsao:radius=0.1,lsao:radius=10,lsao:radius=10:warmup_stride=8,lsao:preset=k16:tangent_strategy=fixed,lsao:preset=3,lsao:preset=4,hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16,hbao,sao \
            --json "$out/lsao.json" > "$out/lsao_full.txt" 2>&1
      grep -E '^[a-z].* @ |total|line_sweep|gather|FAILED' "$out/lsao_full.txt" | tee "$out/lsao.txt"
      ;;
    lsao-error)
      # What the segments cost against whole-line sweeps and the exact (brute-force) sweep, per scene, at
      # 1920x1080: mean absolute difference of the AO images (obscura diff).
      mkdir -p "$out/img"
      variants=(lsao:exact=on lsao:segment_steps=-1 lsao lsao:warmup_stride=1 lsao:warmup_stride=8 lsao:warmup_tolerance=0.2 lsao:hull_capacity=16 lsao:hull_capacity=32 lsao:hull_capacity=64)
      for scene in atrium terrain objects clutter analytic room; do
        for v in "${variants[@]}"; do
          name="${scene}_$(echo "$v" | tr ':=' '__')"
          "$build/bin/obscura" render --scene "$scene" --size 1920x1080 --method "$v" --out "$out/img/$name.png" \
            > /dev/null 2>&1 || { echo "render $name failed"; status=1; }
        done
        for v in "${variants[@]:1}"; do
          name="${scene}_$(echo "$v" | tr ':=' '__')"
          for ref in lsao_exact_on lsao_segment_steps_-1; do
            rm -f "$out/img/d.json"
            # diff exits 1 where the images differ beyond its tolerance (expected here), 2 where it cannot compare.
            "$build/bin/obscura" diff "$out/img/$name.png" "$out/img/${scene}_$ref.png" --json "$out/img/d.json" \
              > /dev/null 2>&1
            diff_status=$?
            if [[ $diff_status -le 1 && -s "$out/img/d.json" ]]; then
              printf '%-9s %-32s vs %-22s %s\n' "$scene" "$v" "$ref" "$(tr -d '\n ' < "$out/img/d.json" | grep -o '"mean_abs":[0-9.e-]*')"
            else
              printf '%-9s %-32s vs %-22s diff failed (%d)\n' "$scene" "$v" "$ref" "$diff_status"
              status=1
            fi
          done
        done
      done > "$out/lsao_error.txt" 2>&1
      cat "$out/lsao_error.txt"
      tar czf "$out/lsao_images.tgz" -C "$out" img && rm -rf "$out/img"
      ;;
    table)
      # docs/performance.md's method table: every method and preset at 720p, 1080p and 4K (+ 10 % guard band
      # per side), then each method at full, half and quarter resolution at 1080p, then the temporal pass
      # still and moving (--motion 1: reprojection through the matrices every frame).
      hbao_k16='hbao:directions=16:steps=48:estimator=horizon_split:intensity=1:power=1:blur_radius=4:blur_sharpness=16'
      methods="hbao,$hbao_k16,sao,lsao,lsao:preset=k16:tangent_strategy=fixed,lsao:preset=k32:tangent_strategy=fixed,ffao,ffao:saao=on,gtao:preset=low,gtao:preset=medium,gtao,gtao:preset=ultra,gtao:thickness_mode=bitmask,gtao:thickness_mode=bitmask:preset=ultra"
      reduced=""
      for m in hbao sao lsao ffao:saao=on gtao gtao:thickness_mode=bitmask; do
        for r in half quarter; do
          reduced+="$m:resolution.scale=$r,"
        done
      done
      {
        echo "== every method and preset"
        run bench --scene atrium --sizes "$table_sizes" --methods "$methods" --json "$out/table.json"
        echo "== reduced resolution"
        run bench --scene atrium --sizes "$table_size" --methods "${reduced%,}" --json "$out/reduced.json"
        echo "== temporal, still camera"
        run bench --scene atrium --sizes "$table_size" --methods hbao:temporal.enabled=on,gtao:temporal.enabled=on \
              --json "$out/temporal_still.json"
        echo "== temporal, moving camera (--motion 1)"
        run bench --scene atrium --sizes "$table_size" --motion 1 \
              --methods hbao:temporal.enabled=on,gtao:temporal.enabled=on,sao:temporal.enabled=on \
              --json "$out/temporal_moving.json"
      } > "$out/table.txt" 2>&1
      # One line per configuration: method @ size, the total and every pass (median ms).
      awk '/ @ /{if(line)print line; line=$1" "$3} /^  [a-z_]+ +[0-9.]+ +[0-9.]+$/{line=line" "$1"="$2}
           /^== /{if(line)print line; line=""; print} /refused|error/{print} END{if(line)print line}' "$out/table.txt" | tee "$out/table_summary.txt"
      ;;
    *) echo "unknown step: $what" >&2; status=2 ;;
  esac
done
exit $status
