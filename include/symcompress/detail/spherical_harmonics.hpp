// Real spherical harmonics in the paper's normalization (section 4.3), orthonormal on the unit sphere:
//   Y_l^m = sqrt(2) N_l^m P_l^m(cos t) cos(m f)         0 < m <= l
//   Y_l^0 = N_l^0 P_l(cos t)
//   Y_l^m = sqrt(2) N_l^|m| P_l^|m|(cos t) sin(|m| f)    -l <= m < 0
//   N_l^m = sqrt((2l + 1) / (4 pi) * (l - m)! / (l + m)!)
// with P_l^m(x) = (1 - x^2)^(m/2) d^m/dx^m P_l(x), WITHOUT the Condon-Shortley phase (-1)^m.
// Coefficients of band l are indexed by shIndex(l, m) = l^2 + l + m, m = -l..l.
#pragma once

#include "symcompress/detail/homogeneous_polynomial.hpp"

#include <Eigen/Core>

#include <vector>

namespace symcompress {

inline int shIndex(int l, int m) { return l * l + l + m; }
inline int shCount(int maxDegree) { return (maxDegree + 1) * (maxDegree + 1); }

// Y_l^m(w / |w|) for every l <= maxDegree, at shIndex(l, m). w must not be zero.
std::vector<double> evaluateSphericalHarmonics(int maxDegree, const Eigen::Vector3d& w);

// The solid harmonic |s|^l Y_l^m(s / |s|): a homogeneous polynomial of degree l.
HomogeneousPolynomial solidHarmonic(int l, int m);

// The (2l + 1)-square matrix D with: if f = sum_m c_m Y_l^m, then f(Q^T w) = sum_m (D c)_m Y_l^m(w), for any
// orthogonal Q (rotations and reflections). Computed exactly by quadrature on the sphere (Gauss-Legendre
// in cos t times a uniform rule in f, exact for the degree-2l products involved): an exact equivalent
// of the Ivanic-Ruedenberg recurrences with no convention to get wrong.
Eigen::MatrixXd shRotationMatrix(int l, const Eigen::Matrix3d& orthogonal);

// Gauss-Legendre nodes and weights on [-1, 1]: exact for polynomials of degree <= 2 * count - 1.
void gaussLegendre(int count, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace symcompress
