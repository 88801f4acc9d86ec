#!/usr/bin/env bash
# Installs the dependencies, builds the obscura CLI and runs `obscura demo`: the built-in atrium scene
# at 640x360 with every available method and the ray-traced reference (256 rays per pixel, traced in
# chunks with progress on stderr), printing each method's time and its error against the reference, and
# writing the images (method, error heat map, reference, contact sheet) into demo-output/.
# On a 2-core llvmpipe machine the references (one per falloff) take about two and a half minutes.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
# The demo needs only the CLI; leaving the tests out keeps it independent of GoogleTest.
OBSCURA_BUILD_TESTS=OFF "$root/scripts/build.sh" obscura_cli

cd "$root"
"${OBSCURA_BUILD_DIR:-$root/build}/bin/obscura" demo --out-dir demo-output --json demo-output/report.json
