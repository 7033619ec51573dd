// Draco's quantization grid of a primitive's positions, in float32 as Draco computes it: the primitive's own
// grid where it has one (Primitive::positionGrid), else the box of its triangles' corners with its largest
// side cut into 2^bits - 1 steps. The writer asks it which bits keep the corners within a bound and which
// triangles edgebreaker would drop.
//
// An explicit grid reaches Draco's encoder as text: ExpertEncoder::SetAttributeExplicitQuantization keeps origin
// and range in draco::Options, which print them with std::to_string, six decimals (libdraco 1.5.5). A grid is
// taken here as Draco reads it back: on a scene 1e-7 across a range reads as 0 and every corner decodes to the
// origin; at 1e-5 the range grows by a tenth.
#pragma once

#include "symcompress/scene.hpp"

#include <cmath>

namespace symcompress {

class DracoGrid {
public:
    DracoGrid(const Primitive& primitive, int bits);
    explicit DracoGrid(const QuantizationGrid& grid);  // as Draco reads it back

    // Whether every corner of the primitive's triangles lies within the grid's levels on a grid of some extent.
    bool holds(const Primitive& primitive) const;

    // The grid as an explicit quantization: the box's corner, its largest side, the bits.
    QuantizationGrid explicitGrid() const;

    // The cell of p on `axis` (a float32 integer), and where Draco's decoder puts it back.
    float cell(const Eigen::Vector3d& p, int axis) const {
        return std::floor((float(p[axis]) - minimum_[axis]) * (levels_ / range_) + 0.5f);
    }
    double dequantized(const Eigen::Vector3d& p, int axis) const {
        return double(cell(p, axis) * (range_ / levels_) + minimum_[axis]);
    }
    // Whether two of the triangle's corners fall in one cell: edgebreaker drops such a triangle.
    bool collapses(const Primitive& primitive, const Triangle& t) const;

private:
    bool sameCell(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
        return cell(a, 0) == cell(b, 0) && cell(a, 1) == cell(b, 1) && cell(a, 2) == cell(b, 2);
    }
    float minimum_[3] = {0, 0, 0};
    float range_ = 1, levels_ = 1;
    int bits_ = 0;
};

}  // namespace symcompress
