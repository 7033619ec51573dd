// The stages of computeFundamentalRegion (fundamental_region.hpp), private to the library.
#pragma once

#include "symcompress/detail/fundamental_region.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <vector>

namespace symcompress::region_detail {

// The Dirichlet cone of a seed under a group (docs/fundamental-regions.md, "The cone construction"): the half-spaces
// n . (x - apex) >= 0 with n = (p - g p) / |p - g p|, keeping only the planes that bound the cone.
struct DirichletCone {
    Eigen::Vector3d apex = Eigen::Vector3d::Zero();
    std::vector<Eigen::Vector3d> normals;  // unit, inward
};

// `nonIdentity` is the group without its identity; the seed must be fixed by none of its elements.
DirichletCone dirichletCone(const std::vector<Eigen::Matrix3d>& nonIdentity, const Eigen::Vector3d& seed,
                            const Eigen::Vector3d& apex);

// min over g of |p - g p| / |p|: how far the seed is from every fixed set (0 when some g fixes it).
double seedSeparation(const std::vector<Eigen::Matrix3d>& nonIdentity, const Eigen::Vector3d& seed);

struct SeedChoice {
    Eigen::Vector3d seed = Eigen::Vector3d::Zero();  // unit
    DirichletCone cone;
    std::size_t estimatedCuts = 0;  // triangles crossing a plane of the cone, on the scored sample
};

// Tries random directions, directions through triangle centroids and, for rotations, directions whose
// bisector plane passes through a vertex; keeps the seed whose cone cuts fewest triangles (ties: the
// seed farthest from every fixed set). `tolerance` is absolute.
SeedChoice chooseSeed(const Primitive& tile, const std::vector<Eigen::Matrix3d>& nonIdentity,
                      const Eigen::Vector3d& centre, double tolerance, const RegionOptions& options);

struct ClippedRegion {
    Primitive region;
    std::size_t trianglesCut = 0;
};

// S ∩ F: vertices within `tolerance` (absolute) of a plane snapped onto it, triangles inside kept whole,
// triangles crossing planes clipped (Sutherland-Hodgman) and fanned, triangles outside dropped.
ClippedRegion clipToCone(const Primitive& tile, const DirichletCone& cone, double tolerance);

// The orbits of the tile's triangles under the group, where the group maps the tile's vertices (welded
// within `tolerance`, absolute) and triangles onto one another and no element other than the identity maps a
// triangle onto itself; none where it does not. The same in any frame the group is conjugated to.
struct TriangleOrbits {
    std::vector<std::uint32_t> positionOf;           // a vertex's welded position
    std::vector<std::vector<std::uint32_t>> images;  // [e][r]: the position element e of nonIdentity takes r to
    std::vector<std::vector<std::uint32_t>> orbits;  // triangles, |G| each
};
std::optional<TriangleOrbits> triangleOrbits(const Primitive& tile, const std::vector<Eigen::Matrix3d>& nonIdentity,
                                             const Eigen::Vector3d& centre, double tolerance);

// One whole triangle of each orbit (the one whose centroid is nearest the seed), compacted, with the tile's
// positions made symmetric: each the mean of its orbit brought back by the group, moved by the group.
// `tile`, `nonIdentity` and `centre` in one frame (the orbits may have been found in another), the elements in
// the order the orbits were found with.
Primitive wholeTriangleRegion(const Primitive& tile, const TriangleOrbits& orbits,
                              const std::vector<Eigen::Matrix3d>& nonIdentity, const Eigen::Vector3d& centre,
                              const Eigen::Vector3d& seed);

struct AlignedFrame {
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the frame's axes, det +1
    bool signedPermutation = false;                          // every element is a signed permutation in this frame
};

// The frame of RegionFrame::Aligned (see fundamental_region.hpp) for the group and the cone's normals.
AlignedFrame chooseAlignedFrame(const std::vector<Eigen::Matrix3d>& nonIdentity,
                                const std::vector<Eigen::Vector3d>& coneNormals);

// The axis of an element: the rotation axis of a proper rotation, the reversed direction of an improper
// one (a mirror's normal, a rotoreflection's axis); none for the identity and the inversion. Unit, with
// an arbitrary sign.
std::optional<Eigen::Vector3d> elementAxis(const Eigen::Matrix3d& element);

// Whether every entry is within `tolerance` of -1, 0 or 1 with one non-zero per row and column.
bool isSignedPermutation(const Eigen::Matrix3d& matrix, double tolerance);

}  // namespace symcompress::region_detail
