#!/usr/bin/env bash
# Compares symcompress's output size with the peer glTF compressors (../shared/bench/peers.sh) on every
# shared model, the generated samples and the toy scene; prints one markdown table for bench/RESULTS.md.
#   bench/compare_peers.sh [BUILD_DIR [KEEP_DIR]]      (KEEP_DIR keeps each input's reports and peer TSV)
#   PEERS_FLAGS="-n" bench/compare_peers.sh            (flags for peers.sh, default "-t 120"; -n skips the
#                                                        decode check, but then no peer has a dev_rel)
# Needs the peers installed as ../shared/bench/README.md says (apt-get install draco gltfpack assimp-utils;
# npm ci --prefix ../shared/bench/node, which scripts/install-deps.sh does).
# symcompress runs with default options; its deviation is symdecompress --verify's max_deviation
# (relative to the bbox diagonal), "bound" is the allowed_deviation it prints (1e-5 + quantisation).
# Peers get the input itself (.gltf/.glb) or `symcompress convert --no-draco` of it (OBJ/PLY/STL/X3D);
# also a glTF on which draco_transcoder fails (missing images, KHR_lights_punctual) gets converted, marked
# "(peers: converted)". The converted GLB has what symcompress keeps (no tangents, lights, animations).
# "-t 120" caps each peer step at 2 minutes: decode_check.mjs hangs on some outputs (gltfpack 0.18 on
# vulkan_subpass_scene), whose dev_rel is then n/a. The whole run took 39 minutes on 2 cores.
# Best peer = smallest output among the recipes that did not FAIL, have 0 validator errors, and whose
# measured dev_rel is at most 10x symcompress's bound. That leaves out draco_encoder (a raw .drc mesh,
# not a glTF scene: no validator), gltfpack -cz (its decoder is missing: dev_rel n/a) and lossy
# simplification. The Draco transcoder column is the draco_transcoder recipe (per primitive, q14/10/12).
# Ratios are symcompress bytes / peer bytes: below 1 means symcompress is smaller.
#   REUSE_PEERS=1 bench/compare_peers.sh BUILD_DIR KEEP_DIR   (the peers' tables already in KEEP_DIR are
#                                                              reused: only symcompress runs again)
#   SC_FLAGS="--drop-unused-texcoords" bench/compare_peers.sh  (extra options for symcompress)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
models="$here/../shared/models"
bench="$here/../shared/bench"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
keep="${2:-$out}"
peers_flags="${PEERS_FLAGS:--t 120}"
sc_flags="${SC_FLAGS:-}"
mkdir -p "$keep"
python3 "$bench/make_toy_scene.py" "$out/toy.glb" >/dev/null
echo "| model | input bytes | symcompress bytes | symcompress dev (bound) | best peer (recipe) bytes | its dev_rel | Draco transcoder bytes | ratio sc/best peer | ratio sc/Draco transcoder |"
echo "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
for name in $(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl) $(cd "$here" && ls samples/*.glb) toy.glb; do
  case "$name" in samples/*) in="$here/$name" ;; toy.glb) in="$out/$name" ;; *) in="$models/$name" ;; esac
  tag="${name//\//_}"
  echo "compare_peers: $name" >&2
  # shellcheck disable=SC2086  # SC_FLAGS is a list of options
  "$build/symcompress" "$in" -o "$out/sc.glb" -q --report "$keep/$tag.report.json" $sc_flags ||
    { echo "| $name | symcompress FAILED | | | | | | | |"; continue; }
  "$build/symdecompress" "$out/sc.glb" -o "$out/flat.glb" --verify "$in" --json >"$keep/$tag.verify.json" || true
  peer_in="$in"
  case "$in" in
    *.gltf|*.glb) ;;
    *) peer_in="$out/converted.glb"; "$build/symcompress" convert "$in" -o "$peer_in" --no-draco -q ;;
  esac
  reuse="${REUSE_PEERS:-}"
  [[ -n $reuse && -s "$keep/$tag.peers.tsv" ]] || reuse=""
  # shellcheck disable=SC2086  # PEERS_FLAGS is a list of flags
  [[ -n $reuse ]] || "$bench/peers.sh" -T $peers_flags "$peer_in" >"$keep/$tag.peers.tsv"
  if [[ -n $reuse && -f "$keep/$tag.converted" ]]; then
    name="$name (peers: converted)"
  elif [[ -z $reuse && $peer_in == "$in" ]] && grep -q $'^draco_transcoder\t.*\tFAIL\t' "$keep/$tag.peers.tsv"; then
    touch "$keep/$tag.converted"
    "$build/symcompress" convert "$in" -o "$out/converted.glb" --no-draco -q 2>/dev/null
    # shellcheck disable=SC2086
    "$bench/peers.sh" -T $peers_flags "$out/converted.glb" >"$keep/$tag.peers.tsv"
    name="$name (peers: converted)"
  fi
  python3 - "$name" "$keep/$tag" <<'PY'
import csv, json, sys
name, base = sys.argv[1], sys.argv[2]
rep, ver = json.load(open(base + ".report.json")), json.load(open(base + ".verify.json"))
sc, bound = rep["output_bytes"], ver["allowed_deviation"]
rows = [r for r in csv.DictReader(open(base + ".peers.tsv"), delimiter="\t") if r["peer"] != "input"]
def num(s):
    try: return float(s)
    except (TypeError, ValueError): return None
ok = [r for r in rows if num(r["bytes"]) and r["val_err"] == "0"
      and num(r["dev_rel"]) is not None and num(r["dev_rel"]) <= 10 * bound]
best = min(ok, key=lambda r: int(r["bytes"]), default=None)
tc = next((r for r in rows if r["peer"] == "draco_transcoder" and num(r["bytes"])), None)
dev = f"{ver['max_deviation']:.1e} ({bound:.1e})" + ("" if ver["verified"] else " NOT VERIFIED")
cells = [name, rep["input_bytes"], sc, dev,
         f"{best['bytes']} ({best['peer']} {best['recipe']})" if best else "-",
         best["dev_rel"] if best else "-", tc["bytes"] if tc else "FAIL",
         f"{sc / int(best['bytes']):.2f}" if best else "-", f"{sc / int(tc['bytes']):.2f}" if tc else "-"]
print("| " + " | ".join(map(str, cells)) + " |")
PY
done
