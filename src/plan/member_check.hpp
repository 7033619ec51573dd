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

enum class Reproduction { Reproduced, Differs, CutOtherwise };

// Whether `prototype` placed by j reproduces `member` triangle for triangle, corner by corner, within
// `tolerance` (a distance), facing the same way (with `geometryOnly`, positions and faces only), or has the same
// corners cut into other triangles (a quad's other diagonal), for the surface check to decide. With `deviation`,
// the largest distance of a member vertex from its match.
Reproduction reproduction(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                          bool geometryOnly, double* deviation = nullptr);

// Whether `prototype` placed by j reproduces `member` triangle for triangle, corner by corner, within
// `tolerance` (a distance), facing the same way; with `geometryOnly`, positions and faces only, else normals,
// texture coordinates and colours too. Where the same corners are cut into other triangles (a quad's other
// diagonal), as surfaces (surfaceDeviation). With `deviation`, the largest distance of a member vertex from its
// match.
bool reproduces(const Primitive& prototype, const Primitive& member, const Isometry& j, double tolerance,
                bool geometryOnly, double* deviation = nullptr);

// A tile's surface with its triangles' hierarchy, built once for the surface check of many placements.
class TileSurface {
public:
    explicit TileSurface(const Primitive& primitive);
    TileSurface(const TileSurface&) = delete;
    TileSurface& operator=(const TileSurface&) = delete;

    const Primitive& primitive() const { return primitive_; }
    // The closest point of the surface to p within sqrt(bound) (a squared distance), with `facing` only on
    // the triangles whose normal points its way: its squared distance (bound when none), its triangle and its
    // barycentric coordinates there.
    double closest(const Eigen::Vector3d& p, double bound, std::uint32_t& triangle, Eigen::Vector3d& weights,
                   const Eigen::Vector3d* facing = nullptr) const;

private:
    const Primitive& primitive_;
    TriangleMesh mesh_;
    TriangleBvh bvh_;
};

// The check for copies tessellated each on its own (docs/compression-plan.md, "The member check"): whether
// `prototype` placed by j stands for `member` as a surface. Every vertex and triangle centroid of each lies
// within `tolerance` of the other's surface; both face the same way; and, unless `geometryOnly`, their normals,
// texture coordinates and colours agree as fields: each one's values at its vertices against the other's
// interpolated where those vertices fall on its surface. Returns the largest of those distances, or nothing.
std::optional<double> surfaceDeviation(const TileSurface& prototype, const TileSurface& member, const Isometry& j,
                                       double tolerance, bool geometryOnly);

}  // namespace symcompress
