// EXT_mesh_gpu_instancing in the glTF writer: plain leaves drawing one mesh written as one node where that is
// smaller, mirrored instances in a batch of their own under a mirroring node, a shear left a node; the reader
// expands the batches back into nodes with their names. Checked by the Khronos validator and, where the
// render check is installed, drawn by three.js as the same scene written a node per instance.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <map>
#include <set>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// A closed tetrahedron with no symmetry, wound outwards: drawn inside out, its lit faces would be the far ones.
Primitive tetrahedron() {
    Primitive p;
    p.positions = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.2, 0}, {0, 0, 0.3}};
    p.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    return p;
}

// A bumpy sphere with no symmetry, 352 triangles: a part worth a node per copy.
Primitive blob() {
    constexpr int rings = 12, sectors = 16;
    constexpr double pi = 3.14159265358979323846;
    Primitive p;
    p.positions.push_back({0, 0, 0.2});
    for (int i = 1; i < rings; ++i)
        for (int j = 0; j < sectors; ++j) {
            const double theta = pi * i / rings, phi = 2 * pi * j / sectors;
            const double r = 0.2 * (1 + 0.15 * std::sin(2 * theta + 0.3) * std::cos(phi - 0.7) +
                                    0.1 * std::cos(3 * phi + 0.2) * std::sin(theta));
            p.positions.push_back(
                r * Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
        }
    p.positions.push_back({0, 0, -0.2});
    auto at = [](int i, int j) { return std::uint32_t(1 + (i - 1) * sectors + (j % sectors)); };
    const auto south = std::uint32_t(p.positions.size() - 1);
    for (int j = 0; j < sectors; ++j) {
        p.triangles.push_back({0, at(1, j), at(1, j + 1)});
        for (int i = 1; i + 1 < rings; ++i) {
            p.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            p.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
        }
        p.triangles.push_back({at(rings - 1, j), south, at(rings - 1, j + 1)});
    }
    return p;
}

Eigen::Matrix4d placed(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& at, double mirror = 1) {
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    t.translate(at);
    t.rotate(Eigen::AngleAxisd(angle, axis.normalized()));
    t.scale(Eigen::Vector3d(mirror, 1, 1));
    return t.matrix();
}

// The tetrahedron with each face cut in four, 16 triangles: a part small enough that a node of its own costs
// more than its triangles among others, while an instance in a batch costs less.
Primitive cutTetrahedron() {
    Primitive part = tetrahedron();
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middleOf;  // each edge cut once
    auto middle = [&](std::uint32_t a, std::uint32_t b) {
        const auto [at, added] = middleOf.emplace(std::minmax(a, b), std::uint32_t(part.positions.size()));
        if (added)  // pushed out from the corner at the origin, unevenly: no symmetry
            part.positions.push_back((part.positions[a] + part.positions[b]) / 2 * (1.1 + 0.03 * double(a + 2 * b)));
        return at->second;
    };
    for (std::size_t face = 0; face < 4; ++face) {  // each face cut in four
        const Triangle t = part.triangles[face];
        const std::uint32_t m0 = middle(t[0], t[1]), m1 = middle(t[1], t[2]), m2 = middle(t[2], t[0]);
        part.triangles.push_back({t[0], m0, m2});
        part.triangles.push_back({t[1], m1, m0});
        part.triangles.push_back({t[2], m2, m1});
        part.triangles[face] = {m0, m1, m2};
    }
    return part;
}

// `rigid` turned copies, `mirrored` mirrored ones and one sheared copy of the tetrahedron, each a named root.
Scene copiesScene(int rigid, int mirrored, bool sheared, const Primitive& part = tetrahedron()) {
    Scene scene;
    scene.meshes.push_back({"part", {part}, "", {}});
    auto add = [&](const std::string& name, const Eigen::Matrix4d& transform) {
        Node node;
        node.name = name;
        node.mesh = 0;
        node.transform = transform;
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
    };
    for (int i = 0; i < rigid; ++i)
        add("rigid " + std::to_string(i), placed(0.7 * i, {1, 2, 3.0 + i}, {0.5 * (i % 5), 0.5 * (i / 5), 0}));
    for (int i = 0; i < mirrored; ++i)
        add("mirrored " + std::to_string(i), placed(0.9 * i, {3, 1, 2}, {0.5 * i, -1, 0.2}, -1));
    if (sheared) {
        Eigen::Matrix4d shear = Eigen::Matrix4d::Identity();
        shear(0, 1) = 0.5;
        shear.topRightCorner<3, 1>() = Eigen::Vector3d(-1, 0, 0);
        add("sheared", shear);
    }
    return scene;
}

// `copies` of `part` turned about the vertical (grass cards, trees), each baked into a mesh of its own, drawn
// by a root named `name` and its number (unnamed when `name` is empty).
Scene bakedCopies(const Primitive& part, int copies, const std::string& name = "") {
    Scene scene;
    for (int i = 0; i < copies; ++i) {
        const Eigen::Matrix4d at = placed(0.7 * i, {0, 0, 1}, {0.5 * (i % 20), 0.5 * (i / 20), 0});
        scene.meshes.push_back({"", {transformPrimitive(part, at)}, "", {}});
        Node node;
        node.mesh = i;
        if (!name.empty()) node.name = name + std::to_string(i);
        scene.roots.push_back(i);
        scene.nodes.push_back(node);
    }
    return scene;
}

// The world transform of every node drawing a mesh, by its name or, where it has none (the child a shear is
// split into), its parent's.
std::map<std::string, Eigen::Matrix4d> worldByName(const Scene& scene) {
    const std::vector<Eigen::Matrix4d> world = worldTransforms(scene);
    std::vector<int> parent(scene.nodes.size(), -1);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
        for (int child : scene.nodes[n].children) parent[std::size_t(child)] = int(n);
    std::map<std::string, Eigen::Matrix4d> out;
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
        if (scene.nodes[n].mesh >= 0)
            out[scene.nodes[n].name.empty() && parent[n] >= 0 ? scene.nodes[std::size_t(parent[n])].name
                                                              : scene.nodes[n].name] = world[n];
    return out;
}

std::vector<const nlohmann::json*> batchNodes(const nlohmann::json& root) {
    std::vector<const nlohmann::json*> batches;
    for (const auto& node : root["nodes"])
        if (node.contains("extensions") && node["extensions"].contains("EXT_mesh_gpu_instancing"))
            batches.push_back(&node);
    return batches;
}

std::size_t instanceCount(const nlohmann::json& root, const nlohmann::json& batch) {
    const auto& attributes = batch["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    return root["accessors"][attributes.begin().value().get<std::size_t>()]["count"];
}

}  // namespace

TEST_CASE("Rigid and mirrored copies are GPU-instanced, a sheared one stays a node, and all read back", "[io][gpu]") {
    TemporaryFolder folder;
    const Scene scene = copiesScene(12, 6, true);
    const auto file = folder / "copies.glb";
    writeScene(scene, file);
    const nlohmann::json root = glbJson(file);

    // Two batches (mirrored apart, under a node that mirrors) and the sheared node as TRS nodes of its own.
    const auto batches = batchNodes(root);
    REQUIRE(batches.size() == 2);
    std::size_t mirroredBatches = 0, instances = 0;
    for (const nlohmann::json* batch : batches) {
        const bool mirrors = batch->contains("scale") && (*batch)["scale"] == nlohmann::json({-1, 1, 1});
        mirroredBatches += mirrors;
        CHECK(instanceCount(root, *batch) == (mirrors ? 6u : 12u));
        instances += instanceCount(root, *batch);
        const auto& attributes = (*batch)["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
        CHECK(root["accessors"][attributes["ROTATION"].get<std::size_t>()]["componentType"] == 5122);  // SHORT
        CHECK_FALSE(attributes.contains("SCALE"));  // rigid: every scale 1
        CHECK((*batch)["extras"]["instanceNames"].size() == instanceCount(root, *batch));
    }
    CHECK(mirroredBatches == 1);
    CHECK(instances == 18);
    CHECK(root["extensionsRequired"] == nlohmann::json({"EXT_mesh_gpu_instancing", "KHR_draco_mesh_compression"}));
    CHECK(root["nodes"].size() == 2 + 2);  // the batches, and the shear's two TRS nodes
    CHECK(root["scenes"][0]["nodes"].size() == 3);

    // Read back: every copy a node again, with its name, at its world transform within the SHORT rotations.
    const Scene back = readScene(file);
    CHECK(back.warnings.empty());
    const auto expected = worldByName(scene), got = worldByName(back);
    REQUIRE(got.size() == expected.size());
    for (const auto& [name, world] : expected) {
        INFO(name);
        REQUIRE(got.count(name));
        CHECK((got.at(name) - world).cwiseAbs().maxCoeff() < 1e-4);
    }
    // The batch nodes keep no extras of their own once their names are given back.
    for (const Node& node : back.nodes) CHECK(node.extrasJson.empty());

    if (interopAvailable()) CHECK(validatorErrors(file).empty());

    // Without Draco the file is float throughout: the rotations too.
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "plain.glb", plain);
    const nlohmann::json plainRoot = glbJson(folder / "plain.glb");
    for (const nlohmann::json* batch : batchNodes(plainRoot)) {
        const auto& attributes = (*batch)["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
        CHECK(plainRoot["accessors"][attributes["ROTATION"].get<std::size_t>()]["componentType"] == 5126);
    }
}

TEST_CASE("Scaled instances carry a SCALE accessor, and unnamed ones no names", "[io][gpu]") {
    TemporaryFolder folder;
    Scene scene = copiesScene(20, 0, false);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        scene.nodes[n].name.clear();
        scene.nodes[n].transform.topLeftCorner<3, 3>() *= 1.0 + 0.25 * double(n);
    }
    const auto file = folder / "scaled.glb";
    writeScene(scene, file);
    const nlohmann::json root = glbJson(file);
    const auto batches = batchNodes(root);
    REQUIRE(batches.size() == 1);
    CHECK((*batches[0])["extensions"]["EXT_mesh_gpu_instancing"]["attributes"].contains("SCALE"));
    CHECK_FALSE(batches[0]->contains("extras"));
    const Scene back = readScene(file);
    std::vector<Eigen::Matrix4d> expected, got;
    const auto world = worldTransforms(back);
    for (std::size_t n = 0; n < back.nodes.size(); ++n)
        if (back.nodes[n].mesh >= 0) got.push_back(world[n]);
    REQUIRE(got.size() == scene.nodes.size());
    for (std::size_t i = 0; i < got.size(); ++i)  // the reader appends the instances in the batch's order
        CHECK((got[i] - scene.nodes[i].transform).cwiseAbs().maxCoeff() < 3e-4);
    if (interopAvailable()) CHECK(validatorErrors(file).empty());
}

TEST_CASE("GPU instancing leaves alone what must stay a node", "[io][gpu]") {
    TemporaryFolder folder;
    const auto file = folder / "out.glb";
    auto batchesOf = [&](const Scene& scene, const WriteOptions& options = {}) {
        writeScene(scene, file, options);
        return batchNodes(glbJson(file)).size();
    };
    SECTION("a single instance, and two, whose batch would cost more than their nodes") {
        CHECK(batchesOf(copiesScene(1, 0, false)) == 0);
        CHECK(batchesOf(copiesScene(2, 0, false)) == 0);
    }
    SECTION("--no-gpu-instancing") {
        WriteOptions options;
        options.gpuInstancing = false;
        CHECK(batchesOf(copiesScene(12, 4, false), options) == 0);
        CHECK(glbJson(file)["nodes"].size() == 16);
        CHECK(glbJson(file)["extensionsRequired"] == nlohmann::json({"KHR_draco_mesh_compression"}));
    }
    SECTION("a node with children, one with extras and an animated one stay nodes, the others are batched") {
        Scene scene = copiesScene(12, 0, false);
        Node child;
        child.name = "child";
        child.transform = placed(0, {0, 0, 1}, {0, 0, 1});
        scene.nodes[0].children.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(child);
        scene.nodes[1].extrasJson = R"({"part":"A-1"})";
        Animation animation;
        AnimationChannel channel;
        channel.node = 2;
        channel.times = {0, 1};
        channel.values = {0, 0, 0, 1, 0, 0};
        animation.channels.push_back(channel);
        scene.animations.push_back(animation);
        validateScene(scene);
        REQUIRE(batchesOf(scene) == 1);
        const nlohmann::json root = glbJson(file);
        CHECK(instanceCount(root, *batchNodes(root)[0]) == 9);
        CHECK(root["nodes"].size() == 3 + 1 + 1);                            // the three kept, the child, the batch
        CHECK(root["animations"][0]["channels"][0]["target"]["node"] == 2);  // renumbered: the third node kept
        CHECK(root["nodes"][2]["name"] == "rigid 2");
        const Scene back = readScene(file);
        const auto expected = worldByName(scene), got = worldByName(back);
        CHECK(got.size() == expected.size());
        for (const Node& node : back.nodes)
            if (node.name == "rigid 1") CHECK(node.extrasJson == R"({"part":"A-1"})");
        if (interopAvailable()) CHECK(validatorErrors(file).empty());
    }
}

namespace {

// `count` turned copies of the blob, roots, unnamed, at translations off any grid (each step a little different).
Scene scatteredBlobs(int count) {
    Scene scene;
    scene.meshes.push_back({"blob", {blob()}, "", {}});
    for (int i = 0; i < count; ++i) {
        Node node;
        node.mesh = 0;
        const Eigen::Vector3d at(0.5 * (i % 10) + 0.01 * std::sin(1.7 * i), 0.5 * (i / 10) + 0.01 * std::cos(2.3 * i),
                                 0.02 * std::sin(0.9 * i));
        node.transform = placed(0.37 * i, {1 + std::sin(double(i)), 2, 3}, at);
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(node);
    }
    return scene;
}

// The largest distance between a mesh vertex placed by the expected and by the read-back world transforms.
double largestVertexMove(const Primitive& part, const std::vector<Eigen::Matrix4d>& expected,
                         const std::vector<Eigen::Matrix4d>& got) {
    double largest = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
        for (const Eigen::Vector3d& p : part.positions)
            largest = std::max(largest, ((got[i] - expected[i]) * p.homogeneous()).head<3>().norm());
    return largest;
}

std::vector<Eigen::Matrix4d> drawingTransforms(const Scene& scene) {
    const std::vector<Eigen::Matrix4d> world = worldTransforms(scene);
    std::vector<Eigen::Matrix4d> out;
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
        if (scene.nodes[n].mesh >= 0) out.push_back(world[n]);
    return out;
}

}  // namespace

TEST_CASE("Many instances: their values through EXT_meshopt_compression, smaller, read back within the allowance",
          "[io][gpu]") {
    TemporaryFolder folder;
    const Scene scene = scatteredBlobs(400);
    for (const char* name : {"many.glb", "many.gltf"}) {
        INFO(name);
        const auto file = folder / name;
        writeScene(scene, file);
        const nlohmann::json root = std::string(name).find(".glb") != std::string::npos
                                        ? glbJson(file)
                                        : nlohmann::json::parse(readTextFile(file));
        CHECK(root["extensionsRequired"] == nlohmann::json({"EXT_mesh_gpu_instancing", "EXT_meshopt_compression",
                                                            "KHR_draco_mesh_compression"}));
        // The fallback buffer: no data, the extension's mark, as long as the views it stands for.
        REQUIRE(root["buffers"].size() == 2);
        CHECK_FALSE(root["buffers"][1].contains("uri"));
        CHECK(root["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"] == true);
        const auto batches = batchNodes(root);
        REQUIRE(batches.size() == 1);
        CHECK(instanceCount(root, *batches[0]) == 400);
        std::size_t decoded = 0, encoded = 0;
        std::set<std::string> filters;
        for (const auto& [attribute, accessor] : (*batches[0])["extensions"]["EXT_mesh_gpu_instancing"]["attributes"].items()) {
            const auto& view = root["bufferViews"][root["accessors"][accessor.get<std::size_t>()]["bufferView"].get<std::size_t>()];
            INFO(attribute);
            REQUIRE(view.contains("extensions"));
            const auto& meshopt = view["extensions"]["EXT_meshopt_compression"];
            CHECK(view["buffer"] == 1);
            CHECK(meshopt["buffer"] == 0);
            CHECK(meshopt["count"] == 400);
            decoded += view["byteLength"].get<std::size_t>();
            encoded += meshopt["byteLength"].get<std::size_t>();
            filters.insert(meshopt.value("filter", "NONE"));
        }
        // Off-grid translations through the exponential filter, turns through the quaternion filter: smaller
        // than the plain batch's float translations and SHORT rotations (20 bytes an instance).
        CHECK(filters == std::set<std::string>{"EXPONENTIAL", "QUATERNION"});
        CHECK(decoded == 400 * 20);
        CHECK(encoded < decoded * 3 / 4);

        // Read back by our reader (meshoptimizer's decoders): every vertex within the allowances together.
        const Scene back = readScene(file);
        CHECK(back.warnings.empty());
        const std::vector<Eigen::Matrix4d> expected = drawingTransforms(scene), got = drawingTransforms(back);
        REQUIRE(got.size() == expected.size());
        // The writer's diagonal: of the mesh's box placed by each instance.
        Eigen::AlignedBox3d meshBox, box;
        for (const Eigen::Vector3d& p : blob().positions) meshBox.extend(p);
        for (const Eigen::Matrix4d& world : expected)
            for (int corner = 0; corner < 8; ++corner)
                box.extend((world * meshBox.corner(Eigen::AlignedBox3d::CornerType(corner)).homogeneous()).head<3>());
        const WriteOptions defaults;
        const double allowed =
            (defaults.instanceRotationDeviation + defaults.instanceTranslationDeviation) * box.diagonal().norm();
        const double moved = largestVertexMove(blob(), expected, got);
        CHECK(moved <= allowed * 1.0001);
        CHECK(moved > 0);  // rounded, not float as it was
        if (interopAvailable()) CHECK(validatorErrors(file).empty());
    }
    // The plan's measure of the batch against the file: what batching saved, within a tenth.
    WriteOptions apart;
    apart.gpuInstancing = false;
    writeScene(scene, folder / "apart.glb", apart);
    const double saved = double(std::filesystem::file_size(folder / "apart.glb")) -
                         double(std::filesystem::file_size(folder / "many.glb"));
    const double estimated = gltfNodesBytes(scene.nodes, apart) - gltfNodesBytes(scene.nodes, WriteOptions());
    INFO("saved " << saved << ", estimated " << estimated);
    CHECK(estimated == Approx(saved).epsilon(0.1));
}

TEST_CASE("A batch far from its parent's origin takes its centre as the batch node's translation, within the allowance",
          "[io][gpu]") {
    // Found by a sweep of variants: the bolts placed 4e5 units away had float32 instance translations rounded by
    // 0.03, five times the budget (verification and the render check failed).
    Scene scene = scatteredBlobs(40);
    const Eigen::Vector3d far(235933.155897762, -188746.524718209, 251662.032957612);
    for (std::size_t n = 0; n < scene.nodes.size(); ++n) {
        scene.nodes[n].transform.topRightCorner<3, 1>() += far;
        // Mirrored in its own frame: a batch of its own, under a mirroring node.
        if (n % 2) scene.nodes[n].transform.col(0).head<3>() *= -1;
    }
    TemporaryFolder folder;
    for (const bool draco : {true, false}) {
        INFO((draco ? "Draco" : "plain"));
        WriteOptions options;
        options.draco = draco;
        writeScene(scene, folder / "far.glb", options);
        const nlohmann::json root = glbJson(folder / "far.glb");
        const auto batches = batchNodes(root);
        REQUIRE(batches.size() == 2);
        for (const auto* batch : batches) {
            REQUIRE(batch->contains("translation"));
            CHECK((Eigen::Vector3d((*batch)["translation"][0], (*batch)["translation"][1], (*batch)["translation"][2]) -
                   far)
                      .norm() < 10);
        }
        const std::vector<Eigen::Matrix4d> expected = drawingTransforms(scene),
                                           got = drawingTransforms(readScene(folder / "far.glb"));
        REQUIRE(got.size() == expected.size());
        Eigen::AlignedBox3d box;
        for (const Eigen::Matrix4d& world : expected) box.extend(world.topRightCorner<3, 1>());
        const WriteOptions defaults;
        // The allowances over the instances' box (the writer's is the drawn box's, a little larger), and float32's
        // own rounding of a translation of a few units from the batch's centre.
        const double allowed =
            (defaults.instanceRotationDeviation + defaults.instanceTranslationDeviation) * (box.diagonal().norm() + 1) +
            1e-6;
        // The batches list the plain instances, then the mirrored: each expected placement against its nearest.
        double farthest = 0;
        for (const Eigen::Matrix4d& placement : expected) {
            double nearest = std::numeric_limits<double>::infinity();
            for (const Eigen::Matrix4d& other : got)
                nearest = std::min(nearest, largestVertexMove(blob(), {placement}, {other}));
            farthest = std::max(farthest, nearest);
        }
        CHECK(farthest <= allowed);
    }
}

TEST_CASE("GPU instancing without Draco stays float and needs no meshopt, as a small batch does not", "[io][gpu]") {
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(scatteredBlobs(400), folder / "plain.glb", plain);
    const nlohmann::json root = glbJson(folder / "plain.glb");
    CHECK(root["extensionsRequired"] == nlohmann::json({"EXT_mesh_gpu_instancing"}));
    CHECK(root["buffers"].size() == 1);
    for (const auto& view : root["bufferViews"]) CHECK_FALSE(view.contains("extensions"));
    const auto batches = batchNodes(root);
    REQUIRE(batches.size() == 1);
    for (const auto& [attribute, accessor] : (*batches[0])["extensions"]["EXT_mesh_gpu_instancing"]["attributes"].items())
        CHECK(root["accessors"][accessor.get<std::size_t>()]["componentType"] == 5126);
    // Read back exactly: float32 as written.
    const Scene scene = scatteredBlobs(400), back = readScene(folder / "plain.glb");
    CHECK(largestVertexMove(blob(), drawingTransforms(scene), drawingTransforms(back)) < 1e-6);

    // With Draco but a dozen instances, meshopt's views would cost more than they save: plain accessors.
    writeScene(scatteredBlobs(12), folder / "few.glb");
    const nlohmann::json few = glbJson(folder / "few.glb");
    REQUIRE(batchNodes(few).size() == 1);
    CHECK(few["extensionsRequired"] == nlohmann::json({"EXT_mesh_gpu_instancing", "KHR_draco_mesh_compression"}));
    for (const auto& view : few["bufferViews"]) CHECK_FALSE(view.contains("extensions"));
}

TEST_CASE("gltfNodesBytes: a batch of rigid instances costs a few bytes each, as written", "[io][gpu]") {
    const Scene scene = copiesScene(40, 0, false);
    WriteOptions options;
    const double batched = gltfNodesBytes(scene.nodes, options);
    options.gpuInstancing = false;
    const double apart = gltfNodesBytes(scene.nodes, options);
    CHECK(batched < apart / 2);
    CHECK(batched / 40 < 45);  // 20 bytes of data, the name's and a share of the accessors' JSON
    // The measure against the file: the batched file is smaller than the other by about their difference.
    TemporaryFolder folder;
    writeScene(scene, folder / "batched.glb");
    writeScene(scene, folder / "apart.glb", options);
    const double saved = double(std::filesystem::file_size(folder / "apart.glb")) -
                         double(std::filesystem::file_size(folder / "batched.glb"));
    CHECK(saved == Approx(apart - batched).margin(300));
}

TEST_CASE("Compressed copies come out GPU-instanced, smaller, verified, and counted in the report",
          "[io][gpu][compress]") {
    TemporaryFolder folder;
    const auto input = folder / "copies.glb";
    WriteOptions asNodes;
    asNodes.gpuInstancing = false;
    writeScene(copiesScene(30, 6, false, blob()), input, asNodes);
    CompressOptions options;
    const CompressionReport batched = compressFile(input, folder / "batched.glb", options);
    options.write.gpuInstancing = false;
    const CompressionReport apart = compressFile(input, folder / "apart.glb", options);
    CHECK(batched.gpuInstancing.batches == 2);
    CHECK(batched.gpuInstancing.instances == 36);
    CHECK(apart.gpuInstancing.batches == 0);
    CHECK(batched.outputBytes < apart.outputBytes);
    CHECK(batched.bytesPerInstance < apart.bytesPerInstance / 2);
    CHECK(nlohmann::json::parse(batched.json())["gpu_instancing"]["instances"] == 36);
    CHECK(decompressFile(folder / "batched.glb", folder / "flat.glb", input).verified);
    if (interopAvailable()) CHECK(validatorErrors(folder / "batched.glb").empty());
    if (renderAvailable()) {
        // Mirrored instances drawn the right way out: as the same scene written a node per instance.
        checkRendersSame(folder / "apart.glb", folder / "batched.glb");
    }
}

TEST_CASE(
    "The plan prices a class's nodes as the batch they become: small parts baked many times are one stored "
    "copy and a batch, and stay as they are without the extension",
    "[io][gpu][compress]") {
    // 200 copies of a 16-triangle part turned about the vertical (grass cards, trees), each baked into a mesh of
    // its own: a node apiece (some 80 bytes of JSON) costs more than its triangles among the others (some 40), an
    // instance in a batch (some 20) less.
    TemporaryFolder folder;
    const auto input = folder / "baked.glb";
    writeScene(bakedCopies(cutTetrahedron(), 200), input);
    CompressOptions options;
    const CompressionReport batched = compressFile(input, folder / "batched.glb", options);
    CHECK(batched.gpuInstancing.instances == 200);
    CHECK(batched.stats.trianglesStored == 16);
    CHECK(decompressFile(folder / "batched.glb", folder / "flat.glb", input).verified);
    options.write.gpuInstancing = false;
    const CompressionReport apart = compressFile(input, folder / "apart.glb", options);
    CHECK(apart.gpuInstancing.batches == 0);
    CHECK(apart.stats.trianglesStored == 3200);
    CHECK(batched.outputBytes < apart.outputBytes);
}

TEST_CASE(
    "Copies whose names alone make sharing cost more than storing them as they are (which loses the names "
    "too) are shared without their names, with a warning, and names that fit are kept",
    "[io][gpu][compress]") {
    TemporaryFolder folder;
    const auto names = [&](const std::filesystem::path& file) {
        const nlohmann::json root = glbJson(file);
        std::size_t count = 0;
        for (const nlohmann::json* batch : batchNodes(root))
            if (batch->contains("extras")) count += (*batch)["extras"]["instanceNames"].size();
        return count;
    };
    SECTION("a 16-triangle part with long names: shared, its names dropped") {
        writeScene(bakedCopies(cutTetrahedron(), 200, "a tuft of grass, card number "), folder / "named.glb");
        const CompressionReport report = compressFile(folder / "named.glb", folder / "out.glb");
        CHECK(report.gpuInstancing.instances == 200);
        CHECK(names(folder / "out.glb") == 0);
        CHECK(std::any_of(report.warnings.begin(), report.warnings.end(), [](const std::string& warning) {
            return warning.find("200 node names") != std::string::npos;
        }));
        CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", folder / "named.glb").verified);
    }
    SECTION("a 352-triangle part: shared with its names") {
        writeScene(bakedCopies(blob(), 20, "part "), folder / "named.glb");
        const CompressionReport report = compressFile(folder / "named.glb", folder / "out.glb");
        CHECK(report.gpuInstancing.instances == 20);
        CHECK(names(folder / "out.glb") == 20);
    }
}

TEST_CASE("Instances that share one name store it once, and every instance reads back with it", "[io][gpu][compress]") {
    // A lathe's 256 sectors, each a copy of its region named after the one node: 256 copies of the name were 1.8 KB
    // of its 6 KB.
    TemporaryFolder folder;
    Scene scene = bakedCopies(blob(), 20);
    for (Node& node : scene.nodes) node.name = "fitting";
    writeScene(scene, folder / "named.glb");
    const CompressionReport report = compressFile(folder / "named.glb", folder / "out.glb");
    REQUIRE(report.gpuInstancing.instances == 20);
    const nlohmann::json root = glbJson(folder / "out.glb");
    const auto batches = batchNodes(root);
    REQUIRE(batches.size() == 1);
    CHECK((*batches.front())["extras"]["instanceNames"] == "fitting");
    const Scene back = readScene(folder / "out.glb");
    std::size_t named = 0;
    for (const Node& node : back.nodes) named += node.mesh >= 0 && node.name == "fitting";
    CHECK(named == 20);
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", folder / "named.glb").verified);
}
