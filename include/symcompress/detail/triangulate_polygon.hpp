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

}  // namespace symcompress
