// The seed isometry between two congruent tiles (paper 6.3.3): covariant frames of both, every sign and
// order choice, each checked with the d_A-style measure.
#pragma once

#include "symcompress/congruence.hpp"

#include "../symmetry/shape_verifier.hpp"

#include <optional>

namespace symcompress {

struct FoundIsometry {
    Eigen::Matrix3d linear;  // about the centroids: x -> to.center() + linear (x - from.center())
    double deviation = 0;    // absolute d_A
};

// A map from shape `from` onto shape `to` within `tolerance` (absolute), or nothing. Frames come from the
// principal axes of the second moments when they are distinct, and from the critical directions of the
// moment functions and the farthest point across the principal axis.
std::optional<FoundIsometry> findIsometry(const TileShape& from, const ShapeVerifier& fromVerifier, const TileShape& to,
                                          const ShapeVerifier& toVerifier, double tolerance);

}  // namespace symcompress
