#!/usr/bin/env bash
# Compresses every shared model and bundled sample to GLB and to X3D and verifies the rebuild against the
# original; prints a table of sizes (from the --report JSON) for bench/RESULTS.md.
#   bench/compress_models.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
models="$here/../shared/models"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
echo "| model | input bytes | GLB: Draco alone | GLB: instancing | GLB: with regions | GLB: final (plan) | GLB ratio | X3D: no instancing | X3D: instancing | X3D: with regions | X3D: final | verified |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | :---: |"
inputs=$(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl | sed "s|^|$models/|")
inputs="$inputs $(ls "$here"/samples/*.glb)"
for path in $inputs; do
  file="${path#"$models/"}"; file="${file#"$here/"}"
  "$build/symcompress" -q "$path" -o "$out/m.glb" --report "$out/g.json"
  "$build/symcompress" -q "$path" -o "$out/m.x3d" --report "$out/x.json"
  verified=yes
  "$build/symdecompress" "$out/m.glb" -o "$out/f.glb" --verify "$path" >/dev/null || verified=no
  "$build/symdecompress" "$out/m.x3d" -o "$out/f.glb" --verify "$path" >/dev/null || verified=no
  python3 - "$file" "$out/g.json" "$out/x.json" "$verified" <<'PY'
import json, sys
g, x = json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
a, b = g["ablation"], x["ablation"]
plan = lambda r: "" if r["plan"] == "final" else f" ({r['plan']})"
print(f"| {sys.argv[1]} | {g['input_bytes']} | {a['draco_alone']} | {a['instancing']} | {a['instancing_and_regions']} | "
      f"{g['output_bytes']}{plan(g)} | {g['ratio']:.2f} | {b['draco_alone']} | {b['instancing']} | "
      f"{b['instancing_and_regions']} | {x['output_bytes']}{plan(x)} | {sys.argv[4]} |")
PY
done
