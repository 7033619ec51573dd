// Verification of a candidate symmetry on the shape itself (paper 5.3, ALGORITHM.md 5):
//   d_A(S) = max(d_M(S, A S), d_M(A S, S)),  d_M(S, R) = max over sample points p of S of dist(p, R),
// with the vertices and triangle centroids of S as sample points, and a refinement of accepted maps by
// least squares on closest-point correspondences.
#pragma once

#include "triangle_bvh.hpp"

#include <Eigen/Core>

#include <vector>

namespace symcompress {

class ShapeVerifier {
public:
    // The mesh must outlive the verifier; maps are taken about `center`.
    ShapeVerifier(const TriangleMesh& mesh, const Eigen::Vector3d& center);

    // d_A of x -> center + linear (x - center) (linear orthogonal). Stops at the first sample point
    // farther than `reject` and returns that point's distance (> reject).
    double deviation(const Eigen::Matrix3d& linear, double reject) const;

    // The map near `linear` (same determinant) that best fits the data: Gauss-Newton on the point-to-plane
    // distances of the mapped sample points to their closest triangles, which converges in a few steps
    // where point-to-point correspondences would only creep along the surface.
    Eigen::Matrix3d refine(const Eigen::Matrix3d& linear, int steps = 6) const;

    // The unit direction across `axis` (through the center) of the sample point farthest from it.
    Eigen::Vector3d farthestFromAxis(const Eigen::Vector3d& axis) const;

private:
    double farthest(const Eigen::Matrix3d& linear, double reject) const;

    const TriangleMesh& mesh_;
    TriangleBvh bvh_;
    Eigen::Vector3d center_;
    std::vector<Eigen::Vector3d> samples_;  // about center_, in an order that spreads over the shape early
};

}  // namespace symcompress
