// Symmetries of assemblies from the constructive algorithm (paper 6.3), against groups known by
// construction and against the single-shape detector run on the whole assembly.
#include "sample_scenes.hpp"
#include "symcompress/assembly.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

using namespace symcompress;

namespace {

SymmetryGroup constructive(const Scene& scene) {
    const auto soup = flattenScene(scene);
    const auto tiles = splitIntoTiles(soup);
    return assemblySymmetries(classifyTiles(tiles), 1e-5);
}

}  // namespace

TEST_CASE("Assemblies with known groups: the constructive algorithm and the whole-shape detector agree",
          "[assembly]") {
    struct Case {
        const char* name;
        Scene scene;
        const char* group;
        int order;
    };
    const std::vector<Case> cases{
        {"three spheres (paper Fig. 8)", samples::makeThreeSpheresScene(), "D3h", 12},
        {"7-fold lamp (paper Fig. 11)", samples::makeLampScene(), "C7v", 14},
        {"bolts baked at random placements", samples::makeBoltsScene(), "C1", 1},
    };
    for (const auto& c : cases) {
        INFO(c.name);
        const SymmetryGroup assembly = constructive(c.scene);
        CHECK(assembly.name == c.group);
        CHECK(assembly.order() == c.order);
        const SymmetryGroup whole = detectSymmetries(worldMesh(c.scene));
        CHECK(whole.name == assembly.name);
        CHECK(whole.order() == assembly.order());
    }
}

TEST_CASE("The sterile room: the constructive group equals the whole-shape group", "[assembly][models]") {
    const Scene scene = readScene(symcompress::testing::modelPath("cge_sterile_room/sterile_room.gltf"));
    const SymmetryGroup assembly = constructive(scene);
    const SymmetryGroup whole = detectSymmetries(worldMesh(scene));
    CHECK(assembly.name == whole.name);
    CHECK(assembly.order() == whole.order());
}
