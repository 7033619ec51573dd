#!/usr/bin/env bash
# Installs what is missing, builds symcompress (Release), compresses the bundled sample (printing the size
# report) and rebuilds it with symdecompress, verifying it against the original.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target symcompress_cli symdecompress
mkdir -p out
build/symcompress samples/bolts.glb -o out/bolts.glb --report out/bolts-report.json
build/symdecompress out/bolts.glb -o out/bolts-rebuilt.glb --verify samples/bolts.glb
