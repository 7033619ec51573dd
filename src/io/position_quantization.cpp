// The position bits of a Draco-compressed primitive: fixed (WriteOptions::positionBits), or the fewest that
// keep every corner within an error bound and collapse no triangle, found by quantizing the corners as Draco
// does (DracoGrid); and the other bits and speeds worth encoding a small primitive with.
#include "draco_grid.hpp"
#include "geometry/bounds.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene_ops.hpp"

#include <algorithm>
#include <cmath>

namespace symcompress {
namespace {

constexpr int kMostPositionBits = 24;  // a float32's mantissa: more bits cannot place a corner closer
// The most triangles of a primitive encoded again with more bits or at other speeds (positionBitsWorthTrying,
// dracoSpeedsWorthTrying): each trial is an encoding, and the plan measures parts by the writer.
constexpr std::size_t kMostTriedTriangles = 20000;

// The largest distance a corner moves through Draco's position quantization at `bits`, over the corners of the
// triangles, less what float32 cannot tell apart: the corners are float32 in the input and in the decoder,
// whose measure of the move (the bunny's 8.12197e-6 at 14 bits, against a bound of 8.12174e-6 at the peers'
// own deviation) is only as exact as half a unit in the last place of the corner's largest coordinate.
double largestQuantizationError(const Primitive& primitive, const DracoGrid& grid) {
    double largest = 0;
    for (const Triangle& t : primitive.triangles)
        for (std::uint32_t v : t) {
            const Eigen::Vector3d& p = primitive.positions[v];
            double squared = 0;
            for (int c = 0; c < 3; ++c) {
                const double error = grid.dequantized(p, c) - p[c];
                squared += error * error;
            }
            const double unresolved = p.cwiseAbs().maxCoeff() * std::ldexp(1.0, -24);  // half a float32 ulp
            const double moved = std::sqrt(squared) - unresolved;
            if (!(moved <= largest)) largest = std::isnan(moved) ? HUGE_VAL : moved;
        }
    return std::max(largest, 0.0);
}

// Whether some triangle with three distinct corners has two in one cell at `bits`: edgebreaker drops it, and
// the writer stores it in a sequential primitive of its own, which costs more than the bits saved. (Triangles
// with two corners at one point collapse at any bits; the writer keeps those apart, at one point.)
bool collapsesTriangles(const Primitive& primitive, const DracoGrid& grid) {
    const auto& p = primitive.positions;
    return std::any_of(primitive.triangles.begin(), primitive.triangles.end(), [&](const Triangle& t) {
        return !hasTwoCornersAtOnePoint(p, t) && grid.collapses(primitive, t);
    });
}

}  // namespace

double positionErrorBound(const Primitive& primitive, const WriteOptions& options) {
    const double bound = primitive.maxPositionError > 0 ? primitive.maxPositionError : options.maxPositionError;
    if (!(bound > 0)) return 0;  // fixed bits: the relative bound only tightens a bound
    if (!(options.maxRelativePositionError > 0) || primitive.drawsNothing()) return bound;
    // Lines and points: the box of every vertex (a line's, a point's).
    const double diagonal = primitive.closeUpDiagonal > 0 ? primitive.closeUpDiagonal
                            : primitive.topology != Topology::Triangles
                                ? boundsOf(primitive.positions).diagonal().norm()
                                : boundsOfCorners(primitive.positions, primitive.triangles).diagonal().norm();
    return std::min(bound, options.maxRelativePositionError * diagonal);
}

std::vector<int> positionBitsWorthTrying(const Primitive& primitive, const WriteOptions& options, int fewest) {
    std::vector<int> more;
    if (!options.encodingTrials || primitive.positionGrid || primitive.triangles.size() > kMostTriedTriangles)
        return more;
    const double bound = positionErrorBound(primitive, options);
    if (!(bound > 0)) return more;
    for (int bits = fewest + 1; bits <= std::min(fewest + 2, kMostPositionBits); ++bits)
        if (largestQuantizationError(primitive, DracoGrid(primitive, bits)) <= bound) more.push_back(bits);
    return more;
}

std::vector<int> dracoSpeedsWorthTrying(const Primitive& primitive, const WriteOptions& options) {
    const int asked = std::clamp(10 - options.compressionLevel, 0, 10);
    if (!options.encodingTrials || asked != 0 || primitive.triangles.size() > kMostTriedTriangles) return {asked};
    // Speeds 2-3 and 8-10 encode alike (measured on the shared models); speed 0 first, the best on most.
    return {0, 1, 2, 5, 8};
}

int positionBitsFor(const Primitive& primitive, const WriteOptions& options) {
    if (primitive.positionGrid) return primitive.positionGrid->bits;
    const double bound = positionErrorBound(primitive, options);
    if (!(bound > 0) || primitive.triangles.empty()) return options.positionBits;
    // A corner moves at most half a step on each axis: sqrt(3)/2 of a step. The bits that bound gives
    // always suffice; fewer often do, where the corners lie near the grid's points.
    const double range = boundsOfCorners(primitive.positions, primitive.triangles).sizes().maxCoeff();
    const int sufficient = std::clamp(int(std::ceil(std::log2(std::sqrt(3.0) / 2 * range / bound + 1))), 1,
                                      kMostPositionBits);
    int bits = std::max(1, sufficient - 3);
    while (bits < kMostPositionBits && largestQuantizationError(primitive, DracoGrid(primitive, bits)) > bound) ++bits;
    // More bits where fewer would collapse triangles, up to the fixed bits (where they collapse anyway).
    while (bits < options.positionBits && collapsesTriangles(primitive, DracoGrid(primitive, bits))) ++bits;
    return bits;
}

std::optional<QuantizationGrid> coarserPositionGrid(const Primitive& primitive, const WriteOptions& options, int bits) {
    if (!options.encodingTrials || primitive.positionGrid || primitive.triangles.size() > kMostTriedTriangles)
        return std::nullopt;
    const double bound = positionErrorBound(primitive, options);
    if (!(bound > 0)) return std::nullopt;
    const QuantizationGrid own = DracoGrid(primitive, bits).explicitGrid();
    // Steps 2^(k/8) times the grid's own, the longest first: 2^(8/8) would be one bit fewer, which the bound refused.
    for (int k = 7; k >= 1; --k) {
        QuantizationGrid coarser = own;
        coarser.range = double(float(own.range * std::exp2(k / 8.0)));
        const DracoGrid grid(coarser);
        if (grid.holds(primitive) && largestQuantizationError(primitive, grid) <= bound &&
            !collapsesTriangles(primitive, grid))
            return coarser;
    }
    return std::nullopt;
}

}  // namespace symcompress
