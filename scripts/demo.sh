#!/usr/bin/env bash
# Installs what is missing, builds symcompress (Release), compresses the bundled samples (printing the size
# reports) and rebuilds them with symdecompress, verifying them against the originals.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$here"
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$(nproc)" --target symcompress_cli symdecompress
mkdir -p out
build/symcompress samples/bolts.glb -o out/bolts.glb --report out/bolts-report.json
build/symdecompress out/bolts.glb -o out/bolts-rebuilt.glb --verify samples/bolts.glb
# The room: its four bookshelves (188 boxes each) are found as one assembly, stored once.
build/symcompress samples/room.glb -o out/room.glb --report out/room-report.json
build/symdecompress out/room.glb -o out/room-rebuilt.glb --verify samples/room.glb
