// The bounding box of a point list, and of the corners of a triangle list (vertices no triangle uses left
// out): the one helper the stages measure sizes and diagonals with.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

namespace symcompress {

inline Eigen::AlignedBox3d boundsOf(const std::vector<Eigen::Vector3d>& points) {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : points) box.extend(p);
    return box;
}

inline Eigen::AlignedBox3d boundsOfCorners(const std::vector<Eigen::Vector3d>& positions,
                                           const std::vector<Triangle>& triangles) {
    Eigen::AlignedBox3d box;
    for (const Triangle& t : triangles)
        for (std::uint32_t v : t) box.extend(positions[v]);
    return box;
}

// Of a mesh's error bound, the most that float32's rounding of its coordinates may take (centreIfFloat32RoundsBeyond).
constexpr double kFloat32RoundingShare = 1.0 / 16;

// The centre of `box` where float32 (in which glTF, Draco and X3D store coordinates) would round its farthest
// corner by more than `allowed` (half float32's spacing on each axis), else zero: coordinates taken about the
// centre round finer, and the translation back is a double in the node that draws them.
inline Eigen::Vector3d centreIfFloat32RoundsBeyond(const Eigen::AlignedBox3d& box, double allowed) {
    if (box.isEmpty()) return Eigen::Vector3d::Zero();
    const double largest = box.min().cwiseAbs().cwiseMax(box.max().cwiseAbs()).maxCoeff();
    if (!(largest > 0) || std::sqrt(3.0) / 2 * std::ldexp(1.0, std::ilogb(largest) - 23) <= allowed)
        return Eigen::Vector3d::Zero();
    return box.center();
}

}  // namespace symcompress
