# Parts in colours of their own, the join by base colour's case (bench/RESULTS.md): N cylinders of random proportions
# (none congruent), each a mesh drawn by a node in a material of its own colour (random, some dark), as a plain GLB.
# Usage: python3 bench/make_colour_parts.py OUT.glb N [SEED]
import json
import math
import random
import struct
import sys

out_path, count = sys.argv[1], int(sys.argv[2])
random.seed(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
binary = bytearray()
gltf = {"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0, "nodes": [], "meshes": [],
        "materials": [], "accessors": [], "bufferViews": [], "buffers": []}


def add_view(data, target):
    offset = len(binary)
    binary.extend(data + b"\0" * ((4 - len(data) % 4) % 4))
    gltf["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": len(data), "target": target})
    return len(gltf["bufferViews"]) - 1


def add_accessor(data, target, component_type, count, kind, **bounds):
    gltf["accessors"].append({"bufferView": add_view(data, target), "componentType": component_type, "count": count,
                              "type": kind, **bounds})
    return len(gltf["accessors"]) - 1


for k in range(count):
    segments, radius, height = random.randint(12, 40), random.uniform(0.2, 1.0), random.uniform(0.5, 3.0)
    positions, normals, indices = [], [], []
    for i in range(segments):
        angle = 2 * math.pi * i / segments
        for z in (0, height):
            positions.append((radius * math.cos(angle), radius * math.sin(angle), z))
            normals.append((math.cos(angle), math.sin(angle), 0))
    for i in range(segments):
        a, b, c, d = 2 * i, 2 * i + 1, 2 * ((i + 1) % segments), 2 * ((i + 1) % segments) + 1
        indices += [a, c, b, b, c, d]
    floats = lambda vectors: b"".join(struct.pack("<3f", *v) for v in vectors)
    position = add_accessor(floats(positions), 34962, 5126, len(positions), "VEC3",
                            min=[min(p[c] for p in positions) for c in range(3)],
                            max=[max(p[c] for p in positions) for c in range(3)])
    normal = add_accessor(floats(normals), 34962, 5126, len(normals), "VEC3")
    index = add_accessor(b"".join(struct.pack("<H", i) for i in indices), 34963, 5123, len(indices), "SCALAR")
    colour = [random.random() ** 2.2 for _ in range(3)] + [1]
    gltf["materials"].append({"name": "colour%d" % k, "pbrMetallicRoughness": {
        "baseColorFactor": colour, "metallicFactor": 0, "roughnessFactor": 0.6}})
    gltf["meshes"].append({"primitives": [{"attributes": {"POSITION": position, "NORMAL": normal}, "indices": index,
                                           "material": k}]})
    gltf["nodes"].append({"mesh": k, "translation": [3.0 * (k % 10), 3.0 * (k // 10), 0]})
    gltf["scenes"][0]["nodes"].append(k)
gltf["buffers"].append({"byteLength": len(binary)})
text = json.dumps(gltf, separators=(",", ":")).encode()
text += b" " * ((4 - len(text) % 4) % 4)
with open(out_path, "wb") as out:
    out.write(struct.pack("<III", 0x46546C67, 2, 12 + 8 + len(text) + 8 + len(binary)))
    out.write(struct.pack("<II", len(text), 0x4E4F534A) + text)
    out.write(struct.pack("<II", len(binary), 0x004E4942) + bytes(binary))
