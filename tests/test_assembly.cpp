// Symmetries of assemblies from the constructive algorithm (paper 6.3), against groups known by
// construction and against the single-shape detector run on the whole assembly.
#include "sample_scenes.hpp"
#include "symcompress/assembly.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

using namespace symcompress;

namespace {

TileClassification classify(const Scene& scene) { return classifyTiles(splitIntoTiles(flattenScene(scene))); }

}  // namespace

TEST_CASE("Assemblies with known groups: the constructive algorithm and the whole-shape detector agree",
          "[assembly]") {
    struct Case {
        const char* name;
        Scene scene;
        std::size_t tiles, classes;
        const char* group;
        int order;
    };
    const std::vector<Case> cases{
        {"pliers (paper 6.4)", samples::makePliersScene(), 2, 1, "C2", 2},
        {"three spheres (paper Fig. 8)", samples::makeThreeSpheresScene(), 3, 1, "D3h", 12},
        {"7-fold lamp (paper Fig. 11)", samples::makeLampScene(), 8, 2, "C7v", 14},
        {"chess board with one 2-fold axis (paper Fig. 11)", samples::makeChessScene(), 70, 4, "C2", 2},
        {"icosahedral assembly (paper Fig. 10)", samples::makeIcosahedralScene(), 60, 1, "Ih", 120},
        {"room", samples::makeRoomScene(), samples::kRoomTiles, samples::kRoomClasses, "C2v", 4},
        {"bolts baked at random placements", samples::makeBoltsScene(), 12, 1, "C1", 1},
    };
    for (const auto& c : cases) {
        INFO(c.name);
        const TileClassification classification = classify(c.scene);
        CHECK(classification.shapes.size() == c.tiles);
        CHECK(classification.classes.size() == c.classes);
        const SymmetryGroup assembly = assemblySymmetries(classification, 1e-5);
        CHECK(assembly.name == c.group);
        CHECK(assembly.order() == c.order);
        const SymmetryGroup whole = detectSymmetries(worldMesh(c.scene));
        CHECK(whole.name == assembly.name);
        CHECK(whole.order() == assembly.order());
    }
}

TEST_CASE("The sterile room: the constructive group equals the whole-shape group", "[assembly][models]") {
    const Scene scene = readScene(symcompress::testing::modelPath("cge_sterile_room/sterile_room.gltf"));
    const SymmetryGroup assembly = assemblySymmetries(classify(scene), 1e-5);
    const SymmetryGroup whole = detectSymmetries(worldMesh(scene));
    CHECK(assembly.name == whole.name);
    CHECK(assembly.order() == whole.order());
}
