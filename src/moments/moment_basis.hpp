// The fixed linear map between monomial integrals and moment coefficients, shared by every surface.
#pragma once

#include "symcompress/detail/homogeneous_polynomial.hpp"

#include <vector>

namespace symcompress {

// For every order 2p <= maxOrder and band 2l <= 2p:
//   harmonics[p - 1][l][m + 2l] = |s|^(2p - 2l) * |s|^(2l) Y_2l^m(s / |s|)   (degree 2p; equals Y_2l^m on the sphere)
//   zonalFactor[p - 1][l] = S(l, p) * sqrt(4 pi / (4l + 1)) = 2 pi * integral_{-1}^{1} (1 - x^2)^p P_2l(x) dx
// so that C(2p; 2l, m) = zonalFactor * integral over S of harmonics[p - 1][l][m + 2l]   (docs/moments.md, "Definitions").
struct MomentBasis {
    int maxOrder = 0;
    std::vector<std::vector<std::vector<HomogeneousPolynomial>>> harmonics;
    std::vector<std::vector<double>> zonalFactor;
};

// Built once per order on first use and shared (immutable, safe to use from any thread).
const MomentBasis& momentBasis(int maxOrder);

// Throws std::invalid_argument unless maxOrder is even and within 2..kMaxMomentOrder.
void checkMomentOrder(int maxOrder);

}  // namespace symcompress
