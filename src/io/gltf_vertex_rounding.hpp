// The vertices of a primitive that Draco cannot hold (a morphed one: its reordering of the vertices would no
// longer match the targets' displacements; lines and points), rounded by EXT_meshopt_compression's exponential
// filter instead of stored as float32: each attribute to the fewest bits that keep it within what Draco's quantization
// allows the same attribute of a primitive it holds, the targets' displacements within that share over the weights they
// are drawn with.
#pragma once

#include "gltf_constants.hpp"
#include "symcompress/io.hpp"
#include "symcompress/scene.hpp"

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace symcompress {

struct IntegerPositionGrid;

// One accessor's values as the file stores them (after one of meshopt's filters, where `filter` names one), and as a
// viewer reads them from the accessor (a grid's integers: before their node's dequantization).
struct RoundedAttribute {
    std::vector<unsigned char> filtered;  // the stored elements, one a vertex
    std::size_t elementBytes = 0;         // of one element (meshopt's byteStride)
    std::vector<float> decoded;
    int bits = 0;
    int components = 0;
    int componentType = kFloat;  // or integers: positions on a grid (gltf_integer_positions.hpp), normalized colours
    bool normalized = false;
    std::string filter = "EXPONENTIAL";  // meshopt's EXPONENTIAL, OCTAHEDRAL, or NONE
};

// What an attribute stored in a view of its own (another filter or component type) costs in the file's JSON beyond
// its data: the view with its EXT_meshopt_compression object, byteStride and target; and the names of
// KHR_mesh_quantization in extensionsUsed and extensionsRequired, where it needs that extension.
constexpr std::size_t kOwnViewBytes = 170, kQuantizationNamesBytes = 48;

// By target (-1: the primitive's own attributes) and attribute name (POSITION, NORMAL, TEXCOORD_0, COLOR_0, or
// one of Primitive::attributes); what is missing stays as read.
using RoundedVertices = std::map<std::pair<int, std::string>, RoundedAttribute>;

// The rounding of `primitive`'s vertices and displacements: POSITION within its error bound (positionErrorBound;
// half of it where morph targets take the other half), the displacements that half over the sum of `largestWeights` (of
// each target, the largest magnitude it is drawn with); NORMAL and TANGENT within the angle of Draco's normal
// quantization, texture coordinates, colours and weights within half a step of its quantization over their span, their
// displacements alike. Joints and an application's attributes stay as read, and everything does where the
// primitive has no error bound.
// With `integerGrid`, POSITION on that grid instead (integerPositions).
RoundedVertices roundedPlainVertices(const Primitive& primitive, const WriteOptions& options,
                                     const std::vector<double>& largestWeights,
                                     const IntegerPositionGrid* integerGrid = nullptr);

// `primitive`'s positions through the exponential filter within `bound` (Euclidean), as roundedPlainVertices rounds
// them where they are on no grid; none where the filter cannot hold them.
std::optional<RoundedAttribute> exponentialPositions(const Primitive& primitive, double bound);

// Whether `rounded` stores an attribute as integers that only KHR_mesh_quantization allows (positions, normals,
// tangents; glTF's core allows them for texture coordinates and colours).
bool needsMeshQuantization(const RoundedVertices& rounded);

// A primitive of lines or points, its vertices in the order of the Hilbert curve through the cells of `grid` (else of
// 2^16 a side over their box), a line's segments each from its earlier vertex and in order: neighbours side by side,
// which meshopt's codecs code smaller (a scan's points as its scanner gave them, an exporter's edges in any order; the
// bunny's edges 0.81 of gltfpack's, which keeps their order). The order in which points and segments are drawn draws
// nothing.
Primitive spatiallySorted(const Primitive& primitive, const IntegerPositionGrid* grid);

// Of each morph target of scene.meshes[mesh], the largest magnitude of a weight it is drawn with: its default,
// a node's, and an animation's keys (cubic splines: with what their tangents can add between keys).
std::vector<double> largestMorphWeights(const Scene& scene, std::size_t mesh);

}  // namespace symcompress
