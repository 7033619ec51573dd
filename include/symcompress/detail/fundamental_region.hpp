// The fundamental region of a symmetric tile (paper 7.1, docs/fundamental-regions.md): the part of the tile
// that, copied once per element of its symmetry group, rebuilds the whole tile.
//
// The tile S is invariant under a finite group G of orthogonal maps x -> c + g (x - c). For a seed point p
// (relative to c) fixed by no g != id, the Dirichlet cone
//
//     F = { x : (x - c) . (p - g p) >= 0  for every g in G, g != id }
//
// is a fundamental domain: the cones g F tile space with disjoint interiors. The region R = S ∩ F is
// stored once, and the union over g in G of g(R) is S again.
//
// What the caller guarantees: G contains the identity, is closed under composition (checked here
// within RegionOptions::groupTolerance, as is orthogonality), and the tile is invariant under it as an
// ORIENTED surface. A tile that is not invariant gives a region whose copies do not rebuild it; that
// is not detected here (the symmetry stage verifies invariance).
//
// Mirrors: an instance g with det(g) = -1 reverses the winding of the triangles it maps. Placed as a
// glTF node whose matrix has a negative determinant, the renderer flips the winding itself, so the
// stored region is written once, unchanged, and referenced by every instance. Code that expands
// instances into a flat mesh by hand must reverse the triangles' index order for those instances, as
// rebuildFromRegion does.
//
// Triangles lying in a plane of F belong to two neighbouring cones; a triangle is kept when it faces into
// F, which counts each such triangle exactly once over the copies.
//
// Flat tiles: when the whole tile lies in a mirror plane of G (a zero-thickness panel), that mirror fixes
// every point and would lay a second, reversed copy on the tile. Only the subgroup of G preserving the
// tile's normal is then used; `instances` is that subgroup.
//
// Seams: the boundary of R lies on the planes of F. After lossy quantization (Draco) the copies meet
// exactly only where quantization commutes with the instance maps; see RegionFrame::Aligned and
// seamPreservingGrid.
#pragma once

#include "symcompress/scene.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace symcompress {

enum class RegionFrame {
    // Region positions and normals stay in the tile's coordinates.
    Tile,
    // Region positions are expressed in an orthonormal frame centred on the tile's centre, chosen so
    // that (first choice) every instance is a signed permutation matrix, i.e. maps the integer grid of
    // any quantization with a grid point at the centre onto itself, and (second) as many planes of F
    // as possible are coordinate planes. Cut vertices on a coordinate plane get that coordinate exactly
    // 0. With Draco's default quantization (box of the data), a single mirror plane then stays closed
    // (the region's minimum on that axis is exactly 0, a grid point); with seamPreservingGrid (and
    // inGridSteps for Draco's explicit quantization), every seam between copies related by a signed
    // permutation stays closed. What remains: groups with no signed
    // permutation frame (5- and 6-fold axes, D3h, Ih, ...) keep gaps up to about one quantization step on
    // the planes that cannot be aligned, and seams of rotation (not mirror) facets whose triangulation is
    // not itself symmetric meet at T-junctions that quantization opens by up to about one step.
    Aligned,
};

// How R = S ∩ F treats the triangles that cross a plane of F.
enum class RegionTriangles {
    // Clipped at the planes (any tessellation): the copies rebuild the surface, with the crossing triangles
    // in pieces.
    Cut,
    // No triangle cut, and the copies draw as many triangles as the tile has. Where the group maps the
    // tile's triangles onto one another, wound alike, and no element other than the identity maps a triangle
    // onto itself,
    // R is one triangle of each orbit (the one whose centroid lies in F): the copies draw the tile's own
    // triangles, each once (FundamentalRegion::wholeTriangles). Else R = S ∩ F where F's planes cut no
    // triangle and split the triangles evenly (a mirror whose halves are tessellated each its own way, along
    // edges on the plane): the copies draw the stored part's triangles in the others' place. Else
    // std::invalid_argument.
    Whole,
    // Whole where it can be, else Cut.
    WholeWherePossible,
    // One triangle of each orbit, or std::invalid_argument.
    OneOfEachOrbit,
};

struct RegionOptions {
    RegionFrame frame = RegionFrame::Tile;
    RegionTriangles triangles = RegionTriangles::Cut;
    // Whole triangles: a vertex's image under an element is the vertex within this distance of it, relative
    // to the tile's radius about its centre (vertices closer than this are one). The tile's positions are
    // made symmetric (each an orbit's mean moved by the group), so they move by up to this much.
    double vertexTolerance = 1e-6;
    // Vertices closer than this to a plane of F, relative to the tile's radius about its centre, are
    // on the plane and are snapped onto it.
    double snapTolerance = 1e-9;
    // Allowed deviation of the group's matrices from orthogonality, identity and closure (absolute,
    // on matrix entries).
    double groupTolerance = 1e-6;
    // Seed candidates: this many random directions, plus directions through triangle centroids and
    // directions whose planes of F pass through vertices (for rotations). Deterministic.
    std::size_t randomCandidates = 64;
    std::uint64_t randomSeed = 0x5eedf00dULL;
    // Seed candidates are scored on at most this many triangles (evenly strided) of the tile.
    std::size_t maxScoredTriangles = 4096;
};

struct FundamentalRegion {
    // R = S ∩ F with all attributes, in region coordinates (see regionToTile). Cut vertices carry
    // attributes interpolated linearly along the cut edge (normals renormalized). Vertices are shared
    // between the region's triangles; cut points on a shared edge are computed once.
    Primitive region;
    // The elements g of G (tile frame) whose copies rebuild the tile: copy k is instanceTransform(*this, k).
    std::vector<Eigen::Matrix3d> instances;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    // The seed p of the Dirichlet cone, a unit vector relative to the centre, tile frame.
    Eigen::Vector3d seed = Eigen::Vector3d::Zero();
    // Unit inward normals of the planes bounding F (tile frame); every plane passes through the centre.
    std::vector<Eigen::Vector3d> facetNormals;
    // Region coordinates -> tile coordinates: a rigid motion (the identity for RegionFrame::Tile), times a
    // uniform power-of-two scale after inGridSteps.
    Eigen::Matrix4d regionToTile = Eigen::Matrix4d::Identity();
    // Whether every instance, expressed in region coordinates, is a signed permutation matrix.
    bool signedPermutationFrame = false;
    // Triangles of the tile that crossed a plane of F and were clipped.
    std::size_t trianglesCut = 0;
    // Whether R is one triangle of each orbit of the tile's (RegionTriangles::Whole): the copies draw the
    // tile's own triangles.
    bool wholeTriangles = false;
    // The largest distance of the rebuilt tile from the tile, where the plan measured it (else 0).
    double deviation = 0;
};

// Throws std::invalid_argument for an empty or malformed tile (scene.hpp invariants, non-finite
// values, zero area), a non-finite centre, or a group that is empty, lacks the identity, has a
// non-orthogonal or repeated matrix, or is not closed under composition.
FundamentalRegion computeFundamentalRegion(const Primitive& tile, const std::vector<Eigen::Matrix3d>& group,
                                           const Eigen::Vector3d& centre, const RegionOptions& options = {});

// Region coordinates -> tile coordinates of copy k: x -> centre + g_k (T x - centre), T = regionToTile.
Eigen::Matrix4d instanceTransform(const FundamentalRegion& region, std::size_t k);

// The union of all copies, in tile coordinates: normals rotated, winding reversed for mirrors so that
// every copy faces the same way as the tile. Seam vertices are not welded.
Primitive rebuildFromRegion(const FundamentalRegion& region);

// The grid covering the region's positions whose step is a power of two and whose points include the
// origin of region coordinates (the tile's centre under RegionFrame::Aligned) in every coordinate; origin
// and range are exact in float. Signed permutation instances then map grid points onto grid points, so
// seams between their copies survive quantization. The step is at most about twice that of the data's
// own box. Throws std::invalid_argument for bits outside [1, 30] or an empty region.
QuantizationGrid seamPreservingGrid(const FundamentalRegion& region, int bits);
// The coarsest seamPreservingGrid on which no corner of the region moves farther than `maxError` (half a
// step on each axis), of at most 24 bits.
QuantizationGrid seamPreservingGridWithin(const FundamentalRegion& region, double maxError);

// The region in units of the grid's step, with the grid in the same units (integer origin, range
// 2^bits - 1); regionToTile takes the scale, so instanceTransform and rebuildFromRegion are unchanged.
// Needed with Draco 1.5: SetAttributeExplicitQuantization passes origin and range through
// std::to_string (6 decimals), which keeps integers exact but not a fractional power-of-two grid.
struct RegionInGridSteps {
    FundamentalRegion region;
    QuantizationGrid grid;
};
RegionInGridSteps inGridSteps(const FundamentalRegion& region, const QuantizationGrid& grid);

}  // namespace symcompress
