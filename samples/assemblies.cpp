// Assemblies whose symmetry groups are known by construction (paper Fig. 8 and 11), baked into one mesh.
#include "sample_scenes.hpp"

#include "symcompress/solids.hpp"

#include <Eigen/Geometry>

#include <cmath>

namespace symcompress::samples {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A UV sphere about the z axis whose azimuth 0 points along `facing`, centred at `centre`.
TriangleMesh uvSphere(const Eigen::Vector3d& centre, double azimuthOffset, int segments, int rings) {
    TriangleMesh mesh;
    mesh.positions.push_back(centre + Eigen::Vector3d(0, 0, -1));
    for (int r = 1; r < rings; ++r) {
        const double polar = kPi * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double azimuth = 2 * kPi * s / segments + azimuthOffset;
            mesh.positions.push_back(centre + Eigen::Vector3d(std::sin(polar) * std::cos(azimuth),
                                                              std::sin(polar) * std::sin(azimuth), -std::cos(polar)));
        }
    }
    mesh.positions.push_back(centre + Eigen::Vector3d(0, 0, 1));
    const auto top = std::uint32_t(mesh.positions.size() - 1);
    auto at = [&](int r, int s) { return std::uint32_t(1 + (r - 1) * segments + (s % segments)); };
    for (int s = 0; s < segments; ++s) {
        mesh.triangles.push_back({0, at(1, s + 1), at(1, s)});
        mesh.triangles.push_back({top, at(rings - 1, s), at(rings - 1, s + 1)});
        for (int r = 1; r + 1 < rings; ++r) {
            mesh.triangles.push_back({at(r, s), at(r, s + 1), at(r + 1, s + 1)});
            mesh.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r + 1, s)});
        }
    }
    return mesh;
}

void appendTo(Primitive& out, const TriangleMesh& part) {
    const auto offset = std::uint32_t(out.positions.size());
    out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
    for (const Triangle& t : part.triangles) out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace

Scene makeThreeSpheresScene() {
    Primitive baked;
    for (int k = 0; k < 3; ++k) {
        const double angle = 2 * kPi * k / 3;
        appendTo(baked, uvSphere(3 * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0), angle, 12, 6));
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
        appendTo(baked, placed);
    }
    TriangleMesh base = triangulateFaces(makePyramid(7, 1.5));
    for (auto& p : base.positions) p *= 0.5;
    appendTo(baked, base);
    return singleMeshScene("lamp", std::move(baked), {0.9, 0.8, 0.5, 1});
}

}  // namespace symcompress::samples
