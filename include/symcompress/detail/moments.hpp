// Generalized moments of a surface (paper section 4, docs/moments.md):
//   M_2p(w) = integral over S of |s x w|^(2p) ds,  |w| = 1, s measured from the area-weighted centroid,
// and their spherical-harmonic coefficients C(2p; 2l, m) (paper eq. 4), computed exactly from the surface
// integrals of the monomials of degree 2p: no sampling of directions, no rotation per triangle.
#pragma once

#include "symcompress/detail/homogeneous_polynomial.hpp"
#include "symcompress/scene.hpp"

#include <Eigen/Core>

#include <vector>

namespace symcompress {

// Orders 2p = 2, 4, ..., maxOrder are supported up to this.
constexpr int kMaxMomentOrder = 32;

struct MomentOptions {
    int maxOrder = 10;  // even, 2..kMaxMomentOrder
    int threads = 0;    // 0: all cores; meshes below a few thousand triangles use one thread anyway
};

// Surface integrals of the monomials of every even degree 2p <= maxOrder about the centroid.
// Invariant: monomialIntegrals[p - 1] has HomogeneousPolynomial::monomialCount(2p) entries; the integral of
// x^i y^j z^k (i + j + k = 2p) is at HomogeneousPolynomial::monomialIndex(2p, j, k).
struct SurfaceMoments {
    int maxOrder = 0;
    double area = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // area-weighted; the vertex mean when the area is 0
    std::vector<std::vector<double>> monomialIntegrals;

    // The integral over the surface (about the centroid) of a polynomial of even degree 2..maxOrder.
    double integrate(const HomogeneousPolynomial& polynomial) const;
};

// One pass over the triangles for all orders (split over threads for large meshes). Throws
// std::invalid_argument for an unsupported order; an empty mesh gives area 0 and zero integrals.
SurfaceMoments computeSurfaceMoments(const TriangleMesh& mesh, const MomentOptions& options = {});

// C(2p; 2l, m) of paper eq. 4: M_2p(w) = sum over l <= p, |m| <= 2l of C(2p; 2l, m) Y_2l^m(w), with Y as in
// spherical_harmonics.hpp. Invariant: bands[p - 1][l] holds C(2p; 2l, m) at index m + 2l (4l + 1 values).
struct MomentCoefficients {
    int maxOrder = 0;
    double area = 0;
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    std::vector<std::vector<Eigen::VectorXd>> bands;

    double operator()(int order, int band, int m) const { return bands[order / 2 - 1][band / 2][m + band]; }
};

MomentCoefficients momentCoefficients(const SurfaceMoments& moments);
MomentCoefficients computeMomentCoefficients(const TriangleMesh& mesh, const MomentOptions& options = {});

// M_order(w) from the coefficients (w need not be unit: its direction is used).
double evaluateMoment(const MomentCoefficients& coefficients, int order, const Eigen::Vector3d& w);

// The coefficients of the surface Q S (Q orthogonal: rotations and reflections), i.e. of w -> M(Q^T w).
MomentCoefficients transformMomentCoefficients(const MomentCoefficients& coefficients, const Eigen::Matrix3d& q);

// M_2p as the homogeneous polynomial of degree 2p that equals it on the unit sphere, with the derivatives
// along the sphere that the search for critical points (paper Theorem 1) needs.
class MomentFunction {
public:
    MomentFunction(const MomentCoefficients& coefficients, int order);

    int order() const { return polynomial_.degree(); }
    const HomogeneousPolynomial& polynomial() const { return polynomial_; }

    // At a unit direction w.
    double value(const Eigen::Vector3d& w) const { return polynomial_(w); }
    // With `euclidean`, also the gradient in space, which tangentialHessian then need not evaluate again.
    Eigen::Vector3d tangentialGradient(const Eigen::Vector3d& w, Eigen::Vector3d* euclidean = nullptr) const;
    // The Riemannian Hessian as a 3x3 matrix that acts on the tangent plane at w (w is in its kernel).
    Eigen::Matrix3d tangentialHessian(const Eigen::Vector3d& w) const;
    Eigen::Matrix3d tangentialHessian(const Eigen::Vector3d& w, const Eigen::Vector3d& euclideanGradient) const;

    // The root-mean-square variation of the function over the sphere relative to its mean: near 0, the
    // order tells nothing about axes (e.g. M_2 of a cube).
    double relativeVariation() const { return otherBandsNorm_ / bandZeroNorm_; }

    // A bound of the function on the sphere: M_2p(w) = ∫ |s x w|^2p ds <= ∫ |s|^2p ds, which is its mean over
    // the sphere (the band-0 term) times (2p + 1)!! / (2p)!!, the mean of |s x w|^2p / |s|^2p. With room for
    // the rounding of evaluating the polynomial.
    double largestValue() const;

private:
    HomogeneousPolynomial polynomial_;
    HomogeneousPolynomial gradient_[3];
    HomogeneousPolynomial hessian_[3][3];
    double bandZeroNorm_ = 0, otherBandsNorm_ = 0;
};

}  // namespace symcompress
