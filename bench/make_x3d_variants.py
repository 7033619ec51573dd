#!/usr/bin/env python3
"""Writes the X3D inputs of bench/RESULTS.md's "X3D output no larger than an X3D input" table into OUT_DIR:
box.x3d (a red Box), uses.x3d (one Shape USEd by 100 Transforms, compact), ring.x3d (48 x 24 planar quads at
uneven longitudes, creaseAngle 1), bent.x3d (60 x 60 flat quads of a curved height field), planar.x3d (the same
grid on a tilted plane). Usage: python3 bench/make_x3d_variants.py OUT_DIR"""
import math
import os
import random
import sys

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
head = '<?xml version="1.0" encoding="UTF-8"?>\n<X3D profile="Interchange" version="3.3">\n<Scene>\n'


def write(name, text):
    with open(os.path.join(out, name), "w") as f:
        f.write(text)


write("box.x3d", "<X3D><Scene><Shape><Appearance><Material diffuseColor='1 0 0'/></Appearance><Box/></Shape></Scene></X3D>\n")

random.seed(1)
lines = [head + '<Transform><Shape DEF="S"><Appearance><Material diffuseColor="0.8 0.2 0.2"/></Appearance><Cylinder/></Shape></Transform>']
for i in range(100):
    x, y, z = (round(random.uniform(-20, 20), 2) for _ in range(3))
    lines.append('<Transform translation="%g %g %g" rotation="0 1 0 %g"><Shape USE="S"/></Transform>'
                 % (x, y, z, round(random.uniform(0, 3), 3)))
write("uses.x3d", "\n".join(lines) + "\n</Scene></X3D>")


def face_set(fields, faces, points):
    return (head + '<Transform rotation="1 0 0 0.3"><Shape>\n<Appearance><Material diffuseColor="0.7 0.5 0.2"/></Appearance>\n'
            '<IndexedFaceSet %s coordIndex="%s">\n<Coordinate point="%s"/>\n</IndexedFaceSet>\n</Shape></Transform>\n</Scene>\n</X3D>\n'
            % (fields, " ".join(faces), " ".join(points)))


random.seed(4)
U, V, R, r = 48, 24, 2.0, 0.6
longitudes = sorted(random.uniform(0, 2 * math.pi) for _ in range(U))
points, faces = [], []
for i in range(U):
    for j in range(V):
        v = 2 * math.pi * j / V
        rr = r * (1 + 0.3 * math.sin(v))
        u = longitudes[i]
        points.append("%.5g %.5g %.5g" % ((R + rr * math.cos(v)) * math.cos(u), (R + rr * math.cos(v)) * math.sin(u), rr * math.sin(v)))
        a, b = i * V + j, ((i + 1) % U) * V + j
        c, d = ((i + 1) % U) * V + (j + 1) % V, i * V + (j + 1) % V
        faces.append("%d %d %d %d -1" % (a, b, c, d))
write("ring.x3d", face_set('creaseAngle="1"', faces, points))

N = 60
for name, height in (("bent.x3d", lambda i, j: round(0.3 * math.sin(i * 0.2) * math.cos(j * 0.3), 3)),
                     ("planar.x3d", lambda i, j: 0.05 * i)):
    points = ["%g %g %g" % (i * 0.1, j * 0.1, height(i, j)) for i in range(N + 1) for j in range(N + 1)]
    faces = []
    for i in range(N):
        for j in range(N):
            a = i * (N + 1) + j
            faces.append("%d %d %d %d -1" % (a, a + N + 1, a + N + 2, a + 1))
    write(name, face_set('solid="false"', faces, points))
