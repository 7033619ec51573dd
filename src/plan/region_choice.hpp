// The choice of a class's fundamental region: of its whole group or of a subgroup, on the grid that keeps
// its seams closed, whichever costs least as written (docs/compression-plan.md, "Fundamental regions").
#pragma once

#include "plan/storage_costs.hpp"
#include "symcompress/detail/fundamental_region.hpp"

#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace symcompress {

// What a region costs and which tile it stands for.
struct RegionCandidate {
    const Primitive& tile;
    const std::vector<Eigen::Matrix3d>& group;  // the tile's symmetries that carry its attributes too
    Eigen::Vector3d center;
    double tolerance = 0;  // a distance: the region's copies must rebuild the tile within it
    int seamGridBits = 0;  // StorageCostModel::seamGridBits
    // > 0: the distance the region's own deviation and its grid's quantization share (what the budget
    // leaves after the class's placements): the grid is then the coarsest within what is left, in place of
    // seamGridBits.
    double seamGridError = 0;
    double seamGridRelativeError = 0;  // StorageCostModel::seamGridRelativeError
    // Whether the whole group's region may cut triangles where the tessellation does not let it keep them
    // whole (PlanOptions::cutTriangles); a subgroup's region always keeps them whole.
    bool cutTriangles = false;
};

// The fundamental region that stores a class's copies in the fewest bytes, of G itself or of a subgroup H
// of G, and what it costs (`nodes` prices the nodes that draw a region's copies in every tile). A region of
// H is about 1/|H| of the tile and costs |H| nodes a copy, so the best |H| balances mesh and nodes: a
// 960-triangle sphere (D32h) drawn once is not worth 128 nodes, but may be worth 4. A region keeps the
// tile's triangles whole (its copies draw the tile's own triangles), so H must map the triangles onto one
// another and fix none: a geodesic sphere's Ih fixes the triangles on its 3-fold axes and mirrors, its D5
// none. Subgroups are tried only where their estimate (tileBytes / |H| + |H| nodeBytes) beats `toBeat`, in
// the order of their estimates, and only the first few that keep the triangles whole: nothing is tried for
// a class whose nodes would cost more than a region saves.
std::pair<std::optional<FundamentalRegion>, double> cheapestRegion(
    const RegionCandidate& candidate, StorageCosts& costs, double tileBytes, double nodeBytes, double toBeat,
    const std::function<double(const FundamentalRegion&)>& nodes);

}  // namespace symcompress
