#!/usr/bin/env bash
# symcompress against the best peer at the peer's own deviation: for every input of bench/compare_peers.sh
# whose peers' table is kept in KEEP_DIR (run compare_peers.sh first), symcompress runs with --max-error set
# to the best peer's dev_rel, and its output is measured the way the peer's was: decode_check.mjs's dev_rel
# (vertex to nearest vertex, both ways) against the same reference the peers read, next to symdecompress's
# own measure (vertex to surface). Prints one markdown table for bench/RESULTS.md.
#   bench/compare_matched.sh BUILD_DIR KEEP_DIR
# dev_rel is printed with 4 digits: the peer's deviation is anywhere within half a unit of the last, so the
# budget is dev_rel plus that half unit (a budget of exactly the printed value can take one bit more than the
# peer's, which lies just above it). Bytes are whole files: images included, which symcompress keeps as
# they are.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$here/build}"
keep="${2:?KEEP_DIR: the folder where compare_peers.sh kept its tables}"
models="$here/../shared/models"
bench="$here/../shared/bench"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
python3 "$bench/make_toy_scene.py" "$out/toy.glb" >/dev/null
echo "| model | best peer (recipe) | its bytes | its dev_rel | budget | symcompress bytes | its dev_rel | its surface deviation | verified | ratio |"
echo "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | :---: | ---: |"
for name in $(cd "$models" && ls */*.gltf */*.glb */*.x3d */*.obj */*.ply */*.stl) $(cd "$here" && ls samples/*.glb) toy.glb; do
  case "$name" in samples/*) in="$here/$name" ;; toy.glb) in="$out/$name" ;; *) in="$models/$name" ;; esac
  tag="${name//\//_}"
  [[ -s "$keep/$tag.peers.tsv" && -s "$keep/$tag.verify.json" ]] || continue
  echo "compare_matched: $name" >&2
  # The reference the peers read: the input, or its conversion.
  ref="$in"
  case "$in" in *.gltf|*.glb) ;; *) ref="$out/converted.glb" ;; esac
  [[ -f "$keep/$tag.converted" ]] && ref="$out/converted.glb"
  [[ $ref == "$in" ]] || "$build/symcompress" convert "$in" -o "$ref" --no-draco -q 2>/dev/null
  python3 - "$keep/$tag" >"$out/best.tsv" <<'PY'
import csv, json, sys
base = sys.argv[1]
bound = json.load(open(base + ".verify.json"))["allowed_deviation"]
def num(s):
    try: return float(s)
    except (TypeError, ValueError): return None
rows = [r for r in csv.DictReader(open(base + ".peers.tsv"), delimiter="\t") if r["peer"] != "input"]
ok = [r for r in rows if num(r["bytes"]) and r["val_err"] == "0" and num(r["dev_rel"])
      and num(r["dev_rel"]) <= 10 * bound]
best = min(ok, key=lambda r: int(r["bytes"]), default=None)
if best:
    mantissa, exponent = f"{float(best['dev_rel']):.3e}".split("e")
    budget = float(best["dev_rel"]) + 0.5 * 10 ** (int(exponent) - 3)
    print(f"{best['bytes']}\t{best['dev_rel']}\t{budget:.5e}\t{best['peer']} {best['recipe']}")
PY
  [[ -s "$out/best.tsv" ]] || continue
  IFS=$'\t' read -r peer_bytes peer_dev budget recipe <"$out/best.tsv"
  "$build/symcompress" "$in" -o "$out/sc.glb" -q --max-error "$budget" --report "$out/sc.json" ||
    { echo "| $name | $recipe | $peer_bytes | $peer_dev | $budget | FAILED | | | | |"; continue; }
  "$build/symdecompress" "$out/sc.glb" -o "$out/flat.glb" --verify "$in" --json >"$out/verify.json" || true
  node "$bench/decode_check.mjs" "$out/sc.glb" --ref "$ref" --json >"$out/decode.json" 2>/dev/null || true
  python3 - "$name" "$recipe" "$peer_bytes" "$peer_dev" "$budget" "$out" <<'PY'
import json, sys
name, recipe, peer_bytes, peer_dev, budget, out = sys.argv[1:]
rep, ver = json.load(open(out + "/sc.json")), json.load(open(out + "/verify.json"))
try: dev = json.load(open(out + "/decode.json")).get("dev_rel", "n/a")
except (ValueError, OSError): dev = "n/a"
sc = rep["output_bytes"]
within = isinstance(dev, (int, float)) and dev <= float(peer_dev) * (1 + 5e-4)
ratio = f"{sc / int(peer_bytes):.2f}" + ("" if within else " (deviation above the peer's)")
print("| " + " | ".join(map(str, [name, recipe, peer_bytes, peer_dev, budget, sc, dev,
      f"{ver['max_deviation']:.2e}", "yes" if ver["verified"] else "NO", ratio])) + " |")
PY
done
