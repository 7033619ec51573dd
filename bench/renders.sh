#!/usr/bin/env bash
# Does the compressed output render as its reference (issue 15)? For every shared model, pbr model and bundled
# sample (or the models named): compresses to FORMAT (glb: three.js renders it; x3d: X_ITE) with
# `symcompress -q IN -o out.FORMAT`, verifies it with symdecompress, and renders it against the input (an
# input of that format, glTF for glb) or the input's plain conversion (`symcompress convert IN -o ref.FORMAT`,
# uncompressed), so that one renderer draws both, with ../shared/bench/render/render_compare.sh, lit and
# normals modes, views a-c. Prints a table: the output's bytes, verified, each view's share of differing object
# pixels (a triangle count that differs beside it; "d:" where a view drew nothing in either image and view d,
# from +z, was drawn in its place), PASS or FAIL.
#   bench/renders.sh [--format glb|x3d] [--build DIR] [--keep DIR] [MODEL...]
# MODEL: a path under ../shared/models or samples/; FORMAT defaults to glb. --keep DIR keeps every model's
# folder (the input's files, ref.FORMAT, out.FORMAT, the renders under lit/ and normals/).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$here/build" keep='' format=glb
while [ $# -gt 0 ]; do
  case "$1" in
    --format) format="$2"; shift 2 ;;
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
  mapfile -t inputs < <(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl pbr/*/*.gltf pbr/*/*.glb \
    2>/dev/null)
  for s in "$here"/samples/*.glb; do inputs+=("samples/$(basename "$s")"); done
fi
work="${keep:-$(mktemp -d)}"
[ -n "$keep" ] || trap 'rm -rf "$work"' EXIT
mkdir -p "$work"

case "$format" in glb | x3d) ;; *) echo "renders.sh: --format is glb or x3d, not '$format'" >&2; exit 2 ;; esac

echo "| model | $format bytes | verified | lit a | lit b | lit c | normals a | normals b | normals c | result |"
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
  case "$format:${in,,}" in
    x3d:*.x3d | glb:*.gltf | glb:*.glb) ref="$in" ;;
    *)
      ref="$dir/ref.$format"
      "$build/symcompress" convert "$in" -o "$ref" --no-draco >/dev/null 2>&1
      ;;
  esac
  out="$dir/out.$format"
  "$build/symcompress" -q "$in" -o "$out"
  bytes=$(stat -c %s "$out")
  verified=yes
  "$build/symdecompress" "$out" -o "$dir/flat.ply" --verify "$in" >/dev/null 2>&1 || verified=no
  cells=() result=PASS
  for mode in lit normals; do
    views=abc
    for attempt in 1 2; do
      set +e
      PATH=/usr/bin:$PATH "$render" "$ref" "$out" --mode "$mode" --views "$views" --out "$dir/$mode" \
        >"$dir/$mode.txt" 2>"$dir/$mode.err"
      status=$?
      set -e
      # A view that draws nothing in either image (a flat model seen edge-on) fails render_compare.sh; it is
      # drawn again from +z (view d) in its place, once.
      empty=$(sed -n 's/^fail: view \([abc]\): nothing drawn in either image$/\1/p' "$dir/$mode.err" | head -1)
      [ $status -ne 0 ] && [ -n "$empty" ] && [ $attempt -eq 1 ] || break
      views=${views/$empty/d}
    done
    [ $status -eq 0 ] || result=FAIL
    for v in $(echo "$views" | fold -w1); do
      line=$(grep "^view $v:" "$dir/$mode.txt" || true)
      pct=$(echo "$line" | sed -n 's/.*differing \([0-9.]*%\).*/\1/p')
      [ -n "$pct" ] || pct='error'
      # A triangle count or bounding box that differs is named beside the pixels.
      tris=$(echo "$line" | sed -n 's/.*triangles \([0-9]*\)\/\([0-9]*\).*/\1 \2/p')
      if [ -n "$tris" ] && [ "${tris% *}" != "${tris#* }" ]; then pct="$pct (tris ${tris/ //})"; fi
      echo "$line" | grep -q 'bbox ok' || [ -z "$line" ] || pct="$pct (bbox)"
      [ "$v" != d ] || pct="d: $pct"
      cells+=("$pct")
    done
  done
  [ "$verified" = yes ] || result=FAIL
  echo "| $input | $bytes | $verified | ${cells[0]} | ${cells[1]} | ${cells[2]} | ${cells[3]} | ${cells[4]} | ${cells[5]} | $result |"
done
