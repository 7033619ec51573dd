// The member check: whether a stored part, placed by an isometry, may stand for a tile. The classes are
// congruent as surfaces; a node may draw a member where the prototype reproduces it vertex for vertex,
// attributes included, facing the same way, or, tessellated otherwise, as a surface with the same attributes
// (docs/compression-plan.md, "The member check").
#pragma once

#include "geometry/triangle_bvh.hpp"
#include "symcompress/congruence.hpp"
#include "symcompress/scene.hpp"

#include <optional>

namespace symcompress {

// AttributesDiffer: every triangle of the member is one of the prototype's at the same places, but a corner's
// normal, texture coordinates or colour differ (the surface check, comparing the same places, cannot pass them:
// drawn from the prototype, that corner would look otherwise).
enum class Reproduction { Reproduced, Differs, CutOtherwise, AttributesDiffer };

// Whether `prototype` placed by j reproduces `member` triangle for triangle, corner by corner, within
// `tolerance` (a distance), facing the same way (with `geometryOnly`, positions and faces only), or has the same
// corners cut into other triangles (a quad's other diagonal), for the surface check to decide, or the same
// triangles with other attributes. With `deviation`, the largest distance of a member vertex from its match.
Reproduction reproduction(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                          bool geometryOnly, double* deviation = nullptr);

// Whether `prototype` placed by j reproduces `member` triangle for triangle, corner by corner, within
// `tolerance` (a distance), facing the same way; with `geometryOnly`, positions and faces only, else normals,
// texture coordinates and colours too. Where the same corners are cut into other triangles (a quad's other
// diagonal), as surfaces (surfaceDeviation). With `deviation`, the largest distance of a member vertex from its
// match.
bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                bool geometryOnly, double* deviation = nullptr);

// The surface's orientation, independent of how it is cut into triangles: its vector area S = ∫ n dA and
// M = ∫ n (x - c)^T dA about its area centroid c (for a closed part, its volume times the identity).
struct OrientedMoments {
    Eigen::Vector3d area = Eigen::Vector3d::Zero();
    Eigen::Matrix3d first = Eigen::Matrix3d::Zero();
};
OrientedMoments orientedMoments(const Primitive& part);

// A tile's surface with its triangles' hierarchy, built once for the surface check of many placements.
class TileSurface {
public:
    explicit TileSurface(const Primitive& primitive);
    TileSurface(const TileSurface&) = delete;
    TileSurface& operator=(const TileSurface&) = delete;

    const Primitive& primitive() const { return primitive_; }
    const OrientedMoments& moments() const { return moments_; }
    double diagonal() const { return diagonal_; }  // of its positions' bounding box
    // The closest point of the surface to p within sqrt(bound) (a squared distance), with `facing` only on
    // the triangles whose normal points its way: its squared distance (bound when none), its triangle and its
    // barycentric coordinates there.
    double closest(const Eigen::Vector3d& p, double bound, std::uint32_t& triangle, Eigen::Vector3d& weights,
                   const Eigen::Vector3d* facing = nullptr) const;
    // The squared distance from p to the surface where it is above `enough`, else some value up to it
    // (TriangleBvh::squaredDistanceAbove): the largest of many distances, faster.
    double squaredDistanceAbove(const Eigen::Vector3d& p, double enough, double bound) const;

private:
    const Primitive& primitive_;
    TriangleMesh mesh_;
    TriangleBvh bvh_;
    OrientedMoments moments_;
    double diagonal_ = 0;
};

// The check for copies tessellated each on its own (docs/compression-plan.md, "The member check"): whether
// `prototype` placed by j stands for `member` as a surface. Every vertex and triangle centroid of each lies
// within `tolerance` of the other's surface; both face the same way; and, unless `geometryOnly`, their normals,
// texture coordinates and colours agree as fields: each one's values at its vertices against the other's
// interpolated where those vertices fall on its surface. Returns the largest of those distances, or nothing.
std::optional<double> surfaceDeviation(const TileSurface& prototype, const TileSurface& member, const Isometry& j,
                                       double tolerance, bool geometryOnly);

}  // namespace symcompress
