#!/usr/bin/env bash
# Times symcompress (GLB output), glTF-Transform's optimize --compress draco and gltfpack -cc -mi on every
# shared model and bundled sample, one after the other, and prints a table of wall-clock seconds and
# symcompress's time over each peer's (issue 18). The peers read glTF only: X3D, OBJ, PLY and STL inputs are
# converted to GLB by symcompress first, and that conversion is not counted. A peer that fails on a file (a
# missing image, say) shows "-" and is left out of the totals.
#   bench/time_peers.sh [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
models="$here/../shared/models"
node_bin="$here/../shared/bench/node/node_modules/.bin"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

# Seconds that "$@" takes, or "-" where it fails.
seconds() {
  local start end
  start=$(date +%s.%N)
  "$@" >/dev/null 2>&1 || { echo "-"; return; }
  end=$(date +%s.%N)
  python3 -c "print(f'{$end - $start:.2f}')"
}

echo "| model | symcompress s | glTF-Transform optimize+draco s | gltfpack -cc -mi s | symcompress / glTF-Transform | symcompress / gltfpack |"
echo "| --- | ---: | ---: | ---: | ---: | ---: |"
inputs=$(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl | sed "s|^|$models/|")
inputs="$inputs $(ls "$here"/samples/*.glb)"
rows="$out/rows.txt"
: >"$rows"
for path in $inputs; do
  file="${path#"$models/"}"; file="${file#"$here/"}"
  peer_input="$path"
  case "$path" in
    *.gltf | *.glb) ;;
    *) "$build/symcompress" convert "$path" -o "$out/input.glb" --no-draco >/dev/null 2>&1 && peer_input="$out/input.glb" ;;
  esac
  ours=$(seconds "$build/symcompress" -q "$path" -o "$out/ours.glb")
  transform=$(seconds "$node_bin/gltf-transform" optimize "$peer_input" "$out/gt.glb" --compress draco --simplify false \
    --texture-compress false)
  pack=$(seconds "$node_bin/gltfpack" -i "$peer_input" -o "$out/gp.glb" -cc -mi)
  echo "$file $ours $transform $pack" >>"$rows"
done
python3 - "$rows" <<'PY'
import sys
totals = [0.0, 0.0, 0.0]
both = 0
ratio = lambda a, b: f"{float(a) / float(b):.2f}" if "-" not in (a, b) and float(b) > 0 else "-"
for line in open(sys.argv[1]):
    name, ours, transform, pack = line.split()
    print(f"| {name} | {ours} | {transform} | {pack} | {ratio(ours, transform)} | {ratio(ours, pack)} |")
    if "-" not in (ours, transform, pack):
        both += 1
        for i, value in enumerate((ours, transform, pack)):
            totals[i] += float(value)
t = [f"{v:.2f}" for v in totals]
print(f"| total ({both} files every tool read) | {t[0]} | {t[1]} | {t[2]} | {ratio(t[0], t[1])} | {ratio(t[0], t[2])} |")
PY
