// Candidate symmetry axes (paper 5.1, docs/symmetry.md §1): the critical points of the moment functions on
// the sphere, which contain every rotation axis and mirror normal (paper Theorem 1).
#pragma once

#include "symcompress/detail/moments.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace symcompress {

// Critical points of each function, from Newton's method on the tangential gradient started at points
// spread over a hemisphere; one direction per axis (w and -w are the same), merged across functions
// when closer than mergeAngle (radians). The searches run on `threads` threads (0: all cores); the axes
// are the same whatever their number.
std::vector<Eigen::Vector3d> findCandidateAxes(const std::vector<MomentFunction>& functions, double mergeAngle,
                                               int threads);

// Whether principal second moments (ascending) are so far apart (relative to the largest, and in units of
// the tolerance relative to the shape's size) that no asymmetry within the tolerance can make two equal:
// every symmetry, and every map onto a congruent shape, then takes principal axes onto principal axes,
// so those three are the only candidates.
inline bool principalAxesAreCertain(const Eigen::Vector3d& ascending, double relativeTolerance) {
    const double gap = std::min(ascending[1] - ascending[0], ascending[2] - ascending[1]);
    return gap > std::max(1e-3, 50 * relativeTolerance) * std::abs(ascending[2]);
}

}  // namespace symcompress
