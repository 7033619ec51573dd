// Triangulation of one planar (or nearly planar) polygon, convex or not.
#pragma once

#include "symcompress/scene.hpp"

#include <vector>

namespace symcompress {

// Triangles over the polygon's corners (indices into `corners`), counter-clockwise in the same sense
// as the polygon's own winding (its Newell normal). Concave polygons are triangulated correctly (ear
// clipping in the polygon's best-fit plane); repeated consecutive corners are skipped. A polygon with
// fewer than 3 distinct corners, or of zero area, gives no triangles.
std::vector<Triangle> triangulatePolygon(const std::vector<Eigen::Vector3d>& corners);

// A face as viewers cut it: a fan from its first corner where the fan covers it (no fan triangle turns against
// the face's Newell normal: a convex face), every triangle kept, those of zero area too, which viewers draw and
// count (n - 2 for n corners, a triangle of zero area as it is); otherwise triangulatePolygon.
std::vector<Triangle> triangulateFace(const std::vector<Eigen::Vector3d>& corners);

}  // namespace symcompress
