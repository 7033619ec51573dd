// The decoder's check: the rebuilt surface against the reference, vertex-to-surface both ways.
#include "symcompress/verify.hpp"

#include "geometry/triangle_bvh.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

namespace symcompress {
namespace {

// The largest distance of a vertex of `from` (one that a triangle uses: a file may list others) to the
// surface `to`.
double farthestVertex(const TriangleMesh& from, const TriangleBvh& to) {
    std::vector<char> used(from.positions.size(), 0);
    for (const Triangle& t : from.triangles) used[t[0]] = used[t[1]] = used[t[2]] = 1;
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, from.positions.size(), 1024), 0.0,
        [&](const tbb::blocked_range<std::size_t>& range, double worst) {
            for (std::size_t i = range.begin(); i != range.end(); ++i)
                if (used[i])
                    worst =
                        std::max(worst, to.squaredDistance(from.positions[i], std::numeric_limits<double>::infinity()));
            return worst;
        },
        [](double a, double b) { return std::max(a, b); });
}

// The area of `from`'s triangles whose centroid has no triangle of `to` facing the same way within
// `distance` (coincident faces of both orientations, as in a two-faced card, count as facing either way).
double flippedArea(const TriangleMesh& from, const TriangleBvh& to, double distance) {
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, from.triangles.size(), 256), 0.0,
        [&](const tbb::blocked_range<std::size_t>& range, double sum) {
            for (std::size_t i = range.begin(); i != range.end(); ++i) {
                const Triangle& t = from.triangles[i];
                const Eigen::Vector3d &a = from.positions[t[0]], &b = from.positions[t[1]], &c = from.positions[t[2]];
                const Eigen::Vector3d normal = (b - a).cross(c - a);
                const double bound = distance * distance;
                if (normal.squaredNorm() > 0 &&
                    !(to.squaredDistance((a + b + c) / 3, bound, nullptr, nullptr, &normal) < bound))
                    sum += 0.5 * normal.norm();
            }
            return sum;
        },
        std::plus<double>());
}

}  // namespace

SurfaceComparison compareSurfaces(const TriangleMesh& rebuilt, const TriangleMesh& reference, double boundsTolerance) {
    SurfaceComparison result;
    const TriangleBvh rebuiltIndex(rebuilt), referenceIndex(reference);
    const double worst = std::max(farthestVertex(rebuilt, referenceIndex), farthestVertex(reference, rebuiltIndex));
    const SurfaceDigest a = digestOf(rebuilt, 0), b = digestOf(reference, 0);
    const double diagonal = b.bounds.isEmpty() ? 0 : b.bounds.diagonal().norm();
    result.maxDeviation = diagonal > 0 ? std::sqrt(worst) / diagonal : 0;
    result.areaRatio = b.area > 0 ? a.area / b.area : 0;
    // A centroid is a little farther from the surface than the vertices: twice the tolerance.
    result.flippedArea =
        a.area > 0 ? flippedArea(rebuilt, referenceIndex,
                                 2 * std::max(boundsTolerance * diagonal, std::sqrt(worst)) + 1e-12 * diagonal) /
                         a.area
                   : 0;
    result.sameBounds = !a.bounds.isEmpty() && !b.bounds.isEmpty() &&
                        (a.bounds.min() - b.bounds.min()).cwiseAbs().maxCoeff() <= boundsTolerance * diagonal &&
                        (a.bounds.max() - b.bounds.max()).cwiseAbs().maxCoeff() <= boundsTolerance * diagonal;
    return result;
}

}  // namespace symcompress
