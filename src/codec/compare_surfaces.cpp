// The decoder's check: the rebuilt surface against the reference, vertex-to-surface both ways.
#include "symcompress/compress.hpp"

#include "../symmetry/triangle_bvh.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
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
                if (used[i]) worst = std::max(worst, to.squaredDistance(from.positions[i], std::numeric_limits<double>::infinity()));
            return worst;
        },
        [](double a, double b) { return std::max(a, b); });
}

double areaOf(const TriangleMesh& mesh) {
    double area = 0;
    for (const Triangle& t : mesh.triangles)
        area += 0.5 * (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
    return area;
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
    result.sameBounds = !a.bounds.isEmpty() && !b.bounds.isEmpty() &&
                        (a.bounds.min() - b.bounds.min()).cwiseAbs().maxCoeff() <= boundsTolerance * diagonal &&
                        (a.bounds.max() - b.bounds.max()).cwiseAbs().maxCoeff() <= boundsTolerance * diagonal;
    return result;
}

}  // namespace symcompress
