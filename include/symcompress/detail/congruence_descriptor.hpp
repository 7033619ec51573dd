// The congruence descriptor of paper eq. 9-10: band energies of the moment coefficients, invariant under
// rotations, reflections and translations.
#pragma once

#include "symcompress/detail/moments.hpp"

#include <vector>

namespace symcompress {

// Normalization: the energy d(2k; 2l) = sum_m C(2k; 2l, m)^2 scales like size^(2(2k + 2)). Each is stored as
//   shape = sqrt(d(2k; 2l)) / (area * rmsRadius^(2k)),
// which is dimensionless and of order 1 for any tile, with the size kept apart in `area` and `rmsRadius`
// (rmsRadius^2 = integral of |s|^2 ds / area). So one relative tolerance compares tiles of any size, and
// scaled copies differ in area and rmsRadius while their shapes agree.
// Invariant: shape lists the bands in order of k, then l: (k = 1: l = 0, 1), (k = 2: l = 0, 1, 2), ...;
// bandCount(maxOrder) entries.
struct CongruenceDescriptor {
    int maxOrder = 0;
    double area = 0;
    double rmsRadius = 0;
    std::vector<double> shape;

    static int bandCount(int maxOrder) {
        const int k = maxOrder / 2;
        return k * (k + 3) / 2;  // sum over k' = 1..k of (k' + 1)
    }
};

CongruenceDescriptor computeCongruenceDescriptor(const MomentCoefficients& coefficients);

// The largest relative difference: |area| and |rmsRadius| relative to the larger of the two, and each order's
// shape entries relative to the largest entry of that order in either descriptor. Two congruent tiles give
// a difference at rounding level; the descriptors must have the same maxOrder.
double descriptorDifference(const CongruenceDescriptor& a, const CongruenceDescriptor& b);

}  // namespace symcompress
