#include "plan/region_choice.hpp"

#include "geometry/bounds.hpp"

#include "symcompress/symmetry.hpp"
#include "symcompress/verify.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace symcompress {
namespace {

// The fundamental region of a tile under a group, if its copies rebuild the tile within the tolerance.
std::optional<FundamentalRegion> regionOf(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                          const Eigen::Vector3d& center, double tolerance) {
    try {
        RegionOptions regionOptions;
        // Instances that are signed permutations in the region's frame map Draco's grid onto itself, so
        // seams on coordinate planes stay closed after quantization.
        regionOptions.frame = RegionFrame::Aligned;
        regionOptions.groupTolerance = 1e-5;
        // Float32 coordinates put a symmetric model's vertices on its planes only to about 1e-7 of its size;
        // cut points that close to a vertex become zero-area triangles once quantized, which Draco's
        // edgebreaker cannot keep (the coffee cup's region tripled in size).
        regionOptions.snapTolerance = 1e-6;
        FundamentalRegion region = computeFundamentalRegion(tile, group, center, regionOptions);
        const Primitive rebuilt = rebuildFromRegion(region);
        TriangleMesh a{rebuilt.positions, rebuilt.triangles}, b{tile.positions, tile.triangles};
        const SurfaceComparison check = compareSurfaces(a, b, 1e-6);
        const double diagonal = digestOf(b, 0).bounds.diagonal().norm();
        if (check.maxDeviation * diagonal > tolerance || std::abs(check.areaRatio - 1) > 1e-6) return std::nullopt;
        region.deviation = check.maxDeviation * diagonal;
        return region;
    } catch (const std::invalid_argument&) {
        return std::nullopt;  // a group the region code does not take (e.g. not closed within its tolerance)
    }
}

// The fundamental region of a tile under `group`, on the grid that keeps its seams closed where its frame
// allows: as it would be stored.
std::optional<FundamentalRegion> storableRegion(const RegionCandidate& candidate,
                                                const std::vector<Eigen::Matrix3d>& group) {
    std::optional<FundamentalRegion> region = regionOf(candidate.tile, group, candidate.center, candidate.tolerance);
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
    std::optional<FundamentalRegion> best = storableRegion(candidate, group);
    // Mirrors that hold only within the tolerance (a bolt's helical thread is near a mirror of itself) may
    // leave no region of the whole group; its rotations alone may still rebuild the tile.
    std::vector<Eigen::Matrix3d> rotations;
    for (const Eigen::Matrix3d& g : group)
        if (g.determinant() > 0) rotations.push_back(g);
    if (!best && rotations.size() > 1 && rotations.size() < group.size())
        best = storableRegion(candidate, rotations);
    double bestCost = best ? cost(*best) : std::numeric_limits<double>::infinity();
    auto estimate = [&](std::size_t order) { return tileBytes / double(order) + double(order) * nodeBytes; };
    std::vector<std::vector<std::size_t>> subgroups;
    try {
        subgroups = subgroupsOf(group, 1e-5);
    } catch (const std::invalid_argument&) {
        return {std::move(best), bestCost};  // not closed within the tolerance: the region code refuses it too
    }
    std::map<std::size_t, std::vector<std::vector<Eigen::Matrix3d>>> byOrder;
    for (const auto& h : subgroups) {
        if (h.size() == 1 || h.size() == group.size() || estimate(h.size()) >= std::min(bestCost, toBeat)) continue;
        std::vector<Eigen::Matrix3d> subgroup;
        for (std::size_t e : h) subgroup.push_back(group[e]);
        if (generatedByMirrors(subgroup)) byOrder[h.size()].push_back(std::move(subgroup));
    }
    std::vector<std::size_t> orders;
    for (const auto& entry : byOrder) orders.push_back(entry.first);
    std::sort(orders.begin(), orders.end(), [&](std::size_t a, std::size_t b) { return estimate(a) < estimate(b); });
    for (std::size_t o = 0; o < std::min<std::size_t>(orders.size(), 2); ++o)
        for (std::size_t c = 0; c < std::min<std::size_t>(byOrder[orders[o]].size(), 2); ++c) {
            std::optional<FundamentalRegion> region = storableRegion(candidate, byOrder[orders[o]][c]);
            // A cut splits triangles and puts new vertices mid-edge (decoders comparing vertices see them
            // as deviations): the whole group may cut, a subgroup is chosen only where it cuts nothing.
            if (region && region->trianglesCut == 0 && cost(*region) < bestCost)
                bestCost = cost(*region), best = std::move(region);
        }
    return {std::move(best), bestCost};
}

}  // namespace symcompress
