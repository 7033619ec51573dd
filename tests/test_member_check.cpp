// The member check: a stored part placed by an isometry stands for a tile only where it reproduces it triangle
// for triangle, attributes included, or as a surface where the same corners are cut into other triangles.
#include "plan/member_check.hpp"
#include "sample_scenes.hpp"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace symcompress;

namespace {

constexpr int kSectors = 8;

// A cone of kSectors sides about z, a tip vertex for each side with that side's normal (how exporters write a
// flat-shaded tip), the rim shared with the sides' mean normals. Side k's tip takes the normal of side
// (k + shift) % kSectors: with shift 0 the cone as it is, else every tip normal is still there, at the same
// place, but on another side.
Primitive coneWithTips(int shift) {
    Primitive cone;
    auto sideNormal = [](int k) {
        const double middle = 2 * M_PI * (k + 0.5) / kSectors;
        return Eigen::Vector3d(std::cos(middle), std::sin(middle), 0.5).normalized();
    };
    for (int k = 0; k < kSectors; ++k) {
        const double angle = 2 * M_PI * k / kSectors;
        cone.positions.push_back({std::cos(angle), std::sin(angle), 0});
        cone.normals.push_back((sideNormal(k) + sideNormal((k + kSectors - 1) % kSectors)).normalized());
    }
    for (int k = 0; k < kSectors; ++k) {
        cone.positions.push_back({0, 0, 2});
        cone.normals.push_back(sideNormal((k + shift) % kSectors));
        cone.triangles.push_back({std::uint32_t(k), std::uint32_t((k + 1) % kSectors), std::uint32_t(kSectors + k)});
    }
    return cone;
}

// A convex part with a normal per face (its corners apart), no symmetry.
Primitive facetedPart() {
    std::mt19937_64 random(7);
    const TriangleMesh mesh = samples::randomConvexPart(random);
    Primitive part;
    for (const Triangle& t : mesh.triangles) {
        const Eigen::Vector3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        const auto first = std::uint32_t(part.positions.size());
        for (const Eigen::Vector3d* p : {&a, &b, &c}) {
            part.positions.push_back(*p);
            part.normals.push_back((b - a).cross(c - a).normalized());
        }
        part.triangles.push_back({first, first + 1, first + 2});
    }
    return part;
}

}  // namespace

TEST_CASE("The member check compares attributes corner by corner, not with any vertex at the same place",
          "[plan][congruence]") {
    const Primitive cone = coneWithTips(0);
    const Isometry identity;
    CHECK(reproduces(cone, cone, identity, 1e-6, false));
    // Every tip normal is at the tip, but on the wrong side: the sides would shade otherwise.
    const Primitive shuffled = coneWithTips(3);
    CHECK_FALSE(reproduces(cone, shuffled, identity, 1e-6, false));
    CHECK(reproduces(cone, shuffled, identity, 1e-6, true));  // as geometry it is the same cone
    // As a surface: the tips' normals at the sides' centroids differ too.
    const TileSurface a(cone), b(shuffled);
    CHECK_FALSE(surfaceDeviation(a, b, identity, 1e-6, false));
    CHECK(surfaceDeviation(a, b, identity, 1e-6, true));
    // A turn by one side carries the cone, tips and all, onto itself; a turn by half a side does not.
    Isometry turn;
    turn.linear = Eigen::AngleAxisd(2 * M_PI / kSectors, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    CHECK(reproduces(cone, cone, turn, 1e-6, false));
    turn.linear = Eigen::AngleAxisd(M_PI / kSectors, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    CHECK_FALSE(reproduces(cone, cone, turn, 1e-6, false));
}

TEST_CASE("The member check takes a mirrored placement's reversed winding, and the same corners cut otherwise",
          "[plan][congruence]") {
    const Primitive part = facetedPart();
    // Its mirror image across x = 0, wound outward again, normals mirrored.
    Isometry mirror;
    mirror.linear = Eigen::Vector3d(-1, 1, 1).asDiagonal();
    Primitive mirrored = part;
    for (Eigen::Vector3d& p : mirrored.positions) p = mirror.linear * p;
    for (Eigen::Vector3d& n : mirrored.normals) n = mirror.linear * n;
    for (Triangle& t : mirrored.triangles) std::swap(t[1], t[2]);
    CHECK(reproduces(part, mirrored, mirror, 1e-6, false));
    CHECK_FALSE(reproduces(part, mirrored, Isometry{}, 1e-6, false));

    // A flat square of 4 x 4 quads, each cut along one diagonal, and the same corners cut along the other.
    auto grid = [](bool otherDiagonal) {
        Primitive square;
        for (int y = 0; y <= 4; ++y)
            for (int x = 0; x <= 4; ++x) {
                square.positions.push_back({double(x), double(y), 0});
                square.normals.push_back(Eigen::Vector3d::UnitZ());
                square.texcoords.push_back({x / 4.0, y / 4.0});
            }
        for (std::uint32_t y = 0; y < 4; ++y)
            for (std::uint32_t x = 0; x < 4; ++x) {
                const std::uint32_t a = y * 5 + x, b = a + 1, c = a + 6, d = a + 5;
                if (otherDiagonal) {
                    square.triangles.push_back({a, b, d});
                    square.triangles.push_back({b, c, d});
                } else {
                    square.triangles.push_back({a, b, c});
                    square.triangles.push_back({a, c, d});
                }
            }
        return square;
    };
    double deviation = -1;
    CHECK(reproduces(grid(false), grid(true), Isometry{}, 1e-6, false, &deviation));
    CHECK(deviation == Approx(0).margin(1e-12));
    // Its texture turned by a quarter: the same corners and normals, another texture mapping.
    Primitive turned = grid(true);
    for (Eigen::Vector2d& uv : turned.texcoords) uv = Eigen::Vector2d(uv.y(), 1 - uv.x());
    CHECK_FALSE(reproduces(grid(false), turned, Isometry{}, 1e-6, false));
}

TEST_CASE("The surface check rejects corners cut otherwise where the surfaces part by more than the tolerance",
          "[plan][congruence]") {
    // 4 x 4 quads whose corners alternate in height: no quad is flat, so its two diagonals fold it into two
    // different surfaces. A triangle's centroid lies on the other fold's edge, 0.4 above or below it: the
    // distance between the surfaces there is less, but of that order.
    auto folded = [](bool otherDiagonal) {
        Primitive square;
        for (int y = 0; y <= 4; ++y)
            for (int x = 0; x <= 4; ++x) square.positions.push_back({double(x), double(y), 0.6 * ((x + y) % 2)});
        for (std::uint32_t y = 0; y < 4; ++y)
            for (std::uint32_t x = 0; x < 4; ++x) {
                const std::uint32_t a = y * 5 + x, b = a + 1, c = a + 6, d = a + 5;
                const Triangle first = otherDiagonal ? Triangle{a, b, d} : Triangle{a, b, c};
                const Triangle second = otherDiagonal ? Triangle{b, c, d} : Triangle{a, c, d};
                square.triangles.push_back(first);
                square.triangles.push_back(second);
            }
        return square;
    };
    const Primitive one = folded(false), other = folded(true);
    CHECK(reproduction(one, other, Isometry{}, 1e-3, true) == Reproduction::CutOtherwise);
    CHECK_FALSE(reproduces(one, other, Isometry{}, 1e-3, true));
    double deviation = -1;
    CHECK(reproduces(one, other, Isometry{}, 1, true, &deviation));
    CHECK(deviation > 0.1);
    CHECK(deviation <= 0.4);
    CHECK(reproduces(one, folded(false), Isometry{}, 1e-3, true));
}
