#!/usr/bin/env bash
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
scripts/bench-gpu.sh .device-build $OUT/r tests bench lsao > $OUT/r.log 2>&1
grep -E "PASSED|FAILED" $OUT/r.log
grep -A6 -E "^(lsao|sao|hbao) @ 1920x1080" $OUT/r.log | head -24
cd $OUT && tar czf r.tgz r && rm -rf r
