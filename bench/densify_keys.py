#!/usr/bin/env python3
"""A .gltf's animations keyed as an exporter that samples every frame keys them: each LINEAR sampler's span between
two keys cut into N by its own interpolation (lerp; slerp for rotations, the shorter way), so that the animation
plays the same with N times the keys. A variant for measuring how well keys that interpolation gives back are
dropped (docs/compression-plan.md). The new keys go in a buffer of their own beside OUT; the input's buffers and
images are linked beside it.

    bench/densify_keys.py IN.gltf OUT.gltf N
"""
import json
import math
import os
import struct
import sys

WIDTH = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}


def slerp(a, b, u):
    d = sum(x * y for x, y in zip(a, b))
    if d < 0:
        b, d = [-x for x in b], -d
    if d > 0.9999999:
        r = [x + (y - x) * u for x, y in zip(a, b)]
    else:
        t = math.acos(d)
        r = [(math.sin((1 - u) * t) * x + math.sin(u * t) * y) / math.sin(t) for x, y in zip(a, b)]
    n = math.sqrt(sum(x * x for x in r))
    return [x / n for x in r]


def main(source, target, n):
    gltf = json.load(open(source))
    folder = os.path.dirname(os.path.abspath(source))
    buffers = [open(os.path.join(folder, b["uri"]), "rb").read() for b in gltf["buffers"]]

    def read(index):
        accessor = gltf["accessors"][index]
        view = gltf["bufferViews"][accessor["bufferView"]]
        width = WIDTH[accessor["type"]]
        offset = view.get("byteOffset", 0) + accessor.get("byteOffset", 0)
        stride = view.get("byteStride", 4 * width)
        data = buffers[view["buffer"]]
        return [list(struct.unpack_from("<%df" % width, data, offset + stride * k)) for k in range(accessor["count"])]

    extra = bytearray()

    def add(values, kind, bounds):
        offset = len(extra)
        for value in values:
            extra.extend(struct.pack("<%df" % len(value), *value))
        gltf["bufferViews"].append({"buffer": len(gltf["buffers"]), "byteOffset": offset, "byteLength": len(extra) - offset})
        accessor = {"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5126, "count": len(values), "type": kind}
        if bounds:
            accessor["min"], accessor["max"] = [min(v[0] for v in values)], [max(v[0] for v in values)]
        gltf["accessors"].append(accessor)
        return len(gltf["accessors"]) - 1

    new_times = {}
    for animation in gltf.get("animations", []):
        for channel in animation["channels"]:
            sampler = animation["samplers"][channel["sampler"]]
            if sampler.get("interpolation", "LINEAR") != "LINEAR" or channel["target"]["path"] == "weights":
                continue
            if sampler.get("densified"):
                continue
            times, values = read(sampler["input"]), read(sampler["output"])
            rotation = gltf["accessors"][sampler["output"]]["type"] == "VEC4"
            dense_times, dense_values = [], []
            for k in range(len(times) - 1):
                for i in range(n):
                    u = i / n
                    dense_times.append([times[k][0] + (times[k + 1][0] - times[k][0]) * u])
                    dense_values.append(slerp(values[k], values[k + 1], u) if rotation
                                        else [x + (y - x) * u for x, y in zip(values[k], values[k + 1])])
            dense_times.append(times[-1])
            dense_values.append(values[-1])
            if sampler["input"] not in new_times:
                new_times[sampler["input"]] = add(dense_times, "SCALAR", True)
            sampler["input"] = new_times[sampler["input"]]
            sampler["output"] = add(dense_values, "VEC4" if rotation else "VEC3", False)
            sampler["densified"] = True
    for animation in gltf.get("animations", []):
        for sampler in animation["samplers"]:
            sampler.pop("densified", None)

    out_folder = os.path.dirname(os.path.abspath(target))
    extra_name = os.path.basename(target) + ".keys.bin"
    open(os.path.join(out_folder, extra_name), "wb").write(extra)
    for item in gltf["buffers"] + gltf.get("images", []):
        uri = item.get("uri")
        if uri and not uri.startswith("data:") and not os.path.exists(os.path.join(out_folder, uri)):
            os.symlink(os.path.join(folder, uri), os.path.join(out_folder, uri))
    gltf["buffers"].append({"uri": extra_name, "byteLength": len(extra)})
    json.dump(gltf, open(target, "w"))


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]))
