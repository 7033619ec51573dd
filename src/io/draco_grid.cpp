// Draco's quantization grid of a primitive's positions (draco_grid.hpp).
#include "draco_grid.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>

namespace symcompress {
namespace {

// A float as draco::Options keeps it (std::to_string) and reads it back: a vector's components by strtof, a
// single value by atof.
float throughOptionsVector(double value) { return std::strtof(std::to_string(float(value)).c_str(), nullptr); }
float throughOptionsValue(double value) { return float(std::atof(std::to_string(float(value)).c_str())); }

}  // namespace

DracoGrid::DracoGrid(const QuantizationGrid& grid) {
    for (int c = 0; c < 3; ++c) minimum_[c] = throughOptionsVector(grid.origin[c]);
    range_ = throughOptionsValue(grid.range);
    levels_ = float((1u << grid.bits) - 1);
    bits_ = grid.bits;
}

DracoGrid::DracoGrid(const Primitive& primitive, int bits) {
    if (const auto& grid = primitive.positionGrid) {
        *this = DracoGrid(*grid);
        return;
    }
    levels_ = float((1u << bits) - 1);
    bits_ = bits;
    float maximum[3];
    for (int c = 0; c < 3; ++c) minimum_[c] = std::numeric_limits<float>::max(), maximum[c] = -minimum_[c];
    for (const Triangle& t : primitive.triangles)
        for (std::uint32_t v : t)
            for (int c = 0; c < 3; ++c) {
                const float value = float(primitive.positions[v][c]);
                minimum_[c] = std::min(minimum_[c], value);
                maximum[c] = std::max(maximum[c], value);
            }
    range_ = 0;
    for (int c = 0; c < 3; ++c) range_ = std::max(range_, maximum[c] - minimum_[c]);
    if (range_ == 0) range_ = 1;
}

QuantizationGrid DracoGrid::explicitGrid() const {
    return {Eigen::Vector3d(minimum_[0], minimum_[1], minimum_[2]), double(range_), bits_};
}

bool DracoGrid::holds(const Primitive& primitive) const {
    if (!(range_ > 0)) return false;
    return std::all_of(primitive.triangles.begin(), primitive.triangles.end(), [&](const Triangle& t) {
        for (std::uint32_t v : t)
            for (int axis = 0; axis < 3; ++axis) {
                const float q = cell(primitive.positions[v], axis);
                if (!(q >= 0 && q <= levels_)) return false;
            }
        return true;
    });
}

bool DracoGrid::collapses(const Primitive& primitive, const Triangle& t) const {
    const auto& p = primitive.positions;
    return sameCell(p[t[0]], p[t[1]]) || sameCell(p[t[1]], p[t[2]]) || sameCell(p[t[0]], p[t[2]]);
}

}  // namespace symcompress
