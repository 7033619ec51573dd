#!/usr/bin/env python3
"""Writes a vase turned in S sectors from a P-point profile (plain glTF + .bin), for timing detection on a
lathe of many sectors: python3 bench/make_lathe.py OUT.gltf [--profile 400] [--sectors 96]."""
import argparse, json, math, os, struct

parser = argparse.ArgumentParser()
parser.add_argument("out")
parser.add_argument("--profile", type=int, default=400)
parser.add_argument("--sectors", type=int, default=96)
args = parser.parse_args()
P, S = args.profile, args.sectors

# A profile from the foot (radius 0.6) through a belly and a neck to the lip, closed at the foot's pole.
profile = []
for k in range(P):
    t = k / (P - 1)
    radius = 0.6 + 0.5 * math.sin(math.pi * t) - 0.25 * math.sin(3 * math.pi * t) ** 2
    profile.append((radius, 2.0 * t))
positions = [(0.0, 0.0, 0.0)]
for r, z in profile:
    for s in range(S):
        a = 2 * math.pi * s / S
        positions.append((r * math.cos(a), r * math.sin(a), z))
indices = []
for s in range(S):  # the foot's disc, a fan about the pole
    indices += [0, 1 + (s + 1) % S, 1 + s]
for k in range(P - 1):
    for s in range(S):
        a, b = 1 + k * S + s, 1 + k * S + (s + 1) % S
        c, d = a + S, b + S
        indices += [a, b, d, a, d, c]
# y up, as glTF wants: (x, y, z) -> (x, z, -y)
positions = [(x, z, -y) for x, y, z in positions]
vertexBytes = b"".join(struct.pack("<3f", *p) for p in positions)
indexBytes = b"".join(struct.pack("<I", i) for i in indices)
binName = os.path.splitext(os.path.basename(args.out))[0] + ".bin"
with open(os.path.join(os.path.dirname(os.path.abspath(args.out)), binName), "wb") as f:
    f.write(vertexBytes + indexBytes)
lo = [min(p[i] for p in positions) for i in range(3)]
hi = [max(p[i] for p in positions) for i in range(3)]
gltf = {
    "asset": {"version": "2.0"},
    "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0, "name": "vase"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3", "min": lo, "max": hi},
        {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"}],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": len(vertexBytes), "target": 34962},
        {"buffer": 0, "byteOffset": len(vertexBytes), "byteLength": len(indexBytes), "target": 34963}],
    "buffers": [{"uri": binName, "byteLength": len(vertexBytes) + len(indexBytes)}],
}
with open(args.out, "w") as f:
    json.dump(gltf, f)
print(f"{args.out}: {len(indices) // 3} triangles, {S} sectors")
