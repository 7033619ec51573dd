// Verification of a candidate symmetry on the shape itself (paper 5.3, docs/symmetry.md §3):
//   d_A(S) = max(d_M(S, A S), d_M(A S, S)),  d_M(S, R) = max over sample points p of S of dist(p, R),
// with the vertices of S as sample points (and the triangle centroids too for meshes of up to
// kCentroidSamplesUpTo triangles, which catches differently split quads), and a refinement of accepted maps by
// least squares on closest-point correspondences.
#pragma once

#include "triangle_bvh.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace symcompress {

constexpr std::size_t kCentroidSamplesUpTo = 100000;

// Sample points that rejected recent maps (indices, most recent first): a near miss tends to fail where
// the last one did, so a search that is given them asks them first. Only the verdict is the same with and
// without them: a rejected map's returned distance is then the first hint's beyond the rejection distance,
// not the first point's in the samples' order. One per thread of work.
class RejectingPoints {
public:
    const std::vector<std::uint32_t>& indices() const { return indices_; }
    void remember(std::uint32_t index);

private:
    static constexpr std::size_t kCapacity = 8;
    std::vector<std::uint32_t> indices_;
};

class ShapeVerifier {
public:
    // The mesh must outlive the verifier; maps are taken about `center`.
    ShapeVerifier(const TriangleMesh& mesh, const Eigen::Vector3d& center);

    // d_A of x -> center + linear (x - center) (linear orthogonal), over the first `points` sample points
    // (all by default; the order spreads them over the shape). Stops at the first sample point farther
    // than `reject` and returns that point's distance (> reject).
    double deviation(const Eigen::Matrix3d& linear, double reject, std::size_t points = SIZE_MAX,
                     RejectingPoints* hints = nullptr) const;

    // The map near `linear` (same determinant) that best fits the data: Gauss-Newton on the point-to-plane
    // distances of the mapped sample points to their closest triangles, which converges in a few steps
    // where point-to-point correspondences would only creep along the surface. Points with no triangle
    // within searchRadius are left out; at most the first `points` sample points are used.
    Eigen::Matrix3d refine(const Eigen::Matrix3d& linear, double searchRadius, int steps = 6,
                           std::size_t points = SIZE_MAX) const;

    // The same between two shapes: the map best taking this shape's sample points onto target's surface,
    // maps taken from this shape's center to target's.
    Eigen::Matrix3d refineOnto(const ShapeVerifier& target, const Eigen::Matrix3d& linear, double searchRadius,
                               int steps = 6, std::size_t points = SIZE_MAX) const;

    // The largest distance from target's surface of this shape's sample points mapped by
    // x -> target center + linear (x - center), over the first `points` of them; stops at the first point
    // farther than `reject` and returns its distance.
    double farthestOnto(const ShapeVerifier& target, const Eigen::Matrix3d& linear, double reject,
                        std::size_t points = SIZE_MAX, RejectingPoints* hints = nullptr) const;

    // Whether deviations up to `distance` come out the same whatever larger rejection distance they are
    // measured with: sample points answer for the surface only within a distance below it.
    bool exactUpTo(double distance) const { return snapSquared_ <= distance * distance; }

    const Eigen::Vector3d& center() const { return center_; }

    // The unit direction across `axis` (through the center) of the sample point farthest from it.
    Eigen::Vector3d farthestFromAxis(const Eigen::Vector3d& axis) const;

private:
    // Squared distance from p (about center_) to the surface (searched up to `bound`), or an upper bound
    // of it no larger than `accept` when p is that close to a sample point: a map that is a symmetry of
    // the tessellation takes sample points onto sample points, found by one hash lookup, not a search.
    // With `enough` >= 0, the distance only when it is above that (else any value up to it, see
    // TriangleBvh::squaredDistanceAbove).
    double squaredDistanceToSurface(const Eigen::Vector3d& p, double accept, double bound, double enough = -1) const;
    std::uint64_t cellKey(const Eigen::Vector3d& p) const;

    const TriangleMesh& mesh_;
    TriangleBvh bvh_;
    Eigen::Vector3d center_;
    std::vector<Eigen::Vector3d> samples_;  // about center_, in an order that spreads over the shape early
    double cellSize_ = 1;
    double snapSquared_ = 0;
    std::unordered_map<std::uint64_t, std::uint32_t> sampleInCell_;  // a sample point of each occupied cell
};

// d_A between two shapes under x -> to.center() + linear (x - from.center()): both ways, with early rejection.
double deviationBetween(const ShapeVerifier& from, const ShapeVerifier& to, const Eigen::Matrix3d& linear,
                        double reject);

}  // namespace symcompress
