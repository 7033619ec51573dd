#!/usr/bin/env bash
# Does the compressed X3D render as its reference (issue 15)? For every shared model and bundled sample (or
# the models named): compresses to X3D (`symcompress -q IN -o out.x3d`), verifies it with symdecompress, and
# renders it against the input (X3D inputs) or the plain conversion (`symcompress convert IN -o ref.x3d`,
# other inputs) with ../shared/bench/render/render_compare.sh, lit and normals modes, views a-c. Prints a
# table: the X3D output's bytes, verified, each view's share of differing object pixels, PASS or FAIL.
#   bench/x3d_renders.sh [--build DIR] [--keep DIR] [MODEL...]    MODEL: a path under ../shared/models or samples/
# --keep DIR keeps every model's folder (inputs linked, ref.x3d, out.x3d, the renders under lit/ and normals/).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$here/build" keep=''
while [ $# -gt 0 ]; do
  case "$1" in
    --build) build=$(readlink -f "$2"); shift 2 ;;
    --keep) keep=$(readlink -f "$2"); shift 2 ;;
    *) break ;;
  esac
done
models="$(readlink -f "$here/../shared/models")"
render="$(readlink -f "$here/../shared/bench/render/render_compare.sh")"
if [ $# -gt 0 ]; then
  inputs=("$@")
else
  mapfile -t inputs < <(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl)
  for s in "$here"/samples/*.glb; do inputs+=("samples/$(basename "$s")"); done
fi
work="${keep:-$(mktemp -d)}"
[ -n "$keep" ] || trap 'rm -rf "$work"' EXIT
mkdir -p "$work"

echo "| model | X3D bytes | verified | lit a | lit b | lit c | normals a | normals b | normals c | result |"
echo "| --- | ---: | :---: | ---: | ---: | ---: | ---: | ---: | ---: | :---: |"
for input in "${inputs[@]}"; do
  if [[ "$input" == samples/* ]]; then source="$here/$input"; else source="$models/$input"; fi
  # The model's folder copied, so that the outputs refer to its textures as the input does and the render
  # server (which serves the files' folders only) finds them.
  dir="$work/$(echo "$input" | tr '/' '_')"
  rm -rf "$dir" && mkdir -p "$dir"
  if [[ "$input" == samples/* ]]; then cp "$source" "$dir"/; else cp -r "$(dirname "$source")"/. "$dir"/; fi
  chmod -R u+w "$dir"
  in="$dir/$(basename "$source")"
  if [[ "${in,,}" == *.x3d ]]; then ref="$in"; else
    ref="$dir/ref.x3d"
    "$build/symcompress" convert "$in" -o "$ref" >/dev/null 2>&1
  fi
  "$build/symcompress" -q "$in" -o "$dir/out.x3d"
  bytes=$(stat -c %s "$dir/out.x3d")
  verified=yes
  "$build/symdecompress" "$dir/out.x3d" -o "$dir/flat.ply" --verify "$in" >/dev/null 2>&1 || verified=no
  cells=() result=PASS
  for mode in lit normals; do
    set +e
    PATH=/usr/bin:$PATH "$render" "$ref" "$dir/out.x3d" --mode "$mode" --views abc --out "$dir/$mode" \
      >"$dir/$mode.txt" 2>"$dir/$mode.err"
    status=$?
    set -e
    [ $status -eq 0 ] || result=FAIL
    for v in a b c; do
      line=$(grep "^view $v:" "$dir/$mode.txt" || true)
      pct=$(echo "$line" | sed -n 's/.*differing \([0-9.]*%\).*/\1/p')
      [ -n "$pct" ] || pct='error'
      # A triangle count or bounding box that differs is named beside the pixels.
      tris=$(echo "$line" | sed -n 's/.*triangles \([0-9]*\)\/\([0-9]*\).*/\1 \2/p')
      if [ -n "$tris" ] && [ "${tris% *}" != "${tris#* }" ]; then pct="$pct (tris ${tris/ //})"; fi
      echo "$line" | grep -q 'bbox ok' || [ -z "$line" ] || pct="$pct (bbox)"
      cells+=("$pct")
    done
  done
  [ "$verified" = yes ] || result=FAIL
  echo "| $input | $bytes | $verified | ${cells[0]} | ${cells[1]} | ${cells[2]} | ${cells[3]} | ${cells[4]} | ${cells[5]} | $result |"
done
