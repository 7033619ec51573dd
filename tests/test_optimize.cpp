// Pruning and deduplication before tiling: each acts where it must and not where it must not; what a
// viewer draws (every material's fields but names, every primitive's texture) stays the same.
#include "sample_scenes.hpp"
#include "symcompress/compress.hpp"
#include "symcompress/io.hpp"
#include "symcompress/optimize.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

// One triangle per material index, side by side.
Scene sceneOfMaterials(const std::vector<Material>& materials, const std::vector<int>& drawn) {
    Scene scene;
    scene.materials = materials;
    Mesh mesh;
    for (std::size_t i = 0; i < drawn.size(); ++i) {
        Primitive triangle;
        triangle.positions = {{double(i), 0, 0}, {double(i) + 1, 0, 0}, {double(i), 1, 0}};
        triangle.triangles = {{0, 1, 2}};
        triangle.material = drawn[i];
        mesh.primitives.push_back(triangle);
    }
    scene.meshes.push_back(mesh);
    scene.nodes.push_back({});
    scene.nodes[0].mesh = 0;
    scene.roots = {0};
    return scene;
}

Material named(const std::string& name, double red) {
    Material material;
    material.name = name;
    material.baseColorFactor = {red, 0.5, 0.5, 1};
    return material;
}

}  // namespace

TEST_CASE("Materials equal but for their names are merged into the first (its name kept) and one factor apart stay two",
          "[optimize]") {
    Scene scene = sceneOfMaterials({named("a", 0.2), named("b", 0.2), named("c", 0.3)}, {0, 1, 2});
    const OptimizeReport report = optimizeScene(scene);
    CHECK(report.materialsMerged == 1);
    CHECK(report.materialsRemoved == 1);
    REQUIRE(scene.materials.size() == 2);
    CHECK(scene.materials[0].name == "a");
    CHECK(scene.materials[1].name == "c");  // baseColorFactor 0.3 against 0.2: not merged
    const auto& primitives = scene.meshes[0].primitives;
    CHECK(primitives[0].material == 0);
    CHECK(primitives[1].material == 0);
    CHECK(primitives[2].material == 1);
    validateScene(scene);

    Scene kept = sceneOfMaterials({named("a", 0.2), named("b", 0.2)}, {0, 1});
    OptimizeOptions noDedup;
    noDedup.dedup = false;
    CHECK(optimizeScene(kept, noDedup).materialsMerged == 0);
    CHECK(kept.materials.size() == 2);
}

TEST_CASE("Textures of the same image are merged and different images stay apart", "[optimize]") {
    Scene scene =
        sceneOfMaterials({named("a", 1), named("b", 1), named("c", 1), named("d", 1), named("e", 1)}, {0, 1, 2, 3, 4});
    scene.textures.resize(5);
    scene.textures[0].bytes = scene.textures[1].bytes = {1, 2, 3};  // the same image twice
    scene.textures[2].bytes = {1, 2, 4};
    scene.textures[3].uri = scene.textures[4].uri = "missing.png";  // not read, the same reference
    for (int m = 0; m < 5; ++m) scene.materials[std::size_t(m)].baseColorTexture.texture = m;
    scene.textures[0].mimeType = scene.textures[1].mimeType = scene.textures[2].mimeType = "image/png";
    const OptimizeReport report = optimizeScene(scene);
    CHECK(report.texturesMerged == 2);
    // Materials b and e become equal to a and d (the same image now): merged too.
    CHECK(report.materialsMerged == 2);
    CHECK(scene.textures.size() == 3);
    CHECK(scene.materials.size() == 3);
    validateScene(scene);
}

TEST_CASE("Materials no primitive uses and textures no material uses are removed and every index remapped",
          "[optimize]") {
    Scene scene = sceneOfMaterials({named("unused", 0.1), named("used", 0.2), named("also unused", 0.3)}, {1, -1});
    scene.textures.resize(2);
    scene.textures[1].bytes = {7};
    scene.materials[1].baseColorTexture.texture = 1;
    scene.materials[2].baseColorTexture.texture = 0;
    const OptimizeReport report = optimizeScene(scene);
    CHECK(report.materialsRemoved == 2);
    CHECK(report.texturesRemoved == 1);
    REQUIRE(scene.materials.size() == 1);
    CHECK(scene.materials[0].name == "used");
    CHECK(scene.materials[0].baseColorTexture.texture == 0);
    CHECK(scene.textures[0].bytes == std::vector<std::uint8_t>{7});
    CHECK(scene.meshes[0].primitives[0].material == 0);
    CHECK(scene.meshes[0].primitives[1].material == -1);
    validateScene(scene);

    Scene kept = sceneOfMaterials({named("unused", 0.1), named("used", 0.2)}, {1});
    OptimizeOptions noPrune;
    noPrune.prune = false;
    CHECK(optimizeScene(kept, noPrune).materialsRemoved == 0);
    CHECK(kept.materials.size() == 2);
}

TEST_CASE(
    "symcompress merges duplicate materials before tiling: one primitive where there were two, and the report says so",
    "[optimize][compress]") {
    // Two boxes apart, each of its own material; the materials differ only by their names.
    TemporaryFolder folder;
    Primitive boxes;
    samples::appendMesh(boxes, samples::boxMesh(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3)));
    Primitive second = boxes;
    for (auto& p : second.positions) p += Eigen::Vector3d(5, 0, 0);
    Scene scene = samples::singleMeshScene("boxes", boxes, {0.5, 0.5, 0.5, 1});
    scene.materials.push_back(scene.materials[0]);
    scene.materials[1].name = "copy of the first";
    second.material = 1;
    scene.meshes[0].primitives.push_back(second);
    WriteOptions plain;
    plain.draco = false;
    const auto input = folder / "boxes.glb";
    writeScene(scene, input, plain);

    const CompressionReport merged = compressFile(input, folder / "merged.glb");
    CHECK(merged.optimizations.materialsMerged == 1);
    const Scene out = readScene(folder / "merged.glb");
    REQUIRE(out.materials.size() == 1);
    Material expected = scene.materials[0];
    CHECK(out.materials[0].baseColorFactor.isApprox(expected.baseColorFactor, 1e-6));
    CHECK(nlohmann::json::parse(merged.json())["optimizations"]["materials_merged"] == 1);

    CompressOptions noDedup;
    noDedup.optimize.dedup = false;
    const CompressionReport apart = compressFile(input, folder / "apart.glb", noDedup);
    CHECK(apart.optimizations.materialsMerged == 0);
    CHECK(readScene(folder / "apart.glb").materials.size() == 2);
    CHECK(merged.outputBytes < apart.outputBytes);
}
