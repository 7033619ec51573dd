#include "symcompress/detail/solids.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>

namespace symcompress {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

// Faces are found as the planes through three points with all points on one side: cubic in the vertex
// count, meant for small solids.
Polyhedron makeConvexPolyhedron(std::vector<Eigen::Vector3d> vertices) {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    for (const auto& v : vertices) center += v;
    center /= double(vertices.size());
    for (auto& v : vertices) v -= center;

    double scale = 0;
    for (const auto& v : vertices) scale = std::max(scale, v.norm());
    const double eps = 1e-9 * scale;

    Polyhedron result;
    result.vertices = vertices;
    std::set<std::vector<std::uint32_t>> seen;
    const std::size_t n = vertices.size();
    for (std::size_t a = 0; a < n; ++a)
        for (std::size_t b = a + 1; b < n; ++b)
            for (std::size_t c = b + 1; c < n; ++c) {
                Eigen::Vector3d normal = (vertices[b] - vertices[a]).cross(vertices[c] - vertices[a]);
                if (normal.norm() < eps * scale) continue;
                normal.normalize();
                double offset = normal.dot(vertices[a]);
                if (offset < 0) normal = -normal, offset = -offset;
                std::vector<std::uint32_t> onPlane;
                bool supporting = true;
                for (std::size_t i = 0; i < n && supporting; ++i) {
                    const double d = normal.dot(vertices[i]) - offset;
                    if (d > eps) supporting = false;
                    else if (d > -eps) onPlane.push_back(std::uint32_t(i));
                }
                if (!supporting || !seen.insert(onPlane).second) continue;
                // Counter-clockwise about the outward normal.
                Eigen::Vector3d faceCenter = Eigen::Vector3d::Zero();
                for (auto i : onPlane) faceCenter += vertices[i];
                faceCenter /= double(onPlane.size());
                const Eigen::Vector3d u = (vertices[onPlane[0]] - faceCenter).normalized();
                const Eigen::Vector3d w = normal.cross(u);
                std::sort(onPlane.begin(), onPlane.end(), [&](std::uint32_t i, std::uint32_t j) {
                    const Eigen::Vector3d pi = vertices[i] - faceCenter, pj = vertices[j] - faceCenter;
                    return std::atan2(pi.dot(w), pi.dot(u)) < std::atan2(pj.dot(w), pj.dot(u));
                });
                result.faces.push_back(onPlane);
            }
    return result;
}

namespace {

std::vector<Eigen::Vector3d> ring(int n, double z, double phase) {
    std::vector<Eigen::Vector3d> points;
    for (int i = 0; i < n; ++i) {
        const double a = 2 * kPi * i / n + phase;
        points.emplace_back(std::cos(a), std::sin(a), z);
    }
    return points;
}

void requireSides(int n, const char* what) {
    if (n < 3) throw std::invalid_argument(std::string(what) + " needs at least 3 sides");
}

}  // namespace

Polyhedron makeTetrahedron() {
    return makeConvexPolyhedron({{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}});
}

Polyhedron makeCube() {
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    return makeConvexPolyhedron(v);
}

Polyhedron makeOctahedron() {
    return makeConvexPolyhedron({{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
}

Polyhedron makeIcosahedron() {
    const double phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Eigen::Vector3d> v;
    for (double s : {-1.0, 1.0})
        for (double t : {-phi, phi}) {
            v.emplace_back(0, s, t);
            v.emplace_back(s, t, 0);
            v.emplace_back(t, 0, s);
        }
    return makeConvexPolyhedron(v);
}

Polyhedron makeDodecahedron() {
    const double phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
    for (double s : {-1 / phi, 1 / phi})
        for (double t : {-phi, phi}) {
            v.emplace_back(0, s, t);
            v.emplace_back(s, t, 0);
            v.emplace_back(t, 0, s);
        }
    return makeConvexPolyhedron(v);
}

Polyhedron makePrism(int n, double height) {
    requireSides(n, "a prism");
    auto v = ring(n, -height / 2, 0);
    for (const auto& p : ring(n, height / 2, 0)) v.push_back(p);
    return makeConvexPolyhedron(v);
}

Polyhedron makeAntiprism(int n, double height) {
    requireSides(n, "an antiprism");
    auto v = ring(n, -height / 2, 0);
    for (const auto& p : ring(n, height / 2, kPi / n)) v.push_back(p);
    return makeConvexPolyhedron(v);
}

Polyhedron makePyramid(int n, double height) {
    requireSides(n, "a pyramid");
    auto v = ring(n, 0, 0);
    v.emplace_back(0, 0, height);
    return makeConvexPolyhedron(v);
}

TriangleMesh triangulateFaces(const Polyhedron& polyhedron) {
    TriangleMesh mesh;
    mesh.positions = polyhedron.vertices;
    for (const auto& face : polyhedron.faces)
        for (std::size_t i = 1; i + 1 < face.size(); ++i) mesh.triangles.push_back({face[0], face[i], face[i + 1]});
    return mesh;
}

TriangleMesh triangulateWithRandomFanPoints(const Polyhedron& polyhedron, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> weight(0.2, 1.0);
    TriangleMesh mesh;
    mesh.positions = polyhedron.vertices;
    for (const auto& face : polyhedron.faces) {
        Eigen::Vector3d point = Eigen::Vector3d::Zero();
        double total = 0;
        for (auto i : face) {
            const double w = weight(random);
            point += w * polyhedron.vertices[i];
            total += w;
        }
        const auto center = std::uint32_t(mesh.positions.size());
        mesh.positions.push_back(point / total);
        for (std::size_t i = 0; i < face.size(); ++i)
            mesh.triangles.push_back({center, face[i], face[(i + 1) % face.size()]});
    }
    return mesh;
}

}  // namespace symcompress
