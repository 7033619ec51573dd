// The position bits of a Draco-compressed primitive: fixed (WriteOptions::positionBits), or the fewest that
// keep every corner within an error bound and collapse no triangle, found by quantizing the corners as Draco
// does.
#include "symcompress/io.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace symcompress {
namespace {

constexpr int kMostPositionBits = 24;  // a float32's mantissa: more bits cannot place a corner closer

// The largest distance a corner moves through Draco's position quantization at `bits` (its
// AttributeQuantizationTransform in float32: the box's minimum and its largest side quantized into
// 2^bits - 1 steps, each value rounded to the nearest), over the corners of the triangles.
// Draco's grid for the primitive at `bits`: the box's minimum and its largest side (float32, as Draco
// computes them), and the corners' cells on it.
struct DracoGrid {
    float minimum[3], range, levels;
    DracoGrid(const Primitive& primitive, int bits);
    float cell(const Eigen::Vector3d& p, int axis) const {
        return std::floor((float(p[axis]) - minimum[axis]) * (levels / range) + 0.5f);
    }
};

DracoGrid::DracoGrid(const Primitive& primitive, int bits) : levels(float((1u << bits) - 1)) {
    float maximum[3];
    for (int c = 0; c < 3; ++c) minimum[c] = std::numeric_limits<float>::max(), maximum[c] = -minimum[c];
    for (const Triangle& t : primitive.triangles)
        for (std::uint32_t v : t)
            for (int c = 0; c < 3; ++c) {
                const float value = float(primitive.positions[v][c]);
                minimum[c] = std::min(minimum[c], value);
                maximum[c] = std::max(maximum[c], value);
            }
    range = 0;
    for (int c = 0; c < 3; ++c) range = std::max(range, maximum[c] - minimum[c]);
    if (range == 0) range = 1;
}

// Whether some triangle has two corners in one cell at `bits`: edgebreaker drops such a triangle, and the
// writer stores it in a sequential primitive of its own, which costs more than the bits it saves.
bool collapsesTriangles(const Primitive& primitive, int bits) {
    const DracoGrid grid(primitive, bits);
    auto same = [&](std::uint32_t a, std::uint32_t b) {
        for (int c = 0; c < 3; ++c)
            if (grid.cell(primitive.positions[a], c) != grid.cell(primitive.positions[b], c)) return false;
        return true;
    };
    for (const Triangle& t : primitive.triangles)
        if (primitive.positions[t[0]] != primitive.positions[t[1]] &&
            primitive.positions[t[1]] != primitive.positions[t[2]] &&
            primitive.positions[t[0]] != primitive.positions[t[2]] &&
            (same(t[0], t[1]) || same(t[1], t[2]) || same(t[0], t[2])))
            return true;
    return false;
}

double largestQuantizationError(const Primitive& primitive, int bits) {
    const DracoGrid grid(primitive, bits);
    const float step = grid.range / grid.levels;
    double largest = 0;
    for (const Triangle& t : primitive.triangles)
        for (std::uint32_t v : t) {
            double squared = 0;
            for (int c = 0; c < 3; ++c) {
                const double error =
                    double(grid.cell(primitive.positions[v], c) * step + grid.minimum[c]) - primitive.positions[v][c];
                squared += error * error;
            }
            largest = std::max(largest, squared);
        }
    return std::sqrt(largest);
}

}  // namespace

int positionBitsFor(const Primitive& primitive, const WriteOptions& options) {
    if (primitive.positionGrid) return primitive.positionGrid->bits;
    const double bound = primitive.maxPositionError > 0 ? primitive.maxPositionError : options.maxPositionError;
    if (!(bound > 0) || primitive.triangles.empty()) return options.positionBits;
    // A corner moves at most half a step on each axis: sqrt(3)/2 of a step. The bits that bound gives
    // always suffice; fewer often do, where the corners lie near the grid's points.
    const Eigen::AlignedBox3d box = [&] {
        Eigen::AlignedBox3d b;
        for (const Triangle& t : primitive.triangles)
            for (std::uint32_t v : t) b.extend(primitive.positions[v]);
        return b;
    }();
    const double range = box.sizes().maxCoeff();
    const int sufficient = std::clamp(int(std::ceil(std::log2(std::sqrt(3.0) / 2 * range / bound + 1))), 1,
                                      kMostPositionBits);
    int bits = std::max(1, sufficient - 3);
    while (bits < kMostPositionBits && largestQuantizationError(primitive, bits) > bound) ++bits;
    // More bits where fewer would collapse triangles, up to the fixed bits (where they collapse anyway).
    while (bits < options.positionBits && collapsesTriangles(primitive, bits)) ++bits;
    return bits;
}

}  // namespace symcompress
