// The bounding box of a point list, and of the corners of a triangle list (vertices no triangle uses left
// out): the one helper the stages measure sizes and diagonals with.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Geometry>

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

}  // namespace symcompress
