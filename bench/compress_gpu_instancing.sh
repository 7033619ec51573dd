#!/usr/bin/env bash
# For each input: symcompress to GLB with and without GPU instancing; sizes, batches, validator, verify.
#   BUILD=build bench/compress_gpu_instancing.sh FILE...
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD:-$here/build}"
out="$(mktemp -d)"; trap 'rm -rf "$out"' EXIT
echo "| model | --no-gpu-instancing | default | batches/instances | bytes/instance before -> after | validator | verified |"
echo "| --- | ---: | ---: | ---: | ---: | :---: | :---: |"
for path in "$@"; do
  name=$(basename "$path"); name=${name%.*}
  $build/symcompress -q "$path" -o $out/$name.nogpu.glb --no-gpu-instancing --report $out/$name.nogpu.json
  $build/symcompress -q "$path" -o $out/$name.glb --report $out/$name.json
  val=$(node /work/shared/bench/validate.js $out/$name.glb | head -1 | grep -o "errors=[0-9]*")
  ver=yes; $build/symdecompress $out/$name.glb -o $out/$name.flat.glb --verify "$path" >/dev/null || ver=no
  python3 - "$name" $out/$name.nogpu.json $out/$name.json "$val" $ver <<'PY'
import json,sys
a,b=json.load(open(sys.argv[2])),json.load(open(sys.argv[3]))
g=b["gpu_instancing"]
print(f"| {sys.argv[1]} | {a['output_bytes']} ({a['plan']}) | {b['output_bytes']} ({b['plan']}) | {g['batches']}/{g['instances']} | {a['bytes_per_instance']:.0f} -> {b['bytes_per_instance']:.0f} | {sys.argv[4]} | {sys.argv[5]} |")
PY
done
