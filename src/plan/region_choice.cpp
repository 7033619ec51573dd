#include "plan/region_choice.hpp"

#include "geometry/bounds.hpp"

#include "symcompress/symmetry.hpp"
#include "symcompress/verify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace symcompress {
namespace {

// The options the plan computes its regions with, for a tile: the same for every group it tries.
RegionOptions regionOptionsFor(const Primitive& tile, const Eigen::Vector3d& center, double tolerance) {
    RegionOptions options;
    // Instances that are signed permutations in the region's frame map Draco's grid onto itself, so
    // seams on coordinate planes stay closed after quantization.
    options.frame = RegionFrame::Aligned;
    options.groupTolerance = 1e-5;
    // Float32 coordinates put a symmetric model's vertices on its planes only to about 1e-7 of its size;
    // cut points that close to a vertex become zero-area triangles once quantized, which Draco's
    // edgebreaker cannot keep (the coffee cup's region tripled in size).
    options.snapTolerance = 1e-6;
    // A vertex's image is the vertex within the tolerance (a torus knot's turns agree only to 7e-6 of its
    // diagonal), but within a quarter of the shortest edge, so that no two vertices of a small tile are one.
    double radius = 0, shortestEdge = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : tile.positions) radius = std::max(radius, (p - center).norm());
    for (const Triangle& t : tile.triangles)
        for (int k = 0; k < 3; ++k)
            if (const double edge = (tile.positions[t[k]] - tile.positions[t[(k + 1) % 3]]).norm(); edge > 0)
                shortestEdge = std::min(shortestEdge, edge);
    if (radius > 0)
        options.vertexTolerance = std::max(std::min(tolerance, shortestEdge / 4) / radius, options.snapTolerance);
    return options;
}

// The fundamental region of a tile under a group, if its copies rebuild the tile within the tolerance.
std::optional<FundamentalRegion> regionOf(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                          const Eigen::Vector3d& center, double tolerance, RegionOptions regionOptions,
                                          RegionTriangles triangles) {
    try {
        regionOptions.triangles = triangles;
        FundamentalRegion region = computeFundamentalRegion(tile, group, center, regionOptions);
        const Primitive rebuilt = rebuildFromRegion(region);
        TriangleMesh a{rebuilt.positions, rebuilt.triangles}, b{tile.positions, tile.triangles};
        const SurfaceComparison check = compareSurfaces(a, b, 1e-6);
        const double diagonal = digestOf(b, 0).bounds.diagonal().norm();
        if (check.maxDeviation * diagonal > tolerance || std::abs(check.areaRatio - 1) > 1e-6) return std::nullopt;
        region.deviation = check.maxDeviation * diagonal;
        return region;
    } catch (const std::invalid_argument&) {
        // A group the region code does not take (e.g. not closed within its tolerance), or one that cannot
        // keep the triangles whole.
        return std::nullopt;
    }
}

// The fundamental region of a tile under `group`, on the grid that keeps its seams closed where its frame
// allows: as it would be stored.
std::optional<FundamentalRegion> storableRegion(const RegionCandidate& candidate, const RegionOptions& options,
                                                const std::vector<Eigen::Matrix3d>& group, RegionTriangles triangles) {
    std::optional<FundamentalRegion> region =
        regionOf(candidate.tile, group, candidate.center, candidate.tolerance, options, triangles);
    if (region && candidate.seamGridBits > 0 && region->signedPermutationFrame) {
        double left = candidate.seamGridError - region->deviation;  // for the grid, of the budget
        if (candidate.seamGridError > 0 && !(left > 0)) return std::nullopt;
        if (candidate.seamGridRelativeError > 0)
            left = std::min(left,
                            candidate.seamGridRelativeError *
                                boundsOfCorners(candidate.tile.positions, candidate.tile.triangles).diagonal().norm());
        RegionInGridSteps onGrid =
            inGridSteps(*region, candidate.seamGridError > 0 ? seamPreservingGridWithin(*region, left)
                                                             : seamPreservingGrid(*region, candidate.seamGridBits));
        region = std::move(onGrid.region);
        region->region.positionGrid = onGrid.grid;
    }
    return region;
}

}  // namespace

std::pair<std::optional<FundamentalRegion>, double> cheapestRegion(
    const RegionCandidate& candidate, StorageCosts& costs, double tileBytes, double nodeBytes, double toBeat,
    const std::function<double(const FundamentalRegion&)>& nodes) {
    const std::vector<Eigen::Matrix3d>& group = candidate.group;
    auto cost = [&](const FundamentalRegion& r) { return costs.asMesh(r.region) + nodes(r); };
    const RegionOptions options = regionOptionsFor(candidate.tile, candidate.center, candidate.tolerance);
    const RegionTriangles whole = candidate.cutTriangles ? RegionTriangles::WholeWherePossible : RegionTriangles::Whole;
    std::optional<FundamentalRegion> best = storableRegion(candidate, options, group, whole);
    // Mirrors that hold only within the tolerance (a bolt's helical thread is near a mirror of itself) may
    // leave no region of the whole group; its rotations alone may still rebuild the tile.
    std::vector<Eigen::Matrix3d> rotations;
    for (const Eigen::Matrix3d& g : group)
        if (g.determinant() > 0) rotations.push_back(g);
    if (!best && rotations.size() > 1 && rotations.size() < group.size())
        best = storableRegion(candidate, options, rotations, whole);
    double bestCost = best ? cost(*best) : std::numeric_limits<double>::infinity();
    auto estimate = [&](std::size_t order) { return tileBytes / double(order) + double(order) * nodeBytes; };
    // A subgroup's order divides the group's: where no divisor's estimate beats the cost to beat, no subgroup's
    // does, and the subgroups are not sought (C360v's 1194: 0.6 s).
    double leastEstimate = std::numeric_limits<double>::infinity();
    for (std::size_t order = 1; order <= group.size(); ++order)
        if (group.size() % order == 0) leastEstimate = std::min(leastEstimate, estimate(order));
    if (leastEstimate >= std::min(bestCost, toBeat)) return {std::move(best), bestCost};
    std::vector<std::vector<std::size_t>> subgroups;
    try {
        subgroups = subgroupsOf(group, 1e-5);
    } catch (const std::invalid_argument&) {
        return {std::move(best), bestCost};  // not closed within the tolerance: the region code refuses it too
    }
    std::stable_sort(subgroups.begin(), subgroups.end(),
                     [&](const auto& a, const auto& b) { return estimate(a.size()) < estimate(b.size()); });
    // Most subgroups of a large group fix some triangle and fail at once (in time linear in |H| and the
    // tile's vertices); a region is made for the first few that do not.
    constexpr std::size_t kRegionsTried = 4, kSubgroupsExamined = 64;
    std::size_t tried = 0, examined = 0;
    for (const std::vector<std::size_t>& h : subgroups) {
        if (tried == kRegionsTried || examined == kSubgroupsExamined ||
            estimate(h.size()) >= std::min(bestCost, toBeat))
            break;
        if (h.size() == 1 || h.size() == group.size()) continue;
        ++examined;
        std::vector<Eigen::Matrix3d> subgroup;
        for (std::size_t e : h) subgroup.push_back(group[e]);
        // Where the copies do not draw the tile's own triangles, a rotation's seam can meet its copy at
        // T-junctions, which quantization opens; a mirror's seam meets its image vertex for vertex.
        std::optional<FundamentalRegion> region =
            storableRegion(candidate, options, subgroup,
                           generatedByMirrors(subgroup) ? RegionTriangles::Whole : RegionTriangles::OneOfEachOrbit);
        if (!region) continue;
        ++tried;
        if (cost(*region) < bestCost) bestCost = cost(*region), best = std::move(region);
    }
    return {std::move(best), bestCost};
}

}  // namespace symcompress
