#!/usr/bin/env bash
# Installs the dependencies, builds the obscura CLI and renders the demo scene with every available
# method into demo-output/ (one PNG per method), printing each method's timing.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
# The demo needs only the CLI; leaving the tests out keeps it independent of GoogleTest.
OBSCURA_BUILD_TESTS=OFF "$root/scripts/build.sh" obscura_cli

cd "$root"
"${OBSCURA_BUILD_DIR:-$root/build}/bin/obscura" demo --out-dir demo-output
