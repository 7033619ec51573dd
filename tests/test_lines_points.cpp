// Lines and points: read from glTF, OBJ and PLY, kept as they are through the compressor (not tiled), written to
// glTF with their modes, and verified by symdecompress (in number, and within the budget of each other).
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/detail/solids.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <meshoptimizer.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <random>
#include <set>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// A glTF file (its buffer in drawing.bin, written into `folder`) of one node drawing: a quad of two triangles, a line
// strip of 4 vertices with colours, a line loop of 3, indexed LINES of a square, 200 points of a random cloud, and
// indexed POINTS naming vertex 2 twice and vertex 0 once.
std::string linesAndPointsGltf(const TemporaryFolder& folder) {
    std::vector<float> floats;
    std::vector<std::uint16_t> shorts;
    auto put = [&](std::initializer_list<float> values) { floats.insert(floats.end(), values); };
    put({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});              // quad, offset 0
    put({0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1});              // strip, 48
    put({1, 0, 0, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 1, 1, 1});  // its colours, 96
    put({0, 0, 2, 1, 0, 2, 1, 1, 2});                       // loop, 160
    std::mt19937 random(7);
    std::uniform_real_distribution<float> unit(0, 1);
    for (int i = 0; i < 600; ++i) floats.push_back(unit(random));     // cloud, 196
    shorts = {0, 1, 2, 0, 2, 3, 0, 1, 1, 2, 2, 3, 3, 0, 2, 2, 0, 0};  // quad, square lines, points (+ padding)
    std::string bytes(reinterpret_cast<const char*>(floats.data()), floats.size() * 4);
    const std::size_t indexOffset = bytes.size();
    bytes.append(reinterpret_cast<const char*>(shorts.data()), shorts.size() * 2);
    writeTextFile(folder / "drawing.bin", bytes);
    nlohmann::json gltf = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"buffers", {{{"byteLength", bytes.size()}, {"uri", "drawing.bin"}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", indexOffset}},
          {{"buffer", 0}, {"byteOffset", indexOffset}, {"byteLength", shorts.size() * 2}}}},
    };
    auto accessor = [&](std::size_t view, std::size_t offset, int type, std::size_t count, const char* shape) {
        gltf["accessors"].push_back(
            {{"bufferView", view}, {"byteOffset", offset}, {"componentType", type}, {"count", count}, {"type", shape}});
        return gltf["accessors"].size() - 1;
    };
    const auto quad = accessor(0, 0, 5126, 4, "VEC3"), strip = accessor(0, 48, 5126, 4, "VEC3"),
               colours = accessor(0, 96, 5126, 4, "VEC4"), loop = accessor(0, 160, 5126, 3, "VEC3"),
               cloud = accessor(0, 196, 5126, 200, "VEC3"), quadIndices = accessor(1, 0, 5123, 6, "SCALAR"),
               squareIndices = accessor(1, 12, 5123, 8, "SCALAR"), pointIndices = accessor(1, 28, 5123, 3, "SCALAR");
    for (std::size_t a : {quad, strip, loop, cloud}) {
        Eigen::AlignedBox3d box;
        for (std::size_t v = 0; v < gltf["accessors"][a]["count"].get<std::size_t>(); ++v)
            box.extend(Eigen::Vector3d(floats[gltf["accessors"][a]["byteOffset"].get<std::size_t>() / 4 + 3 * v],
                                       floats[gltf["accessors"][a]["byteOffset"].get<std::size_t>() / 4 + 3 * v + 1],
                                       floats[gltf["accessors"][a]["byteOffset"].get<std::size_t>() / 4 + 3 * v + 2]));
        gltf["accessors"][a]["min"] = {box.min().x(), box.min().y(), box.min().z()};
        gltf["accessors"][a]["max"] = {box.max().x(), box.max().y(), box.max().z()};
    }
    gltf["meshes"] = {{{"primitives",
                        {{{"attributes", {{"POSITION", quad}}}, {"indices", quadIndices}},
                         {{"attributes", {{"POSITION", strip}, {"COLOR_0", colours}}}, {"mode", 3}},
                         {{"attributes", {{"POSITION", loop}}}, {"mode", 2}},
                         {{"attributes", {{"POSITION", quad}}}, {"indices", squareIndices}, {"mode", 1}},
                         {{"attributes", {{"POSITION", cloud}}}, {"mode", 0}},
                         {{"attributes", {{"POSITION", quad}}}, {"indices", pointIndices}, {"mode", 0}}}}}};
    return gltf.dump();
}

std::set<std::pair<std::uint32_t, std::uint32_t>> segmentSet(const Primitive& primitive) {
    std::set<std::pair<std::uint32_t, std::uint32_t>> out;
    for (const Segment& s : primitive.lines) out.insert({std::min(s[0], s[1]), std::max(s[0], s[1])});
    return out;
}

// The glTF component type of the POSITION of each primitive of `json`'s meshes of mode `mode`.
std::vector<int> positionTypes(const nlohmann::json& json, int mode) {
    std::vector<int> types;
    for (const auto& mesh : json["meshes"])
        for (const auto& primitive : mesh["primitives"])
            if (primitive.value("mode", 4) == mode)
                types.push_back(
                    json["accessors"][primitive["attributes"]["POSITION"].get<std::size_t>()]["componentType"]);
    return types;
}

// How many points, segments and triangles the scene's meshes hold.
std::array<std::size_t, 3> drawnCounts(const Scene& scene) {
    std::array<std::size_t, 3> counts{0, 0, 0};
    for (const Mesh& mesh : scene.meshes)
        for (const Primitive& p : mesh.primitives) {
            if (p.topology == Topology::Points) counts[0] += p.positions.size();
            counts[1] += p.lines.size();
            counts[2] += p.triangles.size();
        }
    return counts;
}

}  // namespace

TEST_CASE("Lines and points: glTF's modes read as segments and points", "[io][lines]") {
    TemporaryFolder folder;
    const auto input = folder / "drawing.gltf";
    writeTextFile(input, linesAndPointsGltf(folder));
    const Scene scene = readScene(input);
    REQUIRE(scene.meshes.size() == 1);
    const std::vector<Primitive>& p = scene.meshes[0].primitives;
    REQUIRE(p.size() == 6);
    CHECK(p[0].topology == Topology::Triangles);
    CHECK(p[0].triangles.size() == 2);
    CHECK(p[1].topology == Topology::Lines);
    CHECK(p[1].lines == std::vector<Segment>{{0, 1}, {1, 2}, {2, 3}});  // the strip
    REQUIRE(p[1].colors.size() == 4);
    CHECK(p[1].colors[1].isApprox(Eigen::Vector4d(0, 1, 0, 1)));
    CHECK(p[2].lines == std::vector<Segment>{{0, 1}, {1, 2}, {2, 0}});  // the loop closed
    CHECK(p[3].lines == std::vector<Segment>{{0, 1}, {1, 2}, {2, 3}, {3, 0}});
    CHECK(p[4].topology == Topology::Points);
    CHECK(p[4].positions.size() == 200);
    // Indexed points: the vertices in the indices' order.
    REQUIRE(p[5].positions.size() == 3);
    CHECK(p[5].positions[0] == Eigen::Vector3d(1, 1, 0));
    CHECK(p[5].positions[1] == Eigen::Vector3d(1, 1, 0));
    CHECK(p[5].positions[2] == Eigen::Vector3d(0, 0, 0));
    CHECK(std::none_of(scene.warnings.begin(), scene.warnings.end(),
                       [](const std::string& w) { return w.find("skipped") != std::string::npos; }));
}

TEST_CASE("Lines and points: kept through the compressor, written with their modes and verified", "[compress][lines]") {
    TemporaryFolder folder;
    const auto input = folder / "drawing.gltf", output = folder / "drawing.glb", flat = folder / "flat.glb";
    writeTextFile(input, linesAndPointsGltf(folder));
    const nlohmann::json report = nlohmann::json::parse(compressFile(input, output, {}).json());
    CHECK(report["line_segments_kept"] == 10);
    CHECK(report["points_kept"] == 203);
    const nlohmann::json json = glbJson(output);
    std::multiset<int> modes;
    for (const auto& mesh : json["meshes"])
        for (const auto& primitive : mesh["primitives"]) modes.insert(primitive.value("mode", 4));
    CHECK(modes == std::multiset<int>{0, 0, 1, 1, 1, 4});
    if (interopAvailable()) CHECK(validatorErrors(output).empty());

    const Scene original = readScene(input), written = readScene(output);
    CHECK(drawnCounts(written) == drawnCounts(original));
    // Segments as they were, each vertex written taken for the original one nearest it (the writer puts the
    // vertices in spatial order).
    const Primitive& strip = original.meshes[0].primitives[1];
    for (const Mesh& mesh : written.meshes)
        for (const Primitive& line : mesh.primitives)
            if (line.topology == Topology::Lines && line.colors.size() == 4) {
                Primitive renumbered = line;
                for (Segment& segment : renumbered.lines)
                    for (std::uint32_t& v : segment) {
                        const auto nearest = std::min_element(
                            strip.positions.begin(), strip.positions.end(), [&](const auto& a, const auto& b) {
                                return (a - line.positions[v]).norm() < (b - line.positions[v]).norm();
                            });
                        v = std::uint32_t(nearest - strip.positions.begin());
                    }
                CHECK(segmentSet(renumbered) == segmentSet(strip));
            }
    const RebuildReport verified = decompressFile(output, flat, input);
    CHECK(verified.verified);
    CHECK(verified.maxDeviation <= 5e-5);
    CHECK(decompressFile(output, flat).verified);  // against the digest, whose bounds hold the points
    if (renderAvailable()) {
        // The lines and points drawn in their material's colour, without vertex colours (the renderer's
        // interpolation of colours along a line steps coarsely: a tiny move flips a pixel between two steps).
        nlohmann::json plain = nlohmann::json::parse(linesAndPointsGltf(folder));
        plain["meshes"][0]["primitives"][1]["attributes"].erase("COLOR_0");
        const auto uncoloured = folder / "uncoloured.gltf", out = folder / "uncoloured.glb";
        writeTextFile(uncoloured, plain.dump());
        // Within a fifth of the default budget: a thin line's pixels flip between neighbours where it passes
        // near their border, so that a move far below a pixel (verified above) still changes a share of them.
        CompressOptions fine;
        fine.maxError = 1e-5;
        compressFile(uncoloured, out, fine);
        checkRendersSame(uncoloured, out);
    }
}

TEST_CASE("Lines and points: a point moved beyond the budget or missing is not verified", "[compress][lines]") {
    TemporaryFolder folder;
    const auto input = folder / "drawing.gltf", output = folder / "drawing.glb", flat = folder / "flat.glb";
    writeTextFile(input, linesAndPointsGltf(folder));
    compressFile(input, output, {});
    Scene moved = readScene(input);
    Primitive& cloud = moved.meshes[0].primitives[4];
    WriteOptions plain;
    plain.draco = false;
    const auto movedFile = folder / "moved.glb", fewerFile = folder / "fewer.glb";
    cloud.positions[17] += Eigen::Vector3d(1e-3, 0, 0);  // 3e-4 of the diagonal
    writeScene(moved, movedFile, plain);
    CHECK_FALSE(decompressFile(output, flat, movedFile).verified);
    cloud.positions[17] -= Eigen::Vector3d(1e-3, 0, 0);
    cloud.positions.pop_back();
    writeScene(moved, fewerFile, plain);
    CHECK_FALSE(decompressFile(output, flat, fewerFile).verified);
}

TEST_CASE("Lines and points: OBJ l and p elements, a vertex-only OBJ or PLY is a point cloud", "[io][lines]") {
    TemporaryFolder folder;
    writeTextFile(folder / "drawing.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nl 1 2 3 4 1\np 2 4\n");
    const Scene obj = readScene(folder / "drawing.obj");
    REQUIRE(obj.meshes.size() == 1);
    std::array<std::size_t, 3> counts = drawnCounts(obj);
    CHECK(counts == std::array<std::size_t, 3>{2, 4, 1});
    for (const Primitive& p : obj.meshes[0].primitives)
        if (p.topology == Topology::Lines) {
            REQUIRE(p.lines.size() == 4);
            CHECK(p.positions[p.lines[3][1]] == Eigen::Vector3d(0, 0, 0));  // the polyline back to its start
        }

    writeTextFile(folder / "cloud.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 2 0 0 0 1\n");
    const Scene cloudObj = readScene(folder / "cloud.obj");
    REQUIRE(cloudObj.meshes.size() == 1);
    REQUIRE(cloudObj.meshes[0].primitives.size() == 1);
    const Primitive& objPoints = cloudObj.meshes[0].primitives[0];
    CHECK(objPoints.topology == Topology::Points);
    CHECK(objPoints.positions.size() == 3);
    CHECK(objPoints.colors.size() == 3);

    writeTextFile(folder / "cloud.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "end_header\n0 0 0\n1 0 0\n0 0 3\n");
    const Scene ply = readScene(folder / "cloud.ply");
    REQUIRE(ply.meshes[0].primitives.size() == 1);
    CHECK(ply.meshes[0].primitives[0].topology == Topology::Points);
    CHECK(ply.meshes[0].primitives[0].positions.size() == 3);

    // Compressed, the cloud keeps its three points, within the budget of the cloud's diagonal.
    const auto out = folder / "cloud.glb", flat = folder / "cloud-flat.glb";
    compressFile(folder / "cloud.ply", out, {});
    const Scene written = readScene(out);
    CHECK(drawnCounts(written) == std::array<std::size_t, 3>{3, 0, 0});
    CHECK(decompressFile(out, flat, folder / "cloud.ply").verified);
    // Three points: a grid of integers would add more JSON than it saves (float32 through meshopt's filter).
    CHECK(positionTypes(glbJson(out), 0) == std::vector<int>{5126});
}

TEST_CASE("Lines and points: OBJ output writes l and p, PLY output a point cloud or a warning", "[io][lines]") {
    TemporaryFolder folder;
    Primitive lines;
    lines.topology = Topology::Lines;
    lines.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    lines.lines = {{0, 1}, {1, 2}};
    Primitive points;
    points.topology = Topology::Points;
    points.positions = {{0, 0, 5}, {0, 1, 5}};
    Scene scene = sceneOfOneMesh("drawing", lines);
    scene.meshes[0].primitives.push_back(points);
    writeScene(scene, folder / "drawing.obj", {});
    const Scene obj = readScene(folder / "drawing.obj");
    CHECK(drawnCounts(obj) == std::array<std::size_t, 3>{2, 2, 0});

    CHECK(formatLosses(scene, folder / "drawing.ply").size() == 1);
    const Scene cloud = sceneOfOneMesh("cloud", points);
    CHECK(formatLosses(cloud, folder / "cloud.ply").empty());
    writeScene(cloud, folder / "cloud.ply", {});
    const Scene ply = readScene(folder / "cloud.ply");
    REQUIRE(ply.meshes[0].primitives.size() == 1);
    CHECK(ply.meshes[0].primitives[0].topology == Topology::Points);
    CHECK(ply.meshes[0].primitives[0].positions == points.positions);
}

TEST_CASE("Lines and points: a line mesh drawn by many nodes is no GPU batch (three.js instances triangles only)",
          "[compress][lines]") {
    TemporaryFolder folder;
    Primitive lines;
    lines.topology = Topology::Lines;
    lines.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}};
    lines.lines = {{0, 1}, {1, 2}};
    Scene scene = sceneOfOneMesh("edges", lines);
    for (int k = 1; k < 40; ++k) {
        Node copy = scene.nodes[0];
        copy.transform(0, 3) = 2.0 * k;
        scene.roots.push_back(int(scene.nodes.size()));
        scene.nodes.push_back(copy);
    }
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "edges.glb", plain);
    compressFile(folder / "edges.glb", folder / "out.glb", {});
    const nlohmann::json json = glbJson(folder / "out.glb");
    CHECK_FALSE(json.value("extensionsUsed", nlohmann::json::array()).dump().find("EXT_mesh_gpu_instancing") !=
                std::string::npos);
    std::size_t drawing = 0;
    for (const auto& node : json["nodes"]) drawing += node.contains("mesh");
    CHECK(drawing == 40);
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", folder / "edges.glb").verified);
}

TEST_CASE("Lines and points: a part's edges kept apart, its faces still found congruent and instanced",
          "[compress][lines]") {
    // A 24-sided prism with its edges in one mesh (as CAD exports draw a part), baked 12 times in random placements.
    const Polyhedron prism = makePrism(24, 1.5);
    const TriangleMesh faces = triangulateFaces(prism);
    Primitive surface, edges;
    surface.positions = edges.positions = faces.positions;
    surface.triangles = faces.triangles;
    edges.topology = Topology::Lines;
    for (const auto& face : prism.faces)
        for (std::size_t k = 0; k < face.size(); ++k)
            if (face[k] < face[(k + 1) % face.size()]) edges.lines.push_back({face[k], face[(k + 1) % face.size()]});
    std::mt19937 random(3);
    std::normal_distribution<double> normal;
    Scene scene;
    for (int copy = 0; copy < 12; ++copy) {
        Eigen::Matrix4d placement = Eigen::Matrix4d::Identity();
        placement.topLeftCorner<3, 3>() =
            Eigen::Quaterniond(samples::drawnVector4([&] { return normal(random); }).normalized()).toRotationMatrix();
        placement.topRightCorner<3, 1>() = Eigen::Vector3d(4.0 * copy, 0, 0);
        Mesh& mesh = scene.meshes.emplace_back();
        mesh.primitives = {transformPrimitive(surface, placement), transformPrimitive(edges, placement)};
        Node node;
        node.mesh = copy;
        scene.roots.push_back(copy);
        scene.nodes.push_back(node);
    }
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "parts.glb", plain);
    const nlohmann::json report =
        nlohmann::json::parse(compressFile(folder / "parts.glb", folder / "out.glb", {}).json());
    INFO(report.dump());
    CHECK(report["instanced_classes"] == 1);
    CHECK(report["instances"].get<int>() >= 12);
    CHECK(report["line_segments_kept"] == 12 * 72);
    CHECK(drawnCounts(readScene(folder / "out.glb"))[1] == 12 * 72);
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", folder / "parts.glb").verified);
}

namespace {

// `primitive` alone in a GLB without Draco (an input), its mesh named after the file.
void writeInput(const Primitive& primitive, const std::filesystem::path& file) {
    WriteOptions plain;
    plain.draco = false;
    writeScene(sceneOfOneMesh(file.stem().string(), primitive), file, plain);
}

// `count` random points in a box of side 2 centred at (10, 20, 30), as a scanner leaves them: away from the origin,
// in no order.
Primitive randomCloud(std::size_t count) {
    Primitive cloud;
    cloud.topology = Topology::Points;
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (std::size_t i = 0; i < count; ++i)
        cloud.positions.push_back(Eigen::Vector3d(10, 20, 30) + samples::drawnVector([&] { return unit(random); }));
    return cloud;
}

}  // namespace

TEST_CASE("Lines and points: positions on a grid of integers within the budget, undone by the node",
          "[compress][lines]") {
    TemporaryFolder folder;
    writeInput(randomCloud(3000), folder / "cloud.glb");
    const auto out = folder / "out.glb", flat = folder / "flat.glb";
    // Default budget: 16 bits a coordinate (the cloud's side over a step of some 1e-4 of its diagonal).
    compressFile(folder / "cloud.glb", out, {});
    nlohmann::json json = glbJson(out);
    CHECK(positionTypes(json, 0) == std::vector<int>{5123});
    CHECK(json["extensionsRequired"].dump().find("KHR_mesh_quantization") != std::string::npos);
    const RebuildReport verified = decompressFile(out, flat, folder / "cloud.glb");
    CHECK(verified.verified);
    CHECK(verified.maxDeviation > 1e-5);  // the grid uses the budget
    if (interopAvailable()) CHECK(validatorErrors(out).empty());
    // A coarse budget: 8 bits.
    CompressOptions coarse;
    coarse.maxError = 4e-3;
    compressFile(folder / "cloud.glb", out, coarse);
    CHECK(positionTypes(glbJson(out), 0) == std::vector<int>{5121});
    CHECK(decompressFile(out, flat, folder / "cloud.glb").verified);
    if (interopAvailable()) CHECK(validatorErrors(out).empty());
    // Finer than 16 bits can hold: float32 through meshopt's filter.
    CompressOptions fine;
    fine.maxError = 2e-6;
    compressFile(folder / "cloud.glb", out, fine);
    json = glbJson(out);
    CHECK(positionTypes(json, 0) == std::vector<int>{5126});
    CHECK(json["extensionsRequired"].dump().find("KHR_mesh_quantization") == std::string::npos);
    CHECK(decompressFile(out, flat, folder / "cloud.glb").verified);
}

TEST_CASE("Lines and points: the grid is undone in a child where the node has children or is animated",
          "[compress][lines]") {
    // Node 0 draws the cloud and has node 1, a cube, for a child; node 2 draws the cloud and is moved by an animation.
    Scene scene = sceneOfOneMesh("cloud", randomCloud(3000));
    const TriangleMesh cube = triangulateFaces(makeCube());
    Primitive box;
    box.positions = cube.positions;
    box.triangles = cube.triangles;
    scene.meshes.push_back({"box", {box}, "", {}});
    Node child, animated;
    child.mesh = 1;
    child.transform(0, 3) = 5;
    animated.mesh = 0;
    scene.nodes[0].children = {1};
    scene.nodes.push_back(child);
    scene.nodes.push_back(animated);
    scene.roots.push_back(2);
    Animation animation;
    AnimationChannel& channel = animation.channels.emplace_back();
    channel.node = 2;
    channel.path = AnimationChannel::Path::Translation;
    channel.times = {0, 1};
    channel.values = {0, 0, 0, 0, 3, 0};
    scene.animations.push_back(animation);
    validateScene(scene);
    TemporaryFolder folder;
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, folder / "scene.glb", plain);
    const auto out = folder / "out.glb";
    compressFile(folder / "scene.glb", out, {});
    const nlohmann::json json = glbJson(out);
    CHECK(positionTypes(json, 0) == std::vector<int>{5123});
    // The node with children and the animated node keep their transforms; the nodes that draw the cloud have none.
    std::size_t drawingCloud = 0;
    for (const auto& node : json["nodes"]) {
        const bool drawsCloud =
            node.contains("mesh") &&
            !positionTypes(
                 {{"meshes", {json["meshes"][node["mesh"].get<std::size_t>()]}}, {"accessors", json["accessors"]}}, 0)
                 .empty();
        drawingCloud += drawsCloud;
        if (node.contains("children") || !drawsCloud) CHECK_FALSE(node.contains("scale"));
        if (drawsCloud) CHECK_FALSE(node.contains("children"));
    }
    CHECK(drawingCloud == 2);
    CHECK(json["animations"][0]["channels"][0]["target"]["path"] == "translation");
    const std::size_t target = json["animations"][0]["channels"][0]["target"]["node"];
    CHECK_FALSE(json["nodes"][target].contains("scale"));
    CHECK(json["nodes"][target].contains("children"));
    CHECK(decompressFile(out, folder / "flat.glb", folder / "scene.glb").verified);
}

TEST_CASE("Lines and points: a wireframe's indices coded by meshopt, in spatial order", "[compress][lines]") {
    // The edges of a 60 x 60 latitude-longitude grid on a sphere (7140 segments), in an exporter's scattered order.
    Primitive wires;
    wires.topology = Topology::Lines;
    constexpr int kSide = 60;
    for (int i = 0; i < kSide; ++i)
        for (int j = 0; j < kSide; ++j) {
            const double theta = M_PI * (i + 0.5) / kSide, phi = 2 * M_PI * j / kSide;
            wires.positions.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                         std::cos(theta));
            const auto at = [&](int a, int b) { return std::uint32_t(a * kSide + (b % kSide)); };
            wires.lines.push_back({at(i, j), at(i, j + 1)});
            if (i + 1 < kSide) wires.lines.push_back({at(i, j), at(i + 1, j)});
        }
    std::shuffle(wires.lines.begin(), wires.lines.end(), std::mt19937(5));
    TemporaryFolder folder;
    writeInput(wires, folder / "wires.glb");
    const auto out = folder / "out.glb";
    compressFile(folder / "wires.glb", out, {});
    const nlohmann::json json = glbJson(out);
    const auto& primitive = json["meshes"][0]["primitives"][0];
    auto codedView = [&](const nlohmann::json& accessor) {
        const std::size_t view = json["accessors"][accessor.get<std::size_t>()]["bufferView"];
        return json["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
    };
    const nlohmann::json indices = codedView(primitive["indices"]),
                         positions = codedView(primitive["attributes"]["POSITION"]);
    CHECK(indices["mode"] == "INDICES");
    CHECK(positions["mode"] == "ATTRIBUTES");
    // Smaller than the same codec makes of the indices as read: its differences from the index before stay small.
    std::vector<std::uint32_t> asRead;
    for (const Segment& segment : wires.lines) asRead.insert(asRead.end(), segment.begin(), segment.end());
    std::vector<unsigned char> coded(meshopt_encodeIndexSequenceBound(asRead.size(), wires.positions.size()));
    coded.resize(meshopt_encodeIndexSequence(coded.data(), coded.size(), asRead.data(), asRead.size()));
    INFO("indices as read " << coded.size() << " bytes");
    CHECK(indices["byteLength"].get<std::size_t>() < coded.size() * 3 / 4);
    const Scene written = readScene(out);
    CHECK(drawnCounts(written)[1] == wires.lines.size());
    CHECK(decompressFile(out, folder / "flat.glb", folder / "wires.glb").verified);
    if (interopAvailable()) CHECK(validatorErrors(out).empty());
    if (renderAvailable()) {
        // Within a tenth of the default budget: at the default, these lines moved by 0.03 pixels flip 3.6% of their
        // pixels between neighbours, though drawn alike (looked at), 0.7% at a fifth; every pixel of a thin line is
        // an edge's.
        CompressOptions fine;
        fine.maxError = 5e-6;
        compressFile(folder / "wires.glb", out, fine);
        checkRendersSame(folder / "wires.glb", out);
    }
}

TEST_CASE(
    "Lines and points: colours as normalized bytes, normals through the octahedral filter, within their allowance",
    "[compress][lines]") {
    Primitive cloud = randomCloud(2000);
    std::mt19937 random(13);
    std::uniform_real_distribution<double> unit(0, 1);
    std::normal_distribution<double> normal;
    for (std::size_t v = 0; v < cloud.positions.size(); ++v) {
        const Eigen::Vector3d rgb = samples::drawnVector([&] { return unit(random); });
        cloud.colors.emplace_back(rgb.x(), rgb.y(), rgb.z(), 1);
        cloud.normals.push_back(samples::drawnVector([&] { return normal(random); }).normalized());
    }
    TemporaryFolder folder;
    writeInput(cloud, folder / "cloud.glb");
    const auto out = folder / "out.glb";
    compressFile(folder / "cloud.glb", out, {});
    const nlohmann::json json = glbJson(out);
    const auto& attributes = json["meshes"][0]["primitives"][0]["attributes"];
    const auto& colours = json["accessors"][attributes["COLOR_0"].get<std::size_t>()];
    const auto& normals = json["accessors"][attributes["NORMAL"].get<std::size_t>()];
    CHECK(colours["componentType"] == 5121);
    CHECK(colours["normalized"] == true);
    CHECK(normals["normalized"] == true);
    CHECK(json["bufferViews"][normals["bufferView"].get<std::size_t>()]["extensions"]["EXT_meshopt_compression"]
              ["filter"] == "OCTAHEDRAL");
    if (interopAvailable()) CHECK(validatorErrors(out).empty());
    // Each point's colour within half a step of 8 bits, its normal within 2^-10 (Draco's allowances at their default
    // bits), matched to the original by position (the points are reordered).
    const Scene written = readScene(out);
    const std::vector<Eigen::Vector3d>& positions = cloud.positions;
    const std::vector<Eigen::Matrix4d> world = worldTransforms(written);
    for (std::size_t n = 0; n < written.nodes.size(); ++n) {
        if (written.nodes[n].mesh < 0) continue;
        const Primitive& read = written.meshes[std::size_t(written.nodes[n].mesh)].primitives[0];
        REQUIRE(read.positions.size() == cloud.positions.size());
        double colourError = 0, normalError = 0;
        for (std::size_t v = 0; v < read.positions.size(); ++v) {
            const Eigen::Vector3d at = (world[n] * read.positions[v].homogeneous()).head<3>();
            const auto nearest = std::min_element(
                positions.begin(), positions.end(),
                [&](const auto& a, const auto& b) { return (a - at).squaredNorm() < (b - at).squaredNorm(); });
            const std::size_t original = std::size_t(nearest - positions.begin());
            colourError = std::max(colourError, (read.colors[v] - cloud.colors[original]).cwiseAbs().maxCoeff());
            normalError = std::max(normalError, (read.normals[v] - cloud.normals[original]).norm());
        }
        CHECK(colourError <= 0.5 / 255 + 1e-7);
        CHECK(normalError <= std::ldexp(1.0, -10));
    }
    CHECK(decompressFile(out, folder / "flat.glb", folder / "cloud.glb").verified);
}
