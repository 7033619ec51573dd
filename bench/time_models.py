# Times each shared model, and any file given after --, compressed to GLB (or to X3D, with --to x3d) by each
# symcompress binary given (the faster of two runs), to compare two builds. Prints a markdown table.
# Usage: python3 bench/time_models.py [--to glb|x3d] BINARY... [-- FILE...]
import glob
import os
import subprocess
import sys
import tempfile
import time

args = sys.argv[1:]
extension = "glb"
if args[:1] == ["--to"]:
    extension, args = args[1], args[2:]
binaries = args[: args.index("--")] if "--" in args else args
extra = args[args.index("--") + 1 :] if "--" in args else []
shared = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "shared", "models")
models = sorted(
    f for ext in ("gltf", "glb", "obj", "ply", "stl", "x3d") for f in glob.glob(os.path.join(shared, "*", "*." + ext))
) + extra
totals = [0.0] * len(binaries)
print("| input | " + " | ".join(binaries) + " |")
print("| --- |" + " ---: |" * len(binaries))
with tempfile.TemporaryDirectory() as folder:
    output = os.path.join(folder, "out." + extension)
    for model in models:
        row = []
        for k, binary in enumerate(binaries):
            best = float("inf")
            for _ in range(2):
                start = time.time()
                subprocess.run([binary, model, "-o", output, "-q"], capture_output=True, check=True)
                best = min(best, time.time() - start)
            totals[k] += best
            row.append("%.2f s" % best)
        print("| %s | %s |" % (os.path.relpath(model, shared) if model.startswith(shared) else model, " | ".join(row)))
print("| total | %s |" % " | ".join("%.2f s" % t for t in totals))
