// Fundamental regions of whole triangles (docs/fundamental-regions.md, "Whole triangles"): one triangle of each
// orbit, so that the copies draw the tile's own triangles. Ground truth from tessellations whose symmetries are
// known by construction: a geodesic sphere and its icosahedral group built from the icosahedron's vertices, a
// cube cut into the triangles of its mirrors, and the same cube fanned from random points.
#include "sample_scenes.hpp"
#include "signed_permutation_groups.hpp"
#include "test_support.hpp"

#include "symcompress/compress.hpp"
#include "symcompress/detail/fundamental_region.hpp"
#include "symcompress/detail/solids.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"
#include "symcompress/symmetry.hpp"
#include "symcompress/verify.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <stdexcept>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

Primitive primitiveOf(const TriangleMesh& mesh) {
    Primitive primitive;
    primitive.positions = mesh.positions;
    primitive.triangles = mesh.triangles;
    return primitive;
}

// The icosahedron's faces split in four `levels` times, every vertex pushed onto the unit sphere.
Primitive geodesicSphere(int levels) {
    Primitive sphere = primitiveOf(triangulateFaces(makeIcosahedron()));
    for (Eigen::Vector3d& p : sphere.positions) p.normalize();
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middles;
        auto middle = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto found = middles.find(key);
            if (found != middles.end()) return found->second;
            const auto index = static_cast<std::uint32_t>(sphere.positions.size());
            sphere.positions.push_back((sphere.positions[a] + sphere.positions[b]).normalized());
            middles.emplace(key, index);
            return index;
        };
        std::vector<Triangle> finer;
        for (const Triangle& t : sphere.triangles) {
            const std::uint32_t ab = middle(t[0], t[1]), bc = middle(t[1], t[2]), ca = middle(t[2], t[0]);
            finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
        }
        sphere.triangles = std::move(finer);
    }
    return sphere;
}

// The 120 orthogonal maps of the icosahedron onto itself: the one taking a vertex and a neighbour to any vertex
// and neighbour, with or without a mirror.
std::vector<Eigen::Matrix3d> icosahedralGroup() {
    const Polyhedron icosahedron = makeIcosahedron();
    std::vector<Eigen::Vector3d> vertices;
    for (const Eigen::Vector3d& v : icosahedron.vertices) vertices.push_back(v.normalized());
    const double edge = [&] {
        double shortest = 10;
        for (std::size_t j = 1; j < vertices.size(); ++j)
            shortest = std::min(shortest, (vertices[j] - vertices[0]).norm());
        return shortest;
    }();
    auto neighbours = [&](std::size_t a, std::size_t b) {
        return std::abs((vertices[a] - vertices[b]).norm() - edge) < 1e-9;
    };
    std::size_t first = 1;
    while (!neighbours(0, first)) ++first;
    auto frame = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, double handedness) {
        Eigen::Matrix3d m;
        m << a, b, handedness * a.cross(b);
        return m;
    };
    const Eigen::Matrix3d from = frame(vertices[0], vertices[first], 1);
    std::vector<Eigen::Matrix3d> group;
    for (std::size_t a = 0; a < vertices.size(); ++a)
        for (std::size_t b = 0; b < vertices.size(); ++b)
            if (a != b && neighbours(a, b))
                for (double handedness : {1.0, -1.0})
                    group.push_back(frame(vertices[a], vertices[b], handedness) * from.inverse());
    std::stable_partition(group.begin(), group.end(),
                          [](const Eigen::Matrix3d& g) { return g.isApprox(Eigen::Matrix3d::Identity(), 1e-12); });
    return group;
}

// The triangle's corners as a sorted list of points, rounded far below any distance between vertices.
using CornerSet = std::array<std::array<long long, 3>, 3>;
CornerSet cornerSet(const std::array<Eigen::Vector3d, 3>& corners) {
    CornerSet set;
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) set[i][k] = std::llround(corners[i][k] * 1e7);
    std::sort(set.begin(), set.end());
    return set;
}
std::array<Eigen::Vector3d, 3> cornersOf(const Primitive& primitive, const Triangle& t) {
    return {primitive.positions[t[0]], primitive.positions[t[1]], primitive.positions[t[2]]};
}

// The elements (besides the identity) that map some triangle of the tile onto itself, by brute force.
std::vector<char> fixesATriangle(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group) {
    std::set<CornerSet> triangles;
    for (const Triangle& t : tile.triangles) triangles.insert(cornerSet(cornersOf(tile, t)));
    std::vector<char> fixes(group.size(), 0);
    for (std::size_t e = 1; e < group.size(); ++e)
        for (const Triangle& t : tile.triangles) {
            std::array<Eigen::Vector3d, 3> image = cornersOf(tile, t);
            for (Eigen::Vector3d& p : image) p = group[e] * p;
            if (cornerSet(image) == cornerSet(cornersOf(tile, t))) fixes[e] = 1;
        }
    return fixes;
}

// Every copy draws a triangle of the tile, facing as it does, and together they draw each one once.
void checkDrawsTheTilesTriangles(const Primitive& tile, const FundamentalRegion& region) {
    std::map<CornerSet, Eigen::Vector3d> normals;  // of the tile's triangles
    for (const Triangle& t : tile.triangles) {
        const auto c = cornersOf(tile, t);
        normals[cornerSet(c)] = (c[1] - c[0]).cross(c[2] - c[0]);
    }
    const Primitive rebuilt = rebuildFromRegion(region);
    REQUIRE(rebuilt.triangles.size() == tile.triangles.size());
    std::set<CornerSet> drawn;
    for (const Triangle& t : rebuilt.triangles) {
        const auto c = cornersOf(rebuilt, t);
        const auto found = normals.find(cornerSet(c));
        REQUIRE(found != normals.end());
        CHECK(found->second.dot((c[1] - c[0]).cross(c[2] - c[0])) > 0);
        drawn.insert(found->first);
    }
    CHECK(drawn.size() == tile.triangles.size());
}

double distanceToNearest(const Eigen::Vector3d& p, const std::vector<Eigen::Vector3d>& points) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& q : points) nearest = std::min(nearest, (q - p).norm());
    return nearest;
}

Eigen::Matrix3d randomRotation(std::uint64_t seed) {
    std::mt19937_64 generator(seed);
    return samples::randomRotation(generator);
}

// A cube cut by its 9 mirror planes into 48 triangles, each split in four: Oh maps the triangles onto one
// another and fixes none.
Primitive kaleidoscopeCube() {
    Primitive cube;
    auto add = [&](const Eigen::Vector3d& p) {
        cube.positions.push_back(p);
        return static_cast<std::uint32_t>(cube.positions.size() - 1);
    };
    for (int axis = 0; axis < 3; ++axis)
        for (double side : {-1.0, 1.0}) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            Eigen::Vector3d centre = Eigen::Vector3d::Zero();
            centre[axis] = side;
            for (int quarter = 0; quarter < 4; ++quarter)
                for (int half = 0; half < 2; ++half) {
                    // Triangle (face centre, corner, edge middle) of the face's quarter.
                    const double su = quarter & 1 ? 1 : -1, sv = quarter & 2 ? 1 : -1;
                    Eigen::Vector3d corner = centre, middle = centre;
                    corner[u] = su, corner[v] = sv;
                    (half ? middle[u] : middle[v]) = half ? su : sv;
                    std::array<Eigen::Vector3d, 3> t{centre, corner, middle};
                    // Outward: counter-clockwise seen from outside.
                    if ((t[1] - t[0]).cross(t[2] - t[0]).dot(centre) < 0) std::swap(t[1], t[2]);
                    const std::array<Eigen::Vector3d, 3> m{(t[0] + t[1]) / 2, (t[1] + t[2]) / 2, (t[2] + t[0]) / 2};
                    for (const auto& small : {std::array<Eigen::Vector3d, 3>{t[0], m[0], m[2]},
                                              std::array<Eigen::Vector3d, 3>{m[0], t[1], m[1]},
                                              std::array<Eigen::Vector3d, 3>{m[2], m[1], t[2]},
                                              std::array<Eigen::Vector3d, 3>{m[0], m[1], m[2]}})
                        cube.triangles.push_back({add(small[0]), add(small[1]), add(small[2])});
                }
        }
    // Shared corners, as a welded mesh has them.
    const std::vector<std::uint32_t> welded = weldPositions(cube.positions, 1e-12);
    for (Triangle& t : cube.triangles)
        for (std::uint32_t& corner : t) corner = welded[corner];
    return cube;
}

// The geodesic sphere with each (flat) face fanned from a random point inside it: symmetric as a surface (Ih), not
// as a tessellation.
Primitive randomlyFannedGeodesicSphere(int levels, std::uint64_t seed) {
    const Primitive sphere = geodesicSphere(levels);
    std::mt19937_64 generator(seed);
    std::uniform_real_distribution<double> weight(0.2, 1.0);
    Primitive fanned;
    fanned.positions = sphere.positions;
    for (const Triangle& t : sphere.triangles) {
        const double a = weight(generator), b = weight(generator), c = weight(generator);
        const auto inner = static_cast<std::uint32_t>(fanned.positions.size());
        fanned.positions.push_back(
            (a * sphere.positions[t[0]] + b * sphere.positions[t[1]] + c * sphere.positions[t[2]]) / (a + b + c));
        for (int k = 0; k < 3; ++k) fanned.triangles.push_back({inner, t[k], t[(k + 1) % 3]});
    }
    return fanned;
}

}  // namespace

TEST_CASE("A geodesic sphere keeps its triangles whole under every subgroup of Ih that fixes none of them",
          "[region]") {
    const Primitive sphere = geodesicSphere(2);
    REQUIRE(sphere.triangles.size() == 320);
    const std::vector<Eigen::Matrix3d> ih = icosahedralGroup();
    REQUIRE(ih.size() == 120);
    REQUIRE(pointGroupName(ih) == "Ih");
    const std::vector<char> fixes = fixesATriangle(sphere, ih);
    // The 3-fold axes through the faces' middle triangles, and the mirrors through rows of triangles.
    CHECK(std::count(fixes.begin(), fixes.end(), 1) == 20 + 15);

    RegionOptions options;
    options.triangles = RegionTriangles::OneOfEachOrbit;
    CHECK_THROWS_AS(computeFundamentalRegion(sphere, ih, Eigen::Vector3d::Zero(), options), std::invalid_argument);
    options.triangles = RegionTriangles::Whole;  // its planes cut triangles too
    CHECK_THROWS_AS(computeFundamentalRegion(sphere, ih, Eigen::Vector3d::Zero(), options), std::invalid_argument);
    options.triangles = RegionTriangles::WholeWherePossible;
    const FundamentalRegion cut = computeFundamentalRegion(sphere, ih, Eigen::Vector3d::Zero(), options);
    CHECK(!cut.wholeTriangles);
    CHECK(cut.trianglesCut > 0);

    std::set<std::string> whole;
    for (const std::vector<std::size_t>& h : subgroupsOf(ih, 1e-9)) {
        std::vector<Eigen::Matrix3d> subgroup;
        bool free = true;
        for (std::size_t e : h) subgroup.push_back(ih[e]), free = free && !fixes[e];
        for (RegionFrame frame : {RegionFrame::Tile, RegionFrame::Aligned}) {
            options.triangles = RegionTriangles::OneOfEachOrbit;
            options.frame = frame;
            INFO(pointGroupName(subgroup) << " of order " << h.size());
            if (!free) {
                CHECK_THROWS_AS(computeFundamentalRegion(sphere, subgroup, Eigen::Vector3d::Zero(), options),
                                std::invalid_argument);
                continue;
            }
            const FundamentalRegion region =
                computeFundamentalRegion(sphere, subgroup, Eigen::Vector3d::Zero(), options);
            CHECK(region.wholeTriangles);
            CHECK(region.trianglesCut == 0);
            CHECK(region.region.triangles.size() * h.size() == sphere.triangles.size());
            checkDrawsTheTilesTriangles(sphere, region);
            whole.insert(pointGroupName(subgroup));
        }
    }
    // The largest: D5 (the rotations about a vertex and the 2-fold axes across it) and S10.
    CHECK(whole.count("D5") == 1);
    CHECK(whole.count("S10") == 1);
    CHECK(whole.count("D5d") == 0);
}

TEST_CASE(
    "Copies of a region of whole triangles meet vertex for vertex after quantization, the tile's float noise "
    "made symmetric",
    "[region]") {
    // The cube turned and its vertices moved by up to 1e-7 of its size (float32 rounding): the orbits are found
    // within the vertex tolerance, and the region's vertices are made symmetric, so that on the seam-preserving
    // grid every copy's seam vertex lands on its neighbour's. Unsymmetrized, steps finer than the noise (28 bits) split
    // them.
    const Primitive exact = kaleidoscopeCube();
    REQUIRE(exact.triangles.size() == 192);
    const Eigen::Matrix3d turn = randomRotation(17);
    const Eigen::Vector3d centre(0.3, -2.0, 1.1);
    std::mt19937_64 generator(3);
    std::uniform_real_distribution<double> noise(-1e-7, 1e-7);
    Primitive tile = exact;
    for (Eigen::Vector3d& p : tile.positions)
        p = centre + turn * p + samples::drawnVector([&] { return noise(generator); });
    std::vector<Eigen::Matrix3d> group;
    for (const Eigen::Matrix3d& g : groupOh()) group.push_back(turn * g * turn.transpose());

    RegionOptions options;
    options.frame = RegionFrame::Aligned;
    options.triangles = RegionTriangles::Whole;
    const FundamentalRegion region = computeFundamentalRegion(tile, group, centre, options);
    CHECK(region.wholeTriangles);
    CHECK(region.signedPermutationFrame);
    CHECK(region.region.triangles.size() == 4);

    const RegionInGridSteps onGrid = inGridSteps(region, seamPreservingGrid(region, 28));
    const Eigen::Matrix3d linear = onGrid.region.regionToTile.topLeftCorner<3, 3>();
    std::set<std::array<double, 3>> drawn;  // every copy's quantized vertices, in region coordinates
    for (const Eigen::Matrix3d& g : onGrid.region.instances) {
        const Eigen::Matrix3d local = (linear.inverse() * g * linear).array().round().matrix();
        for (const Eigen::Vector3d& p : onGrid.region.region.positions) {
            const Eigen::Vector3d q = local * p.array().round().matrix();
            drawn.insert({q.x(), q.y(), q.z()});
        }
    }
    const std::vector<std::uint32_t> welded = weldPositions(exact.positions, 1e-9);
    std::size_t distinct = 0;
    for (std::size_t v = 0; v < welded.size(); ++v) distinct += welded[v] == v;
    CHECK(drawn.size() == distinct);
    // The symmetric positions stay within the noise of the tile's.
    for (const Eigen::Vector3d& p : region.region.positions)
        CHECK(distanceToNearest(region.regionToTile.topLeftCorner<3, 3>() * p + region.centre, tile.positions) <= 2e-7);
}

TEST_CASE(
    "A tessellation that is not symmetric is cut only where cuts are allowed, and the vertex tolerance finds "
    "copies exported each with its own rounding",
    "[region]") {
    const Primitive fanned = primitiveOf(triangulateWithRandomFanPoints(makeCube(), 5));
    RegionOptions options;
    options.triangles = RegionTriangles::Whole;
    CHECK_THROWS_AS(computeFundamentalRegion(fanned, groupOh(), Eigen::Vector3d::Zero(), options),
                    std::invalid_argument);
    options.triangles = RegionTriangles::WholeWherePossible;
    const FundamentalRegion cut = computeFundamentalRegion(fanned, groupOh(), Eigen::Vector3d::Zero(), options);
    CHECK(!cut.wholeTriangles);
    CHECK(cut.trianglesCut > 0);
    options.triangles = RegionTriangles::Cut;
    CHECK(computeFundamentalRegion(fanned, groupOh(), Eigen::Vector3d::Zero(), options).region.triangles.size() ==
          cut.region.triangles.size());

    // A triangle whose image under a half turn is there, but wound the other way: its copy would face away.
    Primitive pair;
    const Eigen::Matrix3d halfTurn = Eigen::Vector3d(-1, -1, 1).asDiagonal();
    pair.positions = {{1, 0, 0}, {2, 1, 0.5}, {1, 2, 0}};
    for (int k = 0; k < 3; ++k) pair.positions.push_back(halfTurn * pair.positions[std::size_t(k)]);
    pair.triangles = {{0, 1, 2}, {3, 4, 5}};
    options.triangles = RegionTriangles::OneOfEachOrbit;
    CHECK(computeFundamentalRegion(pair, {Eigen::Matrix3d::Identity(), halfTurn}, Eigen::Vector3d::Zero(), options)
              .region.triangles.size() == 1);
    pair.triangles[1] = {3, 5, 4};
    CHECK_THROWS_AS(
        computeFundamentalRegion(pair, {Eigen::Matrix3d::Identity(), halfTurn}, Eigen::Vector3d::Zero(), options),
        std::invalid_argument);

    // The geodesic sphere's vertices moved by up to 5e-6 of its radius (a torus knot's turns agree to 7e-6).
    Primitive rounded = geodesicSphere(2);
    std::mt19937_64 generator(9);
    std::uniform_real_distribution<double> noise(-5e-6 / std::sqrt(3.0), 5e-6 / std::sqrt(3.0));
    for (Eigen::Vector3d& p : rounded.positions) p += samples::drawnVector([&] { return noise(generator); });
    const std::vector<Eigen::Matrix3d> ih = icosahedralGroup();
    std::vector<Eigen::Matrix3d> rotations;  // D5, which fixes no triangle
    for (const std::vector<std::size_t>& h : subgroupsOf(ih, 1e-9)) {
        std::vector<Eigen::Matrix3d> subgroup;
        for (std::size_t e : h) subgroup.push_back(ih[e]);
        if (h.size() == 10 && pointGroupName(subgroup) == "D5") {
            rotations = subgroup;
            break;
        }
    }
    REQUIRE(rotations.size() == 10);
    options.triangles = RegionTriangles::OneOfEachOrbit;
    CHECK_THROWS_AS(computeFundamentalRegion(rounded, rotations, Eigen::Vector3d::Zero(), options),
                    std::invalid_argument);  // the default tolerance, 1e-6
    options.vertexTolerance = 2e-5;
    const FundamentalRegion region = computeFundamentalRegion(rounded, rotations, Eigen::Vector3d::Zero(), options);
    CHECK(region.region.triangles.size() == 32);
    for (const Eigen::Vector3d& p : region.region.positions) CHECK(distanceToNearest(p, rounded.positions) <= 1e-5);
}

TEST_CASE(
    "A spheroid tessellated at random gets no region by default, and a region of cut triangles with --cut-triangles",
    "[compress][region]") {
    TemporaryFolder folder;
    // Squashed along y and z: D2h (its mirrors are coordinate planes), whose planes halve some faces.
    Primitive sphere = randomlyFannedGeodesicSphere(3, 4);
    for (Eigen::Vector3d& p : sphere.positions) p = p.cwiseProduct(Eigen::Vector3d(1, 0.8, 0.6));
    const std::filesystem::path input = folder / "sphere.glb";
    WriteOptions plain;
    plain.draco = false;
    writeScene(sceneOfOneMesh("sphere", sphere), input, plain);

    const CompressionReport whole = compressFile(input, folder / "whole.glb");
    CHECK(whole.stats.regionClasses == 0);
    CHECK(sceneStatistics(readScene(folder / "whole.glb")).trianglesDrawn == sphere.triangles.size());

    CompressOptions cutting;
    cutting.cutTriangles = true;
    const CompressionReport cut = compressFile(input, folder / "cut.glb", cutting);
    CHECK(cut.stats.regionClasses == 1);
    CHECK(cut.outputBytes < whole.outputBytes);
    CHECK(sceneStatistics(readScene(folder / "cut.glb")).trianglesDrawn > sphere.triangles.size());
    CHECK(decompressFile(folder / "cut.glb", folder / "flat.glb", input).verified);
}

TEST_CASE(
    "The geodesic sphere and the torus knot are stored as regions that draw the input's triangles, and render "
    "as it does",
    "[compress][region]") {
    TemporaryFolder folder;
    for (const char* model : {"vulkan_geosphere/geosphere.gltf", "vulkan_torusknot/torusknot.gltf"}) {
        INFO(model);
        const std::filesystem::path output = folder / "out.glb";
        const CompressionReport report = compressFile(modelPath(model), output);
        CHECK(report.stats.regionClasses == 1);
        CHECK(report.stats.trianglesStored < report.stats.trianglesIn / 2);
        CHECK(sceneStatistics(readScene(output)).trianglesDrawn == report.stats.trianglesIn);
        if (renderAvailable()) checkRendersSame(modelPath(model), output);
    }
}
