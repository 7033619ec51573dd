#include "sample_scenes.hpp"
#include "symcompress/detail/triangulate_polygon.hpp"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <random>

using namespace symcompress;

namespace {

double shoelaceArea(const std::vector<Eigen::Vector2d>& polygon) {
    double twice = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const auto &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
        twice += a.x() * b.y() - a.y() * b.x();
    }
    return twice / 2;
}

// Checks the triangulation of a planar polygon placed in 3D by `placement`: areas add up to the
// polygon's, every triangle faces the polygon's way and its centroid lies inside the polygon.
void checkTriangulation(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Isometry3d& placement) {
    std::vector<Eigen::Vector3d> corners;
    for (const auto& p : polygon) corners.push_back(placement * Eigen::Vector3d(p.x(), p.y(), 0));
    const auto triangles = triangulatePolygon(corners);
    CHECK(triangles.size() == polygon.size() - 2);
    const Eigen::Vector3d normal = placement.linear() * Eigen::Vector3d::UnitZ();
    double area = 0;
    for (const Triangle& t : triangles) {
        const Eigen::Vector3d cross = (corners[t[1]] - corners[t[0]]).cross(corners[t[2]] - corners[t[0]]);
        CHECK(cross.dot(normal) > 0);
        area += cross.norm() / 2;
        // The centroid must be inside the polygon: a ray-crossing test in the polygon's own plane.
        const Eigen::Vector2d centroid = (polygon[t[0]] + polygon[t[1]] + polygon[t[2]]) / 3;
        bool inside = false;
        for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
            if ((polygon[i].y() > centroid.y()) != (polygon[j].y() > centroid.y()) &&
                centroid.x() < (polygon[j].x() - polygon[i].x()) * (centroid.y() - polygon[i].y()) /
                                       (polygon[j].y() - polygon[i].y()) +
                                   polygon[i].x())
                inside = !inside;
        CHECK(inside);
    }
    CHECK(area == Approx(shoelaceArea(polygon)).epsilon(1e-12));
}

}  // namespace

TEST_CASE("triangulatePolygon handles convex and concave polygons in any orientation", "[triangulate]") {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<std::vector<Eigen::Vector2d>> polygons;
    std::vector<Eigen::Vector2d> hexagon;
    for (int k = 0; k < 6; ++k) hexagon.emplace_back(std::cos(k * M_PI / 3), std::sin(k * M_PI / 3));
    polygons.push_back(hexagon);
    polygons.push_back({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});  // L shape
    std::vector<Eigen::Vector2d> star;
    for (int k = 0; k < 10; ++k) {
        const double radius = k % 2 ? 0.4 : 1.0;
        star.emplace_back(radius * std::cos(k * M_PI / 5), radius * std::sin(k * M_PI / 5));
    }
    polygons.push_back(star);
    // A comb: a bar with four slots cut down from its top edge (the top edge comes back leftwards).
    std::vector<Eigen::Vector2d> comb = {{0, 0}, {8, 0}, {8, 3}};
    for (int slot = 3; slot >= 0; --slot) {
        comb.emplace_back(2 * slot + 1.5, 3);
        comb.emplace_back(2 * slot + 1.5, 1);
        comb.emplace_back(2 * slot + 1.0, 1);
        comb.emplace_back(2 * slot + 1.0, 3);
    }
    comb.emplace_back(0, 3);
    polygons.push_back(comb);
    for (const auto& polygon : polygons)
        for (int trial = 0; trial < 5; ++trial) {
            Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
            placement.linear() =
                samples::drawnQuaternion([&] { return uniform(random); }).normalized().toRotationMatrix();
            placement.translation() = samples::drawnVector([&] { return uniform(random); }) * 10;
            INFO("polygon of " << polygon.size() << " corners, trial " << trial);
            checkTriangulation(polygon, placement);
        }
}

TEST_CASE("triangulatePolygon skips repeated corners and degenerate polygons", "[triangulate]") {
    const std::vector<Eigen::Vector3d> squareWithRepeats = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
    const auto triangles = triangulatePolygon(squareWithRepeats);
    CHECK(triangles.size() == 2);
    for (const Triangle& t : triangles) CHECK((t[0] != t[1] && t[1] != t[2] && t[0] != t[2]));
    CHECK(triangulatePolygon({{0, 0, 0}, {1, 0, 0}}).empty());
    CHECK(triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}).empty());  // collinear: no area
    // A collinear run along one side keeps the area right.
    const auto withRun = triangulatePolygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}});
    double area = 0;
    const std::vector<Eigen::Vector3d> run = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
    for (const Triangle& t : withRun) area += (run[t[1]] - run[t[0]]).cross(run[t[2]] - run[t[0]]).norm() / 2;
    CHECK(area == Approx(2));
}

TEST_CASE(
    "triangulateFace cuts a convex face as viewers do, zero-area triangles and all, and others by "
    "triangulatePolygon",
    "[triangulate]") {
    // The square with repeated corners: a fan of n - 2 = 4 triangles, two of them of zero area, as three.js's
    // OBJLoader and X_ITE draw and count it; the area is the square's.
    const std::vector<Eigen::Vector3d> squareWithRepeats = {{0, 0, 0}, {0, 0, 0}, {1, 0, 0},
                                                            {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
    const auto fan = triangulateFace(squareWithRepeats);
    REQUIRE(fan.size() == 4);
    double area = 0;
    for (const Triangle& t : fan) {
        CHECK(t[0] == 0);
        area += (squareWithRepeats[t[1]] - squareWithRepeats[t[0]])
                    .cross(squareWithRepeats[t[2]] - squareWithRepeats[t[0]])
                    .z() /
                2;
    }
    CHECK(area == Approx(1));
    // A triangle of zero area stays, a collinear quad is two, fewer than 3 corners none.
    CHECK(triangulateFace({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}).size() == 1);
    CHECK(triangulateFace({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}).size() == 2);
    CHECK(triangulateFace({{0, 0, 0}, {1, 0, 0}}).empty());
    // A concave L, whose fan from the corner (2, 0) would cover its notch: cut by ear clipping.
    const std::vector<Eigen::Vector3d> l = {{2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}, {0, 0, 0}};
    CHECK(triangulateFace(l) == triangulatePolygon(l));
    CHECK(triangulateFace(l).size() == 4);
}
