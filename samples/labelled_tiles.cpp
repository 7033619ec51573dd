// Tiles with known congruence: copies of base shapes at random isometries, and near misses of them.
#include "sample_scenes.hpp"

#include <Eigen/Geometry>

#include <random>

namespace symcompress::samples {
namespace {

double diagonalOf(const TriangleMesh& mesh) {
    Eigen::AlignedBox3d box;
    for (const auto& p : mesh.positions) box.extend(p);
    return box.diagonal().norm();
}

// The mesh with one vertex pushed off its surface by `distance`: along its normal (the sum of its
// triangles' area vectors), or, where those cancel (a two-sided sheet), along its first triangle's.
TriangleMesh withVertexMoved(TriangleMesh mesh, std::size_t vertex, double distance) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), first = Eigen::Vector3d::Zero();
    double magnitudes = 0;
    for (const Triangle& t : mesh.triangles)
        if (t[0] == vertex || t[1] == vertex || t[2] == vertex) {
            const Eigen::Vector3d area = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]);
            if (magnitudes == 0) first = area;
            sum += area;
            magnitudes += area.norm();
        }
    const Eigen::Vector3d direction = sum.norm() > 0.1 * magnitudes ? sum : first;
    if (direction.norm() > 0) mesh.positions[vertex] += distance * direction.normalized();
    return mesh;
}

}  // namespace

LabelledTiles labelledCopies(const std::vector<TriangleMesh>& bases, int copies, double perturbation, std::uint64_t seed) {
    std::mt19937_64 random(seed);
    double largest = 0;
    for (const TriangleMesh& base : bases) largest = std::max(largest, diagonalOf(base));
    const double spacing = 1.5 * largest;
    LabelledTiles result;
    auto place = [&](const TriangleMesh& shape, std::size_t label, bool mirror) {
        const std::size_t slot = result.tiles.size();
        Eigen::Matrix3d linear = randomRotation(random);
        if (mirror) linear.col(0) *= -1;
        const Eigen::Vector3d at = spacing * Eigen::Vector3d(double(slot % 16), double(slot / 16 % 16), double(slot / 256));
        Tile tile;
        tile.material = 0;
        tile.mesh = transformed(shape, linear, at);
        result.tiles.push_back(std::move(tile));
        result.labels.push_back(label);
    };
    std::size_t label = 0;
    for (const TriangleMesh& base : bases) {
        for (int copy = 0; copy < copies; ++copy) place(base, label, copy % 2 == 1);
        ++label;
        if (perturbation > 0 && !base.positions.empty()) {
            std::uniform_int_distribution<std::size_t> vertex(0, base.positions.size() - 1);
            place(withVertexMoved(base, vertex(random), perturbation * largest), label++, false);
        }
    }
    return result;
}

}  // namespace symcompress::samples
