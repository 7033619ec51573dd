#!/usr/bin/env bash
# symcompress at each best peer's own deviation, from a table of the peers' results made before
# (bench/best_peers.tsv: model, the best peer's bytes, the budget = its dev_rel plus half a unit of the last
# printed digit), without running the peers again (bench/compare_peers.sh and compare_matched.sh do both, in
# an hour). Each output is verified by symdecompress and measured by decode_check.mjs against the reference
# the peers read (the input, or its plain conversion). Prints a markdown table. An animated model whose peer's
# poses lie farther from the input's than its rest pose (a fourth column: its posed_deviation) gets a second row,
# "poses at the peer's", with `--animation-error` the difference: no farther than the peer at rest or in a pose.
#   bench/at_peer_deviations.sh [BUILD_DIR] [TABLE]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
table="${2:-$here/bench/best_peers.tsv}"
models="$here/../shared/models"
bench="$here/../shared/bench"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
python3 "$bench/make_toy_scene.py" "$out/toy.glb" >/dev/null
echo "| model | best peer bytes | budget | symcompress bytes | its dev_rel | verified | ratio |"
echo "| --- | ---: | ---: | ---: | ---: | :---: | ---: |"
grep -v '^#' "$table" | while IFS=$'\t' read -r name peer budget posed; do
  case "$name" in samples/*) in="$here/$name" ;; toy.glb) in="$out/$name" ;; *) in="$models/$name" ;; esac
  ref="$in"
  case "$in" in *.gltf | *.glb) ;; *) ref="$out/reference.glb" && "$build/symcompress" convert "$in" -o "$ref" --no-draco -q 2>/dev/null ;; esac
  row() {  # LABEL [symcompress options]
    local label="$1"
    shift
    "$build/symcompress" "$in" -o "$out/sc.glb" -q --max-error "$budget" "$@" 2>/dev/null
    bytes=$(stat -c %s "$out/sc.glb")
    verified=no
    "$build/symdecompress" "$out/sc.glb" -o "$out/flat.glb" --verify "$in" >/dev/null 2>&1 && verified=yes
    dev=$(node "$bench/decode_check.mjs" "$out/sc.glb" --ref "$ref" 2>/dev/null | grep -o 'dev_rel=[^ ]*' | cut -d= -f2 || true)
    ratio=$(python3 -c "print(f'{$bytes / $peer:.3f}')")
    echo "| $label | $peer | $budget | $bytes | ${dev:-n/a} | $verified | $ratio |"
  }
  row "$name"
  beside=$(python3 -c "print(f'{${posed:-0} - $budget:.6g}' if ${posed:-0} > $budget else '')")
  [ -z "$beside" ] || row "$name, poses at the peer's ($posed)" --animation-error "$beside"
done
