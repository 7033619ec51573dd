// Symmetries of assemblies from the constructive algorithm (paper 6.3), against groups known by
// construction and against the single-shape detector run on the whole assembly; repeated assemblies.
#include "sample_scenes.hpp"
#include "symcompress/assembly.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "test_support.hpp"

#include <cmath>
#include <random>
#include <set>

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
        const SymmetryGroup assembly = assemblySymmetries(classification);
        CHECK(assembly.name == c.group);
        CHECK(assembly.order() == c.order);
        const SymmetryGroup whole = detectSymmetries(worldMesh(c.scene));
        CHECK(whole.name == assembly.name);
        CHECK(whole.order() == assembly.order());
    }
}

TEST_CASE("The sterile room: the constructive group equals the whole-shape group", "[assembly][models]") {
    const Scene scene = readScene(symcompress::testing::modelPath("cge_sterile_room/sterile_room.gltf"));
    const SymmetryGroup assembly = assemblySymmetries(classify(scene));
    const SymmetryGroup whole = detectSymmetries(worldMesh(scene));
    CHECK(assembly.name == whole.name);
    CHECK(assembly.order() == whole.order());
}

TEST_CASE("Repeated assemblies: the room's bookshelves, tables and chairs, each copy the placement of the first",
          "[assembly]") {
    const auto soup = flattenScene(samples::makeRoomScene());
    const auto tiles = splitIntoTiles(soup);
    const TileClassification classification = classifyTiles(tiles);
    const std::vector<RepeatedAssembly> assemblies = findRepeatedAssemblies(tiles, classification);
    std::multiset<std::pair<std::size_t, std::size_t>> found;  // (copies, tiles per copy)
    for (const RepeatedAssembly& a : assemblies) found.emplace(a.copies.size(), a.copies[0].size());
    CHECK(found.count({4, 188}) == 1);  // bookshelves: 2 sides, 6 boards, 180 books
    CHECK(found.count({4, 5}) == 1);    // tables: top and 4 legs (the chairs stand apart)
    CHECK(found.count({16, 6}) == 1);   // chairs: seat, 4 legs, back
    CHECK(found.size() == 3);           // floor and walls belong to none: mirrors take them onto themselves

    // Brute force: every vertex of a tile of copy 0, placed, is a vertex of the corresponding tile.
    std::set<std::size_t> seen;
    const double distance = 1e-5 * classification.sceneDiagonal;
    for (const RepeatedAssembly& a : assemblies)
        for (std::size_t j = 0; j < a.copies.size(); ++j) {
            REQUIRE(a.copies[j].size() == a.copies[0].size());
            for (std::size_t i = 0; i < a.copies[j].size(); ++i) {
                CHECK(seen.insert(a.copies[j][i]).second);
                const TriangleMesh& from = tiles[a.copies[0][i]].mesh;
                const TriangleMesh& to = tiles[a.copies[j][i]].mesh;
                double worst = 0;
                for (const auto& p : from.positions) {
                    const Eigen::Vector3d placed = a.placements[j].linear * p + a.placements[j].translation;
                    double nearest = std::numeric_limits<double>::infinity();
                    for (const auto& q : to.positions) nearest = std::min(nearest, (q - placed).norm());
                    worst = std::max(worst, nearest);
                }
                CHECK(worst <= distance);
            }
        }
}

TEST_CASE("Repeated assemblies: the copies that spare the most tiles, not only those that reach every one",
          "[assembly]") {
    // Five groups of six random convex parts in a ring; the last four have a seventh part. Copies of seven
    // tiles: 4 x 7, which spare 21 tiles; of the six the five share: 5 x 6, which spare 24.
    std::mt19937_64 random(11);
    std::vector<TriangleMesh> parts;
    for (int k = 0; k < 7; ++k) parts.push_back(samples::randomConvexPart(random));
    samples::OneMeshBuilder builder("groups");
    const int material = builder.addMaterial("grey", {0.6, 0.6, 0.6, 1});
    for (int copy = 0; copy < 5; ++copy) {
        const Eigen::Matrix3d turn = samples::randomRotation(random);
        const Eigen::Vector3d at(15.0 * copy, 4.0 * copy, 0);
        for (int k = 0; k < (copy > 0 ? 7 : 6); ++k) {
            const double angle = k * M_PI / 3.5;
            builder.add(material,
                        samples::transformed(parts[std::size_t(k)], turn,
                                             turn * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0) + at));
        }
    }
    const auto soup = flattenScene(std::move(builder).build());
    const auto tiles = splitIntoTiles(soup);
    REQUIRE(tiles.size() == 4 * 7 + 6);
    const std::vector<RepeatedAssembly> assemblies = findRepeatedAssemblies(tiles, classifyTiles(tiles));
    REQUIRE(assemblies.size() == 1);
    CHECK(assemblies[0].copies.size() == 5);
    CHECK(assemblies[0].copies[0].size() == 6);
}
