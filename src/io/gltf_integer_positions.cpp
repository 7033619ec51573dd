#include "gltf_integer_positions.hpp"

#include "common/number_text.hpp"
#include "gltf_instance_encoding.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace symcompress {
namespace {

// How far a viewer puts `p` from where it was, along axis c: the larger of float32's arithmetic (a GPU's) and
// double's (a reader's).
double moved(const Eigen::Vector3d& p, const IntegerPositionGrid& grid, int c) {
    const double q = grid.coordinate(p, c);
    const double inFloat32 = double(float(float(q) * float(grid.step)) + float(grid.origin[c]));
    return std::max(std::abs(inFloat32 - p[c]), std::abs(q * grid.step + grid.origin[c] - p[c]));
}

bool holdsEveryVertex(const Mesh& mesh, const IntegerPositionGrid& grid, double bound) {
    return std::all_of(mesh.primitives.begin(), mesh.primitives.end(), [&](const Primitive& primitive) {
        return std::all_of(primitive.positions.begin(), primitive.positions.end(), [&](const Eigen::Vector3d& p) {
            return Eigen::Vector3d(moved(p, grid, 0), moved(p, grid, 1), moved(p, grid, 2)).norm() <= bound;
        });
    });
}

// Whether meshopt codes the integers smaller than the exponential filter's floats (within `bound`) by more than the
// JSON they add: their view, the extension's names, the node's dequantization. Each in the order it is written in.
bool pays(const Mesh& mesh, const IntegerPositionGrid& grid, double bound) {
    constexpr std::size_t kDequantizationBytes = 60;
    std::size_t onGrid = kOwnViewBytes + kQuantizationNamesBytes + kDequantizationBytes, asFloats = 0;
    for (const Primitive& primitive : mesh.primitives) {
        if (primitive.drawsNothing()) continue;
        const RoundedAttribute integers = integerPositions(spatiallySorted(primitive, &grid), grid);
        onGrid += meshoptEncoded(integers.filtered, integers.elementBytes).size();
        const std::optional<RoundedAttribute> floats = exponentialPositions(spatiallySorted(primitive, nullptr), bound);
        asFloats +=
            floats ? meshoptEncoded(floats->filtered, floats->elementBytes).size() : primitive.positions.size() * 12;
    }
    return onGrid < asFloats;
}

}  // namespace

std::uint32_t IntegerPositionGrid::coordinate(const Eigen::Vector3d& p, int axis) const {
    const double largest = componentBytes == 1 ? 255 : 65535;
    return std::uint32_t(std::clamp(std::round((p[axis] - origin[axis]) / step), 0.0, largest));
}

Eigen::Matrix4d IntegerPositionGrid::dequantization() const {
    Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
    matrix.topLeftCorner<3, 3>() *= step;
    matrix.topRightCorner<3, 1>() = origin;
    return matrix;
}

std::optional<IntegerPositionGrid> integerPositionGridFor(const Mesh& mesh, const WriteOptions& options) {
    double bound = std::numeric_limits<double>::infinity();
    Eigen::AlignedBox3d box;
    for (const Primitive& primitive : mesh.primitives) {
        if (primitive.drawsNothing()) continue;
        if (primitive.topology == Topology::Triangles || !primitive.targets.empty()) return std::nullopt;
        bound = std::min(bound, positionErrorBound(primitive, options));
        for (const Eigen::Vector3d& p : primitive.positions) box.extend(p);
    }
    if (box.isEmpty() || !(bound > 0) || !std::isfinite(bound) || !box.min().allFinite() || !box.max().allFinite())
        return std::nullopt;
    IntegerPositionGrid grid;
    grid.origin = box.min().unaryExpr(&asFloat32);
    // A vertex moves at most half a step along each axis: sqrt(3)/2 of a step in all. float32's rounding of the
    // dequantized value (near a large origin) can take it a little farther: a finer step where it does.
    for (double step = 2 / std::sqrt(3.0) * bound; step > 2 / std::sqrt(3.0) * bound * 0.9; step *= 1 - 1.0 / 256) {
        grid.step = asFloat32(step);
        const double levels = std::ceil(((box.max() - grid.origin).maxCoeff()) / grid.step) + 1;
        if (!(grid.step > 0) || !(levels <= 65536)) return std::nullopt;
        grid.componentBytes = levels <= 256 ? 1 : 2;
        if (holdsEveryVertex(mesh, grid, bound)) return pays(mesh, grid, bound) ? std::optional(grid) : std::nullopt;
    }
    return std::nullopt;
}

RoundedAttribute integerPositions(const Primitive& primitive, const IntegerPositionGrid& grid) {
    RoundedAttribute out;
    out.componentType = grid.componentBytes == 1 ? kUnsignedByte : kUnsignedShort;
    out.filter = "NONE";
    out.components = 3;
    out.elementBytes = std::size_t(grid.componentBytes) * 4;
    out.bits = grid.componentBytes * 8;
    out.filtered.assign(primitive.positions.size() * out.elementBytes, 0);
    for (std::size_t v = 0; v < primitive.positions.size(); ++v)
        for (int c = 0; c < 3; ++c) {
            const std::uint32_t q = grid.coordinate(primitive.positions[v], c);
            out.decoded.push_back(float(q));
            unsigned char* at = out.filtered.data() + v * out.elementBytes + std::size_t(c * grid.componentBytes);
            if (grid.componentBytes == 1) {
                *at = static_cast<unsigned char>(q);
            } else {  // glTF's data is little-endian
                const auto value = static_cast<std::uint16_t>(q);
                at[0] = static_cast<unsigned char>(value & 0xff);
                at[1] = static_cast<unsigned char>(value >> 8);
            }
        }
    return out;
}

}  // namespace symcompress
