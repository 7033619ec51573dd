// How far apart two unit quaternions' values are as rotations: a rotation is q or -q, so the nearer of the two.
#pragma once

#include <algorithm>
#include <cmath>

namespace symcompress {

// The largest difference of a component (x y z w) between `a` and `b` or `-b`, whichever is nearer.
inline double quaternionDifference(const double* a, const double* b) {
    double same = 0, opposite = 0;
    for (int c = 0; c < 4; ++c) {
        same = std::max(same, std::abs(a[c] - b[c]));
        opposite = std::max(opposite, std::abs(a[c] + b[c]));
    }
    return std::min(same, opposite);
}

}  // namespace symcompress
