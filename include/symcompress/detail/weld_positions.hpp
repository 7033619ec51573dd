// Welding: the vertices of a point list that lie within a tolerance of each other, under one index.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace symcompress {

// Representative index of every position after welding within `tolerance` (absolute): points closer than
// the tolerance to an earlier representative take its index. Order-dependent for chains of points each
// within the tolerance of the next, which is harmless for the tiny tolerances used for welding.
std::vector<std::uint32_t> weldPositions(const std::vector<Eigen::Vector3d>& positions, double tolerance);
// The same for points kept elsewhere (the tiles' split welds the soup's positions without copying them).
std::vector<std::uint32_t> weldPositions(const std::vector<const Eigen::Vector3d*>& positions, double tolerance);

}  // namespace symcompress
