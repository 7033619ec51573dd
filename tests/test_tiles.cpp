#include "sample_scenes.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/tiles.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace symcompress;

namespace {

// An unwelded box: every triangle has its own three vertices, as in an STL soup.
Primitive soupBox(const Eigen::Vector3d& origin, double size, int material = 0) {
    static const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    auto corner = [&](int k) -> Eigen::Vector3d { return origin + size * Eigen::Vector3d(k & 1, (k >> 1) & 1, (k >> 2) & 1); };
    Primitive box;
    box.material = material;
    for (const auto& face : faces)
        for (const auto& triangle : {std::array<int, 3>{face[0], face[1], face[2]}, {face[0], face[2], face[3]}}) {
            const auto base = static_cast<std::uint32_t>(box.positions.size());
            for (int k : triangle) box.positions.push_back(corner(k));
            box.triangles.push_back({base, base + 1, base + 2});
        }
    return box;
}

std::vector<WorldPrimitive> soupOf(std::vector<Primitive> primitives) {
    std::vector<WorldPrimitive> soup;
    for (Primitive& primitive : primitives) soup.push_back({std::move(primitive), 0, 0});
    return soup;
}

}  // namespace

TEST_CASE("weldPositions merges points within the tolerance only", "[tiles]") {
    const std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {1e-7, 0, 0}, {1, 0, 0}, {1, 2e-6, 0}, {0, 0, 0}};
    const auto welded = weldPositions(points, 1e-6);
    CHECK(welded == std::vector<std::uint32_t>{0, 0, 2, 3, 0});
    CHECK(weldPositions(points, 0) == std::vector<std::uint32_t>{0, 1, 2, 3, 0});
}

TEST_CASE("weldPositions agrees with brute force on random clusters", "[tiles]") {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-5, 5), jitter(-1e-4, 1e-4);
    std::vector<Eigen::Vector3d> points;
    for (int cluster = 0; cluster < 200; ++cluster) {
        const Eigen::Vector3d centre = samples::drawnVector([&] { return coordinate(random); });
        for (int k = 0; k < 4; ++k) points.push_back(centre + samples::drawnVector([&] { return jitter(random); }));
    }
    const double tolerance = 1e-3;  // clusters are far apart and tight: each must become one vertex
    const auto welded = weldPositions(points, tolerance);
    for (std::size_t i = 0; i < points.size(); ++i) {
        CHECK(welded[i] == i / 4 * 4);
        CHECK((points[welded[i]] - points[i]).norm() <= tolerance);
    }
}

TEST_CASE("splitIntoTiles finds edge-connected parts of a soup", "[tiles]") {
    SECTION("two separate boxes and one touching at a corner only") {
        auto soup = soupOf({soupBox({0, 0, 0}, 1), soupBox({3, 0, 0}, 1), soupBox({1, 1, 1}, 1)});
        const auto tiles = splitIntoTiles(soup);
        // The third box touches the first at the single point (1,1,1): no shared edge, so a tile of its own.
        REQUIRE(tiles.size() == 3);
        for (const Tile& tile : tiles) {
            CHECK(tile.mesh.triangles.size() == 12);
            CHECK(tile.mesh.positions.size() == 8);  // welded
        }
        CHECK(tiles[1].sources.front().primitive == 1);
    }
    SECTION("boxes sharing a face edge are one tile") {
        auto soup = soupOf({soupBox({0, 0, 0}, 1), soupBox({1, 0, 0}, 1)});
        CHECK(splitIntoTiles(soup).size() == 1);
    }
    SECTION("materials split a connected surface") {
        auto soup = soupOf({soupBox({0, 0, 0}, 1, 0), soupBox({1, 0, 0}, 1, 1)});
        const auto tiles = splitIntoTiles(soup);
        REQUIRE(tiles.size() == 2);
        CHECK(tiles[0].material == 0);
        CHECK(tiles[1].material == 1);
    }
    SECTION("gaps below the weld tolerance are closed, larger ones are not") {
        // Two boxes sharing a face, the second moved by 1e-9: one tile after welding, two without.
        auto soup = soupOf({soupBox({0, 0, 0}, 1), soupBox({1 + 1e-9, 0, 0}, 1)});
        CHECK(splitIntoTiles(soup).size() == 1);
        TileOptions exact;
        exact.weldTolerance = 0;
        CHECK(splitIntoTiles(soup, exact).size() == 2);
    }
    SECTION("an empty soup has no tiles") { CHECK(splitIntoTiles({}).empty()); }
}

TEST_CASE("tilePrimitive gives back the tile's own vertices and attributes", "[tiles]") {
    Primitive box = soupBox({0, 0, 0}, 1);
    for (const Eigen::Vector3d& p : box.positions) box.texcoords.push_back(p.head<2>());
    auto soup = soupOf({soupBox({5, 0, 0}, 1), box});
    const auto tiles = splitIntoTiles(soup);
    REQUIRE(tiles.size() == 2);
    const Primitive second = tilePrimitive(tiles[1], soup);
    CHECK(second.triangles.size() == 12);
    CHECK(second.positions.size() == 36);  // the soup's vertices are not shared: nothing to merge
    REQUIRE(second.texcoords.size() == 36);
    for (std::size_t v = 0; v < 36; ++v) CHECK(second.texcoords[v] == second.positions[v].head<2>());
    CHECK(tilePrimitive(tiles[0], soup).texcoords.empty());
}
