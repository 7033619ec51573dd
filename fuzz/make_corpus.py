#!/usr/bin/env python3
"""Writes the hand-made seeds of fuzz/corpus/<format>/ (stdlib only): small valid files that between them
use every feature each reader knows. The Draco and meshopt GLB seeds are made from these by the tools
(see fuzz/README.md) and committed as they are. Usage: make_corpus.py [CORPUS_FOLDER]"""
import base64
import gzip
import json
import pathlib
import struct
import sys

corpus = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parent / "corpus")


def write(format_, name, data):
    folder = corpus / format_
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data if isinstance(data, bytes) else data.encode())


# --- glTF / GLB -------------------------------------------------------------------------------------------
class Gltf:
    """A glTF document under construction, with one binary buffer."""

    def __init__(self):
        self.doc = {"asset": {"version": "2.0", "generator": "symcompress make_corpus.py"}, "buffers": [],
                    "bufferViews": [], "accessors": [], "meshes": [], "nodes": [], "scenes": [{"nodes": []}],
                    "scene": 0}
        self.blob = bytearray()

    def view(self, data, stride=None, target=None):
        while len(self.blob) % 4:
            self.blob.append(0)
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if stride:
            view["byteStride"] = stride
        if target:
            view["target"] = target
        self.blob += data
        self.doc["bufferViews"].append(view)
        return len(self.doc["bufferViews"]) - 1

    def accessor(self, fmt, values, component_type, type_, minmax=False, normalized=False, target=None):
        data = b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v) for v in values)
        accessor = {"bufferView": self.view(data, target=target), "componentType": component_type,
                    "count": len(values), "type": type_}
        if normalized:
            accessor["normalized"] = True
        if minmax:
            accessor["min"] = [min(v[i] for v in values) for i in range(len(values[0]))]
            accessor["max"] = [max(v[i] for v in values) for i in range(len(values[0]))]
        self.doc["accessors"].append(accessor)
        return len(self.doc["accessors"]) - 1

    def node(self, node, root=True):
        self.doc["nodes"].append(node)
        if root:
            self.doc["scenes"][0]["nodes"].append(len(self.doc["nodes"]) - 1)
        return len(self.doc["nodes"]) - 1

    def finish_buffer(self, embed):
        buffer = {"byteLength": len(self.blob)}
        if embed:
            buffer["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bytes(self.blob)).decode()
        self.doc["buffers"] = [buffer]

    def gltf(self):
        self.finish_buffer(True)
        return json.dumps(self.doc, indent=1)

    def glb(self):
        self.finish_buffer(False)
        text = json.dumps(self.doc, separators=(",", ":")).encode()
        text += b" " * ((4 - len(text) % 4) % 4)
        blob = bytes(self.blob) + b"\0" * ((4 - len(self.blob) % 4) % 4)
        chunks = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(blob), 0x004E4942) + blob
        return struct.pack("<III", 0x46546C67, 2, 12 + len(chunks)) + chunks


FLOAT, UBYTE, USHORT, UINT, BYTE, SHORT = 5126, 5121, 5123, 5125, 5120, 5122
TETRA = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
TETRA_FACES = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3]


def tetrahedron(g, indices_type=USHORT, extras=True, mode=None):
    attributes = {"POSITION": g.accessor("3f", TETRA, FLOAT, "VEC3", minmax=True, target=34962)}
    if extras:
        attributes["NORMAL"] = g.accessor("3f", [(0.0, 0.0, -1.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)],
                                          FLOAT, "VEC3")
        attributes["TEXCOORD_0"] = g.accessor("2H", [(0, 0), (65535, 0), (0, 65535), (32768, 32768)], USHORT, "VEC2",
                                              normalized=True)
        attributes["COLOR_0"] = g.accessor("4B", [(255, 0, 0, 255), (0, 255, 0, 255), (0, 0, 255, 255), (9, 9, 9, 128)],
                                           UBYTE, "VEC4", normalized=True)
    fmt = {UBYTE: "B", USHORT: "H", UINT: "I"}[indices_type]
    primitive = {"attributes": attributes, "indices": g.accessor(fmt, TETRA_FACES, indices_type, "SCALAR", target=34963),
                 "material": 0}
    if mode is not None:
        primitive["mode"] = mode
    g.doc["meshes"].append({"name": "tetrahedron", "primitives": [primitive]})
    g.doc["materials"] = [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1], "metallicFactor": 0.5},
                           "alphaMode": "MASK", "alphaCutoff": 0.3, "doubleSided": True}]
    return len(g.doc["meshes"]) - 1


def plain():
    g = Gltf()
    mesh = tetrahedron(g)
    g.node({"name": "tetra", "mesh": mesh, "translation": [1, 2, 3], "rotation": [0, 0, 0.7071, 0.7071], "scale": [1, -1, 1]})
    return g


def scene_graph():
    """Children, a matrix, a camera, a light, a texture with KHR_texture_transform, a sparse accessor."""
    g = Gltf()
    mesh = tetrahedron(g, UINT, extras=False)
    child = g.node({"mesh": mesh, "matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 0, 0, 1]}, root=False)
    camera = g.node({"camera": 0, "translation": [0, 0, 10]}, root=False)
    light = g.node({"extensions": {"KHR_lights_punctual": {"light": 0}}}, root=False)
    g.node({"name": "group", "children": [child, camera, light]})
    g.doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 100, "aspectRatio": 1.5}},
                        {"type": "orthographic", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 10}}]
    g.doc["extensions"] = {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 1, 1], "intensity": 2, "range": 10, "spot": {"innerConeAngle": 0.1, "outerConeAngle": 0.5}},
        {"type": "directional"}, {"type": "point"}]}}
    g.doc["extensionsUsed"] = ["KHR_lights_punctual", "KHR_texture_transform"]
    png = base64.b64decode("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==")
    g.doc["images"] = [{"mimeType": "image/png", "bufferView": g.view(png)}]
    g.doc["textures"] = [{"source": 0}]
    g.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {
        "index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "scale": [2, 2], "rotation": 0.3}}}
    g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = g.accessor("2f", [(0, 0), (1, 0), (0, 1), (1, 1)], FLOAT, "VEC2")
    # A sparse accessor: the positions of the first one with vertex 3 moved.
    sparse = dict(g.doc["accessors"][0])
    sparse.pop("min"), sparse.pop("max")
    sparse["sparse"] = {"count": 1, "indices": {"bufferView": g.view(struct.pack("<H", 3)), "componentType": USHORT},
                        "values": {"bufferView": g.view(struct.pack("<3f", 0, 0, 2))}}
    g.doc["accessors"].append(sparse)
    g.doc["meshes"].append({"primitives": [{"attributes": {"POSITION": len(g.doc["accessors"]) - 1}, "mode": 5}]})
    g.node({"mesh": 1})
    return g


def materials():
    """Every texture slot, samplers, a texture transform, material extensions with textures, extras."""
    g = plain()
    png = base64.b64decode("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg==")
    g.doc["images"] = [{"mimeType": "image/png", "bufferView": g.view(png)}, {"uri": "missing.png"}]
    g.doc["samplers"] = [{"magFilter": 9728, "minFilter": 9986, "wrapS": 33071, "wrapT": 33648}]
    g.doc["textures"] = [{"source": 0, "sampler": 0}, {"source": 1}]
    g.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = g.accessor("2f", [(0, 0), (1, 0), (0, 1), (1, 1)], FLOAT, "VEC2")
    material = g.doc["materials"][0]
    material["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "rotation": 1}}}
    material["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {"index": 1}
    material["normalTexture"] = {"index": 0, "scale": 0.5}
    material["occlusionTexture"] = {"index": 1, "strength": 0.25}
    material["emissiveTexture"] = {"index": 0}
    material["extensions"] = {"KHR_materials_clearcoat": {"clearcoatFactor": 0.5, "clearcoatNormalTexture": {"index": 1, "scale": 2}},
                              "KHR_materials_emissive_strength": {"emissiveStrength": 3}}
    material["extras"] = {"tag": [1, 2]}
    g.doc["extensionsUsed"] = ["KHR_texture_transform", "KHR_materials_clearcoat", "KHR_materials_emissive_strength"]
    g.doc["extensionsRequired"] = ["KHR_materials_clearcoat"]
    return g


def animated():
    g = plain()
    times = g.accessor("f", [0.0, 0.5, 1.0], FLOAT, "SCALAR", minmax=False)
    moves = g.accessor("3f", [(0, 0, 0), (1, 0, 0), (0, 1, 0)], FLOAT, "VEC3")
    turns = g.accessor("4f", [(0, 0, 0, 1), (0, 0.7071, 0, 0.7071), (0, 1, 0, 0)], FLOAT, "VEC4")
    cubic = g.accessor("3f", [(0, 0, 0)] * 9, FLOAT, "VEC3")
    g.doc["animations"] = [{"name": "move", "samplers": [
        {"input": times, "output": moves}, {"input": times, "output": turns, "interpolation": "STEP"},
        {"input": times, "output": cubic, "interpolation": "CUBICSPLINE"}], "channels": [
        {"sampler": 0, "target": {"node": 0, "path": "translation"}},
        {"sampler": 1, "target": {"node": 0, "path": "rotation"}},
        {"sampler": 2, "target": {"node": 0, "path": "scale"}}]}]
    return g


def instanced():
    g = Gltf()
    mesh = tetrahedron(g, UBYTE, extras=False, mode=4)
    t = g.accessor("3f", [(0, 0, 0), (2, 0, 0), (4, 0, 0)], FLOAT, "VEC3")
    r = g.accessor("4h", [(0, 0, 0, 32767), (0, 32767, 0, 0), (0, 0, 0, 32767)], SHORT, "VEC4", normalized=True)
    s = g.accessor("3f", [(1, 1, 1), (2, 2, 2), (1, 1, 1)], FLOAT, "VEC3")
    g.node({"mesh": mesh, "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": t, "ROTATION": r, "SCALE": s}}}})
    g.doc["extensionsUsed"] = ["EXT_mesh_gpu_instancing", "KHR_mesh_quantization"]
    g.doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    return g


def skinned():
    """A tetrahedron with tangents, a second UV set, joints and weights on a skin of two joints (the second
    animated), and morph targets of positions and normals whose weights are animated."""
    g = Gltf()
    mesh = tetrahedron(g)
    attributes = g.doc["meshes"][mesh]["primitives"][0]["attributes"]
    attributes["TANGENT"] = g.accessor("4f", [(1.0, 0.0, 0.0, 1.0)] * 3 + [(0.0, 1.0, 0.0, -1.0)], FLOAT, "VEC4")
    attributes["TEXCOORD_1"] = g.accessor("2f", [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.5, 0.5)], FLOAT, "VEC2")
    attributes["JOINTS_0"] = g.accessor("4B", [(0, 0, 0, 0), (1, 0, 0, 0), (0, 1, 0, 0), (1, 0, 0, 0)], UBYTE, "VEC4")
    attributes["WEIGHTS_0"] = g.accessor("4f", [(1.0, 0, 0, 0), (1.0, 0, 0, 0), (0.5, 0.5, 0, 0), (1.0, 0, 0, 0)],
                                         FLOAT, "VEC4")
    morph = dict(g.doc["meshes"][mesh]["primitives"][0])
    morph["attributes"] = {"POSITION": attributes["POSITION"], "NORMAL": attributes["NORMAL"]}
    morph["targets"] = [{"POSITION": g.accessor("3f", [(0.0, 0.0, 0.5)] * 4, FLOAT, "VEC3", minmax=True),
                         "NORMAL": g.accessor("3f", [(0.0, 0.1, 0.0)] * 4, FLOAT, "VEC3")}]
    g.doc["meshes"].append({"name": "morphed", "primitives": [morph], "weights": [0.5]})
    g.doc["materials"][0]["normalTexture"] = {"index": 0, "texCoord": 1}
    g.doc["textures"] = [{"source": 0}]
    g.doc["images"] = [{"uri": "missing.png"}]
    hip = g.node({"name": "hip", "children": [1]})
    g.node({"name": "knee", "translation": [0, 1, 0]}, root=False)
    g.node({"name": "skinned", "mesh": mesh, "skin": 0})
    g.node({"name": "morphing", "mesh": 1, "weights": [0.25], "translation": [3, 0, 0]})
    g.doc["skins"] = [{"joints": [hip, 1], "skeleton": hip, "inverseBindMatrices": g.accessor(
        "16f", [tuple(float(i % 5 == 0) for i in range(16)), (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1)],
        FLOAT, "MAT4")}]
    times = g.accessor("f", [0.0, 1.0], FLOAT, "SCALAR")
    g.doc["animations"] = [{"samplers": [
        {"input": times, "output": g.accessor("4f", [(0, 0, 0, 1), (0.3827, 0, 0, 0.9239)], FLOAT, "VEC4")},
        {"input": times, "output": g.accessor("f", [0.0, 1.0], FLOAT, "SCALAR")}], "channels": [
        {"sampler": 0, "target": {"node": 1, "path": "rotation"}},
        {"sampler": 1, "target": {"node": 3, "path": "weights"}}]}]
    return g


for name, make in [("plain", plain), ("scene_graph", scene_graph), ("animated", animated), ("instanced", instanced),
                   ("materials", materials), ("skinned", skinned)]:
    write("glb", name + ".glb", make().glb())
    write("gltf", name + ".gltf", make().gltf())

# --- X3D --------------------------------------------------------------------------------------------------
X3D_HEAD = '<?xml version="1.0" encoding="UTF-8"?>\n<X3D profile="Interchange" version="3.3">\n<head><meta name="title" content="seed"/></head>\n<Scene>\n'
X3D_TAIL = "</Scene>\n</X3D>\n"
x3d_faces = X3D_HEAD + """<WorldInfo title="seed" info='"a" "b"'/>
<NavigationInfo avatarSize="0.25 1.6 0.75" visibilityLimit="100" type='"EXAMINE"'/>
<Background skyColor="0 0 1" groundColor="0 1 0" frontUrl='"front.png"'><MetadataString name="m" value='"v"'/></Background>
<Fog color="1 1 1" visibilityRange="50"/>
<Viewpoint DEF="view" position="0 0 10" orientation="0 1 0 0.3" fieldOfView="0.7" description="front"/>
<OrthoViewpoint fieldOfView="-2 -1 2 1"/>
<DirectionalLight direction="0 -1 0" intensity="0.5"/>
<PointLight location="1 2 3" radius="10" attenuation="1 0 0"/>
<SpotLight location="0 5 0" direction="0 -1 0" cutOffAngle="0.6" beamWidth="0.4" global="false"/>
<Transform DEF="mover" translation="1 0 0" rotation="0 0 1 0.5" scale="1 2 1">
 <Shape DEF="quad">
  <Appearance DEF="look"><Material DEF="red" diffuseColor="1 0 0" specularColor="1 1 1" shininess="0.5" transparency="0.25"/>
   <ImageTexture url='"data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg=="'/></Appearance>
  <IndexedFaceSet solid="false" ccw="true" coordIndex="0 1 2 3 -1 0 3 4 -1" normalPerVertex="true" colorPerVertex="false" colorIndex="0 1" texCoordIndex="0 1 2 3 -1 0 3 1 -1">
   <Coordinate point="0 0 0, 1 0 0, 1 1 0, 0 1 0, 0.5 2 0"/>
   <Normal vector="0 0 1 0 0 1 0 0 1 0 0 1 0 0 1"/>
   <Color color="1 0 0 0 1 0"/>
   <TextureCoordinate point="0 0 1 0 1 1 0 1"/>
  </IndexedFaceSet>
 </Shape>
</Transform>
<Transform translation="0 3 0" center="1 1 1" scaleOrientation="0 1 0 0.2"><Shape USE="quad"/></Transform>
<Group><Shape><Appearance USE="look"/><IndexedTriangleSet index="0 1 2 0 2 3"><CoordinateDouble point="0 0 0 1 0 0 1 1 0 0 1 0"/><ColorRGBA color="1 0 0 1 0 1 0 1 0 0 1 1 1 1 1 0.5"/></IndexedTriangleSet></Shape></Group>
<Shape><Appearance><TwoSidedMaterial diffuseColor="0 1 0"/></Appearance><TriangleSet><Coordinate point="0 0 0 1 0 0 0 1 0"/></TriangleSet></Shape>
<TimeSensor DEF="clock" cycleInterval="2" loop="true"/>
<PositionInterpolator DEF="path" key="0 0.5 1" keyValue="0 0 0 1 0 0 0 0 0"/>
<OrientationInterpolator DEF="spin" key="0 1" keyValue="0 1 0 0 0 1 0 3.14"/>
<ROUTE fromNode="clock" fromField="fraction_changed" toNode="path" toField="set_fraction"/>
<ROUTE fromNode="clock" fromField="fraction_changed" toNode="spin" toField="set_fraction"/>
<ROUTE fromNode="path" fromField="value_changed" toNode="mover" toField="set_translation"/>
<ROUTE fromNode="spin" fromField="value_changed" toNode="mover" toField="set_rotation"/>
""" + X3D_TAIL
x3d_primitives = X3D_HEAD + """<Switch whichChoice="1"><Shape><Box size="1 2 3"/></Shape><Shape><Sphere radius="2"/></Shape></Switch>
<LOD><Shape><Appearance><PhysicalMaterial baseColor="1 1 0" metallic="0.2" roughness="0.3"/></Appearance><Cylinder radius="1" height="2" top="false"/></Shape><Shape><Cone/></Shape></LOD>
<Collision><Anchor><Billboard><StaticGroup><Shape><Cone bottomRadius="2" height="1" bottom="false"/></Shape></StaticGroup></Billboard></Anchor></Collision>
<CADAssembly><CADLayer><CADPart translation="1 1 1"><CADFace><Shape><Box/></Shape></CADFace></CADPart></CADLayer></CADAssembly>
<Shape><Extrusion/></Shape><Shape><Text string='"x"'/></Shape><ProtoInstance name="p"/><Inline url='"missing.x3d"'/>
""" + X3D_TAIL
x3d_made_faces = X3D_HEAD + """<Shape><IndexedTriangleStripSet index="0 1 2 3 -1 1 2 3" colorPerVertex="false"><Coordinate point="0 0 0 0 1 0 1 0 0 1 1 0"/><Color color="1 0 0 0 1 0"/></IndexedTriangleStripSet></Shape>
<Shape><IndexedTriangleFanSet index="0 1 2 3"><Coordinate point="0 0 0 0 1 0 1 0 0 1 1 0"/></IndexedTriangleFanSet></Shape>
<Shape><TriangleStripSet stripCount="4"><Coordinate point="0 0 0 0 1 0 1 0 0 1 1 0"/></TriangleStripSet></Shape>
<Shape><TriangleFanSet fanCount="3 2"><Coordinate point="0 0 0 0 1 0 1 0 0 1 1 0"/></TriangleFanSet></Shape>
<Shape><IndexedQuadSet index="0 1 3 2"><Coordinate point="0 0 0 0 1 0 1 0 0 1 1 0"/></IndexedQuadSet></Shape>
<Shape><QuadSet normalPerVertex="false"><Coordinate point="0 0 0 0 1 0 1 1 0 1 0 0"/><Normal vector="0 0 1"/></QuadSet></Shape>
<Shape><ElevationGrid xDimension="3" zDimension="2" xSpacing="0.5" creaseAngle="1" height="0 1 0 1 0 1"><Color color="1 0 0 0 1 0 0 0 1 1 1 1 0 0 0 1 1 0"/></ElevationGrid></Shape>
<Shape><Rectangle2D size="2 1"/></Shape><Shape><Disk2D innerRadius="0.5"/></Shape><Shape><TriangleSet2D vertices="0 0 1 0 0 1"/></Shape>
<Shape><Circle2D/></Shape><Shape><Arc2D startAngle="4" endAngle="1"/></Shape><Shape><Polyline2D lineSegments="0 0 1 1 2 0"/></Shape><Shape><Polypoint2D point="0 0 1 1"/></Shape><Shape><ArcClose2D closureType="CHORD" endAngle="7"/></Shape>
<Shape><Extrusion spine="0 0 0 0 1 0 1 2 0 0 0 0" crossSection="1 1 1 -1 -1 -1 -1 1 1 1" scale="1 1 0 0 0.5 0.5" orientation="0 1 0 0.5" convex="false" creaseAngle="0.5" beginCap="false"/></Shape>
""" + X3D_TAIL
x3d_prototypes = X3D_HEAD + """<ProtoDeclare name="P"><ProtoInterface><field name="h" type="SFFloat" accessType="initializeOnly" value="2"/>
<field name="g" type="SFNode" accessType="initializeOnly"><Box/></field></ProtoInterface>
<ProtoBody><Transform DEF="t"><Shape><Appearance><Material/></Appearance><IS><connect nodeField="geometry" protoField="g"/></IS></Shape>
<Shape><Cylinder><IS><connect nodeField="height" protoField="h"/></IS></Cylinder></Shape></Transform></ProtoBody></ProtoDeclare>
<ProtoDeclare name="Q"><ProtoBody><Group><ProtoInstance name="P"><fieldValue name="h" value="3"/></ProtoInstance></Group></ProtoBody></ProtoDeclare>
<ExternProtoDeclare name="E" url='"missing.x3d#P"'/>
<Transform><ProtoInstance name="Q" DEF="q"/></Transform><Transform translation="2 0 0"><ProtoInstance name="Q" USE="q"/></Transform>
<ProtoInstance name="P"><fieldValue name="g"><Sphere/></fieldValue></ProtoInstance><ProtoInstance name="E"/>
""" + X3D_TAIL
write("x3d", "faces.x3d", x3d_faces)
write("x3d", "prototypes.x3d", x3d_prototypes)
write("x3d", "made_faces.x3d", x3d_made_faces)
write("x3d", "primitives.x3d", x3d_primitives)
write("x3d", "faces.x3dz", gzip.compress(x3d_faces.encode(), mtime=0))

# --- OBJ (with its MTL after a "#@mtl" line, as fuzz_obj.cpp splits them) ---------------------------------
obj = """# seed
mtllib scene.mtl
o first
v 0 0 0
v 1 0 0 1 0 0
v 1 1 0 0 1 0
v 0 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0.5
vn 0 0 1
usemtl red
f 1/1/1 2/2/1 3/3/1 4/4/1
g second
usemtl unknown
f -4//1 -3//1 -2//1
f 1 2 3
l 1 2
p 1
curv 0 1 1 2
"""
mtl = """newmtl red
Kd 1 0 0
Ks 0.5 0.5 0.5
Ke 0 0 0
Ns 250
d 0.5
Tr 0.25
map_Kd -s 1 1 1 missing.png
"""
write("obj", "with_mtl.obj", obj + "#@mtl\n" + mtl)
write("obj", "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")

# --- PLY --------------------------------------------------------------------------------------------------
ply_header = """ply
format {format} 1.0
comment seed
obj_info none
element vertex 4
property float x
property float y
property float z
property float nx
property float ny
property float nz
property uchar red
property uchar green
property uchar blue
property uchar alpha
property float s
property float t
element face 2
property list uchar int vertex_indices
element edge 1
property int vertex1
property int vertex2
end_header
"""
vertices = [(0, 0, 0, 0, 0, 1, 255, 0, 0, 255, 0, 0), (1, 0, 0, 0, 0, 1, 0, 255, 0, 255, 1, 0),
            (1, 1, 0, 0, 0, 1, 0, 0, 255, 255, 1, 1), (0, 1, 0, 0, 0, 1, 9, 9, 9, 128, 0, 1)]
faces = [[0, 1, 2, 3], [0, 2, 3]]
ascii_body = "".join(" ".join(str(v) for v in vertex) + "\n" for vertex in vertices)
ascii_body += "".join(f"{len(face)} " + " ".join(map(str, face)) + "\n" for face in faces) + "0 1\n"
write("ply", "ascii.ply", ply_header.format(format="ascii") + ascii_body)
for order, name in (("<", "binary_little_endian"), (">", "binary_big_endian")):
    body = b"".join(struct.pack(order + "6f4B2f", *vertex) for vertex in vertices)
    body += b"".join(struct.pack(order + "B" + f"{len(face)}i", len(face), *face) for face in faces)
    body += struct.pack(order + "2i", 0, 1)
    write("ply", name + ".ply", ply_header.format(format=name).encode() + body)
write("ply", "double_uint.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\n"
      "property double z\nelement face 1\nproperty list uint uint vertex_index\nend_header\n".encode() +
      struct.pack("<9d", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<4I", 3, 0, 1, 2))
write("ply", "corner_texcoords.ply", "ply\nformat ascii 1.0\ncomment TextureFile tex.png\nelement vertex 4\n"
      "property float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar int vertex_indices\n"
      "property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2 6 0 0 1 0 1 1\n"
      "3 0 2 3 6 0.5 0.5 1 1 0 1\n")

# --- STL --------------------------------------------------------------------------------------------------
write("stl", "ascii.stl", "solid seed\n" + "".join(
    f"facet normal 0 0 1\n outer loop\n  vertex {a}\n  vertex {b}\n  vertex {c}\n endloop\nendfacet\n"
    for a, b, c in [("0 0 0", "1 0 0", "0 1 0"), ("1 0 0", "1 1 0", "0 1 0")]) + "endsolid seed\n")
triangles = [((0, 0, 1), (0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 1), (1, 0, 0), (1, 1, 0), (0, 1, 0))]
write("stl", "binary.stl", b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(triangles)) +
      b"".join(struct.pack("<12fH", *(c for corner in t for c in corner), 0) for t in triangles))
