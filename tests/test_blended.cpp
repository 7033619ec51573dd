// Blended primitives stay the objects the input drew: viewers sort blended objects back to front, each as a
// whole, and draw an object's triangles in their order without writing depth (three.js with depthWrite off,
// X_ITE), so merging, cutting or batching them changes what is drawn. Each is one tile (splitIntoTiles'
// wholePrimitiveMaterials), instanced by a node of its own or stored by a mesh and node of its own; never in a GPU
// batch, a join, a fundamental region or an assembly.
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/tiles.hpp"
#include "symcompress/verify.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <set>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// A tetrahedron with each face cut in four and its new corners pushed out unevenly: 16 triangles, no symmetry.
Primitive lumpyTetrahedron() {
    Primitive part;
    part.positions = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.2, 0}, {0, 0, 0.3}};
    const std::vector<Triangle> faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middleOf;
    auto middle = [&](std::uint32_t a, std::uint32_t b) {
        const auto [at, added] = middleOf.emplace(std::minmax(a, b), std::uint32_t(part.positions.size()));
        if (added)
            part.positions.push_back((part.positions[a] + part.positions[b]) / 2 * (1.1 + 0.03 * double(a + 2 * b)));
        return at->second;
    };
    for (const Triangle& t : faces) {
        const std::uint32_t m0 = middle(t[0], t[1]), m1 = middle(t[1], t[2]), m2 = middle(t[2], t[0]);
        part.triangles.insert(part.triangles.end(), {{m0, m1, m2}, {t[0], m0, m2}, {t[1], m1, m0}, {t[2], m2, m1}});
    }
    return part;
}

Eigen::Matrix4d turnedAt(double angle, const Eigen::Vector3d& at) {
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    t.translate(at);
    t.rotate(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
    return t.matrix();
}

Material translucent(Material::AlphaMode mode) {
    Material material;
    material.baseColorFactor = {0.9, 0.4, 0.1, 0.5};
    material.alphaMode = mode;
    material.doubleSided = true;
    return material;
}

// `copies` of the part turned about the vertical and overlapping on screen (grass cards, leaves), each baked
// into a mesh of its own drawn by a root node, in one translucent material.
Scene bakedCards(int copies, Material::AlphaMode mode) {
    Scene scene;
    scene.materials.push_back(translucent(mode));
    for (int i = 0; i < copies; ++i) {
        Primitive part =
            transformPrimitive(lumpyTetrahedron(), turnedAt(0.7 * i, {0.12 * (i % 10), 0.12 * (i / 10), 0}));
        part.material = 0;
        scene.meshes.push_back({"", {part}, "", {}});
        Node node;
        node.mesh = i;
        scene.roots.push_back(i);
        scene.nodes.push_back(node);
    }
    return scene;
}

std::size_t batches(const nlohmann::json& root) {
    std::size_t count = 0;
    for (const auto& node : root["nodes"])
        count += node.contains("extensions") && node["extensions"].contains("EXT_mesh_gpu_instancing");
    return count;
}

}  // namespace

TEST_CASE("A blended primitive is one tile, connected or not, and shares none with another", "[tiles]") {
    // Two copies of the part apart in one primitive, and a third primitive touching the first copy.
    Primitive two = lumpyTetrahedron();
    appendPrimitive(two, transformPrimitive(lumpyTetrahedron(), turnedAt(0, {1, 0, 0})));
    std::vector<WorldPrimitive> soup = {{two, 0, 0}, {lumpyTetrahedron(), 1, 1}};
    for (bool blended : {false, true}) {
        INFO((blended ? "blended" : "opaque"));
        TileOptions options;
        options.wholePrimitiveMaterials = {blended};
        for (WorldPrimitive& world : soup) world.primitive.material = 0;
        const std::vector<Tile> tiles = splitIntoTiles(soup, options);
        REQUIRE(tiles.size() == 2);
        CHECK(tiles[0].mesh.triangles.size() == 32);
        CHECK(tiles[1].mesh.triangles.size() == 16);
        // Blended: each primitive whole (its two copies apart in one tile). Opaque: each copy a tile, the third
        // primitive, on the first copy, welded into its tile.
        std::set<std::size_t> firstTileFrom;
        for (const TriangleSource& source : tiles[0].sources) firstTileFrom.insert(source.primitive);
        CHECK(firstTileFrom == (blended ? std::set<std::size_t>{0} : std::set<std::size_t>{0, 1}));
    }
}

TEST_CASE("Blended copies are instanced by nodes of their own, never batched, and draw as the input does",
          "[compress][gpu]") {
    TemporaryFolder folder;
    for (const auto mode : {Material::AlphaMode::Opaque, Material::AlphaMode::Blend}) {
        const bool blended = mode == Material::AlphaMode::Blend;
        INFO((blended ? "blended" : "opaque"));
        const auto input = folder / (blended ? "blended.glb" : "opaque.glb");
        const auto output = folder / (blended ? "blended_out.glb" : "opaque_out.glb");
        WriteOptions plain;
        plain.draco = false;
        writeScene(bakedCards(60, mode), input, plain);
        const CompressionReport report = compressFile(input, output);
        const nlohmann::json root = glbJson(output);
        // One stored copy either way: drawn by a batch where it may be, else by a node per copy.
        CHECK(report.stats.trianglesStored == 16);
        CHECK(batches(root) == (blended ? 0u : 1u));
        if (blended) CHECK(root["nodes"].size() == 60);
        CHECK(decompressFile(output, folder / "flat.glb", input).verified);
        // Overlapping translucent parts: three.js sorts nodes, not the instances of a batch.
        if (blended && renderAvailable()) checkRendersSame(input, output);
    }
}

TEST_CASE("A blended primitive of several parts is stored whole, by one node, not as instances of its parts",
          "[compress]") {
    TemporaryFolder folder;
    Scene scene = bakedCards(1, Material::AlphaMode::Blend);
    for (int i = 1; i < 8; ++i) {
        Primitive part = transformPrimitive(lumpyTetrahedron(), turnedAt(0.9 * i, {0.15 * i, 0.05 * i, 0}));
        part.material = 0;  // appendPrimitive takes the part's
        appendPrimitive(scene.meshes[0].primitives[0], part);
    }
    const auto input = folder / "one.glb";
    writeScene(scene, input);
    const CompressionReport report = compressFile(input, folder / "out.glb");
    CHECK(report.stats.trianglesStored == 8 * 16);
    CHECK(report.stats.instances == 0);
    const Scene out = readScene(folder / "out.glb");
    CHECK(out.meshes.size() == 1);
    CHECK(out.meshes[0].primitives.size() == 1);
    // Double-sided, its triangles drawn over each other in their order: kept through Draco (sequential coding).
    const std::vector<WorldPrimitive> before = flattenScene(readScene(input)), after = flattenScene(out);
    REQUIRE(after.size() == 1);
    const Primitive &a = before[0].primitive, &b = after[0].primitive;
    REQUIRE(b.triangles.size() == a.triangles.size());
    double farthest = 0;
    for (std::size_t t = 0; t < a.triangles.size(); ++t)
        for (int corner = 0; corner < 3; ++corner)
            farthest =
                std::max(farthest, (a.positions[a.triangles[t][corner]] - b.positions[b.triangles[t][corner]]).norm());
    CHECK(farthest < 1e-3);
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", input).verified);
    if (renderAvailable()) checkRendersSame(input, folder / "out.glb");
}

TEST_CASE("A blended symmetric part is drawn whole, not as copies of its fundamental region", "[compress][region]") {
    TemporaryFolder folder;
    Scene scene = readScene(modelPath("vulkan_geosphere/geosphere.gltf"));
    for (Material& material : scene.materials) {
        material.alphaMode = Material::AlphaMode::Blend;
        material.baseColorFactor[3] = 0.6;
    }
    const auto input = folder / "blended.glb";
    WriteOptions plain;
    plain.draco = false;
    writeScene(scene, input, plain);
    const CompressionReport report = compressFile(input, folder / "out.glb");
    CHECK(report.stats.regionClasses == 0);
    CHECK(report.stats.trianglesStored == report.stats.trianglesIn);
    CHECK(decompressFile(folder / "out.glb", folder / "flat.glb", input).verified);
    if (renderAvailable()) checkRendersSame(input, folder / "out.glb");
}

TEST_CASE("The grass's blended flower cards draw as X3D draws them: each card sorted as the input's",
          "[compress][models][gpu]") {
    // 731 cards over an RGBA texture (X3D's AUTO alpha mode blends them): batched, three.js drew them in the batch's
    // order, and 1.9% of the object pixels of view a differed from the input's.
    TemporaryFolder folder;
    const auto input = modelPath("cge_grass_flowers/grass_flowers.x3d");
    const auto reference = folder / "reference.glb", output = folder / "out.glb";
    WriteOptions plain;
    plain.draco = false;
    writeScene(readScene(input), reference, plain);
    const CompressionReport report = compressFile(input, output);
    CHECK(report.gpuInstancing.batches == 0);
    CHECK(report.stats.instances == 731);
    if (renderAvailable()) checkRendersSame(reference, output);
}
