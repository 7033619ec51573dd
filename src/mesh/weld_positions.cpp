#include "symcompress/tiles.hpp"
#include "symcompress/detail/weld_positions.hpp"
#include "geometry/bounds.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>

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
constexpr std::uint32_t kNone = 0xffffffffu;

// Positions as a list of points or of pointers to them.
inline const Eigen::Vector3d& at(const Eigen::Vector3d& p) { return p; }
inline const Eigen::Vector3d& at(const Eigen::Vector3d* p) { return *p; }

template <typename Point>
std::vector<std::uint32_t> weld(const std::vector<Point>& points, double tolerance) {
    std::vector<std::uint32_t> representative(points.size());
    if (points.empty()) return representative;
    Eigen::AlignedBox3d bounds;
    for (const Point& p : points) bounds.extend(at(p));
    auto positions = [&](std::size_t i) -> const Eigen::Vector3d& { return at(points[i]); };
    // A grid of cells kCellsPerTolerance times the tolerance: a point's partners lie in its own cell, or in
    // a neighbouring one only when the point is within the tolerance of that side, so most points need one
    // lookup. Exact welding (tolerance 0) uses a fine grid and exact equality. Cells count from the box's
    // corner in 64-bit integers, so that tiny tolerances on large scenes cannot overflow.
    constexpr double kCellsPerTolerance = 64;
    const double extent = std::max(bounds.diagonal().maxCoeff(), 1e-300);
    const double cellSize = std::max(kCellsPerTolerance * tolerance, extent * 1e-12);
    const double toleranceSquared = tolerance > 0 ? tolerance * tolerance : 0.0;
    // The grid's cells in an open-addressed table (a power of two, at most half full), each with the chain of
    // its representatives in the order they came (`next`): no allocation per cell. A slot's cell is that of
    // its first point.
    struct Slot {
        std::uint32_t first = kNone, last = kNone;
    };
    std::size_t capacity = 16;
    while (capacity < 2 * points.size()) capacity *= 2;
    std::vector<Slot> table(capacity);
    std::vector<std::uint32_t> next(points.size(), kNone);
    const CellHash hash;
    auto cellOf = [&](const Eigen::Vector3d& p) -> Cell { return ((p - bounds.min()).array() / cellSize).floor().cast<long long>(); };
    auto slotOf = [&](const Cell& cell) -> Slot& {  // the cell's slot, or the empty one where it would go
        for (std::size_t s = hash(cell) & (capacity - 1);; s = (s + 1) & (capacity - 1))
            if (table[s].first == kNone || (cellOf(positions(table[s].first)) == cell).all()) return table[s];
    };
    for (std::uint32_t i = 0; i < points.size(); ++i) {
        const Eigen::Vector3d& p = positions(i);
        const Eigen::Array3d scaled = (p - bounds.min()).array() / cellSize;
        const Cell cell = scaled.floor().cast<long long>();  // as cellOf(p)
        // Per axis, the neighbouring cells within reach: -1 and/or +1 only near the cell's sides.
        const Eigen::Array3d within = scaled - scaled.floor(), reach = Eigen::Array3d::Constant(tolerance / cellSize);
        const Eigen::Array3i low = (within <= reach).cast<int>(), high = (within >= 1 - reach).cast<int>();
        std::uint32_t found = i;
        for (int dx = -low.x(); dx <= high.x() && found == i; ++dx)
            for (int dy = -low.y(); dy <= high.y() && found == i; ++dy)
                for (int dz = -low.z(); dz <= high.z() && found == i; ++dz) {
                    const Slot& bucket = slotOf(cell + Cell(dx, dy, dz));
                    for (std::uint32_t candidate = bucket.first; candidate != kNone; candidate = next[candidate])
                        if ((positions(candidate) - p).squaredNorm() <= toleranceSquared) {
                            found = candidate;
                            break;
                        }
                }
        representative[i] = found;
        if (found != i) continue;
        Slot& own = slotOf(cell);
        if (own.first == kNone) {
            own.first = i;
        } else {
            next[own.last] = i;
        }
        own.last = i;
    }
    return representative;
}

}  // namespace

std::vector<std::uint32_t> weldPositions(const std::vector<Eigen::Vector3d>& positions, double tolerance) {
    return weld(positions, tolerance);
}

std::vector<std::uint32_t> weldPositions(const std::vector<const Eigen::Vector3d*>& positions, double tolerance) {
    return weld(positions, tolerance);
}

}  // namespace symcompress
