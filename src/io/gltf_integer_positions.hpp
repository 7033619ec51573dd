// The positions of a mesh of lines and points on a uniform grid of unsigned integers (KHR_mesh_quantization), the
// grid undone by the node that draws the mesh (a translation to its origin, a uniform scale by its step). Draco holds
// no lines or points in glTF, and meshopt codes the differences of neighbouring integers smaller than the exponential
// filter's floats, which spend as many bits on a point near the origin as on the farthest (the bunny's 35947 points:
// 164408 bytes through the filter; gltfpack stores point clouds on such a grid).
#pragma once

#include "gltf_vertex_rounding.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace symcompress {

struct IntegerPositionGrid {
    Eigen::Vector3d origin;  // float32 values, as a node's translation is read
    double step = 0;         // float32, as a node's scale is read
    int componentBytes = 2;  // 1 (UNSIGNED_BYTE) or 2 (UNSIGNED_SHORT)

    // From the grid's integers to the mesh's frame: translation by `origin`, uniform scale by `step`.
    Eigen::Matrix4d dequantization() const;
    // The integer nearest `p` along `axis`, within the grid's range.
    std::uint32_t coordinate(const Eigen::Vector3d& p, int axis) const;
};

// The coarsest grid that keeps every vertex of `mesh` within its primitives' error bound (positionErrorBound,
// Euclidean), at the fewest bytes a component; none where the mesh draws triangles (Draco's), has morph targets (their
// displacements would have to be on the grid too), has no bound (fixed bits), would need more than 16 bits an axis,
// or where meshopt codes the integers no smaller than the exponential filter's floats by the JSON they add (a view,
// the extension's names, the node's dequantization): a few points.
std::optional<IntegerPositionGrid> integerPositionGridFor(const Mesh& mesh, const WriteOptions& options);

// `primitive`'s positions on `grid`: its integers (each vertex padded to 4 bytes, as glTF's vertex strides ask) and
// the values a viewer reads from the accessor (the integers, before the node's dequantization).
RoundedAttribute integerPositions(const Primitive& primitive, const IntegerPositionGrid& grid);

}  // namespace symcompress
