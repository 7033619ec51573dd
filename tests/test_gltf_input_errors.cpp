// Broken glTF input: an index that names no item, another glTF version, a node hierarchy that is no forest, an
// accessor of a type or count glTF has not, a buffer outside the file's folder, a rotation of length 0. Each is one
// clear error naming the file and the item, or, where the item can be left out without losing geometry, a warning
// naming it.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>

using namespace symcompress;
using namespace symcompress::testing;
using Json = nlohmann::json;

namespace {

// One triangle drawn by node 0, with a texture, a camera on node 1, a skin and an animation of node 1: something
// for every kind of index to refer to. The buffer holds the triangle's positions (view 0) and indices (view 1), the
// animation's times (view 2) and translations (view 3), and an inverse bind matrix (view 4).
Json triangleScene() {
    return Json::parse(R"({
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": 140, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAAAAAAAAAAAAgD8="}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 6},
                        {"buffer": 0, "byteOffset": 44, "byteLength": 8}, {"buffer": 0, "byteOffset": 52, "byteLength": 24},
                        {"buffer": 0, "byteOffset": 76, "byteLength": 64}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
                      {"bufferView": 2, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                      {"bufferView": 3, "componentType": 5126, "count": 2, "type": "VEC3"},
                      {"bufferView": 4, "componentType": 5126, "count": 1, "type": "MAT4"}],
        "images": [{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4z8AAAAMBAQDJ/pLvAAAAAElFTkSuQmCC"}],
        "samplers": [{}],
        "textures": [{"source": 0, "sampler": 0}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}],
        "skins": [{"joints": [1], "inverseBindMatrices": 4}],
        "nodes": [{"mesh": 0, "children": [1]}, {"camera": 0}],
        "scenes": [{"nodes": [0]}], "scene": 0,
        "animations": [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
                        "samplers": [{"input": 2, "output": 3}]}]})");
}

// The scene of `json` read: its one triangle still drawn, with a warning holding `warning`.
void expectWarning(const TemporaryFolder& folder, const Json& json, const std::string& warning) {
    const auto file = folder / "warned.gltf";
    writeTextFile(file, json.dump());
    const Scene scene = readScene(file);
    CHECK(worldMesh(scene).triangles.size() == 1);
    bool found = false;
    for (const std::string& text : scene.warnings) found = found || text.find(warning) != std::string::npos;
    INFO("warnings: " << Json(scene.warnings).dump());
    CHECK(found);
}

// A GLB file of `json` whose header says `version`.
std::string glb(const Json& json, std::uint32_t version) {
    std::string text = json.dump();
    while (text.size() % 4) text.push_back(' ');
    const std::uint32_t header[5] = {0x46546C67u, version, std::uint32_t(20 + text.size()), std::uint32_t(text.size()),
                                     0x4E4F534Au};
    std::string bytes(sizeof header, '\0');
    std::memcpy(bytes.data(), header, sizeof header);
    return bytes + text;
}

}  // namespace

TEST_CASE("The glTF test scene reads without a warning", "[io][bad-input]") {
    TemporaryFolder folder;
    writeTextFile(folder / "triangle.gltf", triangleScene().dump());
    const Scene scene = readScene(folder / "triangle.gltf");
    CHECK(worldMesh(scene).triangles.size() == 1);
    CHECK(scene.warnings.empty());
    CHECK(scene.cameras.size() == 1);
    CHECK(scene.skins.size() == 1);
    CHECK(scene.animations.size() == 1);
    CHECK(scene.textures.size() == 1);
}

TEST_CASE("A glTF index by which geometry is found that names no item is an error naming the file and the item",
          "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    auto expect = [&](const std::string& problem) { expectReadError(folder, "scene.gltf", json.dump(), problem); };
    SECTION("a node's mesh") {
        json["nodes"][0]["mesh"] = 5;
        expect("node 0 refers to mesh 5, but the file has 1 mesh");
    }
    SECTION("a negative mesh") {
        json["nodes"][0]["mesh"] = -2;
        expect("node 0 refers to mesh -2, but the file has 1 mesh");
    }
    SECTION("a mesh that is not a number") {
        json["nodes"][0]["mesh"] = "0";
        expect("node 0 refers to mesh \"0\", which is not an index");
    }
    SECTION("a node's child") {
        json["nodes"][0]["children"] = {7};
        expect("node 0 refers to node 7 for its children, but the file has 2 nodes");
    }
    SECTION("children that are no list") {
        json["nodes"][0]["children"] = 1;
        expect("node 0: children must be a list of node indices");
    }
    SECTION("a scene's node") {
        json["scenes"][0]["nodes"] = {9};
        expect("scene 0 refers to node 9, but the file has 2 nodes");
    }
    SECTION("the default scene") {
        json["scene"] = 3;
        expect("the file's \"scene\" refers to scene 3, but the file has 1 scene");
    }
    SECTION("a primitive's indices") {
        json["meshes"][0]["primitives"][0]["indices"] = 8;
        expect("mesh 0 primitive 0 refers to accessor 8 for its indices, but the file has 5 accessors");
    }
    SECTION("a primitive's POSITION") {
        json["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;
        expect("mesh 0 primitive 0 refers to accessor 99 for its POSITION, but the file has 5 accessors");
    }
    SECTION("a primitive's other attribute") {
        json["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 8;
        expect("mesh 0 primitive 0 refers to accessor 8 for its TEXCOORD_1");
    }
    SECTION("a morph target's attribute") {
        json["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 8}}};
        expect("mesh 0 primitive 0 morph target 0 refers to accessor 8 for its POSITION");
    }
    SECTION("an accessor's buffer view") {
        json["accessors"][0]["bufferView"] = 9;
        expect("accessor 0 refers to buffer view 9, but the file has 5 buffer views");
    }
    SECTION("the buffer view of an accessor of indices") {
        json["accessors"][1]["bufferView"] = 9;
        expect("accessor 1 refers to buffer view 9, but the file has 5 buffer views");
    }
    SECTION("a sparse accessor's buffer view") {
        json["accessors"][0]["sparse"] = {
            {"count", 1}, {"indices", {{"bufferView", 1}, {"componentType", 5123}}}, {"values", {{"bufferView", 7}}}};
        expect("accessor 0 (its sparse values) refers to buffer view 7");
    }
    SECTION("a buffer view's buffer") {
        json["bufferViews"][0]["buffer"] = 3;
        expect("buffer view 0 refers to buffer 3, but the file has 1 buffer");
    }
    SECTION("an image's buffer view") {
        json["images"][0] = {{"bufferView", 6}, {"mimeType", "image/png"}};
        expect("image 0 refers to buffer view 6, but the file has 5 buffer views");
    }
}

TEST_CASE("A glTF index of an item that can be left out is a warning naming it, and the geometry is kept",
          "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    SECTION("a primitive's material") {
        json["meshes"][0]["primitives"][0]["material"] = 6;
        expectWarning(folder, json,
                      "mesh 0 primitive 0 refers to material 6, but the file has 1 material: drawn with the default "
                      "material");
    }
    SECTION("a texture's sampler") {
        json["textures"][0]["sampler"] = 5;
        expectWarning(folder, json, "texture 0: sampler 5 does not exist");
    }
    SECTION("a texture's image") {
        json["textures"][0]["source"] = 5;
        expectWarning(folder, json, "texture 0 has no image");
    }
    SECTION("a node's camera") {
        json["nodes"][1]["camera"] = 3;
        expectWarning(folder, json, "node 1 refers to camera 3, but the file has 1 camera: the camera ignored");
    }
    SECTION("a node's skin") {
        json["nodes"][0]["skin"] = 4;
        expectWarning(folder, json, "node 0 refers to skin 4, but the file has 1 skin: the skin ignored");
    }
    SECTION("a skin's joint") {
        json["skins"][0]["joints"] = {1, 8};
        expectWarning(folder, json,
                      "skin 0 refers to node 8 for its joints, but the file has 2 nodes: the skin ignored");
    }
    SECTION("a skin's inverse bind matrices") {
        json["skins"][0]["inverseBindMatrices"] = 8;
        expectWarning(folder, json, "skin 0 refers to accessor 8 for its inverseBindMatrices, but the file has 5");
    }
    SECTION("an animation channel's node") {
        json["animations"][0]["channels"][0]["target"]["node"] = 8;
        expectWarning(folder, json,
                      "animation 0 channel 0 refers to node 8 for its target, but the file has 2 nodes: the channel "
                      "ignored");
    }
    SECTION("an animation channel's sampler") {
        json["animations"][0]["channels"][0]["sampler"] = 8;
        expectWarning(folder, json,
                      "animation 0 channel 0 ignored: it refers to sampler 8, but animation 0 has 1 sampler");
    }
    SECTION("an animation sampler's input") {
        json["animations"][0]["samplers"][0]["input"] = 8;
        expectWarning(folder, json,
                      "animation 0 sampler 0 refers to accessor 8 for its input, but the file has 5 accessors: "
                      "channel 0 ignored");
    }
    SECTION("an animation sampler's output") {
        json["animations"][0]["samplers"][0]["output"] = 8;
        expectWarning(folder, json, "animation 0 sampler 0 refers to accessor 8 for its output");
    }
}

TEST_CASE("glTF 1.0, and versions a glTF 2.0 reader may not read, are refused with a clear error", "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    const std::string convert = "convert it to glTF 2.0 (for example with gltf-pipeline";
    SECTION("asset.version 1.0") {
        json["asset"]["version"] = "1.0";
        expectReadError(folder, "old.gltf", json.dump(), "glTF 1.0 is not supported; " + convert);
    }
    SECTION("an empty glTF 1.0 file") {
        expectReadError(folder, "old.gltf", R"({"asset": {"version": "1.0"}})", "glTF 1.0 is not supported");
    }
    SECTION("GLB version 1") {
        expectReadError(folder, "old.glb", glb(json, 1), "glTF 1.0 (GLB version 1) is not supported; " + convert);
    }
    SECTION("GLB version 3") { expectReadError(folder, "new.glb", glb(json, 3), "GLB version 3 is not supported"); }
    SECTION("no asset.version") {
        json["asset"].erase("version");
        expectReadError(folder, "scene.gltf", json.dump(), "no asset.version, which glTF 2.0 requires");
    }
    SECTION("no asset") {
        json.erase("asset");
        expectReadError(folder, "scene.gltf", json.dump(), "no asset.version");
    }
    SECTION("asset.version that is no version") {
        json["asset"]["version"] = 2.0;
        expectReadError(folder, "scene.gltf", json.dump(), "asset.version 2.0 is not a version such as \"2.0\"");
    }
    SECTION("glTF 3.0") {
        json["asset"]["version"] = "3.0";
        expectReadError(folder, "scene.gltf", json.dump(), "glTF 3.0 is not supported");
    }
    SECTION("asset.minVersion above 2.0") {
        json["asset"]["minVersion"] = "2.1";
        expectReadError(folder, "scene.gltf", json.dump(), "asset.minVersion is 2.1");
    }
    SECTION("glTF 2.1 and asset.minVersion 2.0 are read") {
        json["asset"]["version"] = "2.1";
        json["asset"]["minVersion"] = "2.0";
        writeTextFile(folder / "newer.gltf", json.dump());
        CHECK(worldMesh(readScene(folder / "newer.gltf")).triangles.size() == 1);
    }
}

TEST_CASE("A glTF node hierarchy with a cycle, or a node of two parents, is refused naming a node of it",
          "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    json.erase("animations");
    json.erase("skins");
    auto expect = [&](const std::string& problem) { expectReadError(folder, "scene.gltf", json.dump(), problem); };
    SECTION("a node that is its own child") {
        json["nodes"][0]["children"] = {0};
        expect("the node hierarchy has a cycle: node 0 is its own child");
    }
    SECTION("a cycle of two nodes, from the scene's root") {
        json["nodes"][1]["children"] = {0};
        expect("the node hierarchy has a cycle: node 0 has child 1, which has child 0");
    }
    SECTION("a cycle of three nodes that no scene reaches") {
        json["nodes"] = {{{"mesh", 0}}, {{"children", {2}}}, {{"children", {3}}}, {{"children", {1}}}};
        expect("the node hierarchy has a cycle: node 1 has child 2, which has child 3, which has child 1");
    }
    SECTION("a cycle in a file without scenes") {
        json.erase("scenes");
        json.erase("scene");
        json["nodes"][0]["children"] = {0};
        expect("node 0 is its own child");
    }
    SECTION("a node of two parents") {
        json["nodes"].push_back({{"children", {1}}});
        json["scenes"][0]["nodes"] = {0, 2};
        expect("node 1 is a child of two nodes, 0 and 2");
    }
    SECTION("a child listed twice") {
        json["nodes"][0]["children"] = {1, 1};
        expect("node 0 lists node 1 as its child twice");
    }
    SECTION("a scene's node that has a parent") {
        json["scenes"][0]["nodes"] = {0, 1};
        expect("scene 0 lists node 1 as a root, but it is a child of node 0");
    }
    SECTION("a scene's node listed twice (found by fuzz_gltf: the X3D writer's DEFs then failed)") {
        json["scenes"][0]["nodes"] = {0, 0};
        expect("scene 0 lists node 0 as a root twice");
    }
}

TEST_CASE("An accessor's componentType or type that glTF does not allow is refused naming the accessor",
          "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    auto expect = [&](const std::string& problem) { expectReadError(folder, "scene.gltf", json.dump(), problem); };
    const std::string allowed = " is not one glTF allows (5120-5123, 5125, 5126)";
    SECTION("double") {
        json["accessors"][0]["componentType"] = 5130;
        expect("accessor 0: componentType 5130" + allowed);
    }
    SECTION("signed int") {
        json["accessors"][1]["componentType"] = 5124;
        expect("accessor 1: componentType 5124" + allowed);
    }
    SECTION("a number tinygltf refuses") {
        json["accessors"][2]["componentType"] = 1;
        expect("accessor 2: componentType 1" + allowed);
    }
    SECTION("an unknown type") {
        json["accessors"][0]["type"] = "VEC7";
        expect("accessor 0: type \"VEC7\" is not one glTF allows (SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3, MAT4)");
    }
    SECTION("a type that is no string") {
        json["accessors"][3]["type"] = 3;
        expect("accessor 3: type 3 is not one glTF allows");
    }
}

TEST_CASE("An accessor count that is no number of elements is refused naming the accessor", "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    SECTION("negative") {
        json["accessors"][0]["count"] = -5;
        expectReadError(folder, "scene.gltf", json.dump(), "accessor 0: count -5 is not a number of elements");
    }
    SECTION("a string") {
        json["accessors"][0]["count"] = "12";
        expectReadError(folder, "scene.gltf", json.dump(), "accessor 0: count \"12\" is not a number of elements");
    }
}

TEST_CASE("A buffer uri that is not relative to the glTF file is refused saying so", "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    // Even a file that is there: tinygltf looks for every buffer in the glTF file's folder.
    writeTextFile(folder / "triangle.bin", std::string(140, '\0'));
    for (const std::string uri : {(folder / "triangle.bin").string(), std::string("file:///etc/passwd"),
                                  std::string("https://example.com/triangle.bin")}) {
        json["buffers"][0]["uri"] = uri;
        expectReadError(folder, "scene.gltf", json.dump(),
                        "buffer 0: its uri \"" + uri + "\" is not relative to the glTF file");
    }
    json["buffers"][0]["uri"] = "triangle.bin";  // the same file, named relative to the glTF file, is read
    writeTextFile(folder / "relative.gltf", json.dump());
    CHECK(worldMesh(readScene(folder / "relative.gltf")).triangles.size() == 1);
}

TEST_CASE("A node rotation of length 0 is read as none, with a warning", "[io][bad-input]") {
    TemporaryFolder folder;
    Json json = triangleScene();
    json["nodes"][0]["rotation"] = {0, 0, 0, 0};
    expectWarning(folder, json, "node 0: a rotation of (0, 0, 0, 0), which is no rotation glTF allows, read as none");
    const Scene scene = readScene(folder / "warned.gltf");
    CHECK(scene.nodes[0].transform.isIdentity());
}
