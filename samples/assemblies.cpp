// Assemblies whose symmetry groups are known by construction (paper 6.4, Fig. 8 and 11), baked into one mesh.
#include "sample_scenes.hpp"

#include "symcompress/detail/solids.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace symcompress::samples {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A UV sphere of unit radius about the z axis, as a lathe, turned by `azimuth` and centred at `centre`.
TriangleMesh uvSphere(const Eigen::Vector3d& centre, double azimuth, int segments, int rings) {
    std::vector<Eigen::Vector2d> profile;
    for (int r = 0; r <= rings; ++r) profile.emplace_back(std::sin(kPi * r / rings), -std::cos(kPi * r / rings));
    profile.front().x() = profile.back().x() = 0;  // the poles exactly on the axis
    return transformed(latheMesh(profile, segments, Eigen::Vector3d::Zero()),
                       Eigen::AngleAxisd(azimuth, Eigen::Vector3d::UnitZ()).toRotationMatrix(), centre);
}

}  // namespace

Scene makeThreeSpheresScene() {
    Primitive baked;
    for (int k = 0; k < 3; ++k) {
        const double angle = 2 * kPi * k / 3;
        appendMesh(baked, uvSphere(3 * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0), angle, 12, 6));
    }
    return singleMeshScene("three-spheres", std::move(baked), {0.8, 0.8, 0.8, 1});
}

Scene makeLampScene() {
    // An arm: a convex block symmetric under y -> -y only, reaching out along x.
    const Polyhedron arm = makeConvexPolyhedron({{0.0, 0.15, 0.0}, {0.0, -0.15, 0.0}, {1.6, 0.1, 0.5}, {1.6, -0.1, 0.5},
                                                 {1.4, 0.12, 0.8}, {1.4, -0.12, 0.8}, {0.1, 0.2, 0.4}, {0.1, -0.2, 0.4},
                                                 {0.9, 0.0, 0.9}});
    // makeConvexPolyhedron centres the points: put the arm's root back near the axis, then out by 0.6.
    TriangleMesh armMesh = triangulateFaces(arm);
    Eigen::Vector3d lowest = armMesh.positions.front();
    for (const auto& p : armMesh.positions) lowest = lowest.cwiseMin(p);
    Primitive baked;
    for (int k = 0; k < 7; ++k) {
        const Eigen::Matrix3d turn = Eigen::AngleAxisd(2 * kPi * k / 7, Eigen::Vector3d::UnitZ()).toRotationMatrix();
        TriangleMesh placed = armMesh;
        for (auto& p : placed.positions) p = turn * (p - Eigen::Vector3d(lowest.x(), 0, lowest.z()) + Eigen::Vector3d(0.6, 0, 0.5));
        appendMesh(baked, placed);
    }
    TriangleMesh base = triangulateFaces(makePyramid(7, 1.5));
    for (auto& p : base.positions) p *= 0.5;
    appendMesh(baked, base);
    return singleMeshScene("lamp", std::move(baked), {0.9, 0.8, 0.5, 1});
}

Scene makePliersScene() {
    // A handle: a thin plate whose outline (points of an ellipse at irregular angles) has no symmetry,
    // so that the plate's only symmetry is the mirror through its middle plane.
    std::vector<Eigen::Vector3d> corners;
    for (double degrees : {0.0, 50.0, 110.0, 170.0, 200.0, 260.0, 320.0})
        for (double z : {-0.08, 0.08})
            corners.emplace_back(2.0 * std::cos(degrees * kPi / 180), 0.3 * std::sin(degrees * kPi / 180), z);
    const TriangleMesh handle = triangulateFaces(makeConvexPolyhedron(corners));
    // One handle turned by 25 degrees above the middle plane, the other its half-turn about x below it.
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(25 * kPi / 180, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Matrix3d halfTurn = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const TriangleMesh upper = transformed(handle, turn, {0, 0, 0.1});
    Primitive baked;
    appendMesh(baked, upper);
    appendMesh(baked, transformed(upper, halfTurn, Eigen::Vector3d::Zero()));
    return singleMeshScene("pliers", std::move(baked), {0.6, 0.6, 0.65, 1});
}

Scene makeChessScene() {
    OneMeshBuilder chess("chess");
    const int light = chess.addMaterial("light-squares", {0.9, 0.85, 0.7, 1});
    const int dark = chess.addMaterial("dark-squares", {0.3, 0.2, 0.1, 1});
    // Squares with a groove between them: diagonal neighbours would otherwise share a vertical edge.
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) chess.add((i + j) % 2 ? light : dark, boxMesh({i - 3.5, j - 3.5, -0.2}, {0.98, 0.98, 0.4}));
    const int pieces = chess.addMaterial("pieces", {0.75, 0.55, 0.3, 1});
    const std::vector<Eigen::Vector2d> pawn{{0, 0}, {0.3, 0}, {0.3, 0.08}, {0.2, 0.16}, {0.11, 0.45}, {0.2, 0.52}, {0.16, 0.66}, {0, 0.8}};
    const std::vector<Eigen::Vector2d> rook{{0, 0}, {0.34, 0}, {0.34, 0.1}, {0.23, 0.22}, {0.23, 0.72}, {0.31, 0.78}, {0.31, 0.98}, {0, 0.98}};
    // Pieces moved off their start so that the only symmetry left is the half-turn about the vertical.
    for (double sign : {1.0, -1.0}) {
        for (const Eigen::Vector2d& at : {Eigen::Vector2d(0.5, 1.5), Eigen::Vector2d(3.5, 2.5)})
            chess.add(pieces, latheMesh(pawn, 12, {sign * at.x(), sign * at.y(), 0}));
        chess.add(pieces, latheMesh(rook, 12, {sign * 2.5, sign * 0.5, 0}));
    }
    return std::move(chess).build();
}

}  // namespace symcompress::samples
