// The readers on every shared model (counts from ../shared/models/MANIFEST.md), a transform chain checked
// by hand, and one test per kind of bad input.
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

bool hasWarning(const Scene& scene, const std::string& text) {
    for (const auto& warning : scene.warnings)
        if (warning.find(text) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST_CASE("Every shared model reads with the manifest's triangle counts", "[io][models]") {
    struct Expected {
        const char* file;
        std::size_t drawn, stored;
        const char* warning = nullptr;  // a warning that must be there, when faces are skipped
    };
    // The manifest counts fan-triangulated polygons including faces without area; the readers keep those, as
    // viewers draw and count them (the spider's 56, the teapot's 32).
    const std::vector<Expected> models{
        {"cesium_milk_truck/CesiumMilkTruck.gltf", 3624, 2856},
        {"vianney_house_2/scene.gltf", 56674, 56674},
        {"vulkan_subpass_scene/subpass_scene_opaque.gltf", 23388, 11132},
        {"kenney_racing_forest/decoration-forest.glb", 2006, 2006},
        {"cge_sterile_room/sterile_room.gltf", 5066, 5066},
        {"cge_grass_flowers/grass_flowers.x3d", 5848, 5848},
        {"assimp_spider/spider.obj", 1368, 1368},
        {"savage_chevy_tahoe/ChevyTahoe.x3d", 1298, 1106},
        {"vulkan_torusknot/torusknot.gltf", 2880, 2880},
        {"vulkan_geosphere/geosphere.gltf", 1280, 1280},
        {"khronos_lantern/Lantern.gltf", 5394, 5394},
        {"xj3d_coffee_cup/coffeeCup.x3d", 3914, 3914},
        {"oded_wingnut/wingnut.obj", 6090, 6090},
        {"menger_sponge/Menger_sponge-Binary.stl", 2112, 2112},
        {"xj3d_cad_teapot/teapot.x3d", 1024, 1024},
        {"vulkan_rock/rock.gltf", 180, 180},
        {"cge_cat_x3d/scene.x3d", 4285, 4285},
        {"stanford_bunny/bun_zipper.ply", 69451, 69451},
        {"oded_hammer/hammer.obj", 60160, 60160},
        {"oded_demosthenes/demosthenes-low-res.obj", 16719, 16719},
        {"oded_koala/koala.obj", 99994, 99994},
    };
    for (const auto& model : models) {
        INFO(model.file);
        const Scene scene = readScene(modelPath(model.file));
        REQUIRE_NOTHROW(validateScene(scene));
        const SceneStatistics statistics = sceneStatistics(scene);
        CHECK(statistics.trianglesDrawn == model.drawn);
        CHECK(statistics.trianglesStored == model.stored);
        if (model.warning) CHECK(hasWarning(scene, model.warning));
    }
}

TEST_CASE("The spider's Windows-style texture paths are found", "[io][models]") {
    const Scene scene = readScene(modelPath("assimp_spider/spider.obj"));
    REQUIRE(scene.textures.size() == 5);
    for (const auto& texture : scene.textures) {
        INFO(texture.uri);
        CHECK_FALSE(texture.bytes.empty());
    }
    CHECK_FALSE(hasWarning(scene, "not found"));
}

TEST_CASE("The Chevy Tahoe's transform chain puts a vertex where X3D says", "[io][x3d]") {
    // The first vertex of the second Shape, (10.28, 5.649, -1.264), under Transform(rotation, scale,
    // scaleOrientation, translation) in Body (rotation, non-uniform scale, translation) in ChevyTahoe
    // (rotation), composed by hand as T R SR S SR^-1 per level (no centers): see the manifest's model.
    const Eigen::Vector3d expected(-2.109259798708544, 2.106950176713533, -0.7903237842805562);
    const Scene scene = readScene(modelPath("savage_chevy_tahoe/ChevyTahoe.x3d"));
    double closest = std::numeric_limits<double>::infinity();
    for (const auto& placed : flattenScene(scene))
        for (const auto& p : placed.primitive.positions) closest = std::min(closest, (p - expected).norm());
    CHECK(closest < 1e-9);
}

TEST_CASE("Each kind of bad input gives one clear error naming the file", "[io][bad-input]") {
    TemporaryFolder folder;
    auto expectError = [&](const std::string& name, const std::string& content, const std::string& problem) {
        expectReadError(folder, name, content, problem);
    };
    const std::string triangleGltf = R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 36, "uri": "missing.bin"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})";

    SECTION("empty file") { expectError("empty.glb", "", "empty"); }
    SECTION("truncated GLB") { expectError("truncated.glb", std::string("glTF\x02\0\0\0", 8), "GLB"); }
    SECTION("wrong GLB magic") { expectError("magic.glb", std::string(64, 'x'), "GLB"); }
    SECTION("missing .bin") { expectError("scene.gltf", triangleGltf, "missing.bin"); }
    SECTION("malformed JSON") { expectError("broken.gltf", "{\"asset\": ", "parse error"); }
    SECTION("malformed XML") { expectError("broken.x3d", "<X3D><Scene><Shape></X3D>", "XML"); }
    SECTION("USE of an unknown DEF") {
        expectError("use.x3d", "<X3D><Scene><Shape USE='Nowhere'/></Scene></X3D>", "Nowhere");
    }
    SECTION("X3D index out of range") {
        expectError("index.x3d",
                    "<X3D><Scene><Shape><IndexedFaceSet coordIndex='0 1 7 -1'><Coordinate point='0 0 0 1 0 0 0 1 0'/>"
                    "</IndexedFaceSet></Shape></Scene></X3D>",
                    "7");
    }
    SECTION("NaN coordinate in X3D") {
        expectError("nan.x3d",
                    "<X3D><Scene><Shape><IndexedFaceSet coordIndex='0 1 2 -1'><Coordinate point='0 0 0 1 0 0 0 nan 0'/>"
                    "</IndexedFaceSet></Shape></Scene></X3D>",
                    "finite");
    }
    SECTION("OBJ index out of range") { expectError("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "9"); }
    SECTION("NaN coordinate in OBJ") { expectError("nan.obj", "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n", "finite"); }
    SECTION("truncated binary PLY") {
        expectError("truncated.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\x01\x02",
                    "truncated");
    }
    SECTION("truncated binary STL") { expectError("truncated.stl", std::string(80, ' ') + std::string("\x05\0\0\0", 4), "truncated"); }
    SECTION("truncated binary STL whose header starts with solid") {
        expectError("solid.stl", "solid part" + std::string(70, '\0') + std::string("\x05\0\0\0", 4),
                    "announces 5 triangles");
    }
    SECTION("binary data as OBJ") {
        expectError("binary.obj", std::string("\x8f\x13v\0\xff 1 2\n\x01\0\0f", 14), "not an OBJ text file");
    }
    SECTION("text that is no OBJ") { expectError("text.obj", "Dear reader,\nthis is a letter.\n", "not an OBJ file"); }
    SECTION("OBJ vertex of 5 numbers") {
        expectError("five.obj", "v 0 0 0\nv 1 0 0 1 0\nv 0 1 0\nf 1 2 3\n", "a vertex of 5 numbers");
    }
    SECTION("a directory") {
        std::filesystem::create_directory(folder / "folder.glb");
        try {
            readScene(folder / "folder.glb");
            FAIL("no error for a directory");
        } catch (const FileError& error) {
            CHECK_THAT(error.what(), Catch::Contains("folder.glb") && Catch::Contains("directory"));
        }
    }
}

TEST_CASE("OBJ and MTL: a byte order mark, comments after a statement and continued lines are read", "[io]") {
    TemporaryFolder folder;
    const std::string bom = "\xEF\xBB\xBF";
    auto read = [&](const std::string& obj, const std::string& mtl) {
        writeTextFile(folder / "part.obj", obj);
        writeTextFile(folder / "part.mtl", mtl);
        const Scene scene = readScene(folder / "part.obj");
        for (const std::string& warning : scene.warnings) UNSCOPED_INFO(warning);
        return scene;
    };
    SECTION("a byte order mark before mtllib and newmtl, with Unix and Windows line ends") {
        for (const std::string lineEnd : {"\n", "\r\n"}) {
            const Scene scene = read(bom + "mtllib part.mtl" + lineEnd + "usemtl red" + lineEnd + "v 0 0 0" + lineEnd +
                                         "v 1 0 0" + lineEnd + "v 0 1 0" + lineEnd + "f 1 2 3" + lineEnd,
                                     bom + "newmtl red" + lineEnd + "Kd 1 0 0" + lineEnd);
            CHECK_FALSE(hasWarning(scene, "not defined"));
            REQUIRE(scene.materials.size() == 1);
            CHECK(scene.materials[0].name == "red");
            CHECK(scene.materials[0].phong->diffuseColor == Eigen::Vector3d(1, 0, 0));
            CHECK(sceneStatistics(scene).trianglesDrawn == 1);
        }
    }
    SECTION("comments after statements, a '#' inside a name kept") {
        const Scene scene = read(
            "mtllib part.mtl # the library\nusemtl red#2\t# a name with '#'\nv 0 0 0 # origin\n"
            "v\t1 0 0\t#x\nv 0 1 0\nv 0 0 1 1 0 0 # red\nf 1 2 3 # first\nf 1 3 4 #\n",
            "newmtl red#2 # a comment\nKd 0 1 0 # green\nd 1 # opaque\n");
        CHECK_FALSE(hasWarning(scene, "not defined"));
        REQUIRE(scene.materials.size() == 1);
        CHECK(scene.materials[0].name == "red#2");
        CHECK(scene.materials[0].phong->diffuseColor == Eigen::Vector3d(0, 1, 0));
        CHECK(sceneStatistics(scene).trianglesDrawn == 2);
        CHECK(scene.meshes.at(0).primitives.at(0).colors.size() == 4);
    }
    SECTION("lines continued by a backslash, in the OBJ and its library") {
        const Scene scene = read(
            "mtllib \\\npart.mtl\nusemtl red\nv 0 0 0\nv 1 \\\n  0 0\nv 0 1 0\nv 0 0 1\nf 1 2 \\\n 3\n"
            "f 1 3 \\  \r\n4 # a space after the backslash, and a Windows line end\nf 1 4 2 \\",
            "newmtl red\nKd 1 \\\n0 \\\n0\n");
        CHECK_FALSE(hasWarning(scene, "not defined"));
        REQUIRE(scene.materials.size() == 1);
        CHECK(scene.materials[0].phong->diffuseColor == Eigen::Vector3d(1, 0, 0));
        CHECK(sceneStatistics(scene).trianglesDrawn == 3);
    }
}

TEST_CASE("OBJ: a vertex's weight w is ignored, numbers after its colour too, and unknown statements warned of",
          "[io]") {
    TemporaryFolder folder;
    writeTextFile(folder / "part.obj", "v 0 0 0 1\nv 2 0 0 1.0\nv 0 2 0 0.5\nf 1 2 3\n");
    const Scene weighted = readScene(folder / "part.obj");
    REQUIRE(sceneStatistics(weighted).trianglesDrawn == 1);
    const Primitive& triangle = weighted.meshes.at(0).primitives.at(0);
    CHECK(triangle.colors.empty());
    CHECK(std::count(triangle.positions.begin(), triangle.positions.end(), Eigen::Vector3d(0, 2, 0)) == 1);
    CHECK(hasWarning(weighted, "part.obj: 1 vertex weights w other than 1 ignored"));

    writeTextFile(folder / "part.obj",
                  "s 1\nv 0 0 0 1 0 0 0.5\nv 1 0 0 1 0 0 1\nv 0 1 0 1 0 0\nvendor_tag x\nf 1 2 3\n");
    const Scene withAlpha = readScene(folder / "part.obj");
    const Primitive& red = withAlpha.meshes.at(0).primitives.at(0);
    REQUIRE(red.colors.size() == 3);
    for (const Eigen::Vector4d& color : red.colors) CHECK(color == Eigen::Vector4d(1, 0, 0, 1));
    CHECK(hasWarning(withAlpha, "part.obj: 2 vertices' numbers after x y z r g b ignored"));
    CHECK(hasWarning(withAlpha, "part.obj: 1 statements of keywords OBJ does not have ('vendor_tag' 1) ignored"));
    CHECK_FALSE(hasWarning(withAlpha, "'s'"));
}

TEST_CASE("STL: capital keywords, a byte order mark, and bytes after the announced triangles are read", "[io]") {
    TemporaryFolder folder;
    const std::string facets =
        " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
        "  endloop\n endfacet\n";
    auto upper = [](std::string text) {
        std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return std::toupper(c); });
        return text;
    };
    // A binary STL: `header` padded to 80 bytes, `triangles` copies of one triangle, then `extra` bytes.
    auto binary = [](const std::string& header, std::uint32_t triangles, std::size_t extra) {
        std::string bytes = header + std::string(80 - header.size(), ' ');
        bytes.append(reinterpret_cast<const char*>(&triangles), 4);
        const float record[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
        for (std::uint32_t t = 0; t < triangles; ++t)
            bytes.append(reinterpret_cast<const char*>(record), sizeof record).append(2, '\0');
        return bytes + std::string(extra, '\x7f');
    };
    auto read = [&](const std::string& content) {
        writeTextFile(folder / "part.stl", content);
        return readScene(folder / "part.stl");
    };
    CHECK(sceneStatistics(read(upper("solid part\n" + facets + facets + "endsolid part\n"))).trianglesDrawn == 2);
    CHECK(sceneStatistics(read("\xEF\xBB\xBFsolid part\r\n" + facets + "endsolid part\r\n")).trianglesDrawn == 1);
    CHECK(sceneStatistics(read(binary("solid part", 3, 0))).trianglesDrawn == 3);
    for (const std::string header : {"", "solid part"}) {
        INFO("header '" << header << "'");
        const Scene scene = read(binary(header, 3, 100));
        CHECK(sceneStatistics(scene).trianglesDrawn == 3);
        CHECK(hasWarning(scene, "part.stl: 100 bytes after the 3 triangles its binary header announces ignored"));
    }
}

TEST_CASE("PLY and X3D files that start with a byte order mark are read", "[io]") {
    TemporaryFolder folder;
    const std::string bom = "\xEF\xBB\xBF";
    writeTextFile(folder / "part.ply",
                  bom +
                      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                      "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    CHECK(sceneStatistics(readScene(folder / "part.ply")).trianglesDrawn == 1);
    writeTextFile(folder / "part.x3d",
                  bom +
                      "<?xml version='1.0' encoding='UTF-8'?>\n<X3D><Scene><Shape>"
                      "<IndexedFaceSet coordIndex='0 1 2 -1'><Coordinate point='0 0 0 1 0 0 0 1 0'/>"
                      "</IndexedFaceSet></Shape></Scene></X3D>\n");
    CHECK(sceneStatistics(readScene(folder / "part.x3d")).trianglesDrawn == 1);
}

TEST_CASE("Node animations are read and written back, and channels the scene cannot hold are left out with a warning",
          "[io]") {
    SECTION("the milk truck's turning wheels, through convert") {
        const Scene truck = readScene(modelPath("cesium_milk_truck/CesiumMilkTruck.gltf"));
        CHECK_FALSE(hasWarning(truck, "animation"));
        REQUIRE(truck.animations.size() == 1);
        const auto& channels = truck.animations[0].channels;
        REQUIRE(channels.size() == 2);
        for (const AnimationChannel& channel : channels) {
            CHECK(channel.path == AnimationChannel::Path::Rotation);
            CHECK(channel.interpolation == AnimationChannel::Interpolation::Linear);
            CHECK(truck.nodes[std::size_t(channel.node)].mesh >= 0);  // a wheel
            CHECK(channel.times.size() > 1);
            CHECK(channel.values.size() == 4 * channel.times.size());
        }
        TemporaryFolder folder;
        for (const char* name : {"truck.glb", "truck.gltf"}) {
            writeScene(truck, folder / name);
            const Scene back = readScene(folder / name);
            INFO(name);
            REQUIRE(back.animations.size() == 1);
            REQUIRE(back.animations[0].channels.size() == 2);
            for (std::size_t c = 0; c < 2; ++c) {
                const AnimationChannel &a = channels[c], &b = back.animations[0].channels[c];
                CHECK(a.node == b.node);
                CHECK(a.path == b.path);
                CHECK(a.times == b.times);    // float32 in both files
                CHECK(a.values == b.values);
            }
        }
    }
    SECTION("a channel without a node, one of morph weights and a good one, on a mirrored node") {
        // A triangle, then 2 key times and 2 translations, in one embedded buffer.
        TemporaryFolder folder;
        const auto file = folder / "animated.gltf";
        writeTextFile(file, R"({"asset": {"version": "2.0"},
            "buffers": [{"byteLength": 68, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAABAAAAAAAAAAAA="}],
            "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 8},
                            {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                          {"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [1]},
                          {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0, "scale": [1, -1, 1]}],
            "scenes": [{"nodes": [0]}], "animations": [{"name": "slide", "samplers": [{"input": 1, "output": 2, "interpolation": "STEP"}],
                            "channels": [{"sampler": 0, "target": {"node": 5, "path": "translation"}},
                                         {"sampler": 0, "target": {"node": 0, "path": "weights"}},
                                         {"sampler": 0, "target": {"node": 0, "path": "translation"}}]}]})");
        const Scene scene = readScene(file);
        CHECK(hasWarning(scene,
                         "animation 0 channel 0 refers to node 5 for its target, but the file has 1 node: the "
                         "channel ignored"));
        CHECK(hasWarning(scene, "animation 0 channel 1 ignored: it animates the morph weights of a node without morph targets"));
        // Written back, its mirror moves to x: the rest pose is the same, a channel may not be.
        CHECK(hasWarning(scene, "node 0 is animated with a negative scale on y or z"));
        REQUIRE(scene.animations.size() == 1);
        CHECK(scene.animations[0].name == "slide");
        REQUIRE(scene.animations[0].channels.size() == 1);
        const AnimationChannel& channel = scene.animations[0].channels[0];
        CHECK(channel.node == 0);
        CHECK(channel.interpolation == AnimationChannel::Interpolation::Step);
        CHECK(channel.times == std::vector<double>{0, 1});
        CHECK(channel.values == std::vector<double>{0, 0, 0, 2, 0, 0});
    }
}

TEST_CASE("X3D animations are read from a TimeSensor, interpolators and ROUTEs, and what glTF cannot hold is said", "[io][x3d]") {
    TemporaryFolder folder;
    const auto file = folder / "clock.x3d";
    writeTextFile(file, R"(<X3D><Scene>
        <Transform DEF='door' translation='1 0 0'><Shape><IndexedFaceSet coordIndex='0 1 2 -1'><Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet></Shape></Transform>
        <Transform DEF='hinged' center='1 0 0'><Shape><IndexedFaceSet coordIndex='0 1 2 -1'><Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet></Shape></Transform>
        <Transform USE='door'/>
        <TimeSensor DEF='clock' cycleInterval='4' loop='true'/>
        <OrientationInterpolator DEF='swing' key='0 0.5 1' keyValue='0 1 0 0, 0 1 0 1.5707963, 0 1 0 0'/>
        <PositionInterpolator DEF='push' key='0 1' keyValue='1 0 0, 2 0 0'/>
        <ROUTE fromNode='clock' fromField='fraction_changed' toNode='swing' toField='set_fraction'/>
        <ROUTE fromNode='clock' fromField='fraction_changed' toNode='push' toField='set_fraction'/>
        <ROUTE fromNode='swing' fromField='value_changed' toNode='door' toField='set_rotation'/>
        <ROUTE fromNode='swing' fromField='value_changed' toNode='hinged' toField='rotation'/>
        <ROUTE fromNode='push' fromField='value_changed' toNode='door' toField='set_translation'/>
    </Scene></X3D>)");
    const Scene scene = readScene(file);
    validateScene(scene);
    // The hinged Transform turns about its center, which glTF's translation-rotation-scale cannot hold.
    CHECK(hasWarning(scene, "1 animation ROUTEs left out"));
    REQUIRE(scene.animations.size() == 1);
    CHECK(scene.animations[0].name == "clock");
    // The door is drawn twice (a DEF and a USE): each copy gets the rotation and the translation.
    const auto& channels = scene.animations[0].channels;
    REQUIRE(channels.size() == 4);
    std::set<int> doors;
    for (const AnimationChannel& channel : channels) {
        doors.insert(channel.node);
        CHECK(scene.nodes[std::size_t(channel.node)].name == "door");
        CHECK(channel.times.back() == Approx(4));
    }
    CHECK(doors.size() == 2);
    const AnimationChannel& swing = channels[0];
    CHECK(swing.path == AnimationChannel::Path::Rotation);
    CHECK(swing.times == std::vector<double>{0, 2, 4});
    CHECK(swing.values[4 + 1] == Approx(std::sqrt(0.5)));  // y of a quarter turn about y
    CHECK(swing.values[4 + 3] == Approx(std::sqrt(0.5)));
    CHECK(channels[2].path == AnimationChannel::Path::Translation);
    CHECK(channels[2].values == std::vector<double>{1, 0, 0, 2, 0, 0});
}

namespace {

// Where a node's camera or light is and which way it looks: its world origin and its -z.
std::pair<Eigen::Vector3d, Eigen::Vector3d> placementOf(const Scene& scene, int node) {
    const Eigen::Matrix4d world = worldTransforms(scene)[std::size_t(node)];
    return {world.topRightCorner<3, 1>(), -world.block<3, 1>(0, 2).normalized()};
}

int nodeWith(const Scene& scene, bool camera, int index) {
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
        if ((camera ? scene.nodes[n].camera : scene.nodes[n].light) == index) return int(n);
    return -1;
}

}  // namespace

TEST_CASE("glTF cameras and lights are read and written back, as glTF and as X3D", "[io]") {
    TemporaryFolder folder;
    const Scene room = readScene(modelPath("cge_sterile_room/sterile_room.gltf"));
    REQUIRE(room.cameras.size() == 1);
    REQUIRE(room.lights.size() == 2);
    CHECK(room.cameras[0].name == "Camera");
    CHECK(room.cameras[0].yfov == Approx(0.39959652046304894));
    CHECK(room.cameras[0].aspectRatio == Approx(1.7777777777777777));
    CHECK(room.cameras[0].zfar == 100);
    CHECK(room.lights[0].type == Light::Type::Point);
    CHECK(room.lights[0].intensity == Approx(543.5141306588226));
    CHECK(!hasWarning(room, "camera"));
    CHECK(!hasWarning(room, "light"));

    writeScene(room, folder / "room.glb");
    const Scene glb = readScene(folder / "room.glb");
    REQUIRE(glb.cameras.size() == 1);
    REQUIRE(glb.lights.size() == 2);
    CHECK(glb.cameras[0].yfov == room.cameras[0].yfov);
    CHECK(glb.cameras[0].znear == room.cameras[0].znear);
    CHECK(glb.lights[1].name == "Light.001");
    CHECK(glb.lights[1].intensity == room.lights[1].intensity);
    for (int index : {0, 1}) {
        const auto [at, towards] = placementOf(room, nodeWith(room, false, index));
        const auto [atAgain, towardsAgain] = placementOf(glb, nodeWith(glb, false, index));
        CHECK((at - atAgain).norm() < 1e-5);
        CHECK((towards - towardsAgain).norm() < 1e-6);
    }

    // X3D: a Viewpoint and PointLights in the Transforms of their nodes; intensities above X3D's 1 are cut
    // to 1, and said so before writing.
    CHECK(formatLosses(room, folder / "room.x3d") ==
          std::vector<std::string>{"2 lights brighter than 1 written with intensity 1 (X3D's largest; glTF's intensities are in candela or lux)"});
    writeScene(room, folder / "room.x3d");
    const Scene x3d = readScene(folder / "room.x3d");
    REQUIRE(x3d.cameras.size() == 1);
    REQUIRE(x3d.lights.size() == 2);
    // The room's camera is wider than it is high: X3D's fieldOfView, the smaller angle, is glTF's yfov.
    CHECK(x3d.cameras[0].yfov == Approx(room.cameras[0].yfov));
    CHECK(x3d.cameras[0].name == "Camera");
    CHECK(x3d.lights[0].intensity == 1);
    CHECK(x3d.lights[0].range == 0);  // no limit, both ways
    const auto [camera, view] = placementOf(room, nodeWith(room, true, 0));
    const auto [cameraAgain, viewAgain] = placementOf(x3d, nodeWith(x3d, true, 0));
    CHECK((camera - cameraAgain).norm() < 1e-5);
    CHECK((view - viewAgain).norm() < 1e-6);
    CHECK(formatLosses(room, folder / "room.obj") ==
          std::vector<std::string>{"1 cameras and 2 lights not written: .obj output holds geometry only"});
}

TEST_CASE("X3D viewpoints and lights are read where X3D puts them, written back, and the rest is said", "[io][x3d]") {
    TemporaryFolder folder;
    const auto file = folder / "lit.x3d";
    writeTextFile(file, R"(<X3D><Scene>
        <NavigationInfo avatarSize='0.5 1.6 0.75' visibilityLimit='500'/>
        <Background skyColor='0 0 1'/>
        <WorldInfo title='lit'/>
        <ProximitySensor size='5 5 5'/>
        <Transform translation='10 0 0'>
          <Viewpoint DEF='front' description='Front' position='0 1 5' orientation='0 1 0 0.5' fieldOfView='0.6'/>
          <DirectionalLight DEF='sun' direction='0 -1 0' intensity='0.8' color='1 0.9 0.8' global='true'/>
          <SpotLight DEF='lamp' location='1 2 3' direction='1 0 0' beamWidth='1.2' cutOffAngle='0.5' radius='20' attenuation='0 0 1'/>
          <PointLight DEF='off' on='false'/>
          <PointLight DEF='bulb' location='0 3 0' attenuation='1 0 0'/>
        </Transform>
        <OrthoViewpoint DEF='plan' position='0 10 0' orientation='1 0 0 -1.5707963' fieldOfView='-4 -2 2 2'/>
    </Scene></X3D>)");
    const Scene scene = readScene(file);
    validateScene(scene);
    CHECK(hasWarning(scene, "not kept (symcompress keeps geometry, materials, animations of transforms, viewpoints and "
                            "lights): 1 ProximitySensor"));
    CHECK(scene.x3dEnvironment.size() == 3);  // NavigationInfo, Background, WorldInfo: given back in X3D output
    CHECK(hasWarning(scene, "lights that are off (on='false') left out"));
    REQUIRE(scene.cameras.size() == 2);
    REQUIRE(scene.lights.size() == 3);
    // X3D's default attenuation (none) is kept for X3D output; glTF output says it cannot hold it.
    CHECK_FALSE(scene.lights[1].x3dAttenuation);  // 0 0 1: glTF's own
    REQUIRE(scene.lights[2].x3dAttenuation);
    CHECK(*scene.lights[2].x3dAttenuation == Eigen::Vector3d(1, 0, 0));
    const std::vector<std::string> losses = formatLosses(scene, folder / "again.glb");
    CHECK(std::count(losses.begin(), losses.end(),
                     "1 X3D lights' attenuation not written: .glb lights fall off with the inverse square of the distance") == 1);

    const Camera& front = scene.cameras[0];
    CHECK(front.name == "Front");
    CHECK(front.projection == Camera::Projection::Perspective);
    CHECK(front.yfov == Approx(0.6));
    CHECK(front.znear == Approx(0.25));  // avatarSize[0] / 2
    CHECK(front.zfar == Approx(500));
    const auto [eye, look] = placementOf(scene, nodeWith(scene, true, 0));
    CHECK((eye - Eigen::Vector3d(10, 1, 5)).norm() < 1e-12);
    CHECK((look - Eigen::Vector3d(-std::sin(0.5), 0, -std::cos(0.5))).norm() < 1e-12);  // -z turned 0.5 about y
    CHECK(scene.nodes[std::size_t(nodeWith(scene, true, 0))].name == "front");

    // The plan view: a 6 by 4 window whose centre is 1 to the left of the viewpoint.
    const Camera& plan = scene.cameras[1];
    CHECK(plan.projection == Camera::Projection::Orthographic);
    CHECK(plan.xmag == Approx(3));
    CHECK(plan.ymag == Approx(2));
    const auto [planEye, planLook] = placementOf(scene, nodeWith(scene, true, 1));
    CHECK((planEye - Eigen::Vector3d(-1, 10, 0)).norm() < 1e-6);
    CHECK((planLook - Eigen::Vector3d(0, -1, 0)).norm() < 1e-6);

    const Light& sun = scene.lights[0];
    CHECK(sun.type == Light::Type::Directional);
    CHECK(sun.intensity == Approx(0.8));
    CHECK(sun.color.isApprox(Eigen::Vector3d(1, 0.9, 0.8)));
    CHECK((placementOf(scene, nodeWith(scene, false, 0)).second - Eigen::Vector3d(0, -1, 0)).norm() < 1e-12);
    const Light& lamp = scene.lights[1];
    CHECK(lamp.type == Light::Type::Spot);
    CHECK(lamp.range == 20);
    CHECK(lamp.outerConeAngle == Approx(0.5));
    CHECK(lamp.innerConeAngle < lamp.outerConeAngle);  // X3D's beamWidth wider than the cut-off: no falloff
    CHECK(lamp.innerConeAngle == Approx(0.5));
    const auto [lampAt, lampTowards] = placementOf(scene, nodeWith(scene, false, 1));
    CHECK((lampAt - Eigen::Vector3d(11, 2, 3)).norm() < 1e-12);
    CHECK((lampTowards - Eigen::Vector3d(1, 0, 0)).norm() < 1e-12);

    // Written as X3D (OrthoViewpoint needs the Navigation component at level 3) and as glTF, read back the same.
    writeScene(scene, folder / "again.x3d");
    CHECK(readTextFile(folder / "again.x3d").find("<component name='Navigation' level='3'/>") != std::string::npos);
    writeScene(scene, folder / "again.glb");
    for (const char* name : {"again.x3d", "again.glb"}) {
        const Scene again = readScene(folder / name);
        REQUIRE(again.cameras.size() == 2);
        REQUIRE(again.lights.size() == 3);
        CHECK(again.lights[2].x3dAttenuation == (std::string(name) == "again.x3d" ? std::optional<Eigen::Vector3d>(Eigen::Vector3d(1, 0, 0))
                                                                                : std::nullopt));
        CHECK(again.cameras[0].yfov == Approx(0.6));
        CHECK(again.cameras[1].xmag == Approx(3));
        CHECK(again.lights[1].range == 20);
        CHECK(again.lights[1].outerConeAngle == Approx(0.5));
        for (bool camera : {true, false})
            for (int index : {0, 1}) {
                const auto [at, towards] = placementOf(scene, nodeWith(scene, camera, index));
                const auto [atAgain, towardsAgain] = placementOf(again, nodeWith(again, camera, index));
                CHECK((at - atAgain).norm() < 1e-5);
                CHECK((towards - towardsAgain).norm() < 1e-6);
            }
    }
}

TEST_CASE("X3D's default field of view is an SFFloat, written to glTF in float32's digits", "[io][x3d]") {
    TemporaryFolder folder;
    writeTextFile(folder / "view.x3d", "<X3D><Scene><Viewpoint position='0 0 35'/></Scene></X3D>");
    const Scene scene = readScene(folder / "view.x3d");
    REQUIRE(scene.cameras.size() == 1);
    CHECK(scene.cameras[0].yfov == double(float(M_PI / 4)));
    writeScene(scene, folder / "view.gltf");
    CHECK(readTextFile(folder / "view.gltf").find("\"yfov\": 0.7853982,") != std::string::npos);
    CHECK(float(readScene(folder / "view.gltf").cameras[0].yfov) == float(M_PI / 4));
    // A yfov that is no float32 keeps every digit.
    Scene wide = scene;
    wide.cameras[0].yfov = 0.7853981633974483;
    writeScene(wide, folder / "wide.gltf");
    CHECK(readScene(folder / "wide.gltf").cameras[0].yfov == 0.7853981633974483);
}

TEST_CASE("glTF cameras and lights that break the rules are left out with a warning", "[io]") {
    TemporaryFolder folder;
    const auto file = folder / "broken.gltf";
    writeTextFile(file, R"({"asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "spot", "spot": {"innerConeAngle": 1, "outerConeAngle": 0.5}}]}},
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0, "znear": 0.1}}],
        "nodes": [{"camera": 0}, {"extensions": {"KHR_lights_punctual": {"light": 0}}}, {"extensions": {"KHR_lights_punctual": {"light": 3}}}],
        "scenes": [{"nodes": [0, 1, 2]}]})");
    const Scene scene = readScene(file);
    CHECK(scene.cameras.empty());
    CHECK(scene.lights.empty());
    CHECK(hasWarning(scene, "camera 0 ignored: a perspective camera needs yfov and znear above 0"));
    CHECK(hasWarning(scene, "light 0 ignored: a spot light needs 0 <= innerConeAngle < outerConeAngle <= pi/2"));
    CHECK(hasWarning(scene, "node 2: KHR_lights_punctual light index missing or out of range, ignored"));
}

TEST_CASE("X3D's NavigationInfo, Background, Fog and WorldInfo are given back in X3D output, and said lost in glTF",
          "[io][x3d]") {
    TemporaryFolder folder;
    const auto file = folder / "dark.x3d";
    writeTextFile(file, R"(<X3D><Scene>
        <NavigationInfo DEF='nav' headlight='false' type='"EXAMINE" "ANY"'/>
        <Background DEF='sky' skyColor='0 0 0.2' backUrl='"back.png"'/>
        <Fog color='1 1 1' visibilityRange='30'/>
        <WorldInfo title='dark'><MetadataString name='author' value='"me"'/></WorldInfo>
        <NavigationInfo USE='nav'/>
        <Shape><IndexedFaceSet coordIndex='0 1 2 -1'><Coordinate point='0 0 0 1 0 0 0 1 0'/></IndexedFaceSet></Shape>
    </Scene></X3D>)");
    const Scene scene = readScene(file);
    // Kept once each (the USE is the same node), without DEF names or the Background's relative image URL.
    REQUIRE(scene.x3dEnvironment.size() == 4);
    CHECK(scene.x3dEnvironment[0] == R"(<NavigationInfo headlight="false" type="&quot;EXAMINE&quot; &quot;ANY&quot;"/>)");
    CHECK(scene.x3dEnvironment[1] == R"(<Background skyColor="0 0 0.2"/>)");
    CHECK(scene.x3dEnvironment[3].find("<MetadataString name=\"author\"") != std::string::npos);
    CHECK(hasWarning(scene, "Background images are not kept"));
    CHECK(!hasWarning(scene, "not kept (symcompress keeps"));

    writeScene(scene, folder / "again.x3d");
    const Scene again = readScene(folder / "again.x3d");
    CHECK(again.x3dEnvironment == scene.x3dEnvironment);
    CHECK(formatLosses(scene, folder / "again.x3d").empty());
    CHECK(formatLosses(scene, folder / "dark.glb") ==
          std::vector<std::string>{"X3D's 1 Background, 1 Fog, 1 NavigationInfo, 1 WorldInfo not written: .glb output has no place for them"});
}

TEST_CASE("glTF compressed by meshoptimizer (EXT_meshopt_compression, KHR_mesh_quantization, KHR_texture_transform) reads",
          "[io]") {
    // A quad as gltfpack writes one: integer positions scaled by the node, octahedral 8-bit normals,
    // 16-bit texture coordinates brought back by a texture transform, every buffer view meshopt-coded, and
    // a fallback buffer with no data.
    const std::vector<std::array<std::uint16_t, 4>> positions = {{0, 0, 0, 0}, {1000, 0, 0, 0}, {1000, 500, 0, 0}, {0, 500, 7, 0}};
    std::vector<float> normalFloats = {0, 0, 1, 0, 0, 0.6f, 0.8f, 0, 0.6f, 0, 0.8f, 0, 0, 0, -1, 0};
    std::vector<std::int8_t> normals(16);
    meshopt_encodeFilterOct(normals.data(), 4, 4, 8, normalFloats.data());
    const std::vector<std::array<std::uint16_t, 2>> texcoords = {{0, 0}, {65535, 0}, {65535, 65535}, {0, 32768}};
    const std::vector<std::uint16_t> indices = {0, 1, 2, 0, 2, 3};

    std::vector<unsigned char> binary;
    nlohmann::json views = nlohmann::json::array();
    auto addView = [&](const void* data, std::size_t count, std::size_t stride, const char* mode, const char* filter, bool vertices) {
        std::vector<unsigned char> coded(vertices ? meshopt_encodeVertexBufferBound(count, stride) : meshopt_encodeIndexBufferBound(count, 4));
        coded.resize(vertices ? meshopt_encodeVertexBuffer(coded.data(), coded.size(), data, count, stride)
                              : meshopt_encodeIndexBuffer(coded.data(), coded.size(), static_cast<const std::uint16_t*>(data), count));
        nlohmann::json extension = {{"buffer", 0}, {"byteOffset", binary.size()}, {"byteLength", coded.size()},
                                    {"byteStride", stride}, {"count", count}, {"mode", mode}};
        if (filter) extension["filter"] = filter;
        nlohmann::json view = {{"buffer", 1}, {"byteLength", count * stride}, {"extensions", {{"EXT_meshopt_compression", extension}}}};
        if (vertices) view["byteStride"] = stride;
        binary.insert(binary.end(), coded.begin(), coded.end());
        while (binary.size() % 4) binary.push_back(0);
        views.push_back(view);
    };
    addView(positions.data(), 4, 8, "ATTRIBUTES", nullptr, true);
    addView(normals.data(), 4, 4, "ATTRIBUTES", "OCTAHEDRAL", true);
    addView(texcoords.data(), 4, 4, "ATTRIBUTES", nullptr, true);
    addView(indices.data(), 6, 2, "TRIANGLES", nullptr, false);
    nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"EXT_meshopt_compression", "KHR_mesh_quantization", "KHR_texture_transform"}},
        {"extensionsRequired", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
        {"buffers", {{{"byteLength", binary.size()}},
                     {{"byteLength", 4 * 8 + 4 * 4 + 4 * 4 + 6 * 2}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
        {"bufferViews", views},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5123}, {"count", 4}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1000, 500, 7}}},
                       {{"bufferView", 1}, {"componentType", 5120}, {"normalized", true}, {"count", 4}, {"type", "VEC3"}},
                       {{"bufferView", 2}, {"componentType", 5123}, {"normalized", true}, {"count", 4}, {"type", "VEC2"}},
                       {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}}}},
        {"images", {{{"uri", "data:image/png;base64,iVBORw0KGgo="}}}},  // a PNG's signature
        {"textures", {{{"source", 0}}}},
        {"materials", {{{"pbrMetallicRoughness",
                         {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"offset", {0.25, 0.5}}, {"scale", {2, 4}}}}}}}}}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}, {"indices", 3}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}, {"scale", {0.001, 0.001, 0.001}}, {"translation", {1, 2, 3}}}}},
        {"scenes", {{{"nodes", {0}}}}}};
    std::string json = gltf.dump();
    while (json.size() % 4) json.push_back(' ');
    std::string glb = "glTF";
    auto put32 = [&](std::uint32_t value) { glb.append(reinterpret_cast<const char*>(&value), 4); };
    put32(2);
    put32(std::uint32_t(12 + 8 + json.size() + 8 + binary.size()));
    put32(std::uint32_t(json.size()));
    put32(0x4E4F534Au);
    glb += json;
    put32(std::uint32_t(binary.size()));
    put32(0x004E4942u);
    glb.append(reinterpret_cast<const char*>(binary.data()), binary.size());
    TemporaryFolder folder;
    writeTextFile(folder / "packed.glb", glb);

    const Scene scene = readScene(folder / "packed.glb");
    CHECK(scene.warnings.empty());
    // Broken: the coded bytes garbled, or a view that asks for more than its byteLength. A clear error each.
    std::string garbled = glb;
    for (std::size_t i = glb.size() - binary.size() + 1; i < glb.size(); i += 3) garbled[i] = char(0xff);
    writeTextFile(folder / "garbled.glb", garbled);
    CHECK_THROWS_WITH(readScene(folder / "garbled.glb"), Catch::Contains("(EXT_meshopt_compression): cannot be decoded"));
    std::string greedy = glb;
    const std::size_t at = greedy.find("\"count\":4,\"mode\":\"ATTRIBUTES\"");
    REQUIRE(at != std::string::npos);
    greedy.replace(at, 9, "\"count\":9");
    writeTextFile(folder / "greedy.glb", greedy);
    CHECK_THROWS_WITH(readScene(folder / "greedy.glb"), Catch::Contains("exceeds the buffer view's byteLength"));
    const std::vector<WorldPrimitive> world = flattenScene(scene);
    REQUIRE(world.size() == 1);
    const Primitive& quad = world[0].primitive;
    REQUIRE(quad.positions.size() == 4);
    CHECK((quad.positions[2] - Eigen::Vector3d(2, 2.5, 3)).norm() < 1e-12);
    CHECK((quad.positions[3] - Eigen::Vector3d(1, 2.5, 3.007)).norm() < 1e-12);
    for (std::size_t v = 0; v < 4; ++v) {
        const Eigen::Vector3d expected(normalFloats[4 * v], normalFloats[4 * v + 1], normalFloats[4 * v + 2]);
        CHECK((quad.normals[v] - expected).norm() < 0.02);  // 8 bits
    }
    // The texture transform is kept as the extension (q / 65535 in the coordinates); the base colour texture
    // reads (u, v) = offset + scale * q / 65535.
    REQUIRE(scene.materials.size() == 1);
    REQUIRE(scene.materials[0].baseColorTexture.transform);
    CHECK(scene.materials[0].baseColorTexture.transform->offset == Eigen::Vector2d(0.25, 0.5));
    CHECK(scene.materials[0].baseColorTexture.transform->scale == Eigen::Vector2d(2, 4));
    CHECK((quad.texcoords[1] - Eigen::Vector2d(1, 0)).norm() < 1e-12);
    CHECK((baseColorTexcoord(scene, quad, 1) - Eigen::Vector2d(2.25, 0.5)).norm() < 1e-12);
    CHECK((baseColorTexcoord(scene, quad, 3) - Eigen::Vector2d(0.25, 0.5 + 4 * 32768.0 / 65535)).norm() < 1e-12);
    CHECK(quad.triangles == std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}});
}

TEST_CASE("EXT_mesh_gpu_instancing: every instance of a node's mesh is drawn, at its place", "[io]") {
    TemporaryFolder folder;
    // One triangle drawn twice: at (10, 0, 0) unturned and at (0, 20, 0) turned a quarter about z, under a
    // node that lifts everything by 1 in z.
    writeTextFile(folder / "instanced.gltf", R"({"asset": {"version": "2.0"},
        "extensionsUsed": ["EXT_mesh_gpu_instancing"], "extensionsRequired": ["EXT_mesh_gpu_instancing"],
        "buffers": [{"byteLength": 92, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAgQQAAAAAAAAAAAAAAAAAAoEEAAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAA8wQ1P/MENT8="}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                        {"buffer": 0, "byteOffset": 60, "byteLength": 32}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC4"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "nodes": [{"mesh": 0, "translation": [0, 0, 1],
                   "extensions": {"EXT_mesh_gpu_instancing": {"attributes": {"TRANSLATION": 1, "ROTATION": 2}}}}],
        "scenes": [{"nodes": [0]}]})");
    const Scene scene = readScene(folder / "instanced.gltf");
    CHECK(scene.warnings.empty());
    const TriangleMesh world = worldMesh(scene);
    REQUIRE(world.positions.size() == 6);
    CHECK((world.positions[1] - Eigen::Vector3d(11, 0, 1)).norm() < 1e-12);
    CHECK((world.positions[4] - Eigen::Vector3d(0, 21, 1)).norm() < 1e-6);  // (1, 0, 0) turned to (0, 1, 0)
    CHECK(scene.meshes.size() == 1);
}

TEST_CASE("Broken skins and morph targets are left out with a warning naming them, the rest read", "[io]") {
    // A triangle (positions, then a displacement of 2 elements for its 3 vertices; one matrix over the whole
    // buffer) drawn by four nodes: one skinned
    // by a skin whose joint is no node, one by a skin with fewer inverse bind matrices than joints, one with
    // morph weights its mesh has no targets for, one whose mesh's target is short of a vertex.
    TemporaryFolder folder;
    const auto file = folder / "broken.gltf";
    writeTextFile(file, R"({"asset": {"version": "2.0"},
        "buffers": [{"byteLength": 64, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAA=="}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                        {"buffer": 0, "byteLength": 64}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3"},
                      {"bufferView": 2, "componentType": 5126, "count": 1, "type": "MAT4"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]},
                   {"primitives": [{"attributes": {"POSITION": 0}, "targets": [{"POSITION": 1}]}], "weights": [0.5]}],
        "skins": [{"joints": [9]}, {"joints": [3, 4], "inverseBindMatrices": 2}],
        "nodes": [{"mesh": 0, "skin": 0}, {"mesh": 0, "skin": 1}, {"mesh": 0, "weights": [1]}, {"mesh": 1}, {}],
        "scenes": [{"nodes": [0, 1, 2, 3, 4]}]})");
    const Scene scene = readScene(file);
    CHECK(hasWarning(scene, "skin 0 refers to node 9 for its joints, but the file has 5 nodes: the skin ignored"));
    CHECK(hasWarning(scene, "skin 1 ignored: fewer inverse bind matrices than joints"));
    CHECK(hasWarning(scene, "node 2: morph weights that do not match its mesh's targets ignored"));
    CHECK(hasWarning(scene, "morph targets left out (mesh 1 primitive 0): POSITION of target 0 has 2 elements for 3"));
    CHECK(scene.skins.empty());
    for (const Node& node : scene.nodes) CHECK((node.skin == -1 && node.weights.empty()));
    CHECK(scene.meshes[1].primitives[0].targets.empty());
    CHECK(scene.meshes[1].weights.empty());  // weights without their targets go with them
    validateScene(scene);
}
