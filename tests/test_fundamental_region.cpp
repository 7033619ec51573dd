// Fundamental regions of tiles with known symmetry groups: the copies of the region must rebuild the tile
// (area, coverage both ways, orientation), attributes must be interpolated at the cuts, and seams must
// survive quantization where the frame makes that possible.
#include "sample_scenes.hpp"
#include "signed_permutation_groups.hpp"
#include "symcompress/detail/fundamental_region.hpp"
#include "symcompress/scene_ops.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <set>
#include <stdexcept>

using namespace symcompress;
using namespace symcompress::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- Test solids: convex hulls of a few points, faces counter-clockwise seen from outside. ----

struct Solid {
    std::vector<Eigen::Vector3d> vertices;
    std::vector<std::vector<std::uint32_t>> faces;
};

// Brute force over vertex triples: a plane with every vertex on one side carries a face.
Solid convexHull(const std::vector<Eigen::Vector3d>& vertices) {
    Solid solid{vertices, {}};
    Eigen::Vector3d interior = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& v : vertices) interior += v;
    interior /= static_cast<double>(vertices.size());
    std::set<std::vector<std::uint32_t>> seen;
    const std::size_t n = vertices.size();
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            for (std::size_t k = j + 1; k < n; ++k) {
                Eigen::Vector3d normal = (vertices[j] - vertices[i]).cross(vertices[k] - vertices[i]);
                if (normal.norm() < 1e-9) continue;
                normal.normalize();
                if (normal.dot(vertices[i] - interior) < 0) normal = -normal;
                std::vector<std::uint32_t> onPlane;
                bool supporting = true;
                for (std::uint32_t v = 0; v < n; ++v) {
                    const double d = normal.dot(vertices[v] - vertices[i]);
                    if (d > 1e-9) supporting = false;
                    if (std::abs(d) <= 1e-9) onPlane.push_back(v);
                }
                if (!supporting || !seen.insert(onPlane).second) continue;
                Eigen::Vector3d centre = Eigen::Vector3d::Zero();
                for (std::uint32_t v : onPlane) centre += vertices[v];
                centre /= static_cast<double>(onPlane.size());
                const Eigen::Vector3d u = normal.unitOrthogonal(), w = normal.cross(u);
                std::sort(onPlane.begin(), onPlane.end(), [&](std::uint32_t a, std::uint32_t b) {
                    const Eigen::Vector3d da = vertices[a] - centre, db = vertices[b] - centre;
                    return std::atan2(da.dot(w), da.dot(u)) < std::atan2(db.dot(w), db.dot(u));
                });
                solid.faces.push_back(onPlane);
            }
    return solid;
}

Solid boxSolid(double hx, double hy, double hz) {
    std::vector<Eigen::Vector3d> vertices;
    for (int i = 0; i < 8; ++i) vertices.emplace_back(i & 1 ? hx : -hx, i & 2 ? hy : -hy, i & 4 ? hz : -hz);
    return convexHull(vertices);
}

Solid tetrahedronSolid() {
    return convexHull({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}});
}

Solid pyramidSolid() {
    return convexHull({{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}, {0, 0, 1.5}});
}

Solid octahedronSolid() {
    return convexHull({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
}

Solid prismSolid(int sides, double halfHeight) {
    std::vector<Eigen::Vector3d> vertices;
    for (int i = 0; i < sides; ++i) {
        const double angle = 2 * kPi * i / sides;
        vertices.emplace_back(std::cos(angle), std::sin(angle), -halfHeight);
        vertices.emplace_back(std::cos(angle), std::sin(angle), halfHeight);
    }
    return convexHull(vertices);
}

enum class Fan { FirstVertex, RandomInterior };

// Every face gets its own vertices (flat normals); texcoords and colours are filled in later.
Primitive facetedPrimitive(const Solid& solid, Fan fan, std::uint64_t seed) {
    std::mt19937_64 generator(seed);
    std::uniform_real_distribution<double> weight(0.2, 1.0);
    Primitive primitive;
    for (const std::vector<std::uint32_t>& face : solid.faces) {
        const Eigen::Vector3d& a = solid.vertices[face[0]];
        const Eigen::Vector3d normal =
            (solid.vertices[face[1]] - a).cross(solid.vertices[face[2]] - a).normalized();
        const auto base = static_cast<std::uint32_t>(primitive.positions.size());
        for (std::uint32_t v : face) primitive.positions.push_back(solid.vertices[v]);
        const auto corners = static_cast<std::uint32_t>(face.size());
        if (fan == Fan::FirstVertex) {
            for (std::uint32_t i = 1; i + 1 < corners; ++i) primitive.triangles.push_back({base, base + i, base + i + 1});
        } else {
            Eigen::Vector3d inner = Eigen::Vector3d::Zero();
            double total = 0;
            for (std::uint32_t v : face) {
                const double w = weight(generator);
                inner += w * solid.vertices[v];
                total += w;
            }
            primitive.positions.push_back(inner / total);
            for (std::uint32_t i = 0; i < corners; ++i)
                primitive.triangles.push_back({base + corners, base + i, base + (i + 1) % corners});
        }
        primitive.normals.resize(primitive.positions.size(), normal);
    }
    return primitive;
}

// Shared corners (no per-face copies), fanned from each face's first corner.
Primitive weldedPrimitive(const Solid& solid) {
    Primitive primitive;
    primitive.positions = solid.vertices;
    for (const std::vector<std::uint32_t>& face : solid.faces)
        for (std::size_t i = 1; i + 1 < face.size(); ++i) primitive.triangles.push_back({face[0], face[i], face[i + 1]});
    return primitive;
}

// Dnh about z: rotations by 2 pi k / n, the mirrors through the z axis, and all of them times z -> -z.
std::vector<Eigen::Matrix3d> groupDnh(int n) {
    std::vector<Eigen::Matrix3d> group;
    for (int flip = 0; flip < 2; ++flip)
        for (int mirror = 0; mirror < 2; ++mirror)
            for (int k = 0; k < n; ++k) {
                Eigen::Matrix3d m = Eigen::AngleAxisd(2 * kPi * k / n, Eigen::Vector3d::UnitZ()).toRotationMatrix();
                if (mirror) m = m * Eigen::Vector3d(1, -1, 1).asDiagonal();
                if (flip) m = Eigen::Vector3d(1, 1, -1).asDiagonal() * m;
                group.push_back(m);
            }
    return group;
}

// ---- Placing a tile: random rotation, scale and centre; attributes as linear functions of position. ----

struct Placement {
    Eigen::Matrix3d rotation;
    double scale;
    Eigen::Vector3d centre;
};

Placement randomPlacement(std::uint64_t seed) {
    std::mt19937_64 generator(seed);
    std::normal_distribution<double> gaussian;
    std::uniform_real_distribution<double> uniform(-5, 5);
    const Eigen::Quaterniond q = samples::drawnQuaternion([&] { return gaussian(generator); });
    return {q.normalized().toRotationMatrix(), 0.5 + std::abs(uniform(generator)) / 2,
            samples::drawnVector([&] { return uniform(generator); })};
}

Eigen::Vector2d texcoordAt(const Eigen::Vector3d& x) {
    return {0.3 * x.x() - 0.7 * x.y() + 0.2 * x.z() + 0.5, 0.1 * x.x() + 0.4 * x.y() - 0.9 * x.z() - 0.25};
}
Eigen::Vector4d colorAt(const Eigen::Vector3d& x) {
    return {0.5 + 0.1 * x.x(), 0.5 - 0.05 * x.y(), 0.2 * x.z(), 1 - 0.01 * (x.x() + x.y())};
}

Eigen::Vector2d secondTexcoordAt(const Eigen::Vector3d& x) { return {0.2 * x.y() + 0.1, -0.5 * x.z() + 0.3 * x.x()}; }
// A tangent for each face (flat, as the solids' normals are): a fixed direction in its plane, the handedness
// by the side it faces.
Eigen::Vector4d tangentAt(const Eigen::Vector3d& normal) {
    const Eigen::Vector3d fixed(0.3, -0.5, 0.81), inPlane = (fixed - fixed.dot(normal) * normal).normalized();
    return {inPlane.x(), inPlane.y(), inPlane.z(), normal.dot(Eigen::Vector3d(1, 1, 1)) >= 0 ? 1.0 : -1.0};
}

Primitive place(Primitive primitive, const Placement& placement) {
    for (Eigen::Vector3d& p : primitive.positions) p = placement.centre + placement.scale * (placement.rotation * p);
    for (Eigen::Vector3d& n : primitive.normals) n = placement.rotation * n;
    primitive.texcoords.clear();
    primitive.colors.clear();
    for (const Eigen::Vector3d& p : primitive.positions) {
        primitive.texcoords.push_back(texcoordAt(p));
        primitive.colors.push_back(colorAt(p));
    }
    if (primitive.normals.empty()) return primitive;
    primitive.attributes = {{"TANGENT", 4, {}}, {"TEXCOORD_1", 2, {}}};
    for (std::size_t v = 0; v < primitive.positions.size(); ++v) {
        const Eigen::Vector3d& p = primitive.positions[v];
        const Eigen::Vector4d tangent = tangentAt(primitive.normals[v]);
        primitive.attributes[0].values.insert(primitive.attributes[0].values.end(), tangent.data(), tangent.data() + 4);
        const Eigen::Vector2d second = secondTexcoordAt(p);
        primitive.attributes[1].values.insert(primitive.attributes[1].values.end(), {second.x(), second.y()});
    }
    return primitive;
}

std::vector<Eigen::Matrix3d> place(const std::vector<Eigen::Matrix3d>& group, const Placement& placement) {
    std::vector<Eigen::Matrix3d> placed;
    for (const Eigen::Matrix3d& g : group) placed.push_back(placement.rotation * g * placement.rotation.transpose());
    return placed;
}

// ---- Brute-force geometry. ----

double area(const Primitive& primitive) {
    double total = 0;
    for (const Triangle& t : primitive.triangles)
        total += 0.5 * (primitive.positions[t[1]] - primitive.positions[t[0]])
                           .cross(primitive.positions[t[2]] - primitive.positions[t[0]])
                           .norm();
    return total;
}

double signedVolume(const Primitive& primitive, const Eigen::Vector3d& origin) {
    double total = 0;
    for (const Triangle& t : primitive.triangles)
        total += (primitive.positions[t[0]] - origin)
                     .dot((primitive.positions[t[1]] - origin).cross(primitive.positions[t[2]] - origin)) /
                 6;
    return total;
}

double segmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const Eigen::Vector3d ab = b - a;
    const double length = ab.squaredNorm();
    const double t = length > 0 ? std::clamp((p - a).dot(ab) / length, 0.0, 1.0) : 0.0;
    return (a + t * ab - p).norm();
}

double triangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const double length = normal.norm();
    if (length > 0) {
        const Eigen::Vector3d n = normal / length;
        const Eigen::Vector3d projected = p - n.dot(p - a) * n;
        // Inside when the projection is on the inner side of all three edges.
        if (n.dot((b - a).cross(projected - a)) >= 0 && n.dot((c - b).cross(projected - b)) >= 0 &&
            n.dot((a - c).cross(projected - c)) >= 0)
            return std::abs(n.dot(p - a));
    }
    return std::min({segmentDistance(p, a, b), segmentDistance(p, b, c), segmentDistance(p, c, a)});
}

double meshDistance(const Eigen::Vector3d& p, const Primitive& mesh) {
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle& t : mesh.triangles)
        best = std::min(best, triangleDistance(p, mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]));
    return best;
}

// Vertices, edge midpoints, centroid and a few interior points of every triangle.
std::vector<Eigen::Vector3d> surfaceSamples(const Primitive& mesh) {
    static const std::array<std::array<double, 3>, 10> weights{{{1, 0, 0},
                                                                 {0, 1, 0},
                                                                 {0, 0, 1},
                                                                 {0.5, 0.5, 0},
                                                                 {0, 0.5, 0.5},
                                                                 {0.5, 0, 0.5},
                                                                 {1. / 3, 1. / 3, 1. / 3},
                                                                 {0.7, 0.2, 0.1},
                                                                 {0.05, 0.15, 0.8},
                                                                 {0.3, 0.6, 0.1}}};
    std::vector<Eigen::Vector3d> samples;
    for (const Triangle& t : mesh.triangles)
        for (const auto& w : weights)
            samples.push_back(w[0] * mesh.positions[t[0]] + w[1] * mesh.positions[t[1]] + w[2] * mesh.positions[t[2]]);
    return samples;
}

double oneSidedDistance(const Primitive& from, const Primitive& to) {
    double worst = 0;
    for (const Eigen::Vector3d& p : surfaceSamples(from)) worst = std::max(worst, meshDistance(p, to));
    return worst;
}

Eigen::Vector3d applyAffine(const Eigen::Matrix4d& transform, const Eigen::Vector3d& p) {
    return transform.topLeftCorner<3, 3>() * p + transform.topRightCorner<3, 1>();
}

// Every property of a correct region, against the tile it came from.
void checkRegion(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group, const Eigen::Vector3d& centre,
                 const FundamentalRegion& result, double size) {
    const double tileArea = area(tile);
    REQUIRE(result.instances.size() == group.size());
    REQUIRE(!result.region.triangles.empty());
    // Area: |G| copies of R, no more and no less than S.
    CHECK(std::abs(area(result.region) * static_cast<double>(group.size()) - tileArea) <= 1e-9 * tileArea);

    // The region lies in F.
    for (const Eigen::Vector3d& y : result.region.positions) {
        const Eigen::Vector3d x = applyAffine(result.regionToTile, y);
        for (const Eigen::Vector3d& n : result.facetNormals) CHECK(n.dot(x - centre) >= -1e-9 * size);
    }

    // Attributes at every region vertex, cut points included.
    const Primitive& region = result.region;
    REQUIRE(region.normals.size() == region.positions.size());
    REQUIRE(region.texcoords.size() == region.positions.size());
    REQUIRE(region.colors.size() == region.positions.size());
    REQUIRE(attributeSignature(region) == "TANGENT:4;TEXCOORD_1:2;");
    for (const VertexAttribute& attribute : region.attributes) REQUIRE(attribute.count() == region.positions.size());
    const Eigen::Matrix3d regionTurn = result.regionToTile.topLeftCorner<3, 3>();
    for (std::size_t v = 0; v < region.positions.size(); ++v) {
        const Eigen::Vector3d x = applyAffine(result.regionToTile, region.positions[v]);
        CHECK((region.texcoords[v] - texcoordAt(x)).norm() <= 1e-9 * size);
        CHECK((region.colors[v] - colorAt(x)).norm() <= 1e-9 * size);
        CHECK(std::abs(region.normals[v].norm() - 1) <= 1e-12);
        // The other attributes too: a TANGENT turned into the region's frame, of unit length, its handedness kept.
        const Eigen::Vector4d expected = tangentAt(regionTurn * region.normals[v]);
        const Eigen::Map<const Eigen::Vector4d> tangent(region.attributes[0].vertex(v));
        CHECK((regionTurn * tangent.head<3>() - expected.head<3>()).norm() <= 1e-7);
        CHECK(tangent.w() == expected.w());
        CHECK((Eigen::Map<const Eigen::Vector2d>(region.attributes[1].vertex(v)) - secondTexcoordAt(x)).norm() <=
              1e-9 * size);
    }
    // Flat faces: the normal of each corner is the normal of its triangle, in region coordinates.
    for (const Triangle& t : region.triangles) {
        const Eigen::Vector3d geometric =
            (region.positions[t[1]] - region.positions[t[0]]).cross(region.positions[t[2]] - region.positions[t[0]]);
        if (geometric.norm() < 1e-6 * size * size) continue;  // slivers have no reliable direction
        for (std::uint32_t corner : t) CHECK((region.normals[corner] - geometric.normalized()).norm() <= 1e-7);
    }

    // The copies rebuild S: coverage both ways, the same orientation and volume.
    const Primitive rebuilt = rebuildFromRegion(result);
    CHECK(std::abs(area(rebuilt) - tileArea) <= 1e-9 * tileArea);
    // Each copy's tangents are the region's turned by its instance, the handedness kept (as a viewer draws them).
    REQUIRE(rebuilt.attributes.size() == 2);
    REQUIRE(rebuilt.attributes[0].count() == rebuilt.positions.size());
    for (std::size_t k = 0; k < result.instances.size(); ++k) {
        const Eigen::Matrix3d turn = instanceTransform(result, k).topLeftCorner<3, 3>();
        for (std::size_t v = 0; v < region.positions.size(); ++v) {
            const Eigen::Map<const Eigen::Vector4d> from(region.attributes[0].vertex(v)),
                to(rebuilt.attributes[0].vertex(k * region.positions.size() + v));
            CHECK((turn * from.head<3>() - to.head<3>()).norm() <= 1e-12);
            CHECK(to.w() == from.w());
        }
    }
    CHECK(oneSidedDistance(tile, rebuilt) <= 1e-9 * size);
    CHECK(oneSidedDistance(rebuilt, tile) <= 1e-9 * size);
    const double volume = signedVolume(tile, centre);
    CHECK(std::abs(signedVolume(rebuilt, centre) - volume) <= 1e-9 * std::abs(volume));
    for (const Triangle& t : rebuilt.triangles) {
        const Eigen::Vector3d geometric = (rebuilt.positions[t[1]] - rebuilt.positions[t[0]])
                                              .cross(rebuilt.positions[t[2]] - rebuilt.positions[t[0]]);
        if (geometric.norm() < 1e-6 * size * size) continue;
        for (std::uint32_t corner : t) CHECK((rebuilt.normals[corner] - geometric.normalized()).norm() <= 1e-7);
    }
}

struct Case {
    const char* name;
    Solid solid;
    std::vector<Eigen::Matrix3d> group;
    Fan fan;
};

}  // namespace

TEST_CASE("fundamental regions of solids with known groups rebuild them", "[region]") {
    const std::vector<Case> cases{
        {"cube Oh", boxSolid(1, 1, 1), groupOh(), Fan::FirstVertex},
        {"irregular cube Oh", boxSolid(1, 1, 1), groupOh(), Fan::RandomInterior},
        {"square prism D4h", boxSolid(1, 1, 0.6), groupD4h(), Fan::RandomInterior},
        {"tetrahedron Td", tetrahedronSolid(), groupTd(), Fan::RandomInterior},
        {"pyramid C4v", pyramidSolid(), groupC4v(), Fan::RandomInterior},
        {"octahedron C4", octahedronSolid(), groupC4(), Fan::RandomInterior},
        {"hexagonal prism D6h", prismSolid(6, 0.4), groupDnh(6), Fan::RandomInterior},
        {"irregular cube mirror", boxSolid(1, 1, 1), groupMirrorX(), Fan::RandomInterior},
    };
    REQUIRE(groupTd().size() == 24);
    REQUIRE(groupD4h().size() == 16);
    REQUIRE(groupDnh(6).size() == 24);
    for (const Case& c : cases) {
        for (std::uint64_t trial = 0; trial < 3; ++trial) {
            for (RegionFrame frame : {RegionFrame::Tile, RegionFrame::Aligned}) {
                INFO(c.name << ", trial " << trial << ", frame " << (frame == RegionFrame::Tile ? "tile" : "aligned"));
                const Placement placement = randomPlacement(1000 + trial);
                const Primitive tile = place(facetedPrimitive(c.solid, c.fan, 7 + trial), placement);
                const std::vector<Eigen::Matrix3d> group = place(c.group, placement);
                RegionOptions options;
                options.frame = frame;
                const FundamentalRegion result = computeFundamentalRegion(tile, group, placement.centre, options);
                checkRegion(tile, group, placement.centre, result, placement.scale);
                if (frame == RegionFrame::Aligned && std::string(c.name) != "hexagonal prism D6h")
                    CHECK(result.signedPermutationFrame);
                if (std::string(c.name) == "hexagonal prism D6h") CHECK(!result.signedPermutationFrame);
            }
        }
    }
}

TEST_CASE("the seed avoids cutting triangles when planes can run along edges", "[region]") {
    // C4 about the octahedron's axis: a quarter wedge bounded by planes through its edges holds two whole
    // faces. A plain mirror of the first-vertex-fanned cube runs along face diagonals or midlines.
    const Placement placement = randomPlacement(77);
    const Primitive octahedron = place(facetedPrimitive(octahedronSolid(), Fan::FirstVertex, 1), placement);
    const FundamentalRegion quarter = computeFundamentalRegion(octahedron, place(groupC4(), placement), placement.centre);
    CHECK(quarter.trianglesCut == 0);
    CHECK(quarter.region.triangles.size() == 2);
    CHECK(quarter.facetNormals.size() == 2);

    const Primitive welded = place(weldedPrimitive(octahedronSolid()), placement);
    const FundamentalRegion half = computeFundamentalRegion(welded, place(groupC2z(), placement), placement.centre);
    CHECK(half.trianglesCut == 0);
    CHECK(half.region.triangles.size() == 4);
}

TEST_CASE("cut points on shared edges are made once", "[region]") {
    const Placement placement = randomPlacement(5);
    const Primitive cube = place(weldedPrimitive(boxSolid(1, 1, 1)), placement);
    const FundamentalRegion result = computeFundamentalRegion(cube, place(groupD4h(), placement), placement.centre);
    CHECK(result.trianglesCut > 0);
    // No two region vertices at the same place, and every edge inside the region shared by two triangles.
    for (std::size_t i = 0; i < result.region.positions.size(); ++i)
        for (std::size_t j = i + 1; j < result.region.positions.size(); ++j)
            CHECK((result.region.positions[i] - result.region.positions[j]).norm() > 1e-9);
    CHECK(std::abs(area(result.region) * 16 - area(cube)) <= 1e-9 * area(cube));
}

TEST_CASE("the identity group gives the tile back unchanged", "[region]") {
    const Primitive tile = place(facetedPrimitive(boxSolid(1, 2, 3), Fan::RandomInterior, 3), randomPlacement(9));
    const FundamentalRegion result =
        computeFundamentalRegion(tile, {Eigen::Matrix3d::Identity()}, Eigen::Vector3d(0.5, 0.25, 1));
    CHECK(result.region.positions == tile.positions);
    CHECK(result.region.triangles == tile.triangles);
    CHECK(result.region.normals == tile.normals);
    CHECK(result.region.texcoords == tile.texcoords);
    CHECK(result.region.colors == tile.colors);
    CHECK(result.instances.size() == 1);
    CHECK(result.trianglesCut == 0);
    const Primitive rebuilt = rebuildFromRegion(result);
    CHECK(rebuilt.positions == tile.positions);
    CHECK(rebuilt.triangles == tile.triangles);
}

TEST_CASE("a flat tile does not get a reversed copy from the mirror in its plane", "[region]") {
    // A square plate in z = 0 under D4h: the mirror z -> -z fixes it; the 8 elements keeping +z rebuild it.
    Solid square{{{1, 1, 0}, {-1, 1, 0}, {-1, -1, 0}, {1, -1, 0}}, {{0, 1, 2, 3}}};
    const Placement placement = randomPlacement(21);
    const Primitive plate = place(facetedPrimitive(square, Fan::RandomInterior, 4), placement);
    const FundamentalRegion result = computeFundamentalRegion(plate, place(groupD4h(), placement), placement.centre);
    REQUIRE(result.instances.size() == 8);
    const Primitive rebuilt = rebuildFromRegion(result);
    CHECK(std::abs(area(rebuilt) - area(plate)) <= 1e-9 * area(plate));
    CHECK(oneSidedDistance(plate, rebuilt) <= 1e-9);
    CHECK(oneSidedDistance(rebuilt, plate) <= 1e-9);
    const Eigen::Vector3d up = placement.rotation * Eigen::Vector3d::UnitZ();
    for (const Triangle& t : rebuilt.triangles)
        CHECK((rebuilt.positions[t[1]] - rebuilt.positions[t[0]]).cross(rebuilt.positions[t[2]] - rebuilt.positions[t[0]]).dot(up) > 0);
}

TEST_CASE("the choice of the region is deterministic", "[region]") {
    const Placement placement = randomPlacement(31);
    const Primitive tile = place(facetedPrimitive(boxSolid(1, 1, 1), Fan::RandomInterior, 8), placement);
    const std::vector<Eigen::Matrix3d> group = place(groupOh(), placement);
    const FundamentalRegion a = computeFundamentalRegion(tile, group, placement.centre);
    const FundamentalRegion b = computeFundamentalRegion(tile, group, placement.centre);
    CHECK(a.seed == b.seed);
    CHECK(a.region.positions == b.region.positions);
    CHECK(a.region.triangles == b.region.triangles);
}

TEST_CASE("bad input to computeFundamentalRegion is rejected", "[region]") {
    const Primitive cube = facetedPrimitive(boxSolid(1, 1, 1), Fan::FirstVertex, 0);
    const std::vector<Eigen::Matrix3d> oh = groupOh();
    const Eigen::Vector3d origin = Eigen::Vector3d::Zero();
    CHECK_THROWS_AS(computeFundamentalRegion(Primitive{}, oh, origin), std::invalid_argument);
    CHECK_THROWS_AS(computeFundamentalRegion(cube, {}, origin), std::invalid_argument);

    std::vector<Eigen::Matrix3d> skewed = oh;
    skewed[5](0, 1) += 0.1;
    CHECK_THROWS_AS(computeFundamentalRegion(cube, skewed, origin), std::invalid_argument);
    std::vector<Eigen::Matrix3d> scaled = oh;
    scaled[3] *= 2;
    CHECK_THROWS_AS(computeFundamentalRegion(cube, scaled, origin), std::invalid_argument);
    std::vector<Eigen::Matrix3d> noIdentity = groupC2z();
    noIdentity.erase(noIdentity.begin());
    CHECK_THROWS_AS(computeFundamentalRegion(cube, noIdentity, origin), std::invalid_argument);
    std::vector<Eigen::Matrix3d> open = groupC4();
    open.pop_back();
    CHECK_THROWS_AS(computeFundamentalRegion(cube, open, origin), std::invalid_argument);
    std::vector<Eigen::Matrix3d> repeated = groupC2z();
    repeated.push_back(repeated.back());
    CHECK_THROWS_AS(computeFundamentalRegion(cube, repeated, origin), std::invalid_argument);
    std::vector<Eigen::Matrix3d> notFinite = groupC2z();
    notFinite[1](2, 2) = std::nan("");
    CHECK_THROWS_AS(computeFundamentalRegion(cube, notFinite, origin), std::invalid_argument);

    CHECK_THROWS_AS(computeFundamentalRegion(cube, oh, Eigen::Vector3d(0, std::nan(""), 0)), std::invalid_argument);
    Primitive badIndex = cube;
    badIndex.triangles[0][1] = 1000;
    CHECK_THROWS_AS(computeFundamentalRegion(badIndex, oh, origin), std::invalid_argument);
    Primitive badNormals = cube;
    badNormals.normals.pop_back();
    CHECK_THROWS_AS(computeFundamentalRegion(badNormals, oh, origin), std::invalid_argument);
    Primitive flat = cube;
    for (Eigen::Vector3d& p : flat.positions) p = Eigen::Vector3d::Zero();
    CHECK_THROWS_AS(computeFundamentalRegion(flat, oh, origin), std::invalid_argument);
    Primitive infinite = cube;
    infinite.positions[2].x() = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(computeFundamentalRegion(infinite, oh, origin), std::invalid_argument);
}

namespace {

// Draco's position quantization, in float as draco::Quantizer / Dequantizer do it.
std::vector<Eigen::Vector3d> quantize(const std::vector<Eigen::Vector3d>& positions, const QuantizationGrid& grid) {
    const float levels = static_cast<float>((1 << grid.bits) - 1);
    const float range = static_cast<float>(grid.range);
    const float inverseDelta = levels / range, delta = range / levels;
    std::vector<Eigen::Vector3d> quantized;
    for (const Eigen::Vector3d& p : positions) {
        Eigen::Vector3d q;
        for (int axis = 0; axis < 3; ++axis) {
            const float origin = static_cast<float>(grid.origin[axis]);
            const float value = (static_cast<float>(p[axis]) - origin) * inverseDelta;
            const auto level = static_cast<std::int32_t>(std::floor(value + 0.5f));
            q[axis] = static_cast<double>(static_cast<float>(level) * delta + origin);
        }
        quantized.push_back(q);
    }
    return quantized;
}

// Draco's own box: the minimum of every coordinate and the largest extent.
QuantizationGrid dataGrid(const std::vector<Eigen::Vector3d>& positions, int bits) {
    Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
    Eigen::Vector3f high = -low;
    for (const Eigen::Vector3d& p : positions) {
        low = low.cwiseMin(p.cast<float>());
        high = high.cwiseMax(p.cast<float>());
    }
    QuantizationGrid grid;
    grid.origin = low.cast<double>();
    grid.range = static_cast<double>((high - low).maxCoeff());
    grid.bits = bits;
    return grid;
}

// The widest crack: over every copy and every region vertex on a plane of F where the exact copies meet
// another copy (a seam), the distance from the quantized vertex to the other quantized copies.
std::vector<Primitive> copiesOf(const FundamentalRegion& result) {
    std::vector<Primitive> copies;
    for (std::size_t k = 0; k < result.instances.size(); ++k) {
        FundamentalRegion single = result;
        single.instances = {result.instances[k]};
        copies.push_back(rebuildFromRegion(single));
    }
    return copies;
}

double distanceToOthers(const std::vector<Primitive>& copies, std::size_t k, std::size_t vertex) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t other = 0; other < copies.size(); ++other)
        if (other != k) nearest = std::min(nearest, meshDistance(copies[k].positions[vertex], copies[other]));
    return nearest;
}

double seamGap(const FundamentalRegion& result, const std::vector<Eigen::Vector3d>& quantizedPositions, double size) {
    FundamentalRegion quantized = result;
    quantized.region.positions = quantizedPositions;
    const std::vector<Primitive> exact = copiesOf(result);
    const std::vector<Primitive> copies = copiesOf(quantized);
    double gap = 0;
    for (std::size_t v = 0; v < result.region.positions.size(); ++v) {
        const Eigen::Vector3d x = applyAffine(result.regionToTile, result.region.positions[v]);
        bool onPlane = false;
        for (const Eigen::Vector3d& n : result.facetNormals) onPlane = onPlane || std::abs(n.dot(x - result.centre)) <= 1e-9 * size;
        if (!onPlane) continue;
        for (std::size_t k = 0; k < copies.size(); ++k)
            if (distanceToOthers(exact, k, v) <= 1e-9 * size) gap = std::max(gap, distanceToOthers(copies, k, v));
    }
    return gap;
}

double seamGap(const FundamentalRegion& result, const QuantizationGrid& grid, double size) {
    return seamGap(result, quantize(result.region.positions, grid), size);
}

// A soup of random triangles and all their images: invariant, with an invariant triangulation.
Primitive orbitSoup(const std::vector<Eigen::Matrix3d>& group, int triangles, std::uint64_t seed) {
    std::mt19937_64 generator(seed);
    std::uniform_real_distribution<double> coordinate(-1, 1);
    Primitive soup;
    for (int t = 0; t < triangles; ++t) {
        std::array<Eigen::Vector3d, 3> corners;
        for (Eigen::Vector3d& c : corners) c = {coordinate(generator), coordinate(generator), coordinate(generator)};
        for (const Eigen::Matrix3d& g : group) {
            const auto base = static_cast<std::uint32_t>(soup.positions.size());
            for (const Eigen::Vector3d& c : corners) soup.positions.push_back(g * c);
            if (g.determinant() > 0)
                soup.triangles.push_back({base, base + 1, base + 2});
            else
                soup.triangles.push_back({base, base + 2, base + 1});
        }
    }
    soup.normals.assign(soup.positions.size(), Eigen::Vector3d::UnitZ());
    return soup;
}

struct SeamCase {
    const char* name;
    Primitive tile;  // unplaced
    std::vector<Eigen::Matrix3d> group;
};

}  // namespace

TEST_CASE("seams after 14-bit quantization", "[region]") {
    const int bits = 14;
    const std::vector<SeamCase> cases{
        {"mirror", facetedPrimitive(boxSolid(1, 0.7, 0.4), Fan::RandomInterior, 11), groupMirrorX()},
        {"2-fold axis", orbitSoup(groupC2z(), 12, 5), groupC2z()},
        {"Oh", facetedPrimitive(boxSolid(1, 1, 1), Fan::RandomInterior, 12), groupOh()},
        {"D6h", facetedPrimitive(prismSolid(6, 0.4), Fan::RandomInterior, 13), groupDnh(6)},
    };
    for (const SeamCase& c : cases) {
        INFO(c.name);
        const Placement placement = randomPlacement(4242);
        const Primitive tile = place(c.tile, placement);
        const std::vector<Eigen::Matrix3d> group = place(c.group, placement);
        RegionOptions tileFrame, aligned;
        aligned.frame = RegionFrame::Aligned;
        const FundamentalRegion plain = computeFundamentalRegion(tile, group, placement.centre, tileFrame);
        const FundamentalRegion framed = computeFundamentalRegion(tile, group, placement.centre, aligned);
        const QuantizationGrid plainGrid = dataGrid(plain.region.positions, bits);
        const QuantizationGrid framedGrid = dataGrid(framed.region.positions, bits);
        const QuantizationGrid seamGrid = seamPreservingGrid(framed, bits);
        const double gapPlain = seamGap(plain, plainGrid, placement.scale);
        const double gapFramed = seamGap(framed, framedGrid, placement.scale);
        const double gapSeamGrid = seamGap(framed, seamGrid, placement.scale);
        const double levels = (1 << bits) - 1;
        if (std::getenv("SYMCOMPRESS_REPORT"))
            std::printf("seam gap, %s (%zu triangles cut): tile frame %.3g (step %.3g), aligned %.3g (step %.3g), "
                        "aligned + seam grid %.3g (step %.3g)\n",
                        c.name, framed.trianglesCut, gapPlain, plainGrid.range / levels, gapFramed,
                        framedGrid.range / levels, gapSeamGrid, seamGrid.range / levels);

        // The seam grid: a power-of-two step, the centre on the grid, the region inside it.
        const double step = seamGrid.range / levels;
        CHECK(std::exp2(std::round(std::log2(step))) == step);
        for (int axis = 0; axis < 3; ++axis) CHECK(std::round(seamGrid.origin[axis] / step) * step == seamGrid.origin[axis]);
        CHECK(step <= 2.01 * framedGrid.range / levels);
        for (const Eigen::Vector3d& p : framed.region.positions) {
            CHECK((p - seamGrid.origin).minCoeff() >= 0);
            CHECK((p - seamGrid.origin).maxCoeff() <= seamGrid.range);
        }

        // Every gap is within a few quantization steps.
        CHECK(gapPlain <= 2 * std::sqrt(3.0) * plainGrid.range / levels);
        CHECK(gapFramed <= 2 * std::sqrt(3.0) * framedGrid.range / levels);
        CHECK(gapSeamGrid <= 2 * std::sqrt(3.0) * step);
        // Where theory says the copies meet exactly, they do (up to double rounding of the transforms).
        CHECK(gapPlain > 1e-6 * placement.scale);  // the tile frame opens the seams (for these cases)
        CHECK(framed.signedPermutationFrame == (std::string(c.name) != "D6h"));
        if (std::string(c.name) == "mirror") CHECK(gapFramed <= 1e-12 * placement.scale);
        if (framed.signedPermutationFrame) CHECK(gapSeamGrid <= 1e-12 * placement.scale);

        // In units of the step, the grid is integer (what Draco's explicit quantization can carry) and
        // quantizes exactly as before; the copies still rebuild the tile.
        const RegionInGridSteps steps = inGridSteps(framed, seamGrid);
        CHECK(steps.grid.range == levels);
        CHECK(steps.grid.origin == steps.grid.origin.array().round().matrix());
        CHECK(seamGap(steps.region, steps.grid, placement.scale) == Approx(gapSeamGrid).margin(1e-12));
        CHECK(std::abs(area(rebuildFromRegion(steps.region)) - area(tile)) <= 1e-9 * area(tile));
    }
}
