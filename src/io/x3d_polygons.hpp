// Triangles written back as the polygons they were cut from, for X3D's IndexedFaceSet: a run of consecutive
// triangles that fan from one corner ((a b c) (a c d) (a d e), as the reader cuts a convex face, and as browsers
// cut a face set's polygon, convex='TRUE') joined into one convex, planar polygon (a b c d e). A browser cuts it
// into the same triangles again, so what it draws, the attributes interpolated over each, does not change; one
// face of n corners takes n + 1 indices where its n - 2 triangles take 3n - 6.
#pragma once

#include "symcompress/scene.hpp"

#include <cstdint>
#include <vector>

namespace symcompress::x3d {

// The triangles in order, each joined to the polygon before it where that stays a fan, convex, and within
// `maxTurn` radians of the plane of its first triangle (a triangle's normal turned by at most that from the first
// one's); a triangle that joins none is a polygon of 3 corners. Flat faces need them planar (the browser shades a
// face by one normal); faces whose normals the browser averages at their points can bend, where the writer checks
// what those normals come to.
// A flat face: its normal within 1e-3 radians of each triangle's, below what GLB output's 10-bit normals and the
// writer's crease match (3.5e-3) allow. A smoothed one: up to a quarter turn, the writer's match deciding.
inline constexpr double kMostTurnOfFlatPolygon = 1e-3;
inline constexpr double kMostTurnOfSmoothedPolygon = 1.5707963267948966;

std::vector<std::vector<std::uint32_t>> fanPolygons(const std::vector<Triangle>& triangles,
                                                    const std::vector<Eigen::Vector3d>& positions, double maxTurn);

}  // namespace symcompress::x3d
