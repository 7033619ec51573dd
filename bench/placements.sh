#!/usr/bin/env bash
# Every glTF shared model and bundled sample placed otherwise: its scene under one more root node that scales it
# by 1000 or 1/1000, turns it off the axes, moves it 10 km from the origin, stretches it (2, 1, 0.5), mirrors it,
# or turns and scales it by 1e4. Each variant is compressed to GLB and rebuilt by symdecompress against it; the
# table gives each output's bytes over the model's own output and whether it verified. A scene placed
# otherwise is the same scene: its output should be about as large, and verified.
#   bench/placements.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
models="$here/../shared/models"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# The column-major matrices of the placements, one "name m0,m1,...,m15" a line.
python3 - >"$out/placements.txt" <<'EOF'
import math
def product(a, b): return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
def diagonal(x, y, z): return [[x, 0, 0, 0], [0, y, 0, 0], [0, 0, z, 0], [0, 0, 0, 1]]
axis = [v / math.sqrt(14) for v in (1, 2, 3)]
angle = 0.7
k = [[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]]
kk = [[sum(k[i][m] * k[m][j] for m in range(3)) for j in range(3)] for i in range(3)]
turn = diagonal(1, 1, 1)
for i in range(3):
    for j in range(3):
        turn[i][j] = (i == j) + math.sin(angle) * k[i][j] + (1 - math.cos(angle)) * kk[i][j]
far = diagonal(1, 1, 1)
far[0][3], far[1][3], far[2][3] = 1e4, -2e3, 5e3
for name, m in [("big", diagonal(1e3, 1e3, 1e3)), ("small", diagonal(1e-3, 1e-3, 1e-3)), ("turned", turn),
                ("far", far), ("stretched", diagonal(2, 1, 0.5)), ("mirrored", diagonal(-1, 1, 1)),
                ("turned_big", product(turn, diagonal(1e4, 1e4, 1e4)))]:
    print(name, ",".join(repr(float(m[i][j])) for j in range(4) for i in range(4)))
EOF

# place IN OUT MATRIX: IN's scene roots under a new root node with MATRIX (a .gltf keeps its folder's files).
place() {
  python3 - "$@" <<'EOF'
import json, os, shutil, struct, sys
source, target, matrix = sys.argv[1], sys.argv[2], [float(x) for x in sys.argv[3].split(",")]
def placed(gltf):
    scene = gltf["scenes"][gltf.get("scene", 0)]
    gltf.setdefault("nodes", []).append({"name": "placement", "matrix": matrix, "children": scene.get("nodes", [])})
    scene["nodes"] = [len(gltf["nodes"]) - 1]
    return gltf
if source.endswith(".glb"):
    data = open(source, "rb").read()
    length = struct.unpack("<I", data[12:16])[0]
    text = json.dumps(placed(json.loads(data[20:20 + length])), separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    rest = data[20 + length:]
    open(target, "wb").write(struct.pack("<III", 0x46546C67, 2, 20 + len(text) + len(rest)) +
                             struct.pack("<II", len(text), 0x4E4F534A) + text + rest)
else:
    for entry in os.listdir(os.path.dirname(source)):
        path = os.path.join(os.path.dirname(source), entry)
        if path != source and not os.path.exists(os.path.join(os.path.dirname(target), entry)):
            (shutil.copytree if os.path.isdir(path) else shutil.copy)(path, os.path.join(os.path.dirname(target), entry))
    json.dump(placed(json.load(open(source))), open(target, "w"))
EOF
}

echo "| model | placement | bytes | over the model's own | verified |"
echo "| --- | --- | ---: | ---: | :---: |"
inputs="$(cd "$models" && ls */*.gltf */*.glb | sed "s|^|$models/|") $(ls "$here"/samples/*.glb)"
for input in $inputs; do
  name="${input#"$models"/}"; name="${name#"$here"/}"
  extension="${input##*.}"
  "$build/symcompress" -q "$input" -o "$out/own.glb" 2>/dev/null
  own=$(stat -c %s "$out/own.glb")
  while read -r placement matrix; do
    folder="$out/$placement-$(basename "$(dirname "$input")")"
    mkdir -p "$folder"
    place "$input" "$folder/in.$extension" "$matrix"
    "$build/symcompress" -q "$folder/in.$extension" -o "$folder/out.glb" 2>/dev/null
    bytes=$(stat -c %s "$folder/out.glb")
    verified=no
    "$build/symdecompress" "$folder/out.glb" -o "$folder/flat.glb" --verify "$folder/in.$extension" >/dev/null 2>&1 &&
      verified=yes
    echo "| $name | $placement | $bytes | $(python3 -c "print(f'{$bytes / $own:.3f}')") | $verified |"
  done <"$out/placements.txt"
done
