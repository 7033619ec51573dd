#!/usr/bin/env bash
# Installs what is missing, builds symcompress (Release) and runs it on the bundled sample.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target symcompress_cli symdecompress
mkdir -p out
build/symcompress info samples/bolts.glb
build/symcompress convert samples/bolts.glb -o out/bolts.glb
