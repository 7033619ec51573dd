// Building blocks of the sample generators: meshes appended into one primitive, boxes and lathes.
#include "sample_scenes.hpp"

#include "symcompress/detail/solids.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>

#include <cmath>
#include <random>

namespace symcompress::samples {

void appendMesh(Primitive& out, const TriangleMesh& part) {
    const auto offset = std::uint32_t(out.positions.size());
    out.positions.insert(out.positions.end(), part.positions.begin(), part.positions.end());
    for (const Triangle& t : part.triangles) out.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

TriangleMesh boxMesh(const Eigen::Vector3d& centre, const Eigen::Vector3d& size) {
    TriangleMesh box;
    for (int k = 0; k < 8; ++k)
        box.positions.push_back(centre + 0.5 * Eigen::Vector3d((k & 1) ? size.x() : -size.x(), (k & 2) ? size.y() : -size.y(),
                                                               (k & 4) ? size.z() : -size.z()));
    // Corners indexed by bits (x, y, z); two triangles per face, counter-clockwise seen from outside.
    const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        box.triangles.push_back({std::uint32_t(f[0]), std::uint32_t(f[1]), std::uint32_t(f[2])});
        box.triangles.push_back({std::uint32_t(f[0]), std::uint32_t(f[2]), std::uint32_t(f[3])});
    }
    return box;
}

TriangleMesh latheMesh(const std::vector<Eigen::Vector2d>& profile, int segments, const Eigen::Vector3d& base) {
    // profile.front() and profile.back() are on the axis (radius 0): they become the two poles.
    TriangleMesh lathe;
    lathe.positions.push_back(base + Eigen::Vector3d(0, 0, profile.front().y()));
    for (std::size_t r = 1; r + 1 < profile.size(); ++r)
        for (int s = 0; s < segments; ++s) {
            const double angle = 2 * M_PI * s / segments;
            lathe.positions.push_back(base + Eigen::Vector3d(profile[r].x() * std::cos(angle), profile[r].x() * std::sin(angle),
                                                             profile[r].y()));
        }
    lathe.positions.push_back(base + Eigen::Vector3d(0, 0, profile.back().y()));
    const auto rings = int(profile.size()) - 2;
    const auto top = std::uint32_t(lathe.positions.size() - 1);
    auto at = [&](int r, int s) { return std::uint32_t(1 + r * segments + (s % segments)); };
    for (int s = 0; s < segments; ++s) {
        lathe.triangles.push_back({0, at(0, s + 1), at(0, s)});
        lathe.triangles.push_back({top, at(rings - 1, s), at(rings - 1, s + 1)});
        // Quads between rings at equal azimuths are planar trapezoids: either diagonal keeps the mirrors.
        for (int r = 0; r + 1 < rings; ++r) {
            lathe.triangles.push_back({at(r, s), at(r, s + 1), at(r + 1, s + 1)});
            lathe.triangles.push_back({at(r, s), at(r + 1, s + 1), at(r + 1, s)});
        }
    }
    return lathe;
}

Eigen::Matrix3d randomRotation(std::mt19937_64& random) {
    std::normal_distribution<double> normal;
    return drawnQuaternion([&] { return normal(random); }).normalized().toRotationMatrix();
}

TriangleMesh randomConvexPart(std::mt19937_64& random) {
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> axis(0.4, 1.2);
    const Eigen::Vector3d axes = drawnVector([&] { return axis(random); });
    std::vector<Eigen::Vector3d> points;
    while (points.size() < 16)
        points.push_back(drawnVector([&] { return normal(random); }).normalized().cwiseProduct(axes));
    return triangulateFaces(makeConvexPolyhedron(points));
}

TriangleMesh unevenEllipsoid(int azimuths, std::uint64_t seed) {
    constexpr int kRings = 24;
    std::mt19937_64 random(seed);
    std::uniform_real_distribution<double> slide(-0.2, 0.2);
    std::bernoulli_distribution diagonal(0.5);
    TriangleMesh mesh;
    auto add = [&](double polar, double azimuth) {
        mesh.positions.emplace_back(0.5 * std::sin(polar) * std::cos(azimuth), 0.5 * std::sin(polar) * std::sin(azimuth),
                                    std::cos(polar));
        return std::uint32_t(mesh.positions.size() - 1);
    };
    const std::uint32_t north = add(0, 0);
    std::vector<std::vector<std::uint32_t>> rings(kRings - 1);
    for (int r = 1; r < kRings; ++r)
        for (int s = 0; s < azimuths; ++s) {
            const double azimuthSlide = slide(random), polarSlide = slide(random);  // in this order (drawnVector)
            rings[std::size_t(r - 1)].push_back(
                add(M_PI * (r + polarSlide) / kRings, 2 * M_PI * (s + azimuthSlide) / azimuths));
        }
    const std::uint32_t south = add(M_PI, 0);
    for (std::size_t s = 0; s < std::size_t(azimuths); ++s) {
        const std::size_t t = (s + 1) % std::size_t(azimuths);
        mesh.triangles.push_back({north, rings.front()[s], rings.front()[t]});
        mesh.triangles.push_back({south, rings.back()[t], rings.back()[s]});
        for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
            const std::uint32_t a = rings[r][s], b = rings[r + 1][s], c = rings[r + 1][t], d = rings[r][t];
            if (diagonal(random))
                mesh.triangles.insert(mesh.triangles.end(), {{a, b, c}, {a, c, d}});
            else
                mesh.triangles.insert(mesh.triangles.end(), {{a, b, d}, {b, c, d}});
        }
    }
    const Eigen::Matrix3d turn = randomRotation(random);
    for (Eigen::Vector3d& p : mesh.positions) p = (turn * p).cast<float>().cast<double>();
    return mesh;
}

TriangleMesh transformed(TriangleMesh mesh, const Eigen::Matrix3d& linear, const Eigen::Vector3d& translation) {
    for (auto& p : mesh.positions) p = linear * p + translation;
    if (linear.determinant() < 0)
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
    return mesh;
}

OneMeshBuilder::OneMeshBuilder(std::string name) : name_(std::move(name)) {}

int OneMeshBuilder::addMaterial(const std::string& name, const Eigen::Vector4d& colour) {
    Material material;
    material.name = name;
    material.baseColorFactor = colour;
    material.metallicFactor = 0;
    material.roughnessFactor = 0.6;
    materials_.push_back(material);
    primitives_.emplace_back();
    primitives_.back().material = int(materials_.size()) - 1;
    return primitives_.back().material;
}

void OneMeshBuilder::add(int material, const TriangleMesh& part) { appendMesh(primitives_.at(std::size_t(material)), part); }

Scene OneMeshBuilder::build() && {
    Scene scene;
    scene.materials = std::move(materials_);
    scene.meshes.push_back({name_, std::move(primitives_)});
    Node node;
    node.name = name_;
    node.mesh = 0;
    scene.nodes.push_back(std::move(node));
    scene.roots.push_back(0);
    return scene;
}

}  // namespace symcompress::samples
