// The glTF material model through symcompress (issue 15): every core texture slot with its texCoord, scale
// and KHR_texture_transform, samplers, material extensions with their textures, extensionsRequired, extras
// and unreadable images, the attributes beyond the core ones (tangents, more texture coordinate sets, joints
// and weights), skins and morph targets, compared by value between the input and what comes out.
#include "io/gltf_builder.hpp"
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>

using namespace symcompress;
using namespace symcompress::testing;
namespace fs = std::filesystem;

namespace {

// A texture use as a viewer sees it: the image's content and type, the sampler, the set, scale and transform.
std::string describeUse(const Scene& scene, const TextureRef& use) {
    if (use.texture < 0) return "-";
    const Texture& texture = scene.textures[std::size_t(use.texture)];
    std::ostringstream out;
    out << std::hash<std::string>()(std::string(texture.bytes.begin(), texture.bytes.end())) << "/"
        << texture.bytes.size() << "/" << texture.mimeType << "/" << texture.sampler.magFilter << ","
        << texture.sampler.minFilter << "," << texture.sampler.wrapS << "," << texture.sampler.wrapT << " set "
        << use.texCoord << " scale " << float(use.scale);
    if (texture.bytes.empty()) out << " at " << fs::path(texture.uri).filename().string();
    if (use.transform)
        out << " transform " << float(use.transform->offset.x()) << "," << float(use.transform->offset.y()) << " "
            << float(use.transform->rotation) << " " << float(use.transform->scale.x()) << ","
            << float(use.transform->scale.y()) << " " << use.transform->texCoord;
    return out.str();
}

// Everything of a material a viewer draws with, textures by content (their indices differ between files).
std::string describe(const Scene& scene, const Material& m) {
    std::ostringstream out;
    out << float(m.baseColorFactor.x()) << "," << float(m.baseColorFactor.y()) << "," << float(m.baseColorFactor.z())
        << "," << float(m.baseColorFactor.w()) << " metal " << float(m.metallicFactor) << " rough "
        << float(m.roughnessFactor) << " emissive " << float(m.emissiveFactor.x()) << "," << float(m.emissiveFactor.y())
        << "," << float(m.emissiveFactor.z()) << " alpha " << int(m.alphaMode) << "/" << float(m.alphaCutoff)
        << " doubleSided " << m.doubleSided << " extras " << m.extrasJson;
    const char* slots[] = {"baseColor", "metallicRoughness", "normal", "occlusion", "emissive"};
    const auto refs = m.textureRefs();
    for (int s = 0; s < 5; ++s) out << "\n  " << slots[s] << ": " << describeUse(scene, *refs[std::size_t(s)]);
    for (const MaterialExtension& extension : m.extensions) {
        // By value: the writer prints whole numbers as integers (1 for 1.0).
        nlohmann::json values = nlohmann::json::parse(extension.json);
        writeWholeNumbersAsIntegers(values);
        out << "\n  " << extension.name << (extension.required ? " (required) " : " ") << values.dump();
        for (const auto& [key, use] : extension.textures) out << "\n    " << key << ": " << describeUse(scene, use);
    }
    return out.str();
}

// The descriptions of the materials some primitive draws with.
std::multiset<std::string> drawnMaterials(const Scene& scene) {
    std::set<int> used;
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives)
            if (primitive.material >= 0) used.insert(primitive.material);
    std::multiset<std::string> out;
    for (int m : used) out.insert(describe(scene, scene.materials[std::size_t(m)]));
    return out;
}

std::set<std::string> distinct(const std::multiset<std::string>& items) { return {items.begin(), items.end()}; }

// Every value of the attributes beyond the core ones (and of the morph targets, by their number), by name: a
// vertex's values as a tuple (Draco may reorder and merge vertices, but it stores these without loss).
std::map<std::string, std::set<std::vector<double>>> attributeValues(const Scene& scene) {
    std::map<std::string, std::set<std::vector<double>>> out;
    auto add = [&](const std::string& name, VertexAttribute attribute) {
        for (double& value : attribute.values) value = float(value);
        const auto width = std::size_t(attribute.components);
        for (std::size_t v = 0; v < attribute.count(); ++v)
            out[name].insert(std::vector<double>(attribute.values.begin() + long(v * width),  // as float32, as stored
                                                 attribute.values.begin() + long((v + 1) * width)));
    };
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& primitive : mesh.primitives) {
            for (const VertexAttribute& attribute : primitive.attributes) add(attribute.name, attribute);
            for (std::size_t t = 0; t < primitive.targets.size(); ++t)
                for (const VertexAttribute& attribute : primitive.targets[t])
                    add("target " + std::to_string(t) + " " + attribute.name, attribute);
        }
    return out;
}

// The scene's drawn primitives in world space (flattenScene), as one mesh.
Scene inWorld(const Scene& scene) {
    Scene out = scene;
    out.meshes = {Mesh{}};
    for (const WorldPrimitive& placed : flattenScene(scene)) out.meshes[0].primitives.push_back(placed.primitive);
    return out;
}

// Whether two attributeValues agree: the same attributes, and each tuple of either within the quantization of
// Draco's output of a tuple of the other (tangents at 8 bits over at most [-1, 1], further UV sets and colours
// at 12 bits or more over theirs, skin weights as the budget's share for them rounds them: at 16 bits or more for
// these models; morph targets' displacements as meshopt's exponential filter rounds them, normals' within
// 2^-10 and positions' within the budget's share, below 1e-5 in the morphed cube's frame; the others, stored as
// they are, exactly).
bool sameValues(const std::map<std::string, std::set<std::vector<double>>>& a,
                const std::map<std::string, std::set<std::vector<double>>>& b) {
    auto keys = [](const auto& map) {
        std::set<std::string> out;
        for (const auto& [key, values] : map) out.insert(key);
        return out;
    };
    if (keys(a) != keys(b)) return false;
    auto covered = [](const std::set<std::vector<double>>& from, const std::set<std::vector<double>>& by, double step) {
        return std::all_of(from.begin(), from.end(), [&](const std::vector<double>& x) {
            return std::any_of(by.begin(), by.end(), [&](const std::vector<double>& y) {
                for (std::size_t c = 0; c < x.size(); ++c)
                    if (!(std::abs(x[c] - y[c]) <= step)) return false;
                return x.size() == y.size();
            });
        });
    };
    for (const auto& [key, values] : a) {
        const std::string name = key.substr(key.rfind(' ') + 1);
        const bool displacement = key.rfind("target ", 0) == 0;
        const double step = name == "TANGENT"                    ? 2.0 / 255
                            : name.rfind("TEXCOORD_", 0) == 0    ? 1e-3
                            : name.rfind("WEIGHTS_", 0) == 0     ? 1e-5
                            : displacement && name == "NORMAL"   ? 1.0 / 1024
                            : displacement && name == "POSITION" ? 1e-5
                                                                 : 0;
        if (!covered(values, b.at(key), step) || !covered(b.at(key), values, step)) return false;
    }
    return true;
}

// The scene without the tangents of primitives whose material has no normal map (core or clear-coat's): no
// viewer reads them (the validator's UNUSED_MESH_TANGENT), and symcompress prunes them by default, with their
// morph targets' displacements.
Scene withoutUnreadTangents(Scene scene) {
    for (Mesh& mesh : scene.meshes)
        for (Primitive& primitive : mesh.primitives) {
            const Material* material = primitive.material >= 0 ? &scene.materials[std::size_t(primitive.material)] : nullptr;
            bool normalMap = material && material->normalTexture.texture >= 0;
            if (material)
                for (const MaterialExtension& extension : material->extensions)
                    for (const auto& [key, use] : extension.textures) normalMap |= key == "clearcoatNormalTexture";
            const auto tangents = [](const VertexAttribute& a) { return a.name == "TANGENT"; };
            if (normalMap) continue;
            primitive.attributes.erase(
                std::remove_if(primitive.attributes.begin(), primitive.attributes.end(), tangents),
                primitive.attributes.end());
            for (MorphTarget& target : primitive.targets)
                target.erase(std::remove_if(target.begin(), target.end(), tangents), target.end());
        }
    return scene;
}

// The skins by their joints' names and inverse bind matrices (float32), the morph weights of meshes and nodes,
// and the animation channels by node name, path and first and last key times (keys between that interpolation
// gives back may be dropped: dropRedundantKeys): what moves a skinned or morphed mesh.
std::multiset<std::string> skinsAndMorphs(const Scene& scene) {
    std::multiset<std::string> out;
    for (const Skin& skin : scene.skins) {
        std::ostringstream line;
        line << "skin";
        for (std::size_t j = 0; j < skin.joints.size(); ++j) {
            line << " " << scene.nodes[std::size_t(skin.joints[j])].name;
            if (!skin.inverseBindMatrices.empty())
                for (int i = 0; i < 16; ++i) line << "," << float(skin.inverseBindMatrices[j](i % 4, i / 4));
        }
        if (skin.skeleton >= 0) line << " skeleton " << scene.nodes[std::size_t(skin.skeleton)].name;
        out.insert(line.str());
    }
    for (const Mesh& mesh : scene.meshes)
        if (morphTargetCount(mesh)) {
            std::ostringstream line;
            line << "mesh " << mesh.name << " targets " << morphTargetCount(mesh) << " weights";
            for (double w : mesh.weights) line << " " << float(w);
            out.insert(line.str());
        }
    for (const Node& node : scene.nodes) {
        if (node.skin >= 0) out.insert("skinned node " + node.name);
        if (!node.weights.empty()) out.insert("weights of node " + node.name + " " + std::to_string(node.weights.size()));
    }
    for (const Animation& animation : scene.animations)
        for (const AnimationChannel& channel : animation.channels)
            out.insert("channel " + scene.nodes[std::size_t(channel.node)].name + " " +
                       std::to_string(int(channel.path)) + " from " + std::to_string(channel.times.front()) + " to " +
                       std::to_string(channel.times.back()));
    return out;
}

nlohmann::json gltfJson(const fs::path& file) {
    return file.extension() == ".glb" ? glbJson(file) : nlohmann::json::parse(readTextFile(file));
}

std::set<std::string> listed(const nlohmann::json& root, const char* key) {
    std::set<std::string> out;
    if (root.contains(key))
        for (const auto& name : root[key]) out.insert(name.get<std::string>());
    return out;
}

}  // namespace

TEST_CASE(
    "PBR models: every material's textures, samplers, transforms and extensions come out of symcompress as they went "
    "in",
    "[materials][models]") {
    // Every model of ../shared/models/pbr, with the views of the render check that show them: view b sees
    // texture_transform's planes edge-on and view c texture_settings' and the clear-coat test's label, where
    // the few pixels drawn are mostly edges that Draco's quantization moves by a pixel.
    const std::vector<std::pair<std::string, std::string>> models = {
        {"lantern/Lantern.gltf", "abc"},
        {"cesium_man/CesiumMan.gltf", "abc"},
        {"fox/Fox.gltf", "abc"},
        {"multi_uv/MultiUVTest.gltf", "abc"},
        {"animated_morph_cube/AnimatedMorphCube.gltf", "abc"},
        {"box_specgloss/BoxTextured.gltf", "abc"},
        {"clearcoat/ClearCoatTest.gltf", "ab"},
        {"texture_settings/TextureSettingsTest.gltf", "ab"},
        {"texture_transform/TextureTransformTest.gltf", "ac"},
        {"two_sided_plane/TwoSidedPlane.gltf", "abc"},
        {"unlit/UnlitTest.gltf", "abc"},
        {"vertex_color/VertexColorTest.gltf", "abc"}};
    for (const auto& [model, views] : models) {
        DYNAMIC_SECTION(model) {
            const fs::path input = modelPath("pbr/" + model);
            TemporaryFolder folder;
            const fs::path output = folder / "out.glb";
            compressFile(input, output);
            const Scene before = readScene(input), after = readScene(output);
            // Materials equal but for their names are merged: each drawn look comes out, and no other. By value
            // without the join by base colour, which moves base colours into COLOR_0 (the unlit test's two: the
            // render check below, and test_compress, see that they draw the same).
            CompressOptions unjoined;
            unjoined.optimize.joinByBaseColor = false;
            compressFile(input, folder / "unjoined.glb", unjoined);
            CHECK(distinct(drawnMaterials(readScene(folder / "unjoined.glb"))) == distinct(drawnMaterials(before)));
            // As they were, or turned with their placement where symcompress stored the meshes in world space
            // (the lantern's three, each drawn once, merged: emitScene).
            const Scene read = withoutUnreadTangents(before);
            CHECK((sameValues(attributeValues(after), attributeValues(read)) ||
                   sameValues(attributeValues(after), attributeValues(inWorld(read)))));
            // Every skin and morph target, and every channel but those that hold their node where it rests (Cesium
            // Man's 5: removeStillChannels, test_optimize) or stay within the budget of it (its scales, 1 but for a
            // millionth: dropRedundantKeys, test_redundant_keys); no other channel lost, and the poses verify.
            Scene moving = before;
            removeStillChannels(moving);
            const std::multiset<std::string> expected = skinsAndMorphs(moving), kept = skinsAndMorphs(after);
            CHECK(std::includes(expected.begin(), expected.end(), kept.begin(), kept.end()));
            auto notChannels = [](const std::multiset<std::string>& lines) {
                std::multiset<std::string> out;
                for (const std::string& line : lines)
                    if (line.rfind("channel ", 0) != 0) out.insert(line);
                return out;
            };
            CHECK(notChannels(kept) == notChannels(expected));
            CHECK(decompressFile(output, folder / "flat.glb", input).verified);
            const nlohmann::json in = gltfJson(input), out = glbJson(output);
            for (const std::string& extension : listed(in, "extensionsUsed"))
                CHECK(listed(out, "extensionsUsed").count(extension));
            for (const std::string& extension : listed(in, "extensionsRequired"))
                CHECK(listed(out, "extensionsRequired").count(extension));
            // No kind of error that the input has not (the clear-coat test's own come out wherever the
            // restructured file has them: its material without the tangents its clear-coat normal map needs, once
            // for each primitive drawing it; the skinned models' weights that do not sum to 1 are inside Draco's
            // data, which the validator does not read).
            auto codes = [](const std::vector<std::string>& errors) {
                std::set<std::string> out;
                for (const std::string& error : errors) out.insert(error.substr(0, error.find(' ')));
                return out;
            };
            if (interopAvailable()) {
                const std::set<std::string> added = codes(validatorErrors(output)), had = codes(validatorErrors(input));
                CHECK(std::includes(had.begin(), had.end(), added.begin(), added.end()));
            }
            if (renderAvailable()) checkRendersSame(input, output, views);
        }
    }
}

TEST_CASE("The lantern's missing base colour image keeps its reference, relative to where the output is",
          "[materials][models]") {
    TemporaryFolder folder;
    const fs::path output = folder / "deeper" / "lantern.gltf";
    fs::create_directories(output.parent_path());
    const Scene scene = readScene(modelPath("pbr/lantern/Lantern.gltf"));
    CHECK(std::any_of(scene.warnings.begin(), scene.warnings.end(), [](const std::string& warning) {
        return warning.find("'Lantern_baseColor.png') could not be read; its reference is kept") != std::string::npos;
    }));
    writeScene(scene, output);
    const nlohmann::json root = gltfJson(output);
    const fs::path expected =
        fs::relative(fs::absolute(modelPath("pbr/lantern/Lantern_baseColor.png")), fs::absolute(output.parent_path()));
    REQUIRE(root["materials"][0]["pbrMetallicRoughness"].contains("baseColorTexture"));
    const int texture = root["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"];
    const int image = root["textures"][texture]["source"];
    CHECK(root["images"][image]["uri"] == expected.generic_string());
    CHECK(fs::exists(output.parent_path() / root["images"][image]["uri"].get<std::string>()) == false);
    CHECK(fs::weakly_canonical(output.parent_path() / expected) ==
          fs::weakly_canonical(modelPath("pbr/lantern/Lantern_baseColor.png")));
}

TEST_CASE("A hand-built scene with every feature at once round trips through compress, decompress and convert",
          "[materials]") {
    // Two images (PNG and JPEG signatures: the bytes are carried, not decoded), a NEAREST clamping sampler, a
    // texture transform, a normal map with a scale, occlusion with a strength, an emissive texture on a second
    // UV set, emissive strength, clearcoat with a texture of its own (extensions in the order of their names,
    // as a reader gives them), extras; on a triangle with tangents drawn twice, once mirrored. Beside it a
    // skinned strip (two joints, the second animated) and a morphed triangle (one target, its weight animated).
    Scene scene;
    Texture png, jpeg;
    png.bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 1, 2, 3};
    png.mimeType = "image/png";
    png.sampler = {9728, 9728, 33071, 33648, "pixel art"};
    jpeg.bytes = {0xff, 0xd8, 0xff, 0xe0, 4, 5, 6};
    jpeg.mimeType = "image/jpeg";
    scene.textures = {png, jpeg};
    Material material;
    material.name = "everything";
    material.baseColorTexture.texture = 0;
    material.baseColorTexture.transform = TextureTransform{{0.5, 0.25}, 0.3, {2, 3}, -1};
    material.metallicRoughnessTexture.texture = 1;
    material.normalTexture = {1, 0, 0.75, std::nullopt};
    material.occlusionTexture = {1, 0, 0.5, std::nullopt};
    material.emissiveTexture = {0, 1, 1, std::nullopt};
    material.emissiveFactor = {1, 0.5, 0.25};
    material.extensions.push_back({"KHR_materials_clearcoat",
                                   R"({"clearcoatFactor":0.5})",
                                   {{"clearcoatNormalTexture", {1, 0, 0.25, std::nullopt}}},
                                   false});
    material.extensions.push_back({"KHR_materials_emissive_strength", R"({"emissiveStrength":4.0})", {}, false});
    material.extrasJson = R"({"author":"test","layer":3})";
    scene.materials = {material};
    Primitive triangle;
    triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0.5}};
    triangle.texcoords = {{0, 0}, {1, 0}, {0, 1}};
    triangle.triangles = {{0, 1, 2}};
    triangle.attributes = {{"TANGENT", 4, {1, 0, 0, 1, 1, 0, 0, 1, 0.6, 0.8, 0, -1}},
                           {"TEXCOORD_1", 2, {0.5, 0.5, 0.75, 0.5, 0.5, 0.75}}};
    triangle.material = 0;
    scene.meshes.push_back({"tri", {triangle}, R"({"kind":"part"})", {}});
    Primitive strip;
    strip.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0}};
    strip.triangles = {{0, 1, 3}, {0, 3, 2}, {2, 3, 5}, {2, 5, 4}};
    strip.attributes = {{"JOINTS_0", 4, {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}},
                        {"WEIGHTS_0", 4, {1, 0, 0, 0, 1, 0, 0, 0, 0.5, 0.5, 0, 0, 0.5, 0.5, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}}};
    scene.meshes.push_back({"strip", {strip}, "", {}});
    Primitive morphed = triangle;
    morphed.attributes.clear();
    morphed.material = -1;
    morphed.targets = {{{"POSITION", 3, {0, 0, 0.5, 0, 0, 0.5, 0, 0, 0}}}};
    scene.meshes.push_back({"morphed", {morphed}, "", {0.25}});
    scene.nodes.resize(6);
    scene.nodes[0].mesh = 0;
    scene.nodes[0].name = "left";
    scene.nodes[0].extrasJson = R"({"id":7})";
    scene.nodes[1].mesh = 0;
    scene.nodes[1].transform.topLeftCorner<3, 3>() = Eigen::Vector3d(-1, 1, 1).asDiagonal();
    scene.nodes[1].transform(0, 3) = 3;
    scene.nodes[2].name = "skinned";
    scene.nodes[2].mesh = 1;
    scene.nodes[2].skin = 0;
    scene.nodes[3].name = "hip";
    scene.nodes[3].children = {4};
    scene.nodes[4].name = "knee";
    scene.nodes[4].transform(1, 3) = 1;
    scene.nodes[5].name = "morphing";
    scene.nodes[5].mesh = 2;
    scene.nodes[5].weights = {0.5};
    scene.nodes[5].transform(0, 3) = -3;
    Skin skin;
    skin.name = "legs";
    skin.joints = {3, 4};
    skin.inverseBindMatrices = {Eigen::Matrix4d::Identity(), Eigen::Matrix4d::Identity()};
    skin.inverseBindMatrices[1](1, 3) = -1;
    skin.skeleton = 3;
    scene.skins = {skin};
    AnimationChannel bend;
    bend.node = 4;
    bend.path = AnimationChannel::Path::Rotation;
    bend.times = {0, 1};
    bend.values = {0, 0, 0, 1, 0.38268343, 0, 0, 0.92387953};
    AnimationChannel weight;
    weight.node = 5;
    weight.path = AnimationChannel::Path::Weights;
    weight.weights = 1;
    weight.interpolation = AnimationChannel::Interpolation::Step;
    weight.times = {0, 0.5, 1};
    weight.values = {0, 1, 0.25};
    scene.animations = {{"walk", {bend, weight}}};
    scene.roots = {0, 1, 2, 3, 5};
    validateScene(scene);
    const std::string expected = describe(scene, material);

    TemporaryFolder folder;
    const fs::path input = folder / "everything.gltf";
    writeScene(scene, input);
    const Scene read = readScene(input);
    REQUIRE(read.materials.size() == 1);
    CHECK(describe(read, read.materials[0]) == expected);
    CHECK(read.meshes.at(0).extrasJson == R"({"kind":"part"})");
    CHECK(read.nodes.at(0).extrasJson == R"({"id":7})");
    const auto values = attributeValues(scene);
    const auto moves = skinsAndMorphs(scene);
    CHECK(sameValues(attributeValues(read), values));
    CHECK(skinsAndMorphs(read) == moves);

    compressFile(input, folder / "compressed.glb");
    const RebuildReport rebuilt = decompressFile(folder / "compressed.glb", folder / "rebuilt.glb", input);
    CHECK(rebuilt.verified);
    writeScene(readScene(folder / "rebuilt.glb"), folder / "converted.gltf");
    // Rebuilt, the mirrored copy of the triangle is baked: its tangents turned with it (x negated), their
    // handedness kept, since a viewer builds the bitangent from the placed normal and tangent either way. The
    // compressed file draws it as an instance of the stored triangle or baked beside it, as the plan weighs them
    // (test_compress checks tangents on mirrored instances of tiles).
    auto baked = values;
    for (const std::vector<double>& tangent : values.at("TANGENT"))
        baked["TANGENT"].insert({-tangent[0], tangent[1], tangent[2], tangent[3]});
    for (const char* name : {"compressed.glb", "rebuilt.glb", "converted.gltf"}) {
        INFO(name);
        const Scene out = readScene(folder / name);
        CHECK(drawnMaterials(out) == std::multiset<std::string>{expected});
        CHECK((sameValues(attributeValues(out), baked) ||
               (std::string(name) == "compressed.glb" && sameValues(attributeValues(out), values))));
        CHECK(skinsAndMorphs(out) == moves);
        const nlohmann::json root = gltfJson(folder / name);
        CHECK(listed(root, "extensionsUsed").count("KHR_materials_clearcoat"));
        CHECK(listed(root, "extensionsUsed").count("KHR_texture_transform"));
        CHECK(root["samplers"].size() == 1);
        CHECK(root["samplers"][0]["magFilter"] == 9728);
    }
    const nlohmann::json compressed = glbJson(folder / "compressed.glb");
    bool extrasKept = false;
    for (const auto& node : compressed["nodes"]) extrasKept |= node.contains("extras") && node["extras"]["id"] == 7;
    CHECK(extrasKept);
}

namespace {

// The area each copy of a part (its x / 10, rounded) draws in each material, by the material's description, under
// variant `v` of KHR_materials_variants (-1: none chosen): what a viewer that switches variants shows.
std::map<std::pair<long, std::string>, double> areaByCopyAndMaterial(const Scene& scene, int v) {
    std::map<std::pair<long, std::string>, double> out;
    for (const WorldPrimitive& placed : flattenScene(scene)) {
        int m = placed.primitive.material;
        if (v >= 0 && m >= 0 && !scene.materials[std::size_t(m)].variants.empty() &&
            scene.materials[std::size_t(m)].variants[std::size_t(v)] >= 0)
            m = scene.materials[std::size_t(m)].variants[std::size_t(v)];
        const std::string drawn = m >= 0 ? describe(scene, scene.materials[std::size_t(m)]) : "default";
        const auto& x = placed.primitive.positions;
        for (const Triangle& t : placed.primitive.triangles) {
            const double area = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
            out[{std::lround((x[t[0]] + x[t[1]] + x[t[2]]).x() / 30), drawn}] += area;
        }
    }
    return out;
}

bool sameAreas(const std::map<std::pair<long, std::string>, double>& a,
               const std::map<std::pair<long, std::string>, double>& b) {
    if (a.size() != b.size()) return false;
    for (const auto& [key, area] : a)
        if (!b.count(key) || !(std::abs(b.at(key) - area) <= 1e-3 * area)) return false;
    return true;
}

}  // namespace

TEST_CASE("Material variants (KHR_materials_variants) come out as they went in, under every variant", "[materials]") {
    // Four copies of a part, all grey by default: the first and third turn red under variant 0 and textured blue
    // under variant 1, the fourth red under variant 1, the second never changes. The variant materials are drawn by
    // no primitive by default, and only the blue one reads the texture coordinates.
    std::mt19937_64 random(11);
    const TriangleMesh part = samples::randomConvexPart(random);
    Scene scene;
    Texture png;
    png.bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 1, 2, 3};
    png.mimeType = "image/png";
    scene.textures = {png};
    Material grey, red, blue;
    grey.name = "grey";
    grey.baseColorFactor = {0.5, 0.5, 0.5, 1};
    red.name = "red";
    red.baseColorFactor = {1, 0, 0, 1};
    blue.name = "blue";
    blue.baseColorFactor = {0, 0, 1, 1};
    blue.baseColorTexture.texture = 0;
    scene.materials = {grey, red, blue};
    Mesh copies;
    for (int k = 0; k < 4; ++k) {
        Primitive copy;
        samples::appendMesh(copy, samples::transformed(part, Eigen::Matrix3d::Identity(), {10.0 * k, 0, 0}));
        for (const Eigen::Vector3d& x : copy.positions) copy.texcoords.push_back({x.y(), x.z()});
        copy.material = 0;
        copies.primitives.push_back(copy);
    }
    scene.meshes = {copies};
    scene.nodes.resize(1);
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    TemporaryFolder folder;
    const fs::path plain = folder / "plain.gltf", input = folder / "variants.gltf";
    WriteOptions uncompressed;
    uncompressed.draco = false;
    writeScene(scene, plain, uncompressed);
    // The variants put in by hand, as a file from elsewhere has them.
    nlohmann::json root = nlohmann::json::parse(readTextFile(plain));
    root["extensionsUsed"].push_back("KHR_materials_variants");
    root["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "Red"}}, {{"name", "Blue"}}};
    const nlohmann::json redThenBlue = {
        {"mappings", {{{"material", 1}, {"variants", {0}}}, {{"material", 2}, {"variants", {1}}}}}};
    auto& primitives = root["meshes"][0]["primitives"];
    REQUIRE(primitives.size() == 4);
    primitives[0]["extensions"]["KHR_materials_variants"] = redThenBlue;
    primitives[2]["extensions"]["KHR_materials_variants"] = redThenBlue;
    primitives[3]["extensions"]["KHR_materials_variants"] = {{"mappings", {{{"material", 1}, {"variants", {1}}}}}};
    writeTextFile(input, root.dump());
    fs::copy_file(folder / "plain.bin", folder / "variants.bin");

    const Scene read = readScene(input);
    REQUIRE(read.materialVariants.size() == 2);
    CHECK(read.materialVariants[1].name == "Blue");
    CHECK(read.warnings.empty());
    // The ground truth, from the file: copy 0 and 2 red then blue, copy 3 grey then red, copy 1 grey.
    const auto byVariant = [&](const Scene& s) {
        return std::vector{areaByCopyAndMaterial(s, -1), areaByCopyAndMaterial(s, 0), areaByCopyAndMaterial(s, 1)};
    };
    const auto expected = byVariant(read);
    REQUIRE(expected[1].size() == 4);
    std::set<std::string> underRed;
    for (const auto& [key, area] : expected[1]) underRed.insert(std::to_string(key.first) + key.second.substr(0, 8));
    CHECK(underRed.count("0" + describe(read, red).substr(0, 8)));
    CHECK(underRed.count("3" + describe(read, grey).substr(0, 8)));

    const CompressionReport report = compressFile(input, folder / "compressed.glb");
    CHECK(report.stats.instances >= 1);  // copies that differ only in place and share their variants are one mesh
    const RebuildReport rebuilt = decompressFile(folder / "compressed.glb", folder / "rebuilt.glb", input);
    CHECK(rebuilt.verified);
    for (const char* name : {"compressed.glb", "rebuilt.glb"}) {
        INFO(name);
        const Scene out = readScene(folder / name);
        CHECK(out.warnings.empty());
        REQUIRE(out.materialVariants == read.materialVariants);
        const auto drawn = byVariant(out);
        for (int v = 0; v < 3; ++v) CHECK(sameAreas(drawn[std::size_t(v)], expected[std::size_t(v)]));
        // The texture coordinates only the blue variant reads are kept.
        for (const WorldPrimitive& placed : flattenScene(out))
            if (placed.primitive.material >= 0 &&
                !out.materials[std::size_t(placed.primitive.material)].variants.empty())
                CHECK(!placed.primitive.texcoords.empty());
        const nlohmann::json written = glbJson(folder / name);
        CHECK(listed(written, "extensionsUsed").count("KHR_materials_variants"));
        CHECK(written["extensions"]["KHR_materials_variants"]["variants"][0]["name"] == "Red");
        if (interopAvailable()) CHECK(validatorErrors(folder / name).empty());
    }

    // X3D has no variants: said, and the default materials drawn.
    const CompressionReport x3d = compressFile(input, folder / "compressed.x3d");
    CHECK(std::any_of(x3d.warnings.begin(), x3d.warnings.end(), [](const std::string& warning) {
        return warning.find("2 material variants (KHR_materials_variants) not written") != std::string::npos;
    }));
    // X3D output of glTF materials reads back as X3D's own (described otherwise): the area drawn is compared.
    double greyArea = 0, expectedGrey = 0;
    for (const auto& [key, area] : areaByCopyAndMaterial(readScene(folder / "compressed.x3d"), -1)) greyArea += area;
    for (const auto& [key, area] : expected[0]) expectedGrey += area;
    CHECK(std::abs(greyArea - expectedGrey) <= 1e-3 * expectedGrey);
}

TEST_CASE("Broken KHR_materials_variants mappings are warned about, naming the primitive, and left out",
          "[materials]") {
    Scene scene = samples::singleMeshScene("box",
                                           [] {
                                               Primitive box;
                                               samples::appendMesh(box, samples::boxMesh({0, 0, 0}, {1, 2, 3}));
                                               return box;
                                           }(),
                                           {0.5, 0.5, 0.5, 1});
    TemporaryFolder folder;
    WriteOptions uncompressed;
    uncompressed.draco = false;
    writeScene(scene, folder / "plain.gltf", uncompressed);
    nlohmann::json root = nlohmann::json::parse(readTextFile(folder / "plain.gltf"));
    root["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "only"}}};
    root["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"] = {
        {"mappings", {{{"material", 7}, {"variants", {0}}}, {{"material", 0}, {"variants", {3}}}, "not an object"}}};
    writeTextFile(folder / "broken.gltf", root.dump());
    fs::copy_file(folder / "plain.bin", folder / "broken.bin");
    const Scene read = readScene(folder / "broken.gltf");
    CHECK(read.materials.size() == 1);
    CHECK(read.materials[0].variants.empty());
    CHECK(std::any_of(read.warnings.begin(), read.warnings.end(), [](const std::string& warning) {
        return warning.find("broken.gltf: mesh 0 primitive 0: a KHR_materials_variants mapping") != std::string::npos;
    }));
    CHECK(std::any_of(read.warnings.begin(), read.warnings.end(), [](const std::string& warning) {
        return warning.find("maps a variant that is not in the file's list") != std::string::npos;
    }));
    const CompressionReport report = compressFile(folder / "broken.gltf", folder / "out.glb");
    const nlohmann::json written = glbJson(folder / "out.glb");
    CHECK(written["meshes"][0]["primitives"][0]
              .value("extensions", nlohmann::json::object())
              .count("KHR_materials_variants") == 0);
    if (interopAvailable()) CHECK(validatorErrors(folder / "out.glb").empty());
}

TEST_CASE("Broken material references are warned about and written as nothing, never as a dangling index",
          "[materials]") {
    TemporaryFolder folder;
    // A triangle; the material's base colour texture does not exist, its normal texture's sampler does not,
    // its emissive image holds no image, and its clearcoat extension is a number.
    const fs::path file = folder / "broken.gltf";
    writeTextFile(file, R"({"asset": {"version": "2.0"},
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
        "images": [{"uri": "data:image/png;base64,iVBORw0KGgo="}, {"uri": "data:image/png;base64,aGVsbG8="}],
        "textures": [{"source": 0, "sampler": 4}, {"source": 1}],
        "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 9}}, "normalTexture": {"index": 0},
                       "emissiveTexture": {"index": 1}, "extensions": {"KHR_materials_clearcoat": 5}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
    const Scene scene = readScene(file);
    auto warned = [&](const std::string& text) {
        return std::any_of(scene.warnings.begin(), scene.warnings.end(),
                           [&](const std::string& warning) { return warning.find(text) != std::string::npos; });
    };
    CHECK(warned("broken.gltf: material 0 baseColorTexture: texture index 9 does not exist, left out"));
    CHECK(warned("texture 0: sampler 4 does not exist, the default one used"));
    CHECK(warned("image 1: its bytes are no PNG, JPEG, WebP or KTX2 image"));
    CHECK(warned("material 0: extension KHR_materials_clearcoat is not an object, left out"));
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].baseColorTexture.texture == -1);
    CHECK(scene.materials[0].normalTexture.texture >= 0);
    CHECK(scene.materials[0].extensions.empty());
    validateScene(scene);
    writeScene(scene, folder / "out.glb");
    const nlohmann::json root = glbJson(folder / "out.glb");
    CHECK(root["textures"].size() == 2);
    CHECK(root["images"].size() == 2);
    CHECK_FALSE(root["materials"][0].contains("extensions"));
}

TEST_CASE("An X3D or OBJ texture that is not found keeps its reference, relative to the output", "[materials]") {
    TemporaryFolder folder;
    writeTextFile(folder / "scene.x3d", R"(<X3D version="3.3"><Scene><Shape><Appearance><Material/>
        <ImageTexture url='"maps/missing.png"'/></Appearance><Box/></Shape></Scene></X3D>)");
    const Scene scene = readScene(folder / "scene.x3d");
    REQUIRE(scene.textures.size() == 1);
    fs::create_directories(folder / "out");
    writeScene(scene, folder / "out" / "scene.x3d");
    CHECK_THAT(readTextFile(folder / "out" / "scene.x3d"), Catch::Contains("url='\"../maps/missing.png\"'"));
    writeScene(scene, folder / "out" / "scene.obj");
    CHECK_THAT(readTextFile(folder / "out" / "scene.mtl"), Catch::Contains("map_Kd ../maps/missing.png"));
    writeScene(scene, folder / "out" / "scene.gltf");
    CHECK(gltfJson(folder / "out" / "scene.gltf")["images"][0]["uri"] == "../maps/missing.png");
}

TEST_CASE("An MTL's norm and map_Ke fill glTF's normal and emissive slots, and maps without a slot are warned about",
          "[materials]") {
    TemporaryFolder folder;
    for (const char* image : {"base.png", "glow.png", "normal.png"})
        fs::copy_file(modelPath("pbr/texture_transform/Arrow.png"), folder / image);
    writeTextFile(folder / "part.mtl",
                  "newmtl lit\nKd 1 1 1\nKe 1 0.5 0\nmap_Kd -s 2 2 1 base.png\nmap_Ke glow.png\n"
                  "norm -bm 0.5 normal.png\nmap_Bump -bm 1 height.png\nmap_d alpha.png\nmap_Ks shine.png\n");
    writeTextFile(folder / "part.obj",
                  "mtllib part.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                  "usemtl lit\nf 1/1 2/2 3/3\n");
    const Scene scene = readScene(folder / "part.obj");
    REQUIRE(scene.materials.size() == 1);
    const Material& m = scene.materials[0];
    const auto uriOf = [&](const TextureRef& use) {
        return use.texture < 0 ? std::string() : scene.textures[std::size_t(use.texture)].uri;
    };
    CHECK(uriOf(m.baseColorTexture) == "base.png");
    CHECK(uriOf(m.emissiveTexture) == "glow.png");
    CHECK(uriOf(m.normalTexture) == "normal.png");
    CHECK(m.normalTexture.scale == 0.5);
    // Ke is sRGB-encoded (as Kd): 0.5 decodes to ((0.5 + 0.055) / 1.055)^2.4 (IEC 61966-2-1).
    CHECK(m.emissiveFactor.isApprox(Eigen::Vector3d(1, std::pow(0.555 / 1.055, 2.4), 0)));
    CHECK(m.metallicRoughnessTexture.texture < 0);
    CHECK(m.occlusionTexture.texture < 0);
    const auto warning = std::find_if(scene.warnings.begin(), scene.warnings.end(), [](const std::string& text) {
        return text.find("part.mtl: map_Bump, map_Ks, map_d left out") != std::string::npos;
    });
    CHECK(warning != scene.warnings.end());
    // Through GLB: the slots with their images and scale.
    writeScene(scene, folder / "part.glb");
    const Scene back = readScene(folder / "part.glb");
    REQUIRE(back.materials.size() == 1);
    CHECK(back.materials[0].normalTexture.scale == 0.5);
    CHECK(back.materials[0].emissiveTexture.texture >= 0);
    CHECK(back.textures.at(std::size_t(back.materials[0].normalTexture.texture)).bytes == scene.textures[2].bytes);
}

TEST_CASE("A PLY's TextureFile comment and MeshLab's texture coordinates per corner give a textured mesh",
          "[materials]") {
    TemporaryFolder folder;
    fs::copy_file(modelPath("pbr/box_specgloss/CesiumLogoFlat.png"), folder / "tex.png");
    const std::string head =
        "ply\nformat ascii 1.0\ncomment TextureFile tex.png\nelement vertex 4\nproperty float x\n"
        "property float y\nproperty float z\nelement face 2\n"
        "property list uchar int vertex_indices\nproperty list uchar float texcoord\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    SECTION("the first corner has two pairs of coordinates: two vertices") {
        writeTextFile(folder / "quad.ply", head + "3 0 1 2 6 0 0 1 0 1 1\n3 0 2 3 6 0.5 0.5 1 1 0 1\n");
        const Scene scene = readScene(folder / "quad.ply");
        const Primitive& quad = scene.meshes.at(0).primitives.at(0);
        CHECK(quad.positions.size() == 5);
        REQUIRE(quad.triangles.size() == 2);
        // glTF's v points down: v = 1 - t.
        CHECK(quad.texcoords.at(quad.triangles[0][0]) == Eigen::Vector2d(0, 1));
        CHECK(quad.texcoords.at(quad.triangles[1][0]) == Eigen::Vector2d(0.5, 0.5));
        CHECK(quad.positions.at(quad.triangles[1][0]) == Eigen::Vector3d(0, 0, 0));
        CHECK(quad.texcoords.at(quad.triangles[1][2]) == Eigen::Vector2d(0, 0));
        REQUIRE(quad.material == 0);
        REQUIRE(scene.textures.size() == 1);
        CHECK(scene.textures[0].bytes.size() == fs::file_size(folder / "tex.png"));
        CHECK(scene.materials.at(0).baseColorTexture.texture == 0);
        CHECK(scene.warnings.empty());
    }
    SECTION("a list of the wrong length, or a texture that is not there: warned about") {
        writeTextFile(folder / "short.ply", head + "3 0 1 2 4 0 0 1 0\n3 0 2 3 6 0.5 0.5 1 1 0 1\n");
        const Scene scene = readScene(folder / "short.ply");
        CHECK(scene.meshes.at(0).primitives.at(0).texcoords.empty());
        CHECK(scene.materials.empty());
        REQUIRE(scene.warnings.size() == 1);
        CHECK_THAT(scene.warnings[0], Catch::Contains("short.ply: a face's texcoord list"));
        writeTextFile(folder / "nan.ply", head + "3 0 1 2 6 0 0 1 0 1 nan\n3 0 2 3 6 0.5 0.5 1 1 0 1\n");
        const Scene notFinite = readScene(folder / "nan.ply");
        CHECK(notFinite.meshes.at(0).primitives.at(0).texcoords.empty());
        CHECK(notFinite.warnings.size() == 1);
        fs::remove(folder / "tex.png");
        writeTextFile(folder / "missing.ply", head + "3 0 1 2 6 0 0 1 0 1 1\n3 0 2 3 6 0.5 0.5 1 1 0 1\n");
        const Scene missing = readScene(folder / "missing.ply");
        REQUIRE(missing.textures.size() == 1);
        CHECK(missing.textures[0].bytes.empty());
        REQUIRE(missing.warnings.size() == 1);
        CHECK_THAT(missing.warnings[0], Catch::Contains("texture 'tex.png' not found; its reference is kept"));
    }
}

TEST_CASE("X3D output refers to an image file where it was read, and embeds an image that came embedded",
          "[materials][x3d]") {
    TemporaryFolder folder;
    fs::create_directories(folder / "maps");
    fs::copy_file(modelPath("pbr/texture_transform/Arrow.png"), folder / "maps" / "arrow.png");
    writeTextFile(folder / "scene.x3d", R"(<X3D version="3.3"><Scene><Shape><Appearance><Material/>
        <ImageTexture url='"maps/arrow.png"'/></Appearance><Box/></Shape></Scene></X3D>)");
    const Scene scene = readScene(folder / "scene.x3d");
    REQUIRE(scene.textures.size() == 1);
    REQUIRE_FALSE(scene.textures[0].bytes.empty());
    CHECK(x3dReferencedImageBytes(scene) == fs::file_size(folder / "maps" / "arrow.png"));
    fs::create_directories(folder / "out");
    writeScene(scene, folder / "out" / "scene.x3d");
    const std::string text = readTextFile(folder / "out" / "scene.x3d");
    CHECK_THAT(text, Catch::Contains("url='\"../maps/arrow.png\"'"));
    CHECK_THAT(text, !Catch::Contains("data:"));
    CHECK(readScene(folder / "out" / "scene.x3d").textures[0].bytes == scene.textures[0].bytes);
    writeScene(scene, folder / "out" / "scene.obj");
    CHECK_THAT(readTextFile(folder / "out" / "scene.mtl"), Catch::Contains("map_Kd ../maps/arrow.png"));

    // From a GLB, which holds the image's bytes: embedded in the X3D as they came.
    writeScene(scene, folder / "scene.glb");
    const Scene fromGlb = readScene(folder / "scene.glb");
    CHECK(x3dReferencedImageBytes(fromGlb) == 0);
    writeScene(fromGlb, folder / "out" / "embedded.x3d");
    CHECK_THAT(readTextFile(folder / "out" / "embedded.x3d"), Catch::Contains("url='\"data:image/png;base64,"));
    CHECK(readScene(folder / "out" / "embedded.x3d").textures[0].bytes == scene.textures[0].bytes);
}

TEST_CASE(
    "A texture's core image beside an extension's (KHR_texture_basisu, EXT_texture_webp) is kept as its "
    "fallback, and the extension stays optional",
    "[materials]") {
    // The box of the shared specular-glossiness sample, its texture given a KTX2 image (a header: the bytes are
    // carried, not decoded) with the PNG as the core source; a second texture has the KTX2 image alone.
    TemporaryFolder folder;
    const fs::path source = modelPath("pbr/box_specgloss");
    for (const char* file : {"BoxTextured0.bin", "CesiumLogoFlat.png"}) fs::copy_file(source / file, folder / file);
    std::vector<std::uint8_t> ktx2 = {0xab, 'K', 'T', 'X', ' ', '2', '0', 0xbb, '\r', '\n', 0x1a, '\n'};
    ktx2.resize(32, 0);
    ktx2[20] = 64, ktx2[24] = 64;  // 64 x 64
    std::ofstream(folder / "logo.ktx2", std::ios::binary)
        .write(reinterpret_cast<const char*>(ktx2.data()), long(ktx2.size()));
    nlohmann::json root = nlohmann::json::parse(readTextFile(source / "BoxTextured.gltf"));
    REQUIRE(root["textures"].size() == 1);
    root["images"].push_back({{"uri", "logo.ktx2"}});
    root["textures"][0]["extensions"]["KHR_texture_basisu"]["source"] = 1;
    root["extensionsUsed"].push_back("KHR_texture_basisu");
    writeTextFile(folder / "fallback.gltf", root.dump());
    // The same with the KTX2 image alone: the extension required.
    root["textures"][0].erase("source");
    root["extensionsRequired"] = {"KHR_texture_basisu"};
    writeTextFile(folder / "alone.gltf", root.dump());

    const Scene read = readScene(folder / "fallback.gltf");
    REQUIRE(read.textures.size() == 1);
    CHECK(read.textures[0].mimeType == "image/ktx2");
    REQUIRE(read.textures[0].fallback);
    CHECK(read.textures[0].fallback->mimeType == "image/png");
    CHECK(read.textures[0].fallback->bytes.size() == fs::file_size(source / "CesiumLogoFlat.png"));

    for (const char* name : {"fallback", "alone"}) {
        INFO(name);
        const fs::path output = folder / (std::string(name) + ".glb");
        compressFile(folder / (std::string(name) + ".gltf"), output);
        const nlohmann::json written = glbJson(output);
        const nlohmann::json& texture = written["textures"][0];
        const int ktx2Image = texture["extensions"]["KHR_texture_basisu"]["source"];
        CHECK(written["images"][std::size_t(ktx2Image)]["mimeType"] == "image/ktx2");
        CHECK(listed(written, "extensionsUsed").count("KHR_texture_basisu"));
        if (std::string(name) == "fallback") {
            REQUIRE(texture.contains("source"));
            CHECK(written["images"][texture["source"].get<std::size_t>()]["mimeType"] == "image/png");
            CHECK(!listed(written, "extensionsRequired").count("KHR_texture_basisu"));
            const Scene out = readScene(output);
            REQUIRE(out.textures.at(0).fallback);
            CHECK(out.textures[0].fallback->bytes == read.textures[0].fallback->bytes);
            CHECK(out.textures.at(0).bytes == ktx2);
        } else {
            CHECK(!texture.contains("source"));
            CHECK(listed(written, "extensionsRequired").count("KHR_texture_basisu"));
        }
        if (interopAvailable()) CHECK(validatorErrors(output).empty());
    }
    // X3D lists both, the fallback second: a browser shows the first URL it can read.
    compressFile(folder / "fallback.gltf", folder / "fallback.x3d");
    CHECK(readTextFile(folder / "fallback.x3d").find("url='\"logo.ktx2\" \"CesiumLogoFlat.png\"'") !=
          std::string::npos);
    CHECK(x3dReferencedImageBytes(readScene(folder / "fallback.gltf")) ==
          ktx2.size() + fs::file_size(source / "CesiumLogoFlat.png"));
}
