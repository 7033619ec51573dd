#include "symcompress/tiles.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "geometry/bounds.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace symcompress {

namespace {

using Cell = Eigen::Array<long long, 3, 1>;

struct CellHash {
    std::size_t operator()(const Cell& cell) const {
        // Large odd multipliers spread neighbouring cells over the table (unsigned: wrapping is intended).
        auto word = [](long long v) { return static_cast<std::uint64_t>(v); };
        return static_cast<std::size_t>(word(cell.x()) * 73856093ULL ^ word(cell.y()) * 19349663ULL ^ word(cell.z()) * 83492791ULL);
    }
};
struct CellEqual {
    bool operator()(const Cell& a, const Cell& b) const { return (a == b).all(); }
};

}  // namespace

std::vector<std::uint32_t> weldPositions(const std::vector<Eigen::Vector3d>& positions, double tolerance) {
    std::vector<std::uint32_t> representative(positions.size());
    if (positions.empty()) return representative;
    const Eigen::AlignedBox3d bounds = boundsOf(positions);
    // A grid of cells kCellsPerTolerance times the tolerance: a point's partners lie in its own cell, or in
    // a neighbouring one only when the point is within the tolerance of that side, so most points need one
    // lookup. Exact welding (tolerance 0) uses a fine grid and exact equality. Cells count from the box's
    // corner in 64-bit integers, so that tiny tolerances on large scenes cannot overflow.
    constexpr double kCellsPerTolerance = 64;
    const double extent = std::max(bounds.diagonal().maxCoeff(), 1e-300);
    const double cellSize = std::max(kCellsPerTolerance * tolerance, extent * 1e-12);
    const double toleranceSquared = tolerance > 0 ? tolerance * tolerance : 0.0;
    std::unordered_map<Cell, std::vector<std::uint32_t>, CellHash, CellEqual> grid;
    grid.reserve(positions.size());
    for (std::uint32_t i = 0; i < positions.size(); ++i) {
        const Eigen::Vector3d& p = positions[i];
        const Eigen::Array3d scaled = (p - bounds.min()).array() / cellSize;
        const Cell cell = scaled.floor().cast<long long>();
        // Per axis, the neighbouring cells within reach: -1 and/or +1 only near the cell's sides.
        const Eigen::Array3d within = scaled - scaled.floor(), reach = Eigen::Array3d::Constant(tolerance / cellSize);
        const Eigen::Array3i low = (within <= reach).cast<int>(), high = (within >= 1 - reach).cast<int>();
        std::uint32_t found = i;
        for (int dx = -low.x(); dx <= high.x() && found == i; ++dx)
            for (int dy = -low.y(); dy <= high.y() && found == i; ++dy)
                for (int dz = -low.z(); dz <= high.z() && found == i; ++dz) {
                    auto bucket = grid.find(cell + Cell(dx, dy, dz));
                    if (bucket == grid.end()) continue;
                    for (std::uint32_t candidate : bucket->second)
                        if ((positions[candidate] - p).squaredNorm() <= toleranceSquared) {
                            found = candidate;
                            break;
                        }
                }
        representative[i] = found;
        if (found == i) grid[cell].push_back(i);
    }
    return representative;
}

}  // namespace symcompress
