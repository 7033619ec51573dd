// A bounding-volume hierarchy over the triangles of a mesh, for the point-to-surface distances of the
// verification measure d_A (paper 5.3).
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace symcompress {

// The closest point of the triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5).
Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c);

// Invariant: nodes_[0] is the root; a leaf holds triangles order_[first .. first + count), whose corners are
// corners_[3 first .. 3 (first + count)); an inner node's children are nodes_[first] and nodes_[first + 1],
// its box their union. The mesh must outlive the hierarchy.
class TriangleBvh {
public:
    explicit TriangleBvh(const TriangleMesh& mesh);

    // The closest point of the surface to p and its squared distance, searching only closer than
    // sqrt(bound) (bound: a squared distance). Returns bound itself when nothing is closer.
    // Optionally the closest point and the index of its triangle; with `facing`, only among the triangles
    // whose normal (by their winding) points to the same side as it.
    double squaredDistance(const Eigen::Vector3d& p, double bound, Eigen::Vector3d* closest = nullptr,
                           std::uint32_t* triangle = nullptr, const Eigen::Vector3d* facing = nullptr) const;
    // The squared distance from p to the surface when it is above `enough` (searched up to bound, as
    // above); otherwise some value no larger than `enough`, returned as soon as a triangle that close is
    // found: all that the largest of many distances needs, which most points do not change.
    double squaredDistanceAbove(const Eigen::Vector3d& p, double enough, double bound) const;

    bool empty() const { return order_.empty(); }

private:
    struct Node {
        Eigen::AlignedBox3d box;
        std::uint32_t first = 0, count = 0;  // count > 0: leaf
    };
    template <bool kStopWithinEnough>
    double search(const Eigen::Vector3d& p, double bound, double enough, Eigen::Vector3d* closest,
                  std::uint32_t* triangle, const Eigen::Vector3d* facing) const;
    void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, std::vector<Eigen::Vector3d>& centers);

    const TriangleMesh& mesh_;
    std::vector<Node> nodes_;
    std::vector<std::uint32_t> order_;
    // The corners of the triangles in leaf order: a leaf's triangles side by side in memory, where the
    // mesh would have the search gather them from anywhere.
    std::vector<Eigen::Vector3d> corners_;
};

}  // namespace symcompress
