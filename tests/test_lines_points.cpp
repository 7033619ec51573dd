// Lines and points: read from glTF, OBJ and PLY, kept as they are through the compressor (not tiled), written to
// glTF with their modes, and verified by symdecompress (in number, and within the budget of each other).
#include "symcompress/compress.hpp"
#include "symcompress/detail/solids.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

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
    // Segments as they were (the writer keeps each line primitive's vertices in their order).
    for (const Mesh& mesh : written.meshes)
        for (const Primitive& line : mesh.primitives)
            if (line.topology == Topology::Lines && line.colors.size() == 4)
                CHECK(segmentSet(line) == segmentSet(original.meshes[0].primitives[1]));
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
            Eigen::Quaterniond(
                Eigen::Vector4d(normal(random), normal(random), normal(random), normal(random)).normalized())
                .toRotationMatrix();
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
