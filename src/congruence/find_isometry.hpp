// The seed isometry between two congruent tiles (paper 6.3.3): covariant frames of both, every sign and
// order choice, each checked with the d_A-style measure.
#pragma once

#include "symcompress/congruence.hpp"

#include "geometry/shape_verifier.hpp"

#include <map>
#include <mutex>
#include <optional>
#include <vector>

namespace symcompress {

struct FoundIsometry {
    Eigen::Matrix3d linear;  // about the centroids: x -> to.center() + linear (x - from.center())
    double deviation = 0;    // absolute d_A
};

// What the search needs of one tile, kept across every pair the tile takes part in: its verifier, and the
// critical directions of each order's moment function (Newton from many starts: found once per tile, on
// `threads` threads, 0: all cores). Several pairs may ask one probe at once.
class TileProbe {
public:
    TileProbe(const TriangleMesh& mesh, const Eigen::Vector3d& centroid, int threads)
        : verifier_(mesh, centroid), threads_(threads) {}
    const ShapeVerifier& verifier() const { return verifier_; }
    const std::vector<Eigen::Vector3d>& criticalDirections(const MomentFunction& f, int order);

private:
    ShapeVerifier verifier_;
    int threads_;
    std::mutex mutex_;  // over directions_
    std::map<int, std::vector<Eigen::Vector3d>> directions_;  // by order
};

// A map from shape `from` onto shape `to` within `tolerance` (absolute), or nothing. Frames come from the
// principal axes of the second moments when they are distinct; about a lone principal axis, from the phase of the
// moment functions' Fourier modes on rings about it; else from the critical directions of the moment functions;
// and from the farthest point across the principal axis (docs/congruence.md).
std::optional<FoundIsometry> findIsometry(const TileShape& from, TileProbe& fromProbe, const TileShape& to, TileProbe& toProbe,
                                          double tolerance);

}  // namespace symcompress
