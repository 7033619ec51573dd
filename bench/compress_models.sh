#!/usr/bin/env bash
# Compresses every shared model to GLB and to X3D and verifies the rebuild against the original; prints a
# table of sizes (from the --report JSON) for bench/RESULTS.md.
#   bench/compress_models.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
models="$here/../shared/models"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
echo "| model | input bytes | GLB: Draco alone | GLB: final | GLB ratio | X3D: no instancing | X3D: instancing | X3D: with regions | verified |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | :---: |"
for file in $(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl); do
  "$build/symcompress" -q "$models/$file" -o "$out/m.glb" --report "$out/g.json"
  "$build/symcompress" -q "$models/$file" -o "$out/m.x3d" --report "$out/x.json"
  verified=yes
  "$build/symdecompress" "$out/m.glb" -o "$out/f.glb" --verify "$models/$file" >/dev/null || verified=no
  "$build/symdecompress" "$out/m.x3d" -o "$out/f.glb" --verify "$models/$file" >/dev/null || verified=no
  python3 - "$file" "$out/g.json" "$out/x.json" "$verified" <<'PY'
import json, sys
g, x = json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
a, b = g["ablation"], x["ablation"]
print(f"| {sys.argv[1]} | {g['input_bytes']} | {a['draco_alone']} | {g['output_bytes']} | {g['ratio']:.2f} | "
      f"{b['draco_alone']} | {b['instancing']} | {b['instancing_and_regions']} | {sys.argv[4]} |")
PY
done
