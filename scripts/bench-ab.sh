#!/usr/bin/env bash
# A/B of two obscura CLI binaries on llvmpipe: per method, the two alternate run by run (three pairs), so both
# see the same machine; prints a markdown table of the medians (docs/performance.md, "The core rebuild").
#   scripts/bench-ab.sh OLD/obscura NEW/obscura [METHOD ...]   (default: every method at 1280x720 on the atrium)
set -euo pipefail
command -v python3 > /dev/null || { echo "bench-ab: needs python3 (apt-get install python3)" >&2; exit 1; }
old="$1"; new="$2"; shift 2
methods=("$@")
[[ ${#methods[@]} -gt 0 ]] || methods=(hbao sao lsao ffao ffao:saao=on reference:rays=16)
export EGL_PLATFORM="${EGL_PLATFORM:-surfaceless}" LIBGL_ALWAYS_SOFTWARE="${LIBGL_ALWAYS_SOFTWARE:-1}"
out="$(mktemp -d)"
for i in "${!methods[@]}"; do
  for rep in 1 2 3; do
    for side in old new; do
      bin="$old"; [[ $side == new ]] && bin="$new"
      "$bin" bench --scene atrium --sizes 1280x720 --frames 3 --warmup 1 --methods "${methods[$i]}" \
        --json "$out/${i}_${side}_${rep}.json" > /dev/null
    done
  done
done
python3 - "$out" "${methods[@]}" <<'PY'
import json, statistics, sys
out, names = sys.argv[1], sys.argv[2:]
def total(i, side, rep):
    return json.load(open('%s/%d_%s_%d.json' % (out, i, side, rep)))['results'][0]['total_ms']['median']
print('| method | before: median of 3 runs (ms) | after (ms) | after / before | per-pair ratios |')
print('|---|---|---|---|---|')
for i, name in enumerate(names):
    o = [total(i, 'old', r) for r in (1, 2, 3)]
    n = [total(i, 'new', r) for r in (1, 2, 3)]
    print('| %s | %.1f | %.1f | %.3f | %s |' % (name, statistics.median(o), statistics.median(n),
          statistics.median(n) / statistics.median(o), ', '.join('%.3f' % (b / a) for a, b in zip(o, n))))
PY
rm -rf "$out"
